// OBJ keeps its coordinates in double precision: each loaded coordinate is
// the nearest double to the file's text (std::strtod is the reference), polygons are triangulated
// into triangles that tile them, the real assimp-testmodels files give the triangles and vertices
// assimp gives (within float rounding), and a distance on a real file matches brute force over
// the file's own coordinates to ~1e-12 relative. assimp is linked here as a reference only.
#include "support/mesh_files.hpp"
#include "support/test_support.hpp"

#include <antcd/bvh.hpp>
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>
#include <antcd/points.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
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
  for (const auto& t : m.triangles) out.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
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
    const Vec3 n = (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]);
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
    for (const auto& [ext, text] :
         std::vector<std::pair<std::string, std::string>>{{".obj", obj}}) {
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
  const aiScene* scene = importer.ReadFile(
      path.string(), aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
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
  for (const char* name : {"OBJ/spider.obj", "OBJ/box.obj", "OBJ/concave_polygon.obj",
                           "OBJ/WusonOBJ.obj", "OBJ/regr01.obj"}) {
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
      ours.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
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
      float_worst = std::max(float_worst, std::abs(brute_distance(rounded, points[i]) - oracle) / scale);
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
