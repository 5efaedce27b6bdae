// self_intersections against CGAL::Polygon_mesh_processing::self_intersections with an
// exact-predicates kernel (Epick: exact predicates, which is all a yes/no verdict uses), on
// Debian's assimp models and generated meshes made to intersect themselves.
//
// Both sides read one mesh: the triangles go through CGAL's polygon-soup repair
// (orient_polygon_soup, which duplicates the vertices of non-manifold edges and vertices) into a
// Surface_mesh, and antcd reads that Surface_mesh's vertices and faces, so both see the same
// vertex sharing. CGAL reports a degenerate face f as the pair (f, f) and in no other pair;
// antcd lists it in degenerate_triangles, so those are compared with the (f, f) pairs. One
// intentional difference: CGAL says a face and its reversed duplicate on the same three
// vertices (a two-face closed Surface_mesh) do not intersect; antcd says they do (they are the
// same point set). A Surface_mesh holds no such pair unless built so, and none is built here.
// Faces that name one vertex twice (56 of the spider's 1368, after the loader joins coincident
// vertices) have no place in a Surface_mesh (polygon_soup_to_polygon_mesh's precondition, which
// only Debug builds check): they are left out of the soup, the comparison is on the mesh both
// sides then read, and antcd is checked to list those faces as degenerate on the mesh as loaded.
#include <antcd/load.hpp>
#include <antcd/self.hpp>

#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <vector>

#include "self/self_meshes.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Pairs = std::vector<std::array<std::uint32_t, 2>>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// The mesh as CGAL's repaired Surface_mesh, and that Surface_mesh back as an antcd Mesh.
Mesh through_cgal(const Mesh& in, SurfaceMesh& sm) {
  std::vector<K::Point_3> points;
  for (const Vec3& p : in.vertices) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : in.triangles) {
    // A triangle that names one vertex twice has no place in a Surface_mesh (CGAL's
    // precondition, checked in Debug builds; Release builds drop such faces unchecked).
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    polygons.push_back({t[0], t[1], t[2]});
  }
  PMP::orient_polygon_soup(points, polygons);
  // polygon_soup_to_polygon_mesh's precondition, checked here in every build type.
  EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(polygons));
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return {};
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  Mesh out;
  for (const auto v : sm.vertices()) {
    const K::Point_3& p = sm.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (const auto f : sm.faces()) {
    TriangleIndices t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      t[static_cast<std::size_t>(k++)] = static_cast<std::uint32_t>(v.idx());
    }
    out.triangles.push_back(t);
  }
  return out;
}

struct Compared {
  std::size_t triangles = 0;  ///< of the repaired mesh both sides read
  std::size_t pairs = 0;
  std::size_t degenerate = 0;
};

/// Compares the two on `in`; returns what was compared.
Compared compare(const Mesh& in, const std::string& name) {
  SurfaceMesh sm;
  const Mesh mesh = through_cgal(in, sm);
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> found;
  PMP::self_intersections(sm, std::back_inserter(found));
  Pairs cgal;
  std::vector<std::uint32_t> cgal_degenerate;
  for (const auto& [f, g] : found) {
    const auto a = static_cast<std::uint32_t>(f.idx()), b = static_cast<std::uint32_t>(g.idx());
    if (a == b) {
      cgal_degenerate.push_back(a);
    } else {
      cgal.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(cgal.begin(), cgal.end());
  std::sort(cgal_degenerate.begin(), cgal_degenerate.end());
  const SelfIntersectionResult ours = self_intersections(Model(mesh, {}, name));
  EXPECT_EQ(ours.pairs, cgal) << name;
  EXPECT_EQ(ours.degenerate_triangles, cgal_degenerate) << name;
  SelfIntersectionRequest no_cones;
  no_cones.normal_cones = false;
  EXPECT_EQ(self_intersections(Model(mesh, {}, name), no_cones).pairs, cgal) << name;
  return {mesh.triangles.size(), cgal.size(), cgal_degenerate.size()};
}

TEST(SelfAgainstCgal, AssimpModels) {
  std::size_t pairs = 0;
  for (const char* file : {"OBJ/spider.obj", "OBJ/WusonOBJ.obj", "PLY/Wuson.ply", "OFF/Wuson.off",
                           "STL/Spider_binary.stl", "STL/sphereWithHole.stl", "OBJ/box.obj",
                           "OFF/Cube.off", "STL/Wuson.stl"}) {
    const Mesh m = load_mesh(test::assimp_model(file));
    const Compared c = compare(m, file);
    // The faces left out of CGAL's mesh (those naming one vertex twice) are degenerate to antcd
    // on the mesh as loaded.
    std::vector<std::uint32_t> repeated;
    for (std::size_t f = 0; f < m.triangles.size(); ++f) {
      const auto& t = m.triangles[f];
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        repeated.push_back(static_cast<std::uint32_t>(f));
    }
    EXPECT_EQ(repeated.size(), m.triangles.size() - c.triangles) << file;
    const std::vector<std::uint32_t> degenerate =
        self_intersections(Model(m, {}, file)).degenerate_triangles;
    for (const std::uint32_t f : repeated) {
      EXPECT_TRUE(std::binary_search(degenerate.begin(), degenerate.end(), f))
          << file << " face " << f;
    }
    pairs += c.pairs;
    std::printf("%s: %zu triangles (%zu after CGAL's soup repair), %zu pairs, %zu degenerate\n",
                file, m.triangles.size(), c.triangles, c.pairs, c.degenerate);
  }
  EXPECT_GT(pairs, 0u);  // the spider's parts pass through each other
}

TEST(SelfAgainstCgal, GeneratedMeshesThatIntersectThemselves) {
  struct Case {
    const char* name;
    Mesh mesh;
    bool intersects;
  };
  Mesh duplicated = make_sphere(1, 16, 8);
  {  // every tenth face once more, on vertices of its own (a soup copy)
    const std::size_t n = duplicated.triangles.size();
    for (std::size_t t = 0; t < n; t += 10) {
      TriangleIndices copy{};
      for (int c = 0; c < 3; ++c) {
        copy[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(duplicated.vertices.size());
        duplicated.vertices.push_back(
            duplicated.vertices[duplicated.triangles[t][static_cast<std::size_t>(c)]]);
      }
      duplicated.triangles.push_back(copy);
    }
  }
  Mesh degenerate = test::flat_sheet(6, 6);
  {  // a zero-area triangle lying across the sheet, and one through it
    const auto base = static_cast<std::uint32_t>(degenerate.vertices.size());
    degenerate.vertices.insert(degenerate.vertices.end(), {{0.5, 0.5, 0},
                                                           {2.5, 2.5, 0},
                                                           {4.5, 4.5, 0},
                                                           {3.5, 1.5, -1},
                                                           {3.5, 1.5, 0},
                                                           {3.5, 1.5, 1}});
    degenerate.triangles.push_back({base, base + 1, base + 2});
    degenerate.triangles.push_back({base + 3, base + 4, base + 5});
  }
  Mesh coplanar_fan;  // coplanar triangles around one vertex whose sectors overlap
  coplanar_fan.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {4, 1, 0}, {2, 3, 0}, {-1, 3, 0}};
  coplanar_fan.triangles = {{0, 1, 2}, {0, 3, 4}, {0, 4, 5}};
  Mesh fold_pair;  // an edge-sharing pair folded flat
  fold_pair.vertices = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 0}};
  fold_pair.triangles = {{0, 1, 2}, {1, 0, 3}};
  const std::vector<Case> cases = {
      {"looped sheet", test::looped_sheet(120, 20), true},
      {"folded flat sheet", test::folded_flat_sheet(20, 8, 11), true},
      {"folded flat strip", test::folded_flat_sheet(6, 1, 3), true},
      {"pushed sphere", test::pushed_sphere(1, 0.7, 1.9), true},
      {"dented sphere (no crossing)", test::pushed_sphere(1, 0.7, 0.3), false},
      {"duplicated faces", duplicated, true},
      {"degenerate faces", degenerate, false},
      {"coplanar fan", coplanar_fan, true},
      {"fold pair", fold_pair, true},
      {"two crossing tori",
       merge({make_torus(1, 0.3, 40, 16),
              transformed(make_torus(1, 0.3, 40, 16),
                          Transform::from_axis_angle(Vec3::UnitX(), 1.5708, Vec3(0.5, 0, 0)))}),
       true},
      {"flat sheet", test::flat_sheet(40, 40), false},
      {"bent sheet", test::bent_sheet(80, 40, 3.0), false},
      {"torus", make_torus(1, 0.3, 48, 24), false},
  };
  for (const Case& c : cases) {
    const Compared got = compare(c.mesh, c.name);
    EXPECT_EQ(got.pairs > 0, c.intersects) << c.name;
    std::printf("%s: %zu triangles, %zu pairs, %zu degenerate\n", c.name, c.mesh.triangles.size(),
                got.pairs, got.degenerate);
  }
}

/// Two triangles as one mesh: pair (0, 1) reported or not.
bool reported(const std::vector<Vec3>& v, TriangleIndices a, TriangleIndices b) {
  Mesh m;
  m.vertices = v;
  m.triangles = {a, b};
  return !self_intersections(Model(m)).pairs.empty();
}

/// The sharing rule decided by CGAL's exact predicates, pair by pair: edge-sharing (u, v, p),
/// (v, u, q) intersect iff coplanar with p, q on one side of uv; vertex-sharing (w, a1, a2),
/// (w, b1, b2) iff an edge opposite w meets the other triangle; otherwise do_intersect.
TEST(SelfAgainstCgal, AdjacentAndNearCoplanarPairsOneByOne) {
  using P = K::Point_3;
  const auto pt = [](const Vec3& x) { return P(x.x(), x.y(), x.z()); };
  std::mt19937_64 rng(36);
  std::uniform_int_distribution<int> grid(-4, 4);
  std::size_t seen[3][2] = {};  // [shared edge, shared vertex, none][verdict]
  for (int round = 0; round < 3000; ++round) {
    // Six points on a small integer grid of the plane z = 0 (exactly coplanar), or that plane
    // turned and moved (coplanar up to rounding: near the floating-point certificates' bounds),
    // or with one point lifted a little off it.
    const int kind = round % 3;
    const Transform pose = test::random_pose(rng, 3);
    std::vector<Vec3> g(6), v(6);
    for (std::size_t k = 0; k < 6; ++k) {
      g[k] = Vec3(grid(rng), grid(rng), 0);
      v[k] = kind == 0 ? g[k] : pose.apply(g[k]);
    }
    if (kind == 2) v[static_cast<std::size_t>(round % 6)] += Vec3(0, 0, 1e-9);
    // Triangles of area at least 1/2 on the grid (so far from degenerate after the turn).
    const auto area = [&](int a, int b, int c) {
      return CGAL::collinear(pt(g[static_cast<std::size_t>(a)]), pt(g[static_cast<std::size_t>(b)]),
                             pt(g[static_cast<std::size_t>(c)]));
    };
    // Edge 0-1 shared by (0, 1, 2) and (1, 0, 3).
    if (!area(0, 1, 2) && !area(1, 0, 3)) {
      const bool cgal =
          CGAL::coplanar(pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3])) &&
          CGAL::coplanar_orientation(pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3])) == CGAL::POSITIVE;
      EXPECT_EQ(reported(v, {0, 1, 2}, {1, 0, 3}), cgal) << "edge pair, round " << round;
      ++seen[0][cgal];
    }
    // Vertex 0 shared by (0, 1, 2) and (0, 3, 4).
    if (!area(0, 1, 2) && !area(0, 3, 4)) {
      const K::Triangle_3 ta(pt(v[0]), pt(v[1]), pt(v[2])), tb(pt(v[0]), pt(v[3]), pt(v[4]));
      const bool cgal = CGAL::do_intersect(K::Segment_3(pt(v[1]), pt(v[2])), tb) ||
                        CGAL::do_intersect(K::Segment_3(pt(v[3]), pt(v[4])), ta);
      EXPECT_EQ(reported(v, {0, 1, 2}, {0, 3, 4}), cgal) << "vertex pair, round " << round;
      ++seen[1][cgal];
    }
    // No shared index: (0, 1, 2) and (3, 4, 5).
    if (!area(0, 1, 2) && !area(3, 4, 5)) {
      const bool cgal = CGAL::do_intersect(K::Triangle_3(pt(v[0]), pt(v[1]), pt(v[2])),
                                           K::Triangle_3(pt(v[3]), pt(v[4]), pt(v[5])));
      EXPECT_EQ(reported(v, {0, 1, 2}, {3, 4, 5}), cgal) << "separate pair, round " << round;
      ++seen[2][cgal];
    }
  }
  // Both verdicts met in every case, often.
  for (const auto& s : seen) {
    EXPECT_GT(s[0], 100u);
    EXPECT_GT(s[1], 100u);
  }
  std::printf("edge pairs %zu/%zu, vertex pairs %zu/%zu, separate pairs %zu/%zu (apart/meeting)\n",
              seen[0][0], seen[0][1], seen[1][0], seen[1][1], seen[2][0], seen[2][1]);
}

/// Slivers whose free corner lies so near the shared edge's line that the floating-point 2-D
/// orientation of the certificates (pair_test.cpp) gets its side wrong: the certificates must then
/// defer to the exact predicates (their error bounds), or a coplanar pair folded onto itself, or
/// two overlapping wedges at a shared vertex, would be called apart. The plane is z = 0 (exactly
/// coplanar); corners on a grid of ulps around a point of the line y = x.
TEST(SelfAgainstCgal, SliversWhoseFloatingPointSidesAreWrong) {
  using P = K::Point_3;
  using P2 = K::Point_2;
  const Vec3 v(12, 12, 0), p(24, 24, 0);
  // The sign the certificates compute in floating point for corner p against the line u -> v
  // (differences from u, then one cross product): the value their bound guards.
  const auto float_side = [&](const Vec3& u) {
    const double value = (v.x() - u.x()) * (p.y() - u.y()) - (v.y() - u.y()) * (p.x() - u.x());
    return (value > 0) - (value < 0);
  };
  const auto exact_side = [&](const Vec3& u) {
    const CGAL::Orientation o =
        CGAL::orientation(P2(u.x(), u.y()), P2(v.x(), v.y()), P2(p.x(), p.y()));
    return o == CGAL::LEFT_TURN ? 1 : o == CGAL::RIGHT_TURN ? -1 : 0;
  };
  const double e = std::nextafter(0.5, 1.0) - 0.5;
  std::size_t wrong = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const Vec3 u(0.5 + i * e, 0.5 + j * e, 0);
      const int s = exact_side(u);
      if (s == 0 || float_side(u) != -s) continue;  // the opposite side in floating point
      ++wrong;
      // q on p's exact side, far from the line: (u, v, p) and (v, u, q) are folded flat.
      const Vec3 q = s > 0 ? Vec3(0, 6, 0) : Vec3(6, 0, 0);
      const std::vector<Vec3> edge_pair = {u, v, p, q};
      EXPECT_TRUE(reported(edge_pair, {0, 1, 2}, {1, 0, 3}))
          << "edge pair, u = grid " << i << ", " << j;
      // Vertex u shared by (u, v, a2) and (u, p, b2): p lies in the first wedge or not as its
      // exact side says, a2 and b2 well on either side of the line.
      const Vec3 a2 = s > 0 ? Vec3(-6, 0, 0) : Vec3(0, -6, 0);
      const Vec3 b2 = s > 0 ? Vec3(6, 0, 0) : Vec3(0, 6, 0);
      const std::vector<Vec3> vertex_pair = {u, v, a2, p, b2};
      const auto pt = [](const Vec3& x) { return P(x.x(), x.y(), x.z()); };
      const K::Triangle_3 ta(pt(u), pt(v), pt(a2)), tb(pt(u), pt(p), pt(b2));
      const bool cgal = CGAL::do_intersect(K::Segment_3(pt(v), pt(a2)), tb) ||
                        CGAL::do_intersect(K::Segment_3(pt(p), pt(b2)), ta);
      EXPECT_EQ(reported(vertex_pair, {0, 1, 2}, {0, 3, 4}), cgal)
          << "vertex pair, u = grid " << i << ", " << j;
    }
  }
  // The grid holds corners whose floating-point side is wrong (else this test tests nothing).
  EXPECT_GT(wrong, 20u);
  std::printf("%zu corners with a wrong floating-point side\n", wrong);
}

}  // namespace
}  // namespace antcd
