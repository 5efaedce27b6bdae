// self_intersections and self_proximity (antcd/self.hpp) on hand-made pairs with known answers,
// generated sheets and closed shapes: the traversal against all pairs, the cone cull against no
// cull, thread counts, refit, first-only and proximity against brute force.
#include <antcd/self.hpp>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <set>
#include <vector>

#include "self/pair_test.hpp"
#include "self/self_meshes.hpp"

namespace antcd {
namespace {

using Pairs = std::vector<std::array<std::uint32_t, 2>>;

Mesh two(const std::vector<Vec3>& v, TriangleIndices a, TriangleIndices b) {
  Mesh m;
  m.vertices = v;
  m.triangles = {a, b};
  return m;
}

Pairs pairs_of(const Mesh& m, bool cones = true) {
  SelfIntersectionRequest r;
  r.normal_cones = cones;
  return self_intersections(Model(m), r).pairs;
}

/// Every pair of non-degenerate triangles through the exact pair test: what the traversal must
/// find (checks the traversal and the culls, not the verdicts; those are checked against CGAL).
Pairs all_pairs(const Mesh& m) {
  std::vector<bool> degenerate(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    degenerate[t] =
        self_detail::normal_signs(m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]]) == 0;
  }
  Pairs out;
  for (std::uint32_t i = 0; i < m.triangles.size(); ++i) {
    for (std::uint32_t j = i + 1; j < m.triangles.size(); ++j) {
      int shared = 0;
      if (!degenerate[i] && !degenerate[j] && self_detail::pair_intersects(m, i, j, shared)) {
        out.push_back({i, j});
      }
    }
  }
  return out;
}

TEST(SelfPairs, EdgeSharingPairFoldedFlatIntersects) {
  // (0,1,2) and (1,0,3) share the edge 0-1; 3 on 2's side of it in the same plane.
  const Mesh flat = two({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 0}}, {0, 1, 2}, {1, 0, 3});
  EXPECT_EQ(pairs_of(flat), (Pairs{{0, 1}}));
  const Mesh opened = two({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -2, 0}}, {0, 1, 2}, {1, 0, 3});
  EXPECT_TRUE(pairs_of(opened).empty());
  // Bent about the shared edge at a small angle: they meet on the edge only.
  const Mesh bent = two({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 1e-9}}, {0, 1, 2}, {1, 0, 3});
  EXPECT_TRUE(pairs_of(bent).empty());
}

TEST(SelfPairs, CoplanarOverlapSharingAVertex) {
  // Two coplanar triangles at vertex 0 whose angular sectors overlap.
  const Mesh overlap =
      two({{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {4, 1, 0}, {2, 3, 0}}, {0, 1, 2}, {0, 3, 4});
  EXPECT_EQ(pairs_of(overlap), (Pairs{{0, 1}}));
  // Sectors touching at the vertex only (one on each side of it).
  const Mesh touch =
      two({{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {-4, 0, 0}, {-4, -2, 0}}, {0, 1, 2}, {0, 3, 4});
  EXPECT_TRUE(pairs_of(touch).empty());
  // Sharing a ray: an edge of one along an edge of the other, same direction.
  const Mesh ray =
      two({{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {2, 0, 0}, {2, -1, 0}}, {0, 1, 2}, {0, 4, 3});
  EXPECT_EQ(pairs_of(ray), (Pairs{{0, 1}}));
  // One folding through the other at the shared vertex.
  const Mesh through =
      two({{0, 0, 0}, {4, -1, 0}, {4, 1, 0}, {3, 0, -1}, {3, 0, 1}}, {0, 1, 2}, {0, 3, 4});
  EXPECT_EQ(pairs_of(through), (Pairs{{0, 1}}));
  // Meeting at the vertex only, not coplanar.
  const Mesh apart =
      two({{0, 0, 0}, {4, -1, 0}, {4, 1, 0}, {-3, 0, -1}, {-3, 0, 1}}, {0, 1, 2}, {0, 3, 4});
  EXPECT_TRUE(pairs_of(apart).empty());
}

TEST(SelfPairs, DuplicatedFacesAndCoincidentUnsharedVertices) {
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(pairs_of(two(v, {0, 1, 2}, {0, 1, 2})), (Pairs{{0, 1}}));
  EXPECT_EQ(pairs_of(two(v, {0, 1, 2}, {0, 2, 1})), (Pairs{{0, 1}}));
  // The same geometry without shared indices (a soup): two triangles touching along an edge
  // count, because nothing is shared by index.
  const Mesh soup = two({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {2, 0, 0}, {0, 0, 0}, {1, -1, 0}},
                        {0, 1, 2}, {3, 4, 5});
  EXPECT_EQ(pairs_of(soup), (Pairs{{0, 1}}));
}

TEST(SelfPairs, DegenerateTrianglesAreListedAndPairedWithNothing) {
  // Triangle 1 is a zero-area sliver (collinear corners) lying across triangle 0.
  Mesh m;
  m.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 0.5, 0}, {1, 0.5, 0}, {3, 0.5, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const SelfIntersectionResult r = self_intersections(Model(m));
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_EQ(r.degenerate_triangles, (std::vector<std::uint32_t>{1}));
}

TEST(SelfSheets, IntersectionFreeMeshesGiveNoPairs) {
  for (const Mesh& m :
       {test::flat_sheet(30, 20), test::bent_sheet(60, 30, 3.0), make_sphere(1, 32, 16),
        make_torus(1, 0.3, 40, 20), make_box(Vec3(1, 2, 3), 4)}) {
    const SelfIntersectionResult r = self_intersections(Model(m));
    EXPECT_FALSE(r.intersecting);
    EXPECT_TRUE(r.pairs.empty());
    EXPECT_TRUE(r.degenerate_triangles.empty());
  }
}

TEST(SelfSheets, ConeCullSkipsASmoothSheetWhole) {
  const SelfIntersectionResult r = self_intersections(Model(test::bent_sheet(100, 100, 2.0)));
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_EQ(r.stats.cone_culled, 1u);  // the root
  EXPECT_EQ(r.stats.triangle_pairs, 0u);
  // A sheet bent past a half turn has no axis all its normals face: no cull at the root.
  const SelfIntersectionResult c = self_intersections(Model(test::bent_sheet(100, 100, 4.0)));
  EXPECT_TRUE(c.pairs.empty());
  EXPECT_GT(c.stats.triangle_pairs, 0u);
}

TEST(SelfSheets, TraversalFindsEveryPairWithAndWithoutCones) {
  const std::vector<Mesh> meshes = {
      test::looped_sheet(80, 12), test::folded_flat_sheet(16, 6, 9),
      test::pushed_sphere(1, 0.7, 1.9),
      merge({test::bent_sheet(20, 10, 1.0),
             transformed(test::bent_sheet(20, 10, 1.0),
                         Transform::from_axis_angle(Vec3::UnitX(), 0.3, Vec3(0, 0.5, 0)))})};
  for (const Mesh& m : meshes) {
    const Pairs expected = all_pairs(m);
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(pairs_of(m, true), expected);
    EXPECT_EQ(pairs_of(m, false), expected);
  }
}

TEST(SelfSheets, FoldedFlatSheetReportsTheFoldEdgePairs) {
  // Folded about column 3 of a 6 x 1 strip: triangle 4 ((2,0), (3,0), (3,1)) and triangle 7
  // ((3,0), (4,1), (3,1), vertex (4,1) mirrored onto (2,1)) share the fold edge and lie flat on
  // each other, their third corners on one side of it.
  const Mesh m = test::folded_flat_sheet(6, 1, 3);
  const Pairs p = pairs_of(m);
  const std::array<std::uint32_t, 2> fold{4, 7};
  int shared = 0;
  EXPECT_TRUE(self_detail::pair_intersects(m, 4, 7, shared));
  EXPECT_EQ(shared, 2);
  EXPECT_NE(std::find(p.begin(), p.end(), fold), p.end());
}

TEST(SelfSheets, SameAnswerAtEveryThreadCount) {
  const Model model(test::looped_sheet(200, 40));
  const SelfIntersectionResult many = self_intersections(model);
  for (const int threads : {1, 2, 3}) {
    tbb::task_arena arena(threads);
    const SelfIntersectionResult r = arena.execute([&] { return self_intersections(model); });
    EXPECT_EQ(r.pairs, many.pairs);
    EXPECT_EQ(r.stats.triangle_pairs, many.stats.triangle_pairs);
    EXPECT_EQ(r.stats.node_pairs, many.stats.node_pairs);
    EXPECT_EQ(r.stats.cone_culled, many.stats.cone_culled);
  }
}

TEST(SelfSheets, FirstOnlyStopsAtAPairOfTheFullSet) {
  const Model model(test::looped_sheet(100, 20));
  const SelfIntersectionResult all = self_intersections(model);
  SelfIntersectionRequest first;
  first.first_only = true;
  const SelfIntersectionResult one = self_intersections(model, first);
  ASSERT_EQ(one.pairs.size(), 1u);
  EXPECT_TRUE(one.intersecting);
  EXPECT_NE(std::find(all.pairs.begin(), all.pairs.end(), one.pairs[0]), all.pairs.end());
  EXPECT_LT(one.stats.triangle_pairs, all.stats.triangle_pairs);
}

TEST(SelfSheets, RefitAnswersAsAFreshModel) {
  Model model(test::bent_sheet(60, 20, 1.0));
  EXPECT_TRUE(self_intersections(model).pairs.empty());
  const Mesh looped = test::looped_sheet(60, 20);
  model.refit(looped.vertices);
  EXPECT_EQ(self_intersections(model).pairs, self_intersections(Model(looped)).pairs);
  EXPECT_FALSE(self_intersections(model).pairs.empty());
}

TEST(SelfSheets, RebuildRuleAndNothingChangesOnError) {
  Model model(test::bent_sheet(60, 20, 1.0));
  const std::vector<Vec3> before = model.mesh().vertices;
  EXPECT_EQ(model.refit_growth(), 1.0);
  std::vector<Vec3> bad = test::looped_sheet(60, 20).vertices;
  bad[7] = Vec3(std::nan(""), 0, 0);
  EXPECT_THROW(model.refit(bad), ArgumentError);
  EXPECT_THROW(model.refit(std::vector<Vec3>(3, Vec3::Zero())), ArgumentError);
  EXPECT_THROW(model.refit(test::looped_sheet(60, 20).vertices, -1), ArgumentError);
  EXPECT_EQ(model.mesh().vertices, before);
  // The loop moves vertices far from where the tree grouped them: the refitted boxes loosen.
  const Mesh looped = test::looped_sheet(60, 20);
  EXPECT_FALSE(model.refit(looped.vertices));
  const double growth = model.refit_growth();
  EXPECT_GT(growth, 1.0);
  EXPECT_TRUE(model.refit(looped.vertices, 0.5 * (1 + growth)));  // past the threshold: rebuilt
  EXPECT_EQ(model.refit_growth(), 1.0);
  EXPECT_EQ(model.stats().nodes, Model(looped).stats().nodes);
  EXPECT_EQ(self_intersections(model).pairs, self_intersections(Model(looped)).pairs);
  model.rebuild();
  EXPECT_EQ(self_intersections(model).pairs, self_intersections(Model(looped)).pairs);
}

// ---- self_proximity against brute force over all primitive pairs ----

struct Brute {
  std::set<std::pair<std::uint32_t, std::uint32_t>> vt;
  std::set<std::pair<std::array<std::uint32_t, 2>, std::array<std::uint32_t, 2>>> ee;
};

Brute brute_proximity(const Mesh& m, Scalar delta) {
  Brute b;
  std::set<std::array<std::uint32_t, 2>> edges;
  for (const auto& t : m.triangles) {
    for (int c = 0; c < 3; ++c) {
      const auto x = t[static_cast<std::size_t>(c)], y = t[static_cast<std::size_t>((c + 1) % 3)];
      if (x != y) edges.insert({std::min(x, y), std::max(x, y)});
    }
  }
  for (std::uint32_t p = 0; p < m.vertices.size(); ++p) {
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tri = m.triangles[t];
      if (tri[0] == p || tri[1] == p || tri[2] == p) continue;
      if (geometry::point_triangle_distance_squared(m.vertices[p], m.vertices[tri[0]],
                                                    m.vertices[tri[1]],
                                                    m.vertices[tri[2]]) <= delta * delta) {
        b.vt.insert({p, t});
      }
    }
  }
  for (auto i = edges.begin(); i != edges.end(); ++i) {
    for (auto j = std::next(i); j != edges.end(); ++j) {
      const auto& e = *i;
      const auto& f = *j;
      if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
      if (geometry::segment_segment_distance_squared(m.vertices[e[0]], m.vertices[e[1]],
                                                     m.vertices[f[0]],
                                                     m.vertices[f[1]]) <= delta * delta) {
        b.ee.insert({e, f});
      }
    }
  }
  return b;
}

TEST(SelfProximity, EqualsBruteForce) {
  const std::vector<Mesh> meshes = {test::looped_sheet(40, 8), test::bent_sheet(30, 10, 5.5),
                                    test::pushed_sphere(1, 0.7, 1.9), make_torus(1, 0.2, 30, 8)};
  for (const Mesh& m : meshes) {
    for (const Scalar delta : {0.0, 0.02, 0.1}) {
      const SelfProximityResult r = self_proximity(Model(m), delta);
      const Brute b = brute_proximity(m, delta);
      Brute got;
      for (const SelfProximityPair& p : r.pairs) {
        if (p.kind == SelfProximityPair::Kind::vertex_triangle) {
          got.vt.insert({p.a, p.b});
          EXPECT_LE(p.distance, delta);
          EXPECT_NEAR((p.point_a - p.point_b).norm(), p.distance, 1e-12);
        } else {
          EXPECT_LT(p.a, p.b);
          got.ee.insert({r.edges[p.a], r.edges[p.b]});
          EXPECT_LE(p.distance, delta);
          EXPECT_NEAR((p.point_a - p.point_b).norm(), p.distance, 1e-12);
        }
      }
      EXPECT_EQ(got.vt, b.vt) << "delta " << delta;
      EXPECT_EQ(got.ee, b.ee) << "delta " << delta;
      EXPECT_EQ(got.vt.size() + got.ee.size(), r.pairs.size());  // no pair twice
    }
  }
}

TEST(SelfProximity, RejectsABadDelta) {
  const Model model(test::flat_sheet(3, 3));
  EXPECT_THROW(self_proximity(model, -1), ArgumentError);
  EXPECT_THROW(self_proximity(model, std::nan("")), ArgumentError);
  try {
    (void)self_proximity(model, -2);
    FAIL() << "a negative delta must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("delta must be finite and >= 0, got -2"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace antcd
