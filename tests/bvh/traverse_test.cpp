// Preliminary detection: the dual traversal reports exactly what it should.
#include <antcd/bvh.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "support/test_support.hpp"

namespace antcd {
namespace {

std::vector<std::uint32_t> leaves_of(const Model& m) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < m.nodes().size(); ++i) {
    if (m.nodes()[i].is_leaf()) out.push_back(i);
  }
  return out;
}

bool leaf_triangles_within(const Model& a, std::uint32_t la, const Transform& pa, const Model& b,
                           std::uint32_t lb, const Transform& pb, Scalar delta) {
  const BvhNode& na = a.nodes()[la];
  const BvhNode& nb = b.nodes()[lb];
  const LeafCorners va = a.leaf_corners();
  const LeafCorners vb = b.leaf_corners();
  for (std::uint32_t i = na.first_or_right; i < na.first_or_right + na.count; ++i) {
    for (std::uint32_t j = nb.first_or_right; j < nb.first_or_right + nb.count; ++j) {
      if (geometry::triangles_within(pa.apply(va(i, 0)), pa.apply(va(i, 1)), pa.apply(va(i, 2)),
                                     pb.apply(vb(j, 0)), pb.apply(vb(j, 1)), pb.apply(vb(j, 2)),
                                     delta)) {
        return true;
      }
    }
  }
  return false;
}

bool leaf_volumes_within(const Model& a, std::uint32_t la, const Transform& pa, const Model& b,
                         std::uint32_t lb, const Transform& pb, Scalar delta) {
  // Generous: the traversal widens its tests by a tiny rounding allowance.
  const Scalar slack = delta + 1e-6;
  const BvhNode& na = a.nodes()[la];
  const BvhNode& nb = b.nodes()[lb];
  const Sphere sa{pa.apply(na.center), na.radius};
  const Sphere sb{pb.apply(nb.center), nb.radius};
  Obb oa = na.obb();
  oa.center = pa.apply(oa.center);
  oa.axes = pa.rotation * oa.axes;
  Obb ob = nb.obb();
  ob.center = pb.apply(ob.center);
  ob.axes = pb.rotation * ob.axes;
  return geometry::sphere_overlap(sa, sb, slack) && geometry::obb_overlap(oa, ob, slack);
}

TEST(Traversal, ReportsEveryLeafPairInContactAndOnlyOverlappingOnes) {
  const Model b(load_mesh(test::assimp_model("OBJ/spider.obj")), {5});
  const Scalar r = b.root().radius;  // size the torus like the spider
  const Model a(make_torus(0.7 * r, 0.2 * r, 32, 12), {3});
  std::mt19937_64 rng(9);
  const auto leaves_a = leaves_of(a);
  const auto leaves_b = leaves_of(b);
  int with_contacts = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Scalar delta = trial % 2 == 0 ? 0.0 : 0.05 * b.root().radius;
    const Transform pa = test::random_pose(rng, 0.0);
    Transform pb = test::random_pose(rng, 0.8 * b.root().radius);
    pb.translation -= pb.rotation * b.root().center;
    std::vector<LeafPair> pairs;
    const TraversalStats stats = overlapping_leaves(a, pa, b, pb, delta, pairs);
    EXPECT_EQ(stats.leaf_pairs, pairs.size());
    EXPECT_GE(stats.node_pairs, stats.sphere_rejects + stats.obb_rejects + stats.leaf_pairs);
    std::set<std::pair<std::uint32_t, std::uint32_t>> reported;
    for (const LeafPair& p : pairs) {
      ASSERT_TRUE(a.nodes()[p.node_a].is_leaf());
      ASSERT_TRUE(b.nodes()[p.node_b].is_leaf());
      EXPECT_TRUE(reported.insert({p.node_a, p.node_b}).second) << "pair reported twice";
      EXPECT_TRUE(leaf_volumes_within(a, p.node_a, pa, b, p.node_b, pb, delta));
    }
    for (const std::uint32_t la : leaves_a) {
      for (const std::uint32_t lb : leaves_b) {
        if (leaf_triangles_within(a, la, pa, b, lb, pb, delta)) {
          ++with_contacts;
          EXPECT_TRUE(reported.count({la, lb})) << "missed leaf pair in contact";
        }
      }
    }
  }
  EXPECT_GT(with_contacts, 0);
}

TEST(Traversal, CullsFarApartModelsAtTheRoot) {
  const Model a(make_sphere(1.0, 16, 8));
  Transform far;
  far.translation = Vec3(10, 0, 0);
  std::vector<LeafPair> pairs;
  const TraversalStats s = overlapping_leaves(a, {}, a, far, 0.0, pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_EQ(s.node_pairs, 1u);
  EXPECT_EQ(s.sphere_rejects, 1u);
  // A delta larger than the gap brings leaf pairs back.
  overlapping_leaves(a, {}, a, far, 8.5, pairs);
  EXPECT_FALSE(pairs.empty());
}

TEST(Traversal, ObbTestCullsWhatSpheresCannot) {
  // Two long thin boxes, parallel and close: spheres overlap everywhere, boxes do not.
  const Model a(make_box(Vec3(5, 0.1, 0.1), 8), {2});
  Transform pb;
  pb.translation = Vec3(0, 0.5, 0);
  std::vector<LeafPair> pairs;
  const TraversalStats s = overlapping_leaves(a, {}, a, pb, 0.0, pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_GT(s.obb_rejects, 0u);
}

}  // namespace
}  // namespace antcd
