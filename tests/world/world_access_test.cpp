// The scene runner's World entries (src/world/world_access.hpp): set_checked_poses leaves the World
// as set_poses does, and candidate_slots answers candidate_pairs' pairs, with reused buffers.
#include <antcd/geometry.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "support/test_support.hpp"
#include "world/world_access.hpp"

namespace antcd {
namespace {

using SlotPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

SlotPairs slots_of(const std::vector<ObjectPair>& pairs) {
  SlotPairs out;
  for (const ObjectPair& p : pairs) out.emplace_back(p.a.slot, p.b.slot);
  return out;
}

// Frames that move a few objects a little (the tree's removal and insertion path), most of them
// (the refit path) and some across the world (jumps): the checked and unchecked worlds agree on
// every query, and candidate_slots equals candidate_pairs with the buffers of earlier frames.
TEST(WorldAccess, UncheckedPosesAndSlotPairsMatchThePublicCalls) {
  const std::vector<std::shared_ptr<const Model>> models = {
      std::make_shared<const Model>(make_sphere(0.5, 12, 6)),
      std::make_shared<const Model>(make_box(Vec3(0.6, 0.2, 0.3), 2)),
      std::make_shared<const Model>(make_torus(0.5, 0.15, 16, 8))};
  constexpr int kObjects = 48;
  std::mt19937_64 rng(29);
  World checked;
  World unchecked;
  std::vector<ObjectId> ids;
  std::vector<Transform> poses;
  for (int i = 0; i < kObjects; ++i) {
    poses.push_back(test::random_pose(rng, 3.0));
    ids.push_back(checked.add(models[i % models.size()], poses.back()));
    ASSERT_EQ(unchecked.add(models[i % models.size()], poses.back()), ids.back());
  }
  SlotPairs out{{7, 9}};  // stale content: cleared by the call
  SlotPairs scratch{{1, 2}, {3, 4}};
  std::size_t total = 0;
  for (int frame = 0; frame < 24; ++frame) {
    std::vector<ObjectId> moved;
    std::vector<Transform> moved_poses;
    const int kind = frame % 3;  // 0: a few small moves, 1: most objects, 2: some jump
    std::uniform_real_distribution<Scalar> small(-0.05, 0.05);
    for (int i = 0; i < kObjects; ++i) {
      if (kind == 0 && i % 9 != 0) continue;
      if (kind == 1 && i % 5 == 0) continue;
      Transform p = poses[i];
      if (kind == 2 && i % 4 == 0) {
        p = test::random_pose(rng, 3.0);
      } else {
        p.translation += Vec3(small(rng), small(rng), small(rng));
      }
      poses[i] = p;
      moved.push_back(ids[i]);
      moved_poses.push_back(p);
    }
    checked.set_poses(moved, moved_poses);
    detail::WorldAccess::set_checked_poses(unchecked, moved, moved_poses);
    for (const Scalar delta : {0.0, 0.04}) {
      const std::vector<ObjectPair> expected = checked.candidate_pairs(delta);
      ASSERT_EQ(unchecked.candidate_pairs(delta), expected) << "frame " << frame;
      detail::WorldAccess::candidate_slots(unchecked, delta, out, scratch);
      ASSERT_EQ(out, slots_of(expected)) << "frame " << frame << " delta " << delta;
      ASSERT_EQ(checked.collide_all({delta}).size(), unchecked.collide_all({delta}).size());
      total += expected.size();
    }
    for (int i = 0; i < kObjects; ++i) {
      ASSERT_EQ(unchecked.pose(ids[i]).translation, poses[i].translation);
    }
  }
  EXPECT_GT(total, 100u);  // the frames have pairs to compare
}

}  // namespace
}  // namespace antcd
