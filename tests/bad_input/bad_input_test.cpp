// Bad input: every bad input gives a clear error, never a crash or a hang, and nothing
// is lost.
//
// Library level: each load error is an antcd::Error (MeshError for meshes, SceneError for scenes)
// whose what() is one line naming the input. A bad mesh file must either be refused that way or,
// when what survives is a valid mesh (a text file cut at a line boundary is a smaller mesh), load
// into a mesh that validate_mesh accepts and from which a Model builds or is refused with a
// MeshError. Anything else (another exception type, a crash, a hang) fails.
//
// CLI level: the built `antcd` (ANTCD_CLI) is run as a child process with bad values. Each run must
// exit with code 2, print exactly one line "error: ..." on stderr naming the input, print nothing
// on stdout, and leave its working folder as it was: no output file, no temporary file, an existing
// output file untouched.
//
// Scene schema errors already covered by tests/scene/scene_file_test.cpp are not repeated here.
//
// A hang fails through CTest's per-test TIMEOUT, and the CLI runs have their own time limit.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_run.hpp"
#include "support/mesh_files.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;
using test::binary_stl;
using test::fresh_temp_dir;
using test::read_all;
using test::write_file;

// ---- helpers ----

/// Checks the shape of an error message: it starts with "<source>: " (when `starts` is set) or
/// names `source` somewhere, and is one line.
void expect_names(const std::string& what, const std::string& source, bool starts = true) {
  if (starts) {
    EXPECT_EQ(what.rfind(source + ": ", 0), 0u)
        << "message does not start with the input: " << what;
  } else {
    EXPECT_NE(what.find(source), std::string::npos)
        << "message does not name " << source << ": " << what;
  }
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  EXPECT_EQ(what.find('\r'), std::string::npos) << what;
}

enum class Outcome { Refused, Loaded };

/// Loads `path` and builds a Model from it. Either step may refuse the file with a MeshError naming
/// it; any other exception is a failure. A mesh that loads must pass validate_mesh.
Outcome load_and_build(const fs::path& path, std::string* message = nullptr) {
  const std::string source = path.string();
  try {
    Mesh mesh = load_mesh(path);
    EXPECT_NO_THROW(validate_mesh(mesh, source)) << source;
    const Model model(std::move(mesh), {}, source);
    EXPECT_GT(model.stats().triangles, model.stats().degenerate_triangles) << source;
    return Outcome::Loaded;
  } catch (const MeshError& e) {
    EXPECT_EQ(e.source(), source);
    expect_names(e.what(), source);
    if (message != nullptr) *message = e.what();
    return Outcome::Refused;
  } catch (const std::exception& e) {
    ADD_FAILURE() << source << ": expected a MeshError, got " << typeid(e).name() << ": "
                  << e.what();
  } catch (...) {
    ADD_FAILURE() << source << ": expected a MeshError, got a non-standard exception";
  }
  return Outcome::Refused;
}

/// Expects the file to be refused with a MeshError whose message holds `problem`.
void expect_refused(const fs::path& path, const std::string& problem = "") {
  std::string message;
  if (load_and_build(path, &message) == Outcome::Loaded) {
    ADD_FAILURE() << path << " was loaded; expected a MeshError";
    return;
  }
  EXPECT_NE(message.find(problem), std::string::npos) << message;
}

/// Expects parse_scene to throw a SceneError starting with `source` and holding `problem`.
void expect_scene_error(std::string_view text, const std::string& problem,
                        const std::string& source = "bad.json") {
  try {
    (void)parse_scene(text, "/base", source);
    ADD_FAILURE() << "expected a SceneError holding '" << problem << "'";
  } catch (const SceneError& e) {
    expect_names(e.what(), source);
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SceneError, got " << typeid(e).name() << ": " << e.what();
  }
}

std::string random_bytes(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string out(n, '\0');
  for (char& c : out) c = static_cast<char>(rng() & 0xFF);
  return out;
}

/// The names in a folder (recursively), for "nothing appeared, nothing vanished" checks.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    out.insert(fs::relative(e.path(), dir).generic_string());
  }
  return out;
}

const char* kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// ---- assimp-testmodels' invalid/ folder: one test per file ----

std::vector<std::string> invalid_model_names() {
  std::vector<std::string> names;
  const fs::path dir = fs::path(ANTCD_ASSIMP_MODELS) / "invalid";
  std::error_code ec;
  if (fs::is_directory(dir, ec)) {
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) names.emplace_back();  // one placeholder test that skips
  return names;
}

class PackagedInvalidFile : public ::testing::TestWithParam<std::string> {};

TEST_P(PackagedInvalidFile, IsRefusedCleanly) {
  const fs::path dir = fs::path(ANTCD_ASSIMP_MODELS) / "invalid";
  if (GetParam().empty()) {
    GTEST_SKIP() << dir << " is absent (install the Debian package assimp-testmodels)";
  }
  const fs::path path = dir / GetParam();
  const auto start = std::chrono::steady_clock::now();
  if (GetParam() == "malformed2.obj") {
    // Its only defect is a missing material, which is irrelevant to geometry.
    EXPECT_EQ(load_and_build(path), Outcome::Loaded);
  } else {
    expect_refused(path);
  }
  // OutOfMemory.off once made assimp allocate and zero ~16 GB: every file is refused quickly.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

INSTANTIATE_TEST_SUITE_P(AssimpInvalid, PackagedInvalidFile,
                         ::testing::ValuesIn(invalid_model_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.empty() ? "absent" : info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

// ---- truncated real models ----

class TruncatedModel : public ::testing::TestWithParam<const char*> {};

TEST_P(TruncatedModel, EveryCutIsRefusedOrValid) {
  const fs::path original = fs::path(ANTCD_ASSIMP_MODELS) / GetParam();
  if (!fs::exists(original)) GTEST_SKIP() << original << " is absent";
  const std::string data = read_all(original);
  ASSERT_GT(data.size(), 200u);
  ASSERT_EQ(load_and_build(original), Outcome::Loaded) << "the uncut file must load";
  const std::string ext = original.extension().string();
  const bool binary_stl =
      std::string(GetParam()).find("binary") != std::string::npos && original.extension() == ".stl";
  const std::size_t n = data.size();
  const auto dir = fresh_temp_dir("truncated_" + original.stem().string() + "_" + ext.substr(1));
  std::set<std::size_t> cuts = {1, 2, 5, 16, 50, 83, 84, 85, 100, 134, 199};
  for (const std::size_t part : {10, 4, 3, 2}) cuts.insert(n / part);
  for (const std::size_t back : {100, 51, 50, 49, 2, 1}) cuts.insert(n - back);
  for (const std::size_t cut : cuts) {
    if (cut == 0 || cut >= n) continue;
    SCOPED_TRACE("cut at " + std::to_string(cut) + " of " + std::to_string(n) + " bytes");
    const fs::path path = dir / ("cut_" + std::to_string(cut) + ext);
    write_file(path, data.substr(0, cut));
    const Outcome outcome = load_and_build(path);
    // A binary STL whose size does not match its triangle count is never half-read.
    if (binary_stl) {
      EXPECT_EQ(outcome, Outcome::Refused);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AssimpModels, TruncatedModel,
                         ::testing::Values("STL/Spider_binary.stl", "STL/Spider_ascii.stl",
                                           "OBJ/spider.obj", "PLY/Wuson.ply", "PLY/cube_binary.ply",
                                           "OFF/Wuson.off",
                                           "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

// ---- regressions found by fuzzing (fuzz/fuzz_mesh_load; inputs in tests/bad_input/data) ----

TEST(FuzzRegression, PlyHeaderWithoutEndHeaderDoesNotHang) {
  // A timeout found by fuzz/fuzz_mesh_load: assimp's PLY reader never returns when the file ends
  // inside the header (it parses the last header line again and again, growing memory). load_mesh
  // now refuses a PLY file without an end_header line before assimp reads it.
  const fs::path found = fs::path(ANTCD_BAD_INPUT_DATA) / "fuzz-timeout-ply-header-without-end.ply";
  ASSERT_TRUE(fs::exists(found)) << found;
  const auto start = std::chrono::steady_clock::now();
  expect_refused(found, "the PLY header has no end_header line");
  // The same bytes under the other extensions the fuzzer tries.
  const auto dir = fresh_temp_dir("fuzz_ply_header");
  for (const std::string ext : {".obj", ".stl", ".off", ".dat"}) {
    fs::copy_file(found, dir / ("found" + ext));
    expect_refused(dir / ("found" + ext));
  }
  // Every way a header can end before "end_header".
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";
  const std::string rest =
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::vector<std::pair<std::string, std::string>> unterminated = {
      {"magic_format", "ply\nformat ascii 1.0\n"},
      {"element", "ply\nformat ascii 1.0\nelement vertex 3\n"},
      {"property", head},
      {"property_no_newline", head + "property float"},
      {"comment", "ply\nformat ascii 1.0\ncomment a\n"},
      {"unknown_line", "ply\nformat ascii 1.0\nfoo bar\n"},
      {"binary", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"},
      {"suffixed", head + rest + "end_headerX\n" + body},
      {"in_comment", head + rest + "comment end_header\n" + body},
      {"upper_case", head + rest + "END_HEADER\n" + body},
      {"after_carriage_return", head + rest + "\rend_header\n" + body},
  };
  for (const auto& [name, text] : unterminated) {
    SCOPED_TRACE(name);
    write_file(dir / (name + ".ply"), text);
    expect_refused(dir / (name + ".ply"), "the PLY header has no end_header line");
  }
  // Complete headers still load, including a header longer than the first 4 KiB.
  const std::vector<std::pair<std::string, std::string>> complete = {
      {"plain", head + rest + "end_header\n" + body},
      {"indented", head + rest + " \t end_header\n" + body},
      {"crlf", head + rest + "end_header\r\n" + body},
      {"upper_magic", "PLY" + head.substr(3) + rest + "end_header\n" + body},
      {"long_header",
       head + rest + std::string(10000, ' ').insert(0, "comment") + "\n" + "end_header\n" + body},
  };
  for (const auto& [name, text] : complete) {
    SCOPED_TRACE(name);
    write_file(dir / (name + ".ply"), text);
    EXPECT_EQ(load_and_build(dir / (name + ".ply")), Outcome::Loaded);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

TEST(FuzzRegression, OffWithMoreSkippedFaceLinesThanFacesDoesNotCrash) {
  // A crash (SEGV inside assimp) found by fuzz/fuzz_mesh_load: assimp 5.2's OFF reader drops a face
  // line whose corner count is 0 or above 9 by decrementing the face count without bound; with
  // more such lines than the header's faces the count wraps around and assimp reads far past its
  // face array. load_mesh now walks the file as that reader does and refuses it first.
  const fs::path found = fs::path(ANTCD_BAD_INPUT_DATA) / "fuzz-crash-off-face-count-underflow.off";
  ASSERT_TRUE(fs::exists(found)) << found;
  expect_refused(found, "more face lines with 0 or over 9 corners than faces in the OFF header");
  const auto dir = fresh_temp_dir("fuzz_off_faces");
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> crashing = {
      {"two_empty_faces.off", "OFF\n3 1 0\n" + vertices + "0\n0\n3 0 1 2\n"},
      {"big_polygons.off", "OFF\n3 1 0\n" + vertices + "10 0 1 2 0 1 2 0 1 2 0\n12\n3 0 1 2\n"},
      {"comments.off", "OFF\n3 2 0\n" + vertices + "# a\n# b\n# c\n3 0 1 2\n"},
      {"no_keyword.off", "3 1 0\n" + vertices + "0\n0\n3 0 1 2\n"},
      {"keyword_other_extension.txt", "OFF\n3 1 0\n" + vertices + "0\n0\n3 0 1 2\n"},
  };
  for (const auto& [name, text] : crashing) {
    SCOPED_TRACE(name);
    write_file(dir / name, text);
    expect_refused(dir / name, "more face lines with 0 or over 9 corners");
  }
  // A header without the OFF keyword is checked for plausible counts as well.
  write_file(dir / "huge.off", "999999999 1 0\n" + vertices + "3 0 1 2\n");
  expect_refused(dir / "huge.off", "the OFF header announces 999999999 vertices");
  // As many dropped lines as faces is survivable (assimp then has no face left), and a dropped
  // line among enough faces is only a lost face.
  write_file(dir / "one_dropped.off", "OFF\n3 1 0\n" + vertices + "0\n3 0 1 2\n");
  expect_refused(dir / "one_dropped.off", "contains no triangles");
  write_file(dir / "dropped_among_faces.off", "OFF\n3 2 0\n" + vertices + "0\n3 0 1 2\n3 0 2 1\n");
  EXPECT_EQ(load_and_build(dir / "dropped_among_faces.off"), Outcome::Loaded);
}

// ---- random bytes ----

TEST(BadMeshFile, RandomBytesUnderEveryExtension) {
  const auto dir = fresh_temp_dir("random_bytes");
  const std::vector<std::string> extensions = {
      "",   ".obj", ".stl", ".ply",  ".off", ".glb", ".gltf",    ".dae",   ".3ds", ".fbx",
      ".x", ".ase", ".lwo", ".ms3d", ".smd", ".md2", ".md5mesh", ".blend", ".3mf", ".bin"};
  std::uint64_t seed = 1;
  for (const std::size_t size : {1u, 3u, 17u, 84u, 134u, 500u, 4096u, 65536u}) {
    const std::string bytes = random_bytes(size, seed++);
    for (const std::string& ext : extensions) {
      const fs::path path = dir / ("noise_" + std::to_string(size) + ext);
      SCOPED_TRACE(path.string());
      write_file(path, bytes);
      expect_refused(path);
    }
  }
}

TEST(BadMeshFile, RandomBytesAfterAValidHeader) {
  // The first bytes pick the reader, the rest is noise: the reader itself must cope.
  const auto dir = fresh_temp_dir("random_after_header");
  const std::vector<std::pair<std::string, std::string>> headers = {
      {".stl", "solid noise\n"},
      {".stl", "solid noise\nfacet normal 0 0 1\nouter loop\nvertex "},
      {".ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float "
       "y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"},
      {".ply",
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
       "float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"},
      {".off", "OFF\n4 2 0\n"},
      {".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf "},
      {".glb", std::string("glTF\x02\x00\x00\x00", 8)},
  };
  std::uint64_t seed = 100;
  for (const auto& [ext, header] : headers) {
    for (const std::size_t size : {0u, 7u, 48u, 300u, 5000u}) {
      const fs::path path = dir / ("noisy_" + std::to_string(seed) + ext);
      SCOPED_TRACE(path.string());
      write_file(path, header + random_bytes(size, seed++));
      (void)load_and_build(path);  // refused, or a valid mesh if the noise happens to be one
    }
  }
}

// ---- binary STL whose triangle count lies ----

TEST(BadMeshFile, BinaryStlCountLies) {
  const auto dir = fresh_temp_dir("stl_count_lies");
  const Mesh cube = make_box(Vec3(1, 1, 1));  // 12 triangles
  write_file(dir / "honest.stl", binary_stl(cube));
  ASSERT_EQ(load_and_build(dir / "honest.stl"), Outcome::Loaded);
  const std::uint32_t true_count = 12;
  // Larger than the data (by one, by far, and the count whose 32-bit size computation wraps around
  // to the true file size: 12 + 2^31 triangles of 50 bytes "fit" in 684 bytes modulo 2^32), and
  // smaller than the data (the file then has trailing bytes).
  const std::vector<std::int64_t> lies = {true_count + 1,
                                          1000,
                                          0xFFFFFFFF,
                                          std::int64_t{true_count} + (std::int64_t{1} << 31),
                                          0x80000000,
                                          true_count - 1,
                                          1,
                                          0};
  for (const std::int64_t lie : lies) {
    for (const bool solid : {false, true}) {
      SCOPED_TRACE("count " + std::to_string(lie) + (solid ? ", header 'solid'" : ""));
      const fs::path path = dir / ("lie_" + std::to_string(lie) + (solid ? "_solid" : "") + ".stl");
      write_file(path, binary_stl(cube, solid ? "solid exported" : "", lie));
      expect_refused(path);
    }
  }
}

// ---- OBJ indices out of range ----

TEST(BadMeshFile, ObjIndicesOutOfRange) {
  // Complements tests/mesh/load_test.cpp (99, -9, 0): the first index past the end, indices beyond
  // 32 and 64 bits, relative indices before the first vertex, faces before any vertex, and
  // out-of-range texture-coordinate and normal indices (refused, or ignored since antcd drops
  // those attributes, but never read out of bounds).
  const auto dir = fresh_temp_dir("obj_indices");
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"past_end", tri + "f 1 2 4\n"},
      {"u32_wrap", tri + "f 1 2 4294967297\n"},
      {"u64", tri + "f 1 2 99999999999999999999999\n"},
      {"relative_before_first", tri + "f -1 -2 -4\n"},
      {"face_first", "f 1 2 3\n" + std::string("v 0 0 0\n")},
      {"second_object", tri + "o A\nf 1 2 3\no B\nf 1 2 7\n"},
  };
  for (const auto& [name, text] : refused) {
    SCOPED_TRACE(name);
    write_file(dir / (name + ".obj"), text);
    expect_refused(dir / (name + ".obj"));
  }
  const std::vector<std::pair<std::string, std::string>> attributes = {
      {"texcoord", tri + "vt 0 0\nf 1/1 2/5 3/9\n"},
      {"normal", tri + "vn 0 0 1\nf 1//1 2//7 3//99\n"},
      {"negative_texcoord", tri + "vt 0 0\nf 1/-5 2/-6 3/-7\n"},
  };
  for (const auto& [name, text] : attributes) {
    SCOPED_TRACE(name);
    write_file(dir / (name + ".obj"), text);
    (void)load_and_build(dir / (name + ".obj"));
  }
}

// ---- NaN / Inf coordinates ----

TEST(BadMeshFile, NonFiniteCoordinatesInEveryFormat) {
  const auto dir = fresh_temp_dir("non_finite");
  const std::vector<std::pair<std::string, std::string>> files = {
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n"},
      {"minus_inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"},
      // OBJ is read in double precision: 1e39 is finite there, 1e999 is not.
      {"double_overflow.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"nan.stl",
       "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\n"
       "endloop\nendfacet\nendsolid s\n"},
      {"inf.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
       "float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 "
       "0\n0 inf 0\n3 0 1 2\n"},
      // assimp's OFF reader reads "nan" as 0, but an overflowing number as infinity. OFF keeps
      // double precision too: 1e39 is finite there, 1e999 is not.
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 0 1e999\n3 0 1 2\n"},
  };
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    write_file(dir / name, text);
    expect_refused(dir / name, "non-finite coordinate");
  }
  // Binary STL with NaN and infinity bit patterns.
  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
        -std::numeric_limits<float>::infinity()}) {
    Mesh tri;
    tri.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    tri.triangles = {{0, 1, 2}};
    std::string data = binary_stl(tri);
    std::memcpy(&data[84 + 12 + 4], &bad, 4);  // first corner's y
    const fs::path path = dir / (std::string(std::isnan(bad) ? "nan"
                                             : bad > 0       ? "inf"
                                                             : "ninf") +
                                 "_binary.stl");
    write_file(path, data);
    expect_refused(path, "non-finite coordinate");
  }
}

TEST(BadMeshFile, NonFiniteInMemoryMeshIsRefusedByModel) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::numeric_limits<Scalar>::infinity(), 0)};
  m.triangles = {{0, 1, 2}};
  try {
    const Model model(m, {}, "in-memory");
    ADD_FAILURE() << "expected a MeshError";
  } catch (const MeshError& e) {
    expect_names(e.what(), "in-memory");
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
}

// ---- only degenerate triangles ----

TEST(BadMeshFile, CoordinateMagnitudeLimits) {
  // docs/guarantees.md promises 1e-75 .. 1e75; beyond the zero-area test's range a model of only
  // such triangles is refused with a clear message (never accepted with wrong areas).
  const struct {
    double scale;
    bool accepted;
  } table[] = {{1e-75, true}, {1e75, true}, {1, true}, {1e-90, false}, {1e100, false}};
  for (const auto& row : table) {
    Mesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(row.scale, 0, 0), Vec3(0, row.scale, 0),
                  Vec3(0, 0, row.scale)};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    try {
      const Model model(std::move(m));
      EXPECT_TRUE(row.accepted) << row.scale;
    } catch (const MeshError& e) {
      EXPECT_FALSE(row.accepted) << row.scale << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("non-zero area"), std::string::npos) << e.what();
    }
  }
}

TEST(BadMeshFile, OnlyDegenerateTriangles) {
  const auto dir = fresh_temp_dir("degenerate");
  // Collinear corners, a repeated corner, a point, and a binary STL of zeroed facets (a common
  // output of broken exporters).
  write_file(dir / "collinear.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n");
  expect_refused(dir / "collinear.obj", "has no triangle of non-zero area");
  write_file(dir / "sliver.obj", "v 0 0 0\nv 1 0 0\nv 2 1e-15 0\nf 1 2 3\n");
  expect_refused(dir / "sliver.obj", "has no triangle of non-zero area");
  Mesh zeros;
  zeros.vertices = {Vec3::Zero()};
  zeros.triangles = {{0, 0, 0}, {0, 0, 0}};
  write_file(dir / "zeros.stl", binary_stl(zeros));
  expect_refused(dir / "zeros.stl");
  // One proper triangle among degenerate ones is enough; the others are counted and left out.
  write_file(dir / "mixed.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
  const Model model(load_mesh(dir / "mixed.obj"));
  EXPECT_EQ(model.stats().degenerate_triangles, 1u);
}

// ---- empty files, directories, special files ----

TEST(BadMeshFile, EmptyAndBlankFiles) {
  const auto dir = fresh_temp_dir("empty_files");
  for (const std::string ext : {"", ".obj", ".stl", ".ply", ".off", ".glb", ".gltf", ".dae"}) {
    write_file(dir / ("empty" + ext), "");
    expect_refused(dir / ("empty" + ext), "the file is empty");
    write_file(dir / ("blank" + ext), "  \n\n\t\r\n");
    expect_refused(dir / ("blank" + ext));
  }
}

TEST(BadMeshFile, DirectoryWhereAFileIsExpected) {
  const auto dir = fresh_temp_dir("directory_as_file");
  fs::create_directories(dir / "mesh.obj");
  fs::create_directories(dir / "scene.json" / "inside");
  expect_refused(dir / "mesh.obj", "is a directory");
  try {
    (void)load_scene(dir / "scene.json");
    ADD_FAILURE() << "expected a SceneError";
  } catch (const SceneError& e) {
    expect_names(e.what(), (dir / "scene.json").string());
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  try {
    (void)read_file(dir / "mesh.obj");
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    expect_names(e.what(), (dir / "mesh.obj").string());
  }
  // Writing over a directory fails and leaves the directory and nothing else.
  const auto before = listing(dir);
  EXPECT_THROW(write_file_atomic(dir / "scene.json", "{}"), Error);
  EXPECT_EQ(listing(dir), before);
}

TEST(BadMeshFile, SpecialFilesDoNotBlock) {
  // A FIFO without a writer would block a reader forever; a device never ends.
  const auto dir = fresh_temp_dir("special_files");
  ASSERT_EQ(::mkfifo((dir / "pipe.obj").c_str(), 0600), 0) << std::strerror(errno);
  expect_refused(dir / "pipe.obj", "is not a regular file");
  if (fs::exists("/dev/zero")) expect_refused("/dev/zero", "is not a regular file");
  if (fs::exists("/dev/null")) expect_refused("/dev/null", "is not a regular file");
}

TEST(BadMeshFile, MissingFileAndBrokenLink) {
  const auto dir = fresh_temp_dir("missing_file");
  expect_refused(dir / "absent.obj", "no such file");
  fs::create_symlink(dir / "absent.obj", dir / "dangling.obj");
  expect_refused(dir / "dangling.obj", "no such file");
}

// ---- scene files: schema errors not covered by tests/scene/scene_file_test.cpp ----

#define OBJECT(fields) R"({ "name": "a", "mesh": "m.obj", )" fields " }"
#define SCENE_WITH(object) \
  R"({ "format": "antcd-scene/1", "frames": 2, "objects": [ )" object " ] }"

TEST(BadSceneFile, TopLevelErrors) {
  expect_scene_error("", "not valid JSON");
  expect_scene_error("  \n\t ", "not valid JSON");
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1, "objects": [] } trailing)",
                     "not valid JSON");
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1, "objects": [)", "not valid JSON");
  expect_scene_error("{ \"format\": \"antcd-scene/1\xff\" }", "not valid JSON");  // bad UTF-8
  expect_scene_error("\"antcd-scene/1\"", "the top level must be a JSON object");
  expect_scene_error("null", "the top level must be a JSON object");
  expect_scene_error(R"({ "format": 1, "frames": 1, "objects": [] })", "unknown format 1");
  expect_scene_error(R"({ "format": null, "frames": 1, "objects": [] })", "unknown format");
  expect_scene_error(R"({ "format": ["antcd-scene/1"], "frames": 1, "objects": [] })",
                     "unknown format");
}

TEST(BadSceneFile, FramesErrors) {
  for (const char* frames : {"-1", "10000001", "\"3\"", "true", "null", "[2]", "1e3",
                             "18446744073709551615", "99999999999999999999999"}) {
    SCOPED_TRACE(frames);
    const std::string text = std::string(R"({ "format": "antcd-scene/1", "frames": )") + frames +
                             R"(, "objects": [ )" + OBJECT(R"("poses": [ {} ])") + " ] }";
    expect_scene_error(text, "'frames' must be an integer from 1 to 10000000");
  }
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1e999, "objects": [] })",
                     "not valid JSON");
}

TEST(BadSceneFile, ObjectErrors) {
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1, "objects": { "a": 1 } })",
                     "missing 'objects' array");
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1, "objects": [ 1 ] })",
                     "object 0: must be a JSON object");
  expect_scene_error(R"({ "format": "antcd-scene/1", "frames": 1, "objects": [ null ] })",
                     "object 0: must be a JSON object");
  expect_scene_error(SCENE_WITH(R"({ "name": "", "mesh": "m.obj", "poses": [ {} ] })"),
                     "object 0: missing or empty 'name'");
  expect_scene_error(SCENE_WITH(R"({ "name": 7, "mesh": "m.obj", "poses": [ {} ] })"),
                     "object 0: missing or empty 'name'");
  expect_scene_error(SCENE_WITH(R"({ "name": "a", "mesh": "", "poses": [ {} ] })"),
                     "object 'a': missing or empty 'mesh'");
  expect_scene_error(SCENE_WITH(R"({ "name": "a", "mesh": ["m.obj"], "poses": [ {} ] })"),
                     "object 'a': missing or empty 'mesh'");
  // A NUL in the path would open another file ("m.obj").
  expect_scene_error(SCENE_WITH(R"({ "name": "a", "mesh": "m.obj\u0000x", "poses": [ {} ] })"),
                     "object 'a': 'mesh' holds a NUL byte");
  // The second object is checked as carefully as the first.
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ {} ])") R"(, { "name": "b" })"),
                     "object 'b': missing or empty 'mesh'");
}

TEST(BadSceneFile, ScaleErrors) {
  expect_scene_error(SCENE_WITH(OBJECT(R"("scale": 0, "poses": [ {} ])")),
                     "object 'a': 'scale' must be > 0");
  expect_scene_error(SCENE_WITH(OBJECT(R"("scale": -0.0, "poses": [ {} ])")),
                     "object 'a': 'scale' must be > 0");
  expect_scene_error(SCENE_WITH(OBJECT(R"("scale": "2", "poses": [ {} ])")),
                     "object 'a': 'scale' must be a number");
  expect_scene_error(SCENE_WITH(OBJECT(R"("scale": null, "poses": [ {} ])")),
                     "object 'a': 'scale' must be a number");
  expect_scene_error(SCENE_WITH(OBJECT(R"("scale": 1e999, "poses": [ {} ])")), "not valid JSON");
}

TEST(BadSceneFile, PoseErrors) {
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": { "translation": [0, 0, 0] })")),
                     "object 'a': missing 'poses'");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ 1 ])")),
                     "object 'a': pose 0: a pose must be an object");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ {}, null ])")),
                     "object 'a': pose 1: a pose must be an object");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "translation": { "x": 1 } } ])")),
                     "'translation' must be an array of 3 numbers");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "translation": [0, 0, 0, 0] } ])")),
                     "'translation' must be an array of 3 numbers");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "translation": [0, null, 0] } ])")),
                     "'translation' must be a number");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "rotation_wxyz": [1, 0, 0] } ])")),
                     "'rotation_wxyz' must be an array of 4 numbers");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "rotation_wxyz": 1 } ])")),
                     "'rotation_wxyz' must be an array of 4 numbers");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ { "rotation_wxyz": [1, "0", 0, 0] } ])")),
                     "'rotation_wxyz' must be a number");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ {}, { "rotation_wxyz": [2, 0, 0, 0] } ])")),
                     "object 'a': pose 1: quaternion has length 2");
  expect_scene_error(
      SCENE_WITH(OBJECT(R"("poses": [ { "rotation_wxyz": [1e200, 1e200, 0, 0] } ])")),
      "quaternion has length");
}

TEST(BadSceneFile, DeepNestingIsRefusedAsItIsRead) {
  // Regression: a file of nested brackets overflowed the stack (json::dump() in a message), then
  // took gigabytes (a JSON value per level). Nesting deeper than 32 levels is refused while
  // parsing, wherever it is; 31 levels in an unknown field are only an unknown field.
  const std::string head = R"({ "format": "antcd-scene/1", "frames": 1, "objects": [ )";
  const std::string object = R"({ "name": "a", "mesh": "m.obj", )";
  for (const std::size_t depth : {std::size_t{33}, std::size_t{1'000'000}}) {
    const std::string nested = std::string(depth, '[') + std::string(depth, ']');
    expect_scene_error(R"({ "format": )" + nested + R"(, "frames": 1, "objects": [] })",
                       "nested deeper than 32 levels");
    expect_scene_error(head + object + R"("poses": [ {} ], "deep": )" + nested + " } ] }",
                       "nested deeper than 32 levels");
    expect_scene_error(head + object + R"("poses": [ { "translation": )" + nested + " } ] } ] }",
                       "nested deeper than 32 levels");
    expect_scene_error(head + std::string(depth, '['), "nested deeper than 32 levels");
  }
  expect_scene_error(head + object + R"("poses": [ {} ], "deep": )" + std::string(28, '[') +
                         std::string(28, ']') + " } ] }",
                     "object 'a': unknown field 'deep'");
}

TEST(BadSceneFile, LongFormatValueGivesAShortMessage) {
  const std::string text =
      R"({ "format": ")" + std::string(1'000'000, 'x') + R"(", "frames": 1, "objects": [] })";
  try {
    (void)parse_scene(text, "/base", "long.json");
    ADD_FAILURE() << "expected a SceneError";
  } catch (const SceneError& e) {
    expect_names(e.what(), "long.json");
    EXPECT_LT(std::string(e.what()).size(), 300u);
  }
}

TEST(BadSceneFile, ControlCharactersInNamesKeepTheMessageOnOneLine) {
  // Regression: a name holding a newline (valid JSON: "a\nb") broke the one-line message.
  expect_scene_error(SCENE_WITH(R"({ "name": "line\nbreak\r", "mesh": "", "poses": [ {} ] })"),
                     "missing or empty 'mesh'");
  expect_scene_error(SCENE_WITH(OBJECT(R"("poses": [ {} ], "bad\nkey": 1)")), "unknown field");
}

TEST(BadSceneFile, SceneWhoseMeshIsBad) {
  // The scene parses; building it fails on the mesh, with the object or the mesh file named.
  const auto dir = fresh_temp_dir("scene_bad_mesh");
  write_file(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  write_file(dir / "noise.stl", random_bytes(1000, 9));
  fs::create_directories(dir / "folder.obj");
  for (const std::string mesh : {"flat.obj", "noise.stl", "folder.obj", "absent.obj"}) {
    SCOPED_TRACE(mesh);
    const std::string text =
        R"({ "format": "antcd-scene/1", "frames": 1, "objects": [ { "name": "o",
        "mesh": ")" +
        mesh + R"(", "poses": [ {} ] } ] })";
    write_file(dir / "scene.json", text);
    try {
      const Scene scene(load_scene(dir / "scene.json"));
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      expect_names(e.what(), (dir / mesh).string(), false);
    }
  }
}

// ---- error lines: printable and bounded ----

TEST(PrintableLine, EscapesControlBytesAndCutsLongQuotes) {
  const std::string long_quote(5000, 'x');
  const struct {
    std::string in;
    std::string out;
  } table[] = {
      {"plain: message", "plain: message"},
      {"two\nlines\r\n", "two lines"},
      {"tab\there", "tab here"},
      {"ansi '\x1b[31mred\x1b[0m' bell\x07", "ansi '\\x1B[31mred\\x1B[0m' bell\\x07"},
      {std::string("nul ") + '\0' + "byte", "nul \\x00byte"},
      {"del \x7f", "del \\x7F"},
      {"utf-8 \xc3\xa9t\xc3\xa9 \xe2\x86\x92 kept", "utf-8 \xc3\xa9t\xc3\xa9 \xe2\x86\x92 kept"},
      {"binary \xff\xfe\xc3", "binary \\xFF\\xFE\\xC3"},
      {"C1 CSI \xc2\x9b"
       "2J",
       "C1 CSI \\xC2\\x9B2J"},
      {"overlong \xc0\xaf", "overlong \\xC0\\xAF"},
      {"f.csv:2: got '" + long_quote + "'", "f.csv:2: got '" + std::string(80, 'x') + "...'"},
      {"got '" + long_quote, "got '" + std::string(80, 'x') + "..."},
      {"can't open 'a.obj'", "can't open 'a.obj'"},
      {"(expected '" + long_quote + "') after",
       "(expected '" + std::string(80, 'x') + "...') after"},
  };
  for (const auto& row : table) EXPECT_EQ(printable_line(row.in), row.out) << row.in.substr(0, 40);
  // Unquoted text is bounded too, and so is any mix.
  const std::string noise = random_bytes(1 << 20, 5);
  for (const std::string& text : {std::string(1 << 20, 'y'), noise, "'" + noise}) {
    const std::string line = printable_line(text);
    EXPECT_LE(line.size(), kPrintableLineLength + 8);
    for (const char c : line) {
      const auto u = static_cast<unsigned char>(c);
      EXPECT_TRUE(u >= 0x20 && u != 0x7F) << "byte " << static_cast<int>(u);
    }
  }
}

// ---- the command-line tool ----

#ifdef ANTCD_CLI

using test::CliRun;

/// Runs `antcd args...` in `cwd` (stdin from /dev/null), killing it after `timeout_s`.
CliRun run_cli(const std::vector<std::string>& args, const fs::path& cwd, double timeout_s = 120) {
  return test::run_program(ANTCD_CLI, args, cwd, timeout_s);
}

std::string describe(const std::vector<std::string>& args) {
  std::string s = "antcd";
  for (const auto& a : args) s += " " + a;
  return s;
}

/// A working folder with a valid mesh, a degenerate one, a valid scene and an existing result.
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = fresh_temp_dir(std::string("cli_") + info->name());
    fs::remove_all(work_.parent_path() / (work_.filename().string() + "_io"));
    write_file(work_ / "tet.obj", kTetrahedronObj);
    write_file(work_ / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    write_file(work_ / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    write_file(work_ / "scene.json", R"({ "format": "antcd-scene/1", "frames": 2, "objects": [
      { "name": "a", "mesh": "tet.obj", "poses": [ {} ] },
      { "name": "b", "mesh": "tet.obj", "poses": [ { "translation": [0.5, 0, 0] },
                                                   { "translation": [5, 0, 0] } ] } ] })");
    write_file(work_ / "result.json", kPrevious);
    fs::create_directories(work_ / "folder.obj");
    fs::create_directories(work_ / "out");
  }

  /// Runs antcd with `args` in the working folder and checks the failure contract: exit code 2,
  /// exactly one stderr line "error: ..." holding `named`, nothing on stdout, the folder unchanged
  /// (no output, no temporary file) and result.json still holding the previous result.
  void expect_usage_failure(const std::vector<std::string>& args, const std::string& named) {
    SCOPED_TRACE(describe(args));
    const auto before = listing(work_);
    const CliRun r = run_cli(args, work_);
    test::expect_clean_refusal(r, named);
    EXPECT_EQ(listing(work_), before);
    EXPECT_EQ(read_all(work_ / "result.json"), kPrevious);
  }

  static constexpr const char* kPrevious = "{ \"previous\": \"result\" }\n";
  fs::path work_;
};

TEST_F(Cli, PointsBadInputs) {
  write_file(work_ / "points.csv", "x,y,z\n0.1,0.1,0.1\n5,5,5\n");
  write_file(work_ / "short.csv", "0,0,0\n1,2\n");
  write_file(work_ / "nan.csv", "0,0,0\nnan,0,0\n");
  write_file(work_ / "empty.csv", "# nothing\n");
  const CliRun ok = run_cli({"points", "tet.obj", "points.csv"}, work_);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(std::count(ok.out.begin(), ok.out.end(), '\n'), 3) << ok.out;  // header + 2 points
  const CliRun random = run_cli({"points", "tet.obj", "--random", "7", "--json"}, work_);
  EXPECT_EQ(random.exit_code, 0) << random.err;
  expect_usage_failure({"points", "tet.obj", "short.csv"}, "short.csv:2");
  expect_usage_failure({"points", "tet.obj", "nan.csv"}, "nan.csv:2");
  expect_usage_failure({"points", "tet.obj", "empty.csv"}, "empty.csv");
  expect_usage_failure({"points", "tet.obj", "missing.csv"}, "missing.csv");
  expect_usage_failure({"points", "tet.obj"}, "--random");
  expect_usage_failure({"points", "tet.obj", "points.csv", "--random", "3"}, "--random");
  expect_usage_failure({"points", "tet.obj", "--random", "3", "--pose", "1,2"}, "--pose");
  expect_usage_failure({"points", "nan.obj", "--random", "3"}, "nan.obj");
}

TEST_F(Cli, HostilePointsFiles) {
  write_file(work_ / "ansi.csv", "0,0,0\n\x1b[31mred\x07,1,2\n");
  write_file(work_ / "huge_line.csv", std::string(2'000'000, 'a'));
  write_file(work_ / "spaces.csv", "0,0,0\n1,2,3" + std::string(5000, ' ') + "\n");
  write_file(work_ / "nul.csv", std::string("0,0,0\n1,2,3\0junk\n", 17));
  write_file(work_ / "binary.csv", random_bytes(100'000, 11));
  ASSERT_EQ(::mkfifo((work_ / "fifo.csv").c_str(), 0600), 0) << std::strerror(errno);
  expect_usage_failure({"points", "tet.obj", "ansi.csv"}, "ansi.csv:2");
  expect_usage_failure({"points", "tet.obj", "huge_line.csv"}, "huge_line.csv:1: line longer");
  expect_usage_failure({"points", "tet.obj", "spaces.csv"}, "spaces.csv:2: line longer");
  expect_usage_failure({"points", "tet.obj", "nul.csv"}, "nul.csv:2");
  expect_usage_failure({"points", "tet.obj", "binary.csv"}, "binary.csv");
  expect_usage_failure({"points", "tet.obj", "fifo.csv"},
                       "fifo.csv: cannot open the points file: is not a regular file");
  expect_usage_failure({"points", "tet.obj", "/dev/zero"},
                       "/dev/zero: cannot open the points file: is not a regular file");
}

TEST_F(Cli, ThirdPartyMessagesStayOffStderr) {
  // assimp's OpenDDL parser writes "nullptr returned by creating DDLNode." to std::cerr itself.
  const fs::path ogex = test::assimp_model("OpenGEX/empty_camera.ogex");
  fs::copy_file(ogex, work_ / "camera.ogex");
  write_file(work_ / "camera.json", R"({ "format": "antcd-scene/1", "frames": 1, "objects": [
      { "name": "a", "mesh": "camera.ogex", "poses": [ {} ] } ] })");
  expect_usage_failure({"info", "camera.ogex"}, "camera.ogex");
  expect_usage_failure({"collide", "tet.obj", "camera.ogex"}, "camera.ogex");
  expect_usage_failure({"run", "camera.json", "--out", "result.json"}, "camera.ogex");
}

TEST_F(Cli, OutOfRangeIntegers) {
  // CLI11 alone reads "-1" as 2^64 - 1 and saturates overflowing values: each must be refused.
  const std::vector<std::pair<std::vector<std::string>, std::string>> table = {
      {{"points", "tet.obj", "--random", "3", "--seed", "-1"}, "--seed"},
      {{"points", "tet.obj", "--random", "3", "--seed", "18446744073709551616"}, "--seed"},
      {{"points", "tet.obj", "--random", "3", "--seed", "1e3"}, "--seed"},
      {{"run", "scene.json", "--seed", "99999999999999999999999", "--out", "result.json"},
       "--seed"},
      {{"run", "scene.json", "--method", "maco", "--frame-evaluations", "-1"},
       "--frame-evaluations"},
      {{"scene", "generate", "--out", "generated", "--seed", "0x10"}, "--seed"},
      {{"demo", "--seed", "-7"}, "--seed"},
  };
  for (const auto& [args, named] : table) expect_usage_failure(args, named);
  const CliRun largest =
      run_cli({"points", "tet.obj", "--random", "3", "--seed", "18446744073709551615"}, work_);
  EXPECT_EQ(largest.exit_code, 0) << largest.err;
}

TEST_F(Cli, ValidInputsSucceed) {
  // The fixture's inputs are good: each failure below is due to the one bad value.
  const CliRun info = run_cli({"info", "tet.obj"}, work_);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  const CliRun collide = run_cli({"collide", "tet.obj", "tet.obj", "--delta", "0.1"}, work_);
  EXPECT_EQ(collide.exit_code, 0) << collide.err;
  const CliRun run = run_cli({"run", "scene.json", "--out", "out/run.json"}, work_);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(work_ / "out" / "run.json"));
  EXPECT_EQ(listing(work_ / "out"), std::set<std::string>{"run.json"});
}

TEST_F(Cli, NegativeDelta) {
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--delta", "-1"}, "--delta");
  expect_usage_failure({"run", "scene.json", "--delta", "-0.5", "--out", "result.json"}, "--delta");
  expect_usage_failure({"run", "scene.json", "--feature-delta", "-2", "--out", "out/r.json"},
                       "--feature-delta");
}

TEST_F(Cli, NonNumericAndNonFiniteValues) {
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--delta", "abc"}, "--delta");
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--delta", "nan"}, "--delta");
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--pose-a", "1,2"}, "--pose-a");
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--pose-b", "0,0,inf"}, "--pose-b");
  expect_usage_failure({"collide", "tet.obj", "tet.obj", "--pose-b", "0,0,0,2,0,0,0"}, "--pose-b");
}

TEST_F(Cli, ZeroAnts) {
  expect_usage_failure(
      {"run", "scene.json", "--method", "maco", "--ants", "0", "--out", "result.json"}, "--ants");
  expect_usage_failure({"run", "scene.json", "--method", "aco", "--iterations", "0"},
                       "--iterations");
  expect_usage_failure({"run", "scene.json", "--samples", "0"}, "--samples");
  expect_usage_failure({"run", "scene.json", "--threads", "0"}, "--threads");
  expect_usage_failure({"info", "tet.obj", "--leaf-size", "0"}, "--leaf-size");
}

TEST_F(Cli, ZeroFrames) {
  expect_usage_failure({"scene", "generate", "--out", "generated", "--frames", "0"}, "--frames");
  expect_usage_failure({"demo", "--frames", "0"}, "--frames");
  expect_usage_failure({"scene", "generate", "--out", "generated", "--objects", "1"}, "--objects");
}

TEST_F(Cli, UnknownMethod) {
  expect_usage_failure({"run", "scene.json", "--method", "telepathy", "--out", "result.json"},
                       "--method");
  expect_usage_failure({"info", "tet.obj", "--covariance", "median"}, "--covariance");
  expect_usage_failure({"run", "scene.json", "--method", "maco", "--verdict", "centroid"},
                       "--verdict");
  expect_usage_failure({"run", "scene.json", "--method", "maco", "--frame-seconds", "-1"},
                       "--frame-seconds");
  expect_usage_failure({"run", "scene.json", "--method", "exact", "--colony-only"},
                       "--colony-only");
}

TEST_F(Cli, UnknownCommandOrOption) {
  expect_usage_failure({"frobnicate"}, "frobnicate");
  expect_usage_failure({"info", "tet.obj", "--colour"}, "--colour");
  expect_usage_failure({}, "subcommand");
}

TEST_F(Cli, MissingFile) {
  expect_usage_failure({"info", "absent.obj"}, "absent.obj");
  expect_usage_failure({"collide", "tet.obj", "absent.stl"}, "absent.stl");
  expect_usage_failure({"run", "absent.json", "--out", "result.json"}, "absent.json");
  expect_usage_failure({"compare", "absent.json", "result.json"}, "absent.json");
  expect_usage_failure({"scene", "generate", "--out", "generated", "--mesh", "absent.obj"},
                       "absent.obj");
}

TEST_F(Cli, DirectoryAsMesh) {
  expect_usage_failure({"info", "folder.obj"}, "folder.obj");
  expect_usage_failure({"collide", "folder.obj", "tet.obj"}, "folder.obj");
  expect_usage_failure({"run", "out", "--out", "result.json"}, "out");
}

TEST_F(Cli, BadMesh) {
  expect_usage_failure({"info", "flat.obj"}, "flat.obj");
  expect_usage_failure({"info", "nan.obj"}, "nan.obj");
  expect_usage_failure({"collide", "tet.obj", "flat.obj"}, "flat.obj");
  write_file(work_ / "noise.stl", random_bytes(2000, 3));
  expect_usage_failure({"info", "noise.stl"}, "noise.stl");
  // A mesh that is bad for the generator: refused before anything is written.
  expect_usage_failure({"scene", "generate", "--out", "generated", "--mesh", "flat.obj"},
                       "flat.obj");
}

TEST_F(Cli, BadScene) {
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"not_json.json", "{ nope"},
      {"schema.json", R"({ "format": "antcd-scene/1", "frames": 0, "objects": [] })"},
      {"missing_mesh.json", R"({ "format": "antcd-scene/1", "frames": 1, "objects": [
        { "name": "a", "mesh": "absent.obj", "poses": [ {} ] } ] })"},
      {"flat_mesh.json", R"({ "format": "antcd-scene/1", "frames": 1, "objects": [
        { "name": "a", "mesh": "flat.obj", "poses": [ {} ] } ] })"},
      {"deep.json", R"({ "format": )" + std::string(500'000, '[') + std::string(500'000, ']') +
                        R"(, "frames": 1, "objects": [] })"},
  };
  for (const auto& [name, text] : scenes) write_file(work_ / name, text);
  for (const auto& [name, text] : scenes) {
    // A failed run keeps the previous result, writes no new one and leaves no temporary file.
    expect_usage_failure({"run", name, "--out", "result.json"},
                         name == "missing_mesh.json" ? "absent.obj"
                         : name == "flat_mesh.json"  ? "flat.obj"
                                                     : name);
    expect_usage_failure({"run", name, "--out", "out/new.json"},
                         name == "missing_mesh.json" ? "absent.obj"
                         : name == "flat_mesh.json"  ? "flat.obj"
                                                     : name);
  }
  expect_usage_failure({"compare", "not_json.json", "result.json"}, "not_json.json");
}

TEST_F(Cli, UnwritableOutput) {
  // The run succeeds but its result cannot be written: exit 2, the path named, nothing left.
  expect_usage_failure({"run", "scene.json", "--out", "absent_dir/r.json"}, "absent_dir/r.json");
  fs::create_directories(work_ / "taken.json" / "inside");
  expect_usage_failure({"run", "scene.json", "--out", "taken.json"}, "taken.json");
  EXPECT_TRUE(fs::is_directory(work_ / "taken.json" / "inside"));
  // A scene folder that is a file.
  expect_usage_failure({"scene", "generate", "--out", "tet.obj", "--objects", "2", "--frames", "2"},
                       "tet.obj");
  EXPECT_EQ(read_all(work_ / "tet.obj"), kTetrahedronObj);
}

#else

TEST(Cli, NotBuilt) { GTEST_SKIP() << "the antcd command-line tool is not part of this build"; }

#endif

}  // namespace
}  // namespace antcd
