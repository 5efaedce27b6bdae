// OBJ, OFF and PLY keep their coordinates in double precision: each loaded coordinate is
// the nearest double to the file's text (std::strtod is the reference; a binary PLY's doubles bit
// for bit), in every OFF and PLY layout the re-reading follows, while layouts it does not follow
// load assimp's floats; polygons are triangulated into triangles that tile them, the real
// assimp-testmodels files give the triangles and vertices assimp gives (within float rounding),
// and a distance on a real file matches brute force over the file's own coordinates to ~1e-12
// relative. assimp is linked here as a reference only.
#include "support/mesh_files.hpp"
#include "support/test_support.hpp"

#include <antcd/bvh.hpp>
#include <antcd/geometry.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/points.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace antcd {
namespace {

using test::assimp_model;
using test::fresh_temp_dir;
using test::write_file;

/// The corners of every triangle, in triangle order.
std::vector<std::array<Vec3, 3>> corners(const Mesh& m) {
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& t : m.triangles)
    out.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  return out;
}

/// A point list and triangles (0-based) in each text format, coordinates printed as `text`.
struct TextMesh {
  std::vector<std::array<std::string, 3>> text;
  std::vector<std::array<int, 3>> triangles;

  [[nodiscard]] std::vector<std::array<Vec3, 3>> expected() const {
    std::vector<std::array<Vec3, 3>> out;
    for (const auto& t : triangles) {
      std::array<Vec3, 3> c;
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) {
          c[k][a] = std::strtod(text[static_cast<std::size_t>(t[k])][a].c_str(), nullptr);
        }
      }
      out.push_back(c);
    }
    return out;
  }
  [[nodiscard]] std::string obj() const {
    std::string s = "# written by load_precision_test\n";
    for (const auto& p : text) s += "v " + p[0] + ' ' + p[1] + ' ' + p[2] + '\n';
    for (const auto& t : triangles) {
      s += "f " + std::to_string(t[0] + 1) + ' ' + std::to_string(t[1] + 1) + ' ' +
           std::to_string(t[2] + 1) + '\n';
    }
    return s;
  }
  [[nodiscard]] std::string faces_off() const {
    std::string s;
    for (const auto& t : triangles) {
      s += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) +
           '\n';
    }
    return s;
  }
  [[nodiscard]] std::string off() const {
    std::string s =
        "OFF\n" + std::to_string(text.size()) + ' ' + std::to_string(triangles.size()) + " 0\n";
    for (const auto& p : text) s += p[0] + ' ' + p[1] + ' ' + p[2] + '\n';
    return s + faces_off();
  }
  [[nodiscard]] std::string ply() const {
    std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(text.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(triangles.size()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : text) s += p[0] + ' ' + p[1] + ' ' + p[2] + '\n';
    return s + faces_off();
  }
};

std::string shortest(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  EXPECT_EQ(ec, std::errc{});
  return std::string(buffer, end);
}

Scalar to_float_value(Scalar x) {
  volatile float f = static_cast<float>(x);
  return f;
}

void expect_every_format_reproduces(const TextMesh& m, const std::string& name) {
  const auto dir = fresh_temp_dir("precision_" + name);
  const auto expected = m.expected();
  const std::vector<std::pair<std::string, std::string>> files = {
      {name + ".obj", m.obj()},
      {name + ".off", m.off()},
      {name + ".ply", m.ply()},
  };
  for (const auto& [file, text] : files) {
    SCOPED_TRACE(file);
    write_file(dir / file, text);
    const Mesh loaded = load_mesh(dir / file);
    EXPECT_EQ(loaded.triangles.size(), m.triangles.size());
    EXPECT_EQ(corners(loaded), expected);  // bit-exact
  }
}

TEST(LoadPrecision, CoordinatesNotRepresentableInFloatAreKept) {
  TextMesh m;
  m.text = {{"0.1", "1.0000001", "123456.789012345"},
            {"0.30000000000000004", "-7.123456789012345e-5", "2.718281828459045"},
            {"1e39", "0.2", "+0.7"},
            {"3.141592653589793", "1e-7", "-123456.789012346"}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  // None of these is a float value: a float reader would change every one of them.
  for (const auto& p : m.text) {
    for (const auto& x : p) {
      const double v = std::strtod(x.c_str(), nullptr);
      EXPECT_NE(to_float_value(v), v) << x;
    }
  }
  expect_every_format_reproduces(m, "tetra");
  // The values spelled out, independent of strtod.
  const auto dir = fresh_temp_dir("precision_literal");
  write_file(dir / "t.obj", m.obj());
  const Mesh loaded = load_mesh(dir / "t.obj");
  EXPECT_EQ(loaded.vertices[0], Vec3(0.1, 1.0000001, 123456.789012345));
  EXPECT_EQ(loaded.vertices[1], Vec3(1e39, 0.2, 0.7));  // in order of first use: 0, 2, 1, 3
}

TEST(LoadPrecision, RandomDoublesRoundTripExactly) {
  // 900 random doubles over many magnitudes, printed as their shortest round-trip text (up to 17
  // significant digits): every format reads each one back to the same double.
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  TextMesh m;
  for (int i = 0; i < 300; ++i) {
    std::array<std::string, 3> p;
    for (auto& x : p) x = shortest(std::ldexp(mantissa(rng), exponent(rng)));
    m.text.push_back(p);
  }
  for (int i = 0; i + 2 < 300; i += 3) m.triangles.push_back({i, i + 1, i + 2});
  expect_every_format_reproduces(m, "random");
}

/// 300 random doubles over many magnitudes (float's range and beyond), as printf's %.17g or
/// %.16e (scientific) writes them, on 100 triangles.
TextMesh random_text_mesh(const char* format, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-60, 60);
  TextMesh m;
  for (int i = 0; i < 100; ++i) {
    std::array<std::string, 3> p;
    for (auto& x : p) {
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, format, std::ldexp(mantissa(rng), exponent(rng)));
      x = buffer;
    }
    m.text.push_back(p);
  }
  for (int i = 0; i + 2 < 100; i += 3) m.triangles.push_back({i, i + 1, i + 2});
  return m;
}

TEST(LoadPrecision, PrintfDoublesRoundTripExactly) {
  expect_every_format_reproduces(random_text_mesh("%.17g", 11), "g17");
  expect_every_format_reproduces(random_text_mesh("%.16e", 12), "e16");
}

std::string with_crlf(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

void append_le(std::string& out, const void* value, std::size_t size) {
  out.append(static_cast<const char*>(value), size);  // the test machines are little-endian
}

TEST(LoadPrecision, OffAndPlyLayoutsKeepTheFileCoordinates) {
  const TextMesh m = random_text_mesh("%.17g", 13);
  const std::string n = std::to_string(m.text.size());
  const std::string f = std::to_string(m.triangles.size());
  auto vertex_lines = [&](const std::string& before, const std::string& after) {
    std::string s;
    for (const auto& p : m.text) s += before + p[0] + ' ' + p[1] + "\t" + p[2] + after + '\n';
    return s;
  };
  std::vector<std::pair<std::string, std::string>> files = {
      // OFF: comments before and after the keyword, CRLF line ends.
      {"comments_crlf.off",
       with_crlf("# made by a test\n  OFF\n# counts next\n\n" + n + ' ' + f + " 0\n# vertices\n" +
                 vertex_lines(" ", "  ") + m.faces_off())},
      // Colours and normals after the coordinates, no keyword at all, counts on the keyword line.
      {"colours.off",
       "COFF\n" + n + ' ' + f + " 0\n" + vertex_lines("", " 255 0 0 255") + m.faces_off()},
      {"normals.off", "NOFF\n" + n + ' ' + f + " 0\n" + vertex_lines("", " 0 0 1") + m.faces_off()},
      {"no_keyword.off", n + ' ' + f + " 0\n" + vertex_lines("", "") + m.faces_off()},
      {"one_line.off", "OFF " + n + ' ' + f + " 0\n" + vertex_lines("", "") + m.faces_off()},
      // PLY: comments, obj_info, normals before and colours after x/y/z, CRLF line ends.
      {"properties_crlf.ply",
       with_crlf("ply\nformat ascii 1.0\ncomment made by a test\nobj_info none\nelement vertex " +
                 n +
                 "\nproperty float nx\nproperty float ny\nproperty float nz\nproperty double x\n"
                 "property double y\nproperty double z\nproperty uchar red\nproperty uchar green\n"
                 "property uchar blue\nelement face " +
                 f + "\nproperty list uchar int vertex_indices\nend_header\n" +
                 vertex_lines("0 0 1 ", " 10 20 30") + m.faces_off())},
      // Properties in another order (z, x, y).
      {"zxy.ply",
       [&] {
         std::string s =
             "ply\nformat ascii 1.0\nelement vertex " + n +
             "\nproperty double z\nproperty double x\nproperty double y\nelement face " + f +
             "\nproperty list uchar int vertex_indices\nend_header\n";
         for (const auto& p : m.text) s += p[2] + ' ' + p[0] + ' ' + p[1] + '\n';
         return s + m.faces_off();
       }()},
  };
  // Binary little-endian PLY with double coordinates between float normals.
  {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + n +
                    "\nproperty float nx\nproperty double x\nproperty double y\nproperty double z\n"
                    "property float nz\nelement face " +
                    f + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& p : m.text) {
      const float normal = 1;
      append_le(s, &normal, sizeof normal);
      for (const auto& x : p) {
        const double v = std::strtod(x.c_str(), nullptr);
        append_le(s, &v, sizeof v);
      }
      append_le(s, &normal, sizeof normal);
    }
    for (const auto& t : m.triangles) {
      s += '\3';
      for (const int i : t) append_le(s, &i, sizeof i);
    }
    files.emplace_back("binary_double.ply", s);
  }
  const auto dir = fresh_temp_dir("precision_layouts");
  const auto expected = m.expected();
  for (const auto& [file, text] : files) {
    SCOPED_TRACE(file);
    write_file(dir / file, text);
    const Mesh loaded = load_mesh(dir / file);
    EXPECT_EQ(corners(loaded), expected);  // bit-exact
  }
}

TEST(LoadPrecision, LayoutsNotFollowedLoadAssimpFloats) {
  // Layouts the re-reading does not follow load as before, with assimp's floats, never with
  // other numbers of the file: a homogeneous OFF (assimp divides x, y, z by w) and a big-endian
  // binary PLY.
  const TextMesh m = random_text_mesh("%.17g", 14);
  const auto expected = m.expected();
  const auto dir = fresh_temp_dir("precision_fallback");
  std::string off =
      "4OFF\n" + std::to_string(m.text.size()) + ' ' + std::to_string(m.triangles.size()) + " 0\n";
  for (const auto& p : m.text) off += p[0] + ' ' + p[1] + ' ' + p[2] + " 2\n";
  write_file(dir / "homogeneous.off", off + m.faces_off());
  std::string ply =
      "ply\nformat binary_big_endian 1.0\nelement vertex " + std::to_string(m.text.size()) +
      "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
      std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  auto big_endian = [&](const void* value, std::size_t size) {
    const auto* bytes = static_cast<const char*>(value);
    for (std::size_t i = size; i-- > 0;) ply += bytes[i];
  };
  for (const auto& p : m.text) {
    for (const auto& x : p) {
      const double v = std::strtod(x.c_str(), nullptr);
      big_endian(&v, sizeof v);
    }
  }
  for (const auto& t : m.triangles) {
    ply += '\3';
    for (const int i : t) big_endian(&i, sizeof i);
  }
  write_file(dir / "big_endian.ply", ply);
  for (const auto& [file, divisor] : std::vector<std::pair<std::string, double>>{
           {"homogeneous.off", 2.0}, {"big_endian.ply", 1.0}}) {
    SCOPED_TRACE(file);
    const auto loaded = corners(load_mesh(dir / file));
    ASSERT_EQ(loaded.size(), expected.size());
    for (std::size_t t = 0; t < loaded.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 3; ++a) {
          const double v = loaded[t][static_cast<std::size_t>(k)][a];
          const double want = expected[t][static_cast<std::size_t>(k)][a] / divisor;
          EXPECT_EQ(to_float_value(v), v);  // a float, as assimp read it
          EXPECT_LE(std::abs(v - want), 3e-7 * std::abs(want));
        }
      }
    }
  }
}

// ---- triangulation ----

/// Sum of the triangles' areas and whether each one faces +z (all in the z = 0.25 plane).
struct Tiling {
  std::size_t triangles = 0;
  Scalar area = 0;
  bool all_face_up = true;
};

Tiling tiling(const Mesh& m) {
  Tiling t;
  t.triangles = m.triangles.size();
  for (const auto& tri : m.triangles) {
    const Vec3 n =
        (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]);
    t.area += n.norm() / 2;
    t.all_face_up = t.all_face_up && n.z() > 0;
  }
  return t;
}

TEST(LoadPrecision, PolygonsAreTriangulatedIntoTheirArea) {
  // Counter-clockwise polygons in the plane z = 0.25, each with its exact area: a convex quad, a
  // dart (a quad whose corner 1 is reflex: only the diagonal 1-3 lies inside), an L-shaped hexagon
  // and a comb-shaped 8-gon (several reflex corners, for the ear clipping).
  struct Polygon {
    std::vector<std::array<double, 2>> xy;
    double area;
  };
  const std::vector<Polygon> polygons = {
      {{{0, 0}, {2, 0}, {2, 1}, {0, 1}}, 2.0},
      {{{0, 0}, {1, 0.9}, {2, 0}, {1, 3}}, 2.1},
      {{{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {0, 2}}, 4.0},
      {{{0, 0}, {4, 0}, {4, 3}, {3, 3}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}, 8.0},
  };
  const auto dir = fresh_temp_dir("precision_polygons");
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const auto& poly = polygons[i];
    const std::size_t n = poly.xy.size();
    std::string indices1;
    for (std::size_t k = 0; k < n; ++k) indices1 += ' ' + std::to_string(k + 1);
    std::string obj;
    for (std::size_t k = 0; k < n; ++k) {
      obj += "v " + shortest(poly.xy[k][0]) + ' ' + shortest(poly.xy[k][1]) + " 0.25\n";
    }
    obj += "f" + indices1 + '\n';
    // The same polygon as one OFF face and one PLY face.
    std::string points;
    for (std::size_t k = 0; k < n; ++k) {
      points += shortest(poly.xy[k][0]) + ' ' + shortest(poly.xy[k][1]) + " 0.25\n";
    }
    std::string face = std::to_string(n);
    for (std::size_t k = 0; k < n; ++k) face += ' ' + std::to_string(k);
    const std::string off = "OFF\n" + std::to_string(n) + " 1 0\n" + points + face + '\n';
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(n) +
                            "\nproperty double x\nproperty double y\nproperty double z\n"
                            "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                            points + face + '\n';
    for (const auto& [ext, text] : std::vector<std::pair<std::string, std::string>>{
             {".obj", obj}, {".off", off}, {".ply", ply}}) {
      SCOPED_TRACE("polygon " + std::to_string(i) + ext);
      const auto path = dir / ("polygon" + std::to_string(i) + ext);
      write_file(path, text);
      const Mesh m = load_mesh(path);
      const Tiling t = tiling(m);
      EXPECT_EQ(t.triangles, n - 2);
      EXPECT_EQ(m.vertices.size(), n);
      // The triangles tile the polygon: no triangle flipped (all face +z like the polygon) and
      // their areas add up to the polygon's.
      EXPECT_TRUE(t.all_face_up);
      EXPECT_NEAR(t.area, poly.area, 1e-12);
    }
  }
}

// ---- agreement with assimp on real files ----

struct AssimpMesh {
  std::size_t triangles = 0;
  std::vector<std::array<float, 3>> positions;  // distinct positions of triangle corners
};

AssimpMesh assimp_reference(const std::filesystem::path& path) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_SortByPType |
                                           aiProcess_JoinIdenticalVertices);
  AssimpMesh out;
  if (scene == nullptr) {
    ADD_FAILURE() << "assimp cannot read " << path << ": " << importer.GetErrorString();
    return out;
  }
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh& mesh = *scene->mMeshes[i];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      ++out.triangles;
      for (unsigned k = 0; k < 3; ++k) {
        const aiVector3D& p = mesh.mVertices[face.mIndices[k]];
        out.positions.push_back({p.x, p.y, p.z});
      }
    }
  }
  std::sort(out.positions.begin(), out.positions.end());
  out.positions.erase(std::unique(out.positions.begin(), out.positions.end()), out.positions.end());
  return out;
}

TEST(LoadPrecision, RealFilesAgreeWithAssimpWithinFloatRounding) {
  for (const char* name :
       {"OBJ/spider.obj", "OBJ/box.obj", "OBJ/concave_polygon.obj", "OBJ/WusonOBJ.obj",
        "OBJ/regr01.obj", "OFF/Cube.off", "OFF/Wuson.off", "PLY/Wuson.ply", "PLY/cube.ply",
        "PLY/cube_binary.ply", "PLY/cube_uv.ply", "PLY/float-color.ply"}) {
    SCOPED_TRACE(name);
    const auto path = assimp_model(name);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
    const Mesh m = load_mesh(path);
    const AssimpMesh ref = assimp_reference(path);
    EXPECT_EQ(m.triangles.size(), ref.triangles);
    ASSERT_EQ(m.vertices.size(), ref.positions.size());
    // Each loaded position, rounded to float, is one of assimp's, to within assimp's own number
    // parsing (not always correctly rounded): 2 float ulps.
    std::vector<std::array<float, 3>> ours;
    for (const Vec3& v : m.vertices) {
      ours.push_back(
          {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
    }
    std::sort(ours.begin(), ours.end());
    double worst = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        const double a = ours[i][static_cast<std::size_t>(k)];
        const double b = ref.positions[i][static_cast<std::size_t>(k)];
        worst = std::max(worst, std::abs(a - b) / std::max(1.0, std::abs(b)));
      }
    }
    EXPECT_LE(worst, 2.5e-7);
  }
}

TEST(LoadPrecision, WusonOffAndPlyGiveTheFilesOwnNumbers) {
  // The same model in both formats, coordinates printed with 6 decimals (none a float value):
  // both load the same doubles, the nearest to the text.
  const auto off_path = assimp_model("OFF/Wuson.off");
  const auto ply_path = assimp_model("PLY/Wuson.ply");
  if (!std::filesystem::exists(off_path) || !std::filesystem::exists(ply_path)) {
    GTEST_SKIP() << "assimp-testmodels' Wuson files are absent";
  }
  auto sorted_vertices = [](const Mesh& m) {
    std::vector<std::array<double, 3>> v;
    for (const Vec3& p : m.vertices) v.push_back({p.x(), p.y(), p.z()});
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto off = sorted_vertices(load_mesh(off_path));
  const auto ply = sorted_vertices(load_mesh(ply_path));
  EXPECT_EQ(off, ply);
  // Lines of both files, as text.
  for (const auto& p : {std::array<double, 3>{0.0, 0.498178, -0.278300},
                        std::array<double, 3>{0.163313, 0.540615, -0.268688}}) {
    EXPECT_TRUE(std::binary_search(off.begin(), off.end(), p));
    EXPECT_TRUE(std::binary_search(ply.begin(), ply.end(), p));
  }
}

// ---- a distance on a real file against the file's own coordinates ----

Scalar brute_distance(const Mesh& mesh, const Vec3& p) {
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    if (geometry::is_degenerate_triangle(a, b, c)) continue;
    best = std::min(best, std::sqrt(geometry::point_triangle_distance_squared(p, a, b, c)));
  }
  return best;
}

TEST(LoadPrecision, DistanceOnRealFileMatchesOracleOnFileCoordinates) {
  for (const char* name : {"OBJ/spider.obj", "OBJ/WusonOBJ.obj"}) {
    SCOPED_TRACE(name);
    const auto path = assimp_model(name);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
    const Mesh reference = test::parse_obj_reference(path);
    Mesh rounded = reference;  // what a single-precision loader gives
    for (Vec3& v : rounded.vertices) {
      for (int k = 0; k < 3; ++k) v[k] = to_float_value(v[k]);
    }
    const Model model(load_mesh(path));
    const Aabb box = reference.bounds();
    const Vec3 extent = box.max - box.min;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<Scalar> uni(-0.25, 1.25);
    std::vector<Vec3> points;
    for (int i = 0; i < 200; ++i) {
      points.push_back(box.min + Vec3(uni(rng), uni(rng), uni(rng)).cwiseProduct(extent));
    }
    const SignedDistanceResult result = signed_distance(model, Transform::identity(), points);
    ASSERT_EQ(result.points.size(), points.size());
    double worst = 0;
    double float_worst = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Scalar oracle = brute_distance(reference, points[i]);
      const Scalar scale = std::max<Scalar>(oracle, 1e-3 * extent.norm());
      worst = std::max(worst, std::abs(std::abs(result.points[i].distance) - oracle) / scale);
      float_worst =
          std::max(float_worst, std::abs(brute_distance(rounded, points[i]) - oracle) / scale);
    }
    EXPECT_LE(worst, 1e-12);
    // The check can fail: with float coordinates the same distances are off by far more.
    EXPECT_GT(float_worst, 1e-9);
    std::cout << "[          ] " << name << ": worst relative error " << worst
              << " (float coordinates: " << float_worst << ")\n";
  }
}

}  // namespace
}  // namespace antcd
