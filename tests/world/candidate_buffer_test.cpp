// World::candidate_pairs into a reused buffer (the scene runner's call every frame) answers what
// the allocating call does, frame after frame, with stale content and storage from earlier frames.
#include <antcd/geometry.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

ObjectId ids_stale() { return ObjectId{7, 3}; }

// Frames that move a few objects a little (the tree's removal and insertion path), most of them
// (the refit path) and some across the world (jumps): two worlds given the same poses agree on
// every query, and the buffered call equals candidate_pairs with the buffers of earlier frames.
TEST(WorldCandidateBuffer, ReusedBufferAnswersAsTheAllocatingCall) {
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
  std::vector<ObjectPair> out{{ids_stale(), ids_stale()}};  // stale content: cleared by the call
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
    unchecked.set_poses(moved, moved_poses);
    for (const Scalar delta : {0.0, 0.04}) {
      const std::vector<ObjectPair> expected = checked.candidate_pairs(delta);
      ASSERT_EQ(unchecked.candidate_pairs(delta), expected) << "frame " << frame;
      unchecked.candidate_pairs(delta, out);
      ASSERT_EQ(out, expected) << "frame " << frame << " delta " << delta;
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
