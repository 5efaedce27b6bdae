// SamplingOptions::triangle_masks: the feature spaces leave out the leaf pairs that the exact
// query's traversal culls triangle by triangle. Checked to drop leaf pairs (the switch changes
// the search) and never a triangle pair within delta: with every candidate sampled, the masked and
// unmasked spaces hold the same colliding pairs, and as many as collide() reports.
#include <antcd/collide.hpp>
#include <antcd/load.hpp>
#include <antcd/random.hpp>

#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace antcd {
namespace {

struct Tally {
  std::uint64_t dropped = 0;
  int colliding = 0;
  int separate_at_once = 0;  // no leaf pair left by the masks, while the volumes overlap
};

void compare_spaces(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                    Scalar delta, const std::string& what, Tally& tally) {
  SamplingOptions masked;
  masked.samples_per_side = 1'000'000;  // every candidate: the spaces are complete
  masked.delta = delta;
  SamplingOptions plain = masked;
  plain.triangle_masks = false;
  const FeatureSpace on = build_feature_space(a, pa, b, pb, masked, 7);
  const FeatureSpace off = build_feature_space(a, pa, b, pb, plain, 7);
  ASSERT_LE(on.leaf_pairs, off.leaf_pairs) << what;
  tally.dropped += off.leaf_pairs - on.leaf_pairs;
  if (on.leaf_pairs == 0 && off.leaf_pairs > 0) ++tally.separate_at_once;

  CollisionRequest all;
  all.delta = delta;
  all.all_contacts = true;
  const CollisionResult truth = collide(a, pa, b, pb, all);
  tally.colliding += truth.colliding ? 1 : 0;
  const std::uint64_t with_masks = on.leaf_pairs == 0 ? 0 : count_colliding(on);
  const std::uint64_t without = off.leaf_pairs == 0 ? 0 : count_colliding(off);
  EXPECT_EQ(with_masks, without) << what;
  EXPECT_EQ(with_masks, truth.contacts.size()) << what;
}

TEST(TriangleMasks, DropLeafPairsButNoTrianglePairWithinDeltaOnGeneratedShapes) {
  // A coarse box (leaves of big triangles) against a small fine sphere near its surface, as in
  // ExactCollide.LargeLeavesAroundASmallMeshMatchBruteForce.
  const Model box(make_box(Vec3(1.0, 0.7, 0.5), 2), {}, "coarse box");
  const Model sphere(make_sphere(0.06, 16, 8), {}, "small sphere");
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  Tally tally;
  const int poses = 120;
  for (int i = 0; i < poses; ++i) {
    const int axis = static_cast<int>(rng() % 3);
    const Vec3 half(1.0, 0.7, 0.5);
    Vec3 c(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
    c[axis] = (u(rng) < 0 ? -1 : 1) * (half[axis] + 0.09 * u(rng));
    Transform pb = test::random_pose(rng, 0.0);
    pb.translation = c;
    for (const Scalar delta : {0.0, 0.02}) {
      const std::string what = "pose " + std::to_string(i) + " delta " + std::to_string(delta);
      compare_spaces(box, Transform::identity(), sphere, pb, delta, what, tally);
      compare_spaces(sphere, pb, box, Transform::identity(), delta, what + " swapped", tally);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(tally.dropped, 0u);
  EXPECT_GT(tally.separate_at_once, 0);
  EXPECT_GT(tally.colliding, poses / 5);
}

TEST(TriangleMasks, DropLeafPairsButNoTrianglePairWithinDeltaOnRealMeshes) {
  // The case that motivated them: assimp's spider (about 65 units across) and the Wuson (about 3)
  // placed at the spider's vertices, where the spider's leaves of big triangles swallow it.
  const Model spider(load_mesh(test::assimp_model("OBJ/spider.obj")), {}, "spider");
  const Model wuson(load_mesh(test::assimp_model("PLY/Wuson.ply")), {}, "Wuson");
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  Tally tally;
  const int poses = 60;
  for (int i = 0; i < poses; ++i) {
    const Vec3& v = spider.mesh().vertices[rng() % spider.mesh().vertices.size()];
    Transform pb = test::random_pose(rng, 0.0);
    pb.translation = v + 1.5 * Vec3(u(rng), u(rng), u(rng));
    const std::string what = "pose " + std::to_string(i);
    compare_spaces(spider, Transform::identity(), wuson, pb, 0.0, what, tally);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(tally.dropped, 0u);
  EXPECT_GT(tally.colliding, poses / 10);
}

}  // namespace
}  // namespace antcd
