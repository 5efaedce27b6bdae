// Tests of load_mesh, validate_mesh, save_obj and the Mesh helpers.
//
// Reference values for the assimp-testmodels files were established as follows:
// - OBJ/box.obj, OFF/Cube.off: 8 corners listed in the file at ±0.5, six quad faces -> 12
//   triangles, 8 vertices, bounds [-0.5, 0.5]³.
// - PLY/cube.ply: 8 corners in {0, 1}³, six quads -> 12 triangles, bounds [0, 1]³.
// - STL/Spider_binary.stl: 68484 bytes = 84 + 50 · 1368, and the header count is 1368;
//   STL/Spider_ascii.stl holds 1368 "facet normal" records: both give 1368 triangles. Joining
//   identical positions leaves 722 vertices in both (the same count as OBJ/spider.obj, the same
//   model at another scale). Their bounds agree up to the ASCII file's printed precision.
// - glTF2 BoxTextured: 24 vertices (4 per face, for the per-face normals and texture coordinates)
//   at ±0.5 and 36 indices -> 12 triangles, 8 distinct positions. The root node's matrix is a
//   rotation by -90° about x, which maps the cube onto itself: bounds [-0.5, 0.5]³.
// - PLY/Wuson.ply and OFF/Wuson.off are the same model: 3732 triangles on 2117 positions.
#include "support/mesh_files.hpp"
#include "support/test_support.hpp"

#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace antcd {
namespace {

using test::append_f32;
using test::append_stl_facet;
using test::append_u32;
using test::ascii_stl;
using test::assimp_model;
using test::binary_stl;
using test::fresh_temp_dir;
using test::write_file;

// ---- helpers ----

/// Expects `f` to throw a MeshError whose message names `path` and contains `problem`, is one
/// line, and whose source() is the path.
template <class F>
void expect_mesh_error(F&& f, const std::filesystem::path& path, const std::string& problem) {
  try {
    f();
    ADD_FAILURE() << "expected a MeshError for " << path;
  } catch (const MeshError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.source(), path.string());
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.find('\r'), std::string::npos) << what;
  }
}

void expect_load_error(const std::filesystem::path& path, const std::string& problem) {
  expect_mesh_error([&] { (void)load_mesh(path); }, path, problem);
}

Scalar signed_volume(const Mesh& m) {
  Scalar six_v = 0;
  for (const auto& t : m.triangles) {
    six_v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
  }
  return six_v / 6;
}

void expect_bounds(const Mesh& m, const Vec3& lo, const Vec3& hi, Scalar tol = 0) {
  const Aabb b = m.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], lo[k], tol) << "axis " << k;
    EXPECT_NEAR(b.max[k], hi[k], tol) << "axis " << k;
  }
}

/// The positions of every triangle's corners, in triangle order: equal for two meshes exactly
/// when they describe the same triangles, whatever the vertex numbering.
std::vector<std::array<Vec3, 3>> corner_positions(const Mesh& m) {
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& t : m.triangles)
    out.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  return out;
}

/// x rounded to the nearest float. Through a volatile: GCC 12 at -O2 (SLP vectorizer) was seen
/// to drop a plain `v[k] = static_cast<float>(v[k])` round trip on Eigen vectors.
Scalar to_float_value(Scalar x) {
  volatile float f = static_cast<float>(x);
  return f;
}

std::size_t count_entries(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                std::filesystem::directory_iterator()));
}

// ---- real files from assimp-testmodels ----

TEST(LoadMesh, ObjBox) {
  const Mesh m = load_mesh(assimp_model("OBJ/box.obj"));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  expect_bounds(m, Vec3::Constant(-0.5), Vec3::Constant(0.5));
  EXPECT_EQ(m.degenerate_triangle_count(), 0u);
  // A closed unit cube: |signed volume| = 1 (box.obj's faces are wound inward, so the sign is not
  // asserted; antcd keeps the file's winding).
  EXPECT_NEAR(std::abs(signed_volume(m)), 1.0, 1e-12);
}

TEST(LoadMesh, ObjSpider) {
  const Mesh m = load_mesh(assimp_model("OBJ/spider.obj"));
  EXPECT_EQ(m.triangles.size(), 1368u);
  EXPECT_EQ(m.vertices.size(), 722u);
  validate_mesh(m, "spider");
}

TEST(LoadMesh, StlAsciiAndBinarySpiderAgree) {
  const Mesh ascii = load_mesh(assimp_model("STL/Spider_ascii.stl"));
  const Mesh binary = load_mesh(assimp_model("STL/Spider_binary.stl"));
  EXPECT_EQ(ascii.triangles.size(), 1368u);
  EXPECT_EQ(binary.triangles.size(), 1368u);
  EXPECT_EQ(ascii.vertices.size(), 722u);
  EXPECT_EQ(binary.vertices.size(), 722u);
  // Same model: bounds agree to the ASCII file's printed precision.
  const Aabb a = ascii.bounds();
  const Aabb b = binary.bounds();
  EXPECT_LT((a.min - b.min).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_LT((a.max - b.max).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NEAR(b.min.y(), -4.0, 1e-6);
  EXPECT_NEAR(b.max.y(), 4.0, 1e-6);
}

TEST(LoadMesh, PlyCube) {
  const Mesh m = load_mesh(assimp_model("PLY/cube.ply"));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  expect_bounds(m, Vec3::Zero(), Vec3::Ones());
  EXPECT_NEAR(std::abs(signed_volume(m)), 1.0, 1e-12);
}

TEST(LoadMesh, OffCube) {
  const Mesh m = load_mesh(assimp_model("OFF/Cube.off"));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  expect_bounds(m, Vec3::Constant(-0.5), Vec3::Constant(0.5));
  EXPECT_NEAR(std::abs(signed_volume(m)), 1.0, 1e-12);
}

TEST(LoadMesh, WusonPlyAndOffAgree) {
  const Mesh ply = load_mesh(assimp_model("PLY/Wuson.ply"));
  const Mesh off = load_mesh(assimp_model("OFF/Wuson.off"));
  EXPECT_EQ(ply.triangles.size(), 3732u);
  EXPECT_EQ(off.triangles.size(), 3732u);
  EXPECT_EQ(ply.vertices.size(), 2117u);
  EXPECT_EQ(off.vertices.size(), 2117u);
  EXPECT_LT((ply.bounds().min - off.bounds().min).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((ply.bounds().max - off.bounds().max).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(LoadMesh, Gltf2TextBoxJoinsPerFaceVertices) {
  const Mesh m = load_mesh(assimp_model("glTF2/BoxTextured-glTF/BoxTextured.gltf"));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);  // 24 in the file, differing only in normal and UV
  expect_bounds(m, Vec3::Constant(-0.5), Vec3::Constant(0.5), 1e-7);
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-6);  // glTF winding is counter-clockwise: outward
}

TEST(LoadMesh, Gltf2BinaryBox) {
  const Mesh m = load_mesh(assimp_model("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  expect_bounds(m, Vec3::Constant(-0.5), Vec3::Constant(0.5), 1e-7);
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-6);
}

TEST(LoadMesh, Gltf2WithInfiniteCoordinatesIsRejected) {
  expect_load_error(assimp_model("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"),
                    "has a non-finite coordinate");
}

// ---- files written by the tests ----

TEST(LoadMesh, QuadIsTriangulated) {
  const auto dir = fresh_temp_dir("load_quad");
  write_file(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const Mesh m = load_mesh(dir / "quad.obj");
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 4u);
  // Both halves keep the quad's counter-clockwise winding (+z normal) and cover it: area 1.
  Scalar area = 0;
  for (const auto& t : m.triangles) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_GT(n.z(), 0);
    area += n.norm() / 2;
  }
  EXPECT_DOUBLE_EQ(area, 1.0);
}

TEST(LoadMesh, BinaryStlCubeJoinsCorners) {
  const auto dir = fresh_temp_dir("load_stl_cube");
  const Mesh cube = make_box(Vec3(1, 2, 3));
  write_file(dir / "cube.stl", binary_stl(cube));
  const Mesh m = load_mesh(dir / "cube.stl");
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);  // 36 corners in the file, 8 positions
  expect_bounds(m, Vec3(-1, -2, -3), Vec3(1, 2, 3));
  EXPECT_DOUBLE_EQ(signed_volume(m), 48.0);  // winding kept: outward
  EXPECT_EQ(corner_positions(m), corner_positions(cube));
}

TEST(LoadMesh, BinaryStlNativeReaderKeepsFileOrderAndJoinsOnlyEqualPositions) {
  // Binary STL is read without assimp (src/io/stl_binary.cpp): vertices numbered in order of
  // first use, corners in file order, -0 and +0 joined, positions 1e-6 apart kept apart (assimp
  // joined corners closer than 1e-5), a facet with two equal corners kept (zero area), and a
  // header starting with "solid" still read as binary when the size says so.
  const auto dir = fresh_temp_dir("load_stl_native");
  std::string data(80, '\0');
  const std::string solid = "solid but binary";
  data.replace(0, solid.size(), solid);
  append_u32(data, 4);
  append_stl_facet(data, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  append_stl_facet(data, {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
  append_stl_facet(data, {Vec3(-0.0, 1, 0), Vec3(1, 1, 0), Vec3(1, 1, 1e-6)});
  append_stl_facet(data, {Vec3(2, 2, 2), Vec3(2, 2, 2), Vec3(3, 2, 2)});
  write_file(dir / "mixed.STL", data);
  const Mesh m = load_mesh(dir / "mixed.STL");
  ASSERT_EQ(m.vertices.size(), 7u);
  const std::vector<Vec3> expected = {Vec3(0, 0, 0),
                                      Vec3(1, 0, 0),
                                      Vec3(0, 1, 0),
                                      Vec3(1, 1, 0),
                                      Vec3(1, 1, static_cast<float>(1e-6)),
                                      Vec3(2, 2, 2),
                                      Vec3(3, 2, 2)};
  EXPECT_EQ(m.vertices, expected);
  const std::vector<TriangleIndices> triangles = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {5, 5, 6}};
  EXPECT_EQ(m.triangles, triangles);
  EXPECT_EQ(m.degenerate_triangle_count(), 1u);
}

TEST(LoadMesh, BinaryStlTestModelsKeepTheirCounts) {
  // The counts assimp's reader gave for the packaged binary STL files (same meshes, checked bit
  // for bit when the native reader replaced it).
  struct Expected {
    const char* file;
    std::size_t vertices;
    std::size_t triangles;
  };
  for (const Expected& e :
       {Expected{"STL/Wuson.stl", 2117, 3732}, Expected{"STL/3DSMaxExport.STL", 1042, 2000},
        Expected{"STL/Spider_binary.stl", 722, 1368}}) {
    SCOPED_TRACE(e.file);
    const Mesh m = load_mesh(assimp_model(e.file));
    EXPECT_EQ(m.vertices.size(), e.vertices);
    EXPECT_EQ(m.triangles.size(), e.triangles);
  }
}

TEST(LoadMesh, AsciiStlCubeJoinsCorners) {
  const auto dir = fresh_temp_dir("load_ascii_stl_cube");
  const Mesh cube = make_box(Vec3(0.5, 0.25, 2));
  write_file(dir / "cube.stl", ascii_stl(cube));
  const Mesh m = load_mesh(dir / "cube.stl");
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  expect_bounds(m, Vec3(-0.5, -0.25, -2), Vec3(0.5, 0.25, 2));
  EXPECT_DOUBLE_EQ(signed_volume(m), 2.0);
}

TEST(LoadMesh, VerticesSharedBetweenObjectsAreJoined) {
  // Two OBJ objects become two assimp meshes; the two positions they share are joined.
  const auto dir = fresh_temp_dir("load_two_objects");
  write_file(dir / "two.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no A\nf 1 2 3\no B\nf 1 3 4\n");
  const Mesh m = load_mesh(dir / "two.obj");
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 4u);
}

TEST(LoadMesh, NodeTransformsAreApplied) {
  // glTF scene: one triangle (0,0,0) (1,0,0) (0,1,0) placed twice: by node 0 translated by
  // (10,0,0); by node 2, mirrored in x (scale -1,1,1), under node 1 translated by (0,0,5).
  const auto dir = fresh_temp_dir("load_nodes");
  std::string bin;
  for (const std::uint16_t i : {0, 1, 2}) bin.append(reinterpret_cast<const char*>(&i), 2);
  bin.append(2, '\0');  // align the positions to 4 bytes
  for (const float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append_f32(bin, x);
  ASSERT_EQ(bin.size(), 44u);
  write_file(dir / "tri.bin", bin);
  write_file(dir / "nodes.gltf", R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [
    {"mesh": 0, "translation": [10, 0, 0]},
    {"translation": [0, 0, 5], "children": [2]},
    {"mesh": 0, "scale": [-1, 1, 1]}
  ],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "mode": 4}]}],
  "buffers": [{"uri": "tri.bin", "byteLength": 44}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 6, "target": 34963},
    {"buffer": 0, "byteOffset": 8, "byteLength": 36, "target": 34962}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5123, "count": 3, "type": "SCALAR"},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]}
  ]
})");
  const Mesh m = load_mesh(dir / "nodes.gltf");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 6u);
  expect_bounds(m, Vec3(-1, 0, 0), Vec3(11, 1, 5));
  std::set<std::array<Scalar, 3>> positions;
  for (const Vec3& v : m.vertices) positions.insert({v.x(), v.y(), v.z()});
  const std::set<std::array<Scalar, 3>> expected{{10, 0, 0}, {11, 0, 0}, {10, 1, 0},
                                                 {0, 0, 5},  {-1, 0, 5}, {0, 1, 5}};
  EXPECT_EQ(positions, expected);
  // The mirrored copy's winding is restored: both triangles face +z like the original.
  for (const auto& t : m.triangles) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_GT(n.z(), 0);
  }
}

TEST(LoadMesh, LoadingPrintsNothing) {
  const auto dir = fresh_temp_dir("load_quiet");
  write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  (void)load_mesh(assimp_model("OBJ/spider.obj"));
  (void)load_mesh(assimp_model("glTF2/BoxTextured-glTF/BoxTextured.gltf"));
  EXPECT_THROW((void)load_mesh(dir / "bad.obj"), MeshError);
  EXPECT_THROW((void)load_mesh(assimp_model("invalid/malformed.obj")), MeshError);
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

TEST(LoadMesh, ConcurrentLoadsAgree) {
  // One file per reader: assimp (STL, OFF, PLY), tinyobjloader (OBJ).
  for (const char* name :
       {"STL/Spider_binary.stl", "OBJ/spider.obj", "OFF/Wuson.off", "PLY/Wuson.ply"}) {
    SCOPED_TRACE(name);
    const auto path = assimp_model(name);
    const Mesh reference = load_mesh(path);
    std::vector<Mesh> results(8);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < results.size(); ++i) {
      threads.emplace_back([&, i] {
        for (int round = 0; round < 3; ++round) results[i] = load_mesh(path);
      });
    }
    for (auto& t : threads) t.join();
    for (const Mesh& m : results) {
      EXPECT_EQ(m.vertices, reference.vertices);
      EXPECT_EQ(m.triangles, reference.triangles);
    }
  }
}

// ---- bad input: one test per problem ----

TEST(LoadMeshErrors, MissingFile) {
  const auto dir = fresh_temp_dir("err_missing");
  expect_load_error(dir / "nothing_here.obj", "no such file");
}

TEST(LoadMeshErrors, Directory) {
  const auto dir = fresh_temp_dir("err_directory");
  expect_load_error(dir, "is a directory");
}

TEST(LoadMeshErrors, EmptyFile) {
  const auto dir = fresh_temp_dir("err_empty");
  write_file(dir / "empty.stl", "");
  expect_load_error(dir / "empty.stl", "not a readable mesh: the file is empty");
}

TEST(LoadMeshErrors, PackagedEmptyObj) {
  expect_load_error(assimp_model("invalid/empty.obj"), "not a readable mesh");
}

TEST(LoadMeshErrors, TextGarbageWithUnknownExtension) {
  const auto dir = fresh_temp_dir("err_text");
  write_file(dir / "notes.txt", "hello world\nthis is not a mesh\n");
  expect_load_error(dir / "notes.txt", "not a readable mesh: No suitable reader found");
}

TEST(LoadMeshErrors, TextGarbageAsStl) {
  const auto dir = fresh_temp_dir("err_text_stl");
  write_file(dir / "notes.stl", "hello world\nthis is not a mesh\n");
  expect_load_error(dir / "notes.stl", "not a readable mesh");
}

TEST(LoadMeshErrors, TextGarbageAsObj) {
  // The OBJ reader skips lines it does not know, so nothing is left: no triangles.
  const auto dir = fresh_temp_dir("err_text_obj");
  write_file(dir / "notes.obj", "hello world\nthis is not a mesh\n");
  expect_load_error(dir / "notes.obj", "contains no triangles");
}

std::string random_bytes(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string out(n, '\0');
  for (char& c : out) c = static_cast<char>(rng() & 0xFF);
  return out;
}

TEST(LoadMeshErrors, RandomBytes) {
  const auto dir = fresh_temp_dir("err_random");
  const std::string noise = random_bytes(4096, 12345);
  for (const char* name : {"noise.bin", "noise.stl", "noise.ply", "noise.off", "noise.glb"}) {
    write_file(dir / name, noise);
    expect_load_error(dir / name, "not a readable mesh");
  }
  // As .obj, the bytes are read as lines of unknown keywords: a file without any face.
  write_file(dir / "noise.obj", noise);
  expect_load_error(dir / "noise.obj", "contains no triangles");
}

TEST(LoadMeshErrors, TruncatedBinaryStl) {
  // The header announces 1000 triangles but only 10 follow.
  const auto dir = fresh_temp_dir("err_truncated");
  std::string data = binary_stl(make_sphere(1, 8, 4));
  ASSERT_EQ(data.size(), 84u + 50u * 48u);
  const std::uint32_t lie = 1000;
  std::memcpy(&data[80], &lie, 4);
  data.resize(84 + 50 * 10);
  write_file(dir / "truncated.stl", data);
  expect_load_error(dir / "truncated.stl", "not a readable mesh");
}

TEST(LoadMeshErrors, TruncatedBinaryStlWithSolidHeader) {
  // Many exporters start the binary header with "solid"; assimp then tries the ASCII syntax,
  // finds no facet and reports no triangles.
  const auto dir = fresh_temp_dir("err_truncated_solid");
  std::string data = binary_stl(make_sphere(1, 8, 4), "solid exported by a CAD program");
  const std::uint32_t lie = 1000;
  std::memcpy(&data[80], &lie, 4);
  data.resize(84 + 50 * 10);
  write_file(dir / "truncated.stl", data);
  expect_load_error(dir / "truncated.stl", "contains no triangles");
}

TEST(LoadMeshErrors, BinaryStlNonFiniteCoordinateNamesTheFacet) {
  const auto dir = fresh_temp_dir("err_stl_nan");
  std::string data(80, '\0');
  append_u32(data, 3);
  append_stl_facet(data, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  append_stl_facet(data, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  append_stl_facet(
      data, {Vec3(0, 0, 0), Vec3(1, std::numeric_limits<double>::infinity(), 0), Vec3(0, 1, 0)});
  write_file(dir / "inf.stl", data);
  expect_load_error(dir / "inf.stl", "facet 2 has a non-finite coordinate");
  std::string nan = data;
  const float quiet_nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[84 + 12], &quiet_nan, 4);  // facet 0, first corner's x
  write_file(dir / "nan.stl", nan);
  expect_load_error(dir / "nan.stl", "facet 0 has a non-finite coordinate");
}

TEST(LoadMeshErrors, BinaryStlWithoutFacets) {
  const auto dir = fresh_temp_dir("err_stl_zero");
  std::string data(80, '\0');
  append_u32(data, 0);
  write_file(dir / "zero.stl", data);
  expect_load_error(dir / "zero.stl", "contains no triangles");
}

TEST(LoadMeshErrors, ObjIndexOutOfRange) {
  // The face is refused (neither clamped nor dropped); OBJ counts vertices from 1.
  const auto dir = fresh_temp_dir("err_obj_index");
  write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
  expect_load_error(dir / "bad.obj",
                    "face 1 references vertex 99 but the file has 3 vertices (counted from 1)");
  write_file(dir / "negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n");
  expect_load_error(dir / "negative.obj", "face 1 references a vertex before the first one");
  write_file(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
  expect_load_error(dir / "zero.obj", "not a readable mesh: Failed parse `f' line");
  // An index past int's range would wrap (atoi) to another vertex: refused.
  write_file(dir / "huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n");
  expect_load_error(dir / "huge.obj", "the face on line 4 has a vertex index out of range");
  expect_load_error(assimp_model("invalid/malformed.obj"), "not a readable mesh");
}

TEST(LoadMeshErrors, ObjNanCoordinate) {
  const auto dir = fresh_temp_dir("err_obj_nan");
  write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\nf 1 3 4\n");
  expect_load_error(dir / "nan.obj", "vertex 4 (line 4) has a non-finite coordinate 'nan'");
  write_file(dir / "word.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n");
  expect_load_error(dir / "word.obj", "vertex 2 (line 2) has a coordinate that is not a number");
  write_file(dir / "short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  expect_load_error(dir / "short.obj", "vertex 2 (line 2) has fewer than 3 coordinates");
}

TEST(LoadMeshErrors, ObjOverflowingCoordinate) {
  const auto dir = fresh_temp_dir("err_obj_inf");
  write_file(dir / "inf.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_load_error(dir / "inf.obj", "vertex 1 (line 1) has a non-finite coordinate '1e999'");
}

TEST(LoadMeshErrors, OnlyLines) {
  const auto dir = fresh_temp_dir("err_lines");
  write_file(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  expect_load_error(dir / "lines.obj", "contains no triangles");
  expect_load_error(assimp_model("OBJ/testline.obj"), "contains no triangles");
}

TEST(LoadMeshErrors, OnlyPoints) {
  expect_load_error(assimp_model("OBJ/testpoints.obj"), "contains no triangles");
  expect_load_error(assimp_model("PLY/points.ply"), "contains no triangles");
}

TEST(LoadMeshErrors, OffHeaderAnnouncingTooMuch) {
  // assimp's OFF reader allocates for the header's counts before reading: the packaged
  // OutOfMemory.off (309 bytes, 353535235358 vertices) made it allocate ~16 GB and take a minute.
  // load_mesh refuses such headers up front.
  const auto start = std::chrono::steady_clock::now();
  expect_load_error(assimp_model("invalid/OutOfMemory.off"),
                    "not a readable mesh: the OFF header announces 353535235358 vertices");
  const auto dir = fresh_temp_dir("err_off_header");
  write_file(dir / "liar.off", "# a comment\nOFF\n2000000000 12 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "liar.off", "the OFF header announces 2000000000 vertices and 12 faces");
  // Same content under an extension no reader claims: assimp picks its OFF reader by content,
  // so the check looks at the content too.
  write_file(dir / "honest.dat", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(dir / "honest.dat").triangles.size(), 1u);
  write_file(dir / "liar.dat", "OFF 2000000000 12 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "liar.dat", "the OFF header announces");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  // A binary OFF's counts are not text (no header check applies): refused quickly all the same.
  std::string binary = "OFF BINARY\n";
  for (const std::uint32_t count : {200000000u, 200000000u, 0u}) {
    for (int shift = 24; shift >= 0; shift -= 8)
      binary.push_back(static_cast<char>(count >> shift));
  }
  binary.append(64, '\0');
  write_file(dir / "binary.off", binary);
  expect_load_error(dir / "binary.off", "not a readable mesh");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  // An honest header passes the check.
  write_file(dir / "honest.off",
             "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n"
             "0 1 0 255 0 0 255\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(dir / "honest.off").triangles.size(), 1u);
}

TEST(LoadMeshErrors, PlyBodyThatDoesNotHoldItsHeader) {
  // assimp's PLY reader trusts the header and corrupted its heap on this input (found by
  // fuzzing): 4 vertices of 28 bytes announced, 77 bytes of body, and "face" declared twice.
  const auto dir = fresh_temp_dir("err_ply_layout");
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float nx\n"
      "property double x\nproperty double y\nproperty double z\nelement face 2\n"
      "property list uchar int vertex_indices\n";
  write_file(dir / "twice.ply", header +
                                    "property double y\nelement face 4\n"
                                    "property list uchar int vertex_indices\nend_header\n" +
                                    std::string(77, '\x01'));
  expect_load_error(dir / "twice.ply", "declares element 'face' a second time");
  // The same without the second element: the body ends inside the third vertex.
  write_file(dir / "short.ply", header + "end_header\n" + std::string(77, '\x01'));
  expect_load_error(dir / "short.ply", "the PLY body ends inside element 'vertex' #2 (of 4)");

  // A binary triangle (x y z as float, then one face), whole and with its face list cut short.
  std::string tri =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nproperty uchar flags\nend_header\n";
  for (const float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) test::append_f32(tri, c);
  const std::string vertices_only = tri;
  tri.push_back('\x03');
  for (const std::uint32_t i : {0u, 1u, 2u}) test::append_u32(tri, i);
  tri.push_back('\x00');  // flags, after the list
  write_file(dir / "tri.ply", tri);
  EXPECT_EQ(load_mesh(dir / "tri.ply").triangles.size(), 1u);
  write_file(dir / "cut.ply", tri.substr(0, tri.size() - 2));
  expect_load_error(dir / "cut.ply", "the PLY body ends inside element 'face' #0 (of 1)");
  std::string far = vertices_only + '\x03';
  for (const std::uint32_t i : {0u, 1u, 7u}) test::append_u32(far, i);
  far.push_back('\x00');
  write_file(dir / "far.ply", far);
  expect_load_error(dir / "far.ply",
                    "element 'face' #0 names vertex 7 but the file has 3 vertices");
  // A signed list length below zero.
  std::string negative = vertices_only;
  negative.replace(negative.find("list uchar"), 10, "list char");
  negative += std::string(1, '\xff') + std::string(13, '\0');  // length -1, then 13 bytes
  write_file(dir / "negative.ply", negative);
  expect_load_error(dir / "negative.ply", "gives list 'vertex_indices' a negative length");

  // The same triangle big-endian is read (counts and indices in the file's byte order).
  std::string be =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list ushort int vertex_indices\nend_header\n";
  const auto append_be = [&](std::uint32_t bits, int bytes) {
    for (int shift = 8 * (bytes - 1); shift >= 0; shift -= 8) {
      be.push_back(static_cast<char>(bits >> shift));
    }
  };
  for (const float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
    append_be(std::bit_cast<std::uint32_t>(c), 4);
  }
  append_be(3, 2);
  for (const std::uint32_t i : {0u, 1u, 2u}) append_be(i, 4);
  write_file(dir / "be.ply", be);
  EXPECT_EQ(load_mesh(dir / "be.ply").triangles.size(), 1u);
  be.back() = '\x03';
  write_file(dir / "be_far.ply", be);
  expect_load_error(dir / "be_far.ply", "names vertex 3 but the file has 3 vertices");
}

TEST(LoadMeshErrors, PlyAsciiThatDoesNotHoldItsHeader) {
  const auto dir = fresh_temp_dir("err_ply_ascii");
  const std::string header =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty double x\n"
      "property double y\nproperty double z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  write_file(dir / "ok.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_mesh(dir / "ok.ply").triangles.size(), 1u);
  write_file(dir / "short_line.ply", header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "short_line.ply",
                    "element 'vertex' #1 has fewer values than its properties");
  write_file(dir / "short_list.ply", header + "0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
  expect_load_error(dir / "short_list.ply",
                    "element 'face' #0 has fewer values than its properties");
  write_file(dir / "no_face.ply", header + "0 0 0\n1 0 0\n0 1 0\n");
  expect_load_error(dir / "no_face.ply", "the PLY body ends before element 'face' #0 (of 1)");
  write_file(dir / "far.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n");
  expect_load_error(dir / "far.ply", "names vertex -1 but the file has 3 vertices");
  write_file(dir / "length.ply", header + "0 0 0\n1 0 0\n0 1 0\nthree 0 1 2\n");
  expect_load_error(dir / "length.ply", "gives list 'vertex_indices' the length 'three'");
  // A header announcing billions is refused at once, before anything is allocated for it.
  const auto start = std::chrono::steady_clock::now();
  std::string liar = header;
  liar.replace(liar.find("vertex 3"), 8, "vertex 4000000000");
  write_file(dir / "liar.ply", liar + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "liar.ply", "the PLY header announces 4000000000 of element 'vertex'");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  // Content starting with "ply" under an extension no reader claims gets the same check.
  write_file(dir / "short_line.dat", header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "short_line.dat", "has fewer values than its properties");
  // Unknown types and malformed lines in the header are named.
  std::string typo = header;
  typo.replace(typo.find("double y"), 8, "dubble y");
  write_file(dir / "typo.ply", typo + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "typo.ply",
                    "the PLY header's line 6 ('property dubble y') is not understood");
  // An element assimp does not know: it reads none of its instances (the count is taken from the
  // name), so one before the vertices would shift them; last, it changes nothing.
  std::string blob = header;
  blob.replace(blob.find("element vertex"), 0, "element blob 1\nproperty uchar r\n");
  write_file(dir / "blob_first.ply", blob + "7\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "blob_first.ply",
                    "the PLY element 'blob' comes before element 'vertex': assimp reads no "
                    "instance");
  std::string last = header;
  last.replace(last.find("end_header"), 0, "element camera 1\nproperty float view_px\n");
  write_file(dir / "camera_last.ply", last + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0.5\n");
  EXPECT_EQ(load_mesh(dir / "camera_last.ply").triangles.size(), 1u);
  std::string digits = header;
  digits.replace(digits.find("element vertex 3"), 16, "element 4999999999vertex 3");
  write_file(dir / "digits.ply", digits + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "digits.ply",
                    "the PLY element name '4999999999vertex' starts with a digit");
  // A header that ends the file (assimp never returned on this one).
  write_file(dir / "no_body.ply", "ply\nformat ascii 1.0\nabcdefghijklmnopqrstuvwxyz\nend_header");
  expect_load_error(dir / "no_body.ply", "the PLY file ends on its end_header line (no body)");
  // Two packaged files assimp read as empty are now refused with the reason.
  expect_load_error(assimp_model("PLY/pond.0.ply"),
                    "the PLY body ends inside element 'vertex' #70048 (of 70051)");
  expect_load_error(assimp_model("PLY/issue623.ply"),
                    "element 'vertex' #0 has fewer values than its properties");
}

TEST(LoadMeshErrors, PackagedInvalidFilesDoNotCrash) {
  // Every file of assimp-testmodels' invalid/ folder fails cleanly, except malformed2.obj whose
  // only defect is a missing material (irrelevant to geometry).
  for (const auto& entry : std::filesystem::directory_iterator(assimp_model("invalid"))) {
    const auto name = entry.path().filename().string();
    if (name == "malformed2.obj") {
      EXPECT_EQ(load_mesh(entry.path()).triangles.size(), 10u);
      continue;
    }
    expect_load_error(entry.path(), "");
  }
}

// ---- validate_mesh on meshes built in memory ----

Mesh unit_tetrahedron() {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(ValidateMesh, AcceptsValidMesh) { EXPECT_NO_THROW(validate_mesh(unit_tetrahedron(), "tet")); }

TEST(ValidateMesh, NoTriangles) {
  Mesh m = unit_tetrahedron();
  m.triangles.clear();
  expect_mesh_error([&] { validate_mesh(m, "in-memory tet"); }, "in-memory tet",
                    "contains no triangles");
  expect_mesh_error([&] { validate_mesh(Mesh{}, "nothing"); }, "nothing", "contains no triangles");
}

TEST(ValidateMesh, NanCoordinate) {
  Mesh m = unit_tetrahedron();
  m.vertices[2].y() = std::numeric_limits<Scalar>::quiet_NaN();
  expect_mesh_error([&] { validate_mesh(m, "tet"); }, "tet",
                    "vertex 2 has a non-finite coordinate");
}

TEST(ValidateMesh, InfiniteCoordinate) {
  Mesh m = unit_tetrahedron();
  m.vertices[3].z() = -std::numeric_limits<Scalar>::infinity();
  expect_mesh_error([&] { validate_mesh(m, "tet"); }, "tet",
                    "vertex 3 has a non-finite coordinate");
}

TEST(ValidateMesh, IndexOutOfRange) {
  Mesh m = unit_tetrahedron();
  m.triangles[3][1] = 99;
  try {
    validate_mesh(m, "tet");
    ADD_FAILURE() << "expected a MeshError";
  } catch (const MeshError& e) {
    EXPECT_STREQ(e.what(), "tet: triangle 3 references vertex 99 but the mesh has 4 vertices");
  }
}

// ---- Mesh helpers ----

TEST(MeshBounds, EmptyMeshHasEmptyBounds) {
  EXPECT_TRUE(Mesh{}.bounds().empty());
  const Aabb b = unit_tetrahedron().bounds();
  EXPECT_EQ(b.min, Vec3::Zero());
  EXPECT_EQ(b.max, Vec3::Ones());
}

TEST(MeshBounds, NanCoordinatesAreSkipped) {
  Mesh m = unit_tetrahedron();
  m.vertices.emplace_back(std::numeric_limits<Scalar>::quiet_NaN(), 5, -5);
  const Aabb b = m.bounds();
  EXPECT_EQ(b.min, Vec3(0, 0, -5));
  EXPECT_EQ(b.max, Vec3(1, 5, 1));
}

TEST(MeshDegenerate, CountsZeroAreaTriangles) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
  m.triangles = {{0, 1, 2},   // proper
                 {0, 1, 3},   // collinear corners
                 {0, 0, 2},   // repeated corner
                 {1, 1, 1}};  // a point
  EXPECT_EQ(m.degenerate_triangle_count(), 3u);
  EXPECT_EQ(unit_tetrahedron().degenerate_triangle_count(), 0u);
}

TEST(MeshDegenerate, OutOfRangeTriangleCountsAsDegenerate) {
  Mesh m = unit_tetrahedron();
  m.triangles.push_back({0, 1, 7});
  EXPECT_EQ(m.degenerate_triangle_count(), 1u);
}

// ---- save_obj ----

TEST(SaveObj, RoundTripThroughLoader) {
  // OBJ is read in double precision: the round trip save -> load reproduces every triangle's
  // corners exactly, for arbitrary doubles (none of them is a float value here).
  const Mesh original = transformed(
      make_torus(2, 0.5, 24, 12), Transform::from_axis_angle(Vec3(1, 2, 3), 0.7, Vec3(0.1, -3, 7)));
  std::size_t float_values = 0;
  for (const Vec3& v : original.vertices) {
    for (int k = 0; k < 3; ++k) float_values += to_float_value(v[k]) == v[k] ? 1 : 0;
  }
  EXPECT_LT(float_values, original.vertices.size() / 10);
  const auto dir = fresh_temp_dir("save_round_trip");
  save_obj(original, dir / "torus.obj");
  const Mesh loaded = load_mesh(dir / "torus.obj");
  EXPECT_EQ(loaded.vertices.size(), original.vertices.size());
  EXPECT_EQ(corner_positions(loaded), corner_positions(original));
  EXPECT_EQ(count_entries(dir), 1u);  // no temporary file left behind
}

TEST(SaveObj, WritesEveryDoubleExactly) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Scalar> uni(-1e6, 1e6);
  Mesh m;
  for (int i = 0; i < 300; ++i)
    m.vertices.emplace_back(uni(rng), uni(rng) * 1e-300, uni(rng) * 1e300);
  m.vertices.emplace_back(0.1, -0.0, std::numeric_limits<Scalar>::denorm_min());
  for (std::uint32_t i = 0; i + 2 < m.vertices.size(); i += 3)
    m.triangles.push_back({i, i + 1, i + 2});
  const auto dir = fresh_temp_dir("save_exact");
  save_obj(m, dir / "exact.obj");

  const Mesh back = test::parse_obj_reference(dir / "exact.obj");
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.triangles, m.triangles);
}

TEST(SaveObj, OverwritesExistingFile) {
  const auto dir = fresh_temp_dir("save_overwrite");
  write_file(dir / "mesh.obj", "old content\n");
  save_obj(make_box(Vec3(1, 1, 1)), dir / "mesh.obj");
  EXPECT_EQ(load_mesh(dir / "mesh.obj").triangles.size(), 12u);
  EXPECT_EQ(count_entries(dir), 1u);
}

TEST(SaveObj, MissingDirectoryThrowsAndLeavesNothing) {
  const auto dir = fresh_temp_dir("save_missing_dir");
  const auto path = dir / "no_such_dir" / "mesh.obj";
  try {
    save_obj(make_box(Vec3(1, 1, 1)), path);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "no_such_dir"));
  EXPECT_EQ(count_entries(dir), 0u);
}

TEST(SaveObj, FailedRenameRemovesTemporary) {
  // The target is a non-empty directory: the temporary file is written, the rename fails.
  const auto dir = fresh_temp_dir("save_rename_fails");
  std::filesystem::create_directories(dir / "taken.obj" / "inside");
  try {
    save_obj(make_box(Vec3(1, 1, 1)), dir / "taken.obj");
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "taken.obj").string()), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(count_entries(dir), 1u);  // only the directory that was in the way
  EXPECT_TRUE(std::filesystem::is_directory(dir / "taken.obj" / "inside"));
}

TEST(SaveObj, SpecialFileTargetIsRefusedAndKept) {
  // The temporary-file-then-rename write would replace a FIFO (or a device such as /dev/null)
  // with a regular file.
  const auto dir = fresh_temp_dir("save_special_target");
  const auto fifo = dir / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    save_obj(make_box(Vec3(1, 1, 1)), fifo);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_EQ(count_entries(dir), 1u);
}

TEST(SaveObj, InvalidMeshIsRefused) {
  const auto dir = fresh_temp_dir("save_invalid");
  Mesh m = unit_tetrahedron();
  m.triangles[0][0] = 4;
  expect_mesh_error([&] { save_obj(m, dir / "bad.obj"); }, dir / "bad.obj", "references vertex 4");
  EXPECT_EQ(count_entries(dir), 0u);
}

// ---- scale ----

TEST(LoadMeshLarge, FiveMillionTriangleBinaryStl) {
  // A height field of 2000 x 1250 grid cells, two triangles each: 5,000,000 triangles on
  // 2001 x 1251 grid points. Coordinates are small integers and quarters, exact in float.
  constexpr std::uint32_t nx = 2000;
  constexpr std::uint32_t ny = 1250;
  constexpr std::uint32_t triangle_count = 2 * nx * ny;
  const auto dir = fresh_temp_dir("load_5m");
  const auto path = dir / "grid.stl";
  auto point = [](std::uint32_t i, std::uint32_t j) {
    return Vec3(i, j, ((i * 7 + j * 13) % 5) * 0.25);
  };
  {
    std::ofstream out(path, std::ios::binary);
    std::string chunk(80, '\0');
    append_u32(chunk, triangle_count);
    for (std::uint32_t i = 0; i < nx; ++i) {
      for (std::uint32_t j = 0; j < ny; ++j) {
        append_stl_facet(chunk, {point(i, j), point(i + 1, j), point(i + 1, j + 1)});
        append_stl_facet(chunk, {point(i, j), point(i + 1, j + 1), point(i, j + 1)});
      }
      out.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      chunk.clear();
    }
    ASSERT_TRUE(out.good());
  }
  ASSERT_EQ(std::filesystem::file_size(path), 84u + 50u * triangle_count);

  const auto start = std::chrono::steady_clock::now();
  const Mesh m = load_mesh(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::filesystem::remove_all(dir);
  RecordProperty("load_seconds", std::to_string(seconds));
  std::cout << "[          ] 5M-triangle binary STL loaded in " << seconds << " s\n";

  EXPECT_EQ(m.triangles.size(), std::size_t{triangle_count});
  EXPECT_EQ(m.vertices.size(), std::size_t{(nx + 1) * (ny + 1)});
  expect_bounds(m, Vec3(0, 0, 0), Vec3(nx, ny, 1));
  EXPECT_EQ(m.degenerate_triangle_count(), 0u);
}

}  // namespace
}  // namespace antcd
