// A pose both models share never changes a query's answer: two triangles that touch exactly
// (a shared vertex, a shared edge, a vertex on the other's edge) are reported touching under any
// shared random pose, by collide(), distance() and the World alike. The relative placement of two
// poses with bitwise-equal rotations has the exact identity rotation (bvh/traverse.hpp
// relative_pose).
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "bvh/traverse.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

std::shared_ptr<const Model> triangle_model(const Vec3& p, const Vec3& q, const Vec3& r) {
  Mesh m;
  m.vertices = {p, q, r};
  m.triangles = {{0, 1, 2}};
  return std::make_shared<const Model>(std::move(m));
}

struct TouchingPair {
  const char* what;
  std::array<Vec3, 3> a;
  std::array<Vec3, 3> b;
};

// Each pair touches exactly in its model frame (coordinates chosen so the contact point is exact).
const TouchingPair kTouching[] = {
    {"shared vertex",
     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
     {Vec3(0, 0, 0), Vec3(-1, 0, 0.5), Vec3(0, -1, 0.25)}},
    {"shared edge",
     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 0.75)}},
    {"vertex on edge",
     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
     {Vec3(0.5, 0, 0), Vec3(0.25, -1, 0.5), Vec3(0.75, -1, -0.5)}},
    {"vertex on face",
     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
     {Vec3(0.25, 0.25, 0), Vec3(0.25, 1, 1), Vec3(1, 0.25, 1)}},
};

TEST(SharedPose, TouchingTrianglesTouchUnderEveryRandomSharedPose) {
  std::mt19937_64 rng(28);
  CollisionRequest first;
  first.max_contacts = 1;
  for (const TouchingPair& pair : kTouching) {
    const auto a = triangle_model(pair.a[0], pair.a[1], pair.a[2]);
    const auto b = triangle_model(pair.b[0], pair.b[1], pair.b[2]);
    ASSERT_TRUE(collide(*a, Transform::identity(), *b, Transform::identity(), first).colliding)
        << pair.what;
    int missed_collide = 0;
    int missed_distance = 0;
    int missed_world = 0;
    int missed_model = 0;
    const int trials = 200;
    for (int trial = 0; trial < trials; ++trial) {
      const Transform pose = test::random_pose(rng, 10);
      if (!collide(*a, pose, *b, pose, first).colliding) ++missed_collide;
      if (distance(*a, pose, *b, pose).distance != 0) ++missed_distance;
      World world;
      const ObjectId ia = world.add(a, pose);
      world.add(b, pose);
      if (world.collide_all(first).size() != 1) ++missed_world;
      if (world.collide_model(*b, pose, first).size() != 2) ++missed_model;
      (void)ia;
    }
    EXPECT_EQ(missed_collide, 0) << pair.what << " (of " << trials << " poses)";
    EXPECT_EQ(missed_distance, 0) << pair.what << " (of " << trials << " poses)";
    EXPECT_EQ(missed_world, 0) << pair.what << " (of " << trials << " poses)";
    EXPECT_EQ(missed_model, 0) << pair.what << " (of " << trials << " poses)";
  }
}

TEST(SharedPose, EqualPosesComposeToTheExactIdentity) {
  std::mt19937_64 rng(2028);
  for (int trial = 0; trial < 1000; ++trial) {
    const Transform pose = test::random_pose(rng, 1e3);
    const Transform rel = detail::relative_pose(pose, pose);
    ASSERT_TRUE(rel.rotation == Mat3::Identity()) << trial;
    ASSERT_TRUE(rel.translation == Vec3::Zero()) << trial;
    // Same rotation, different translations: still exactly the identity rotation.
    Transform moved = pose;
    moved.translation += Vec3(0.5, -2, 3);
    ASSERT_TRUE(detail::relative_pose(pose, moved).rotation == Mat3::Identity()) << trial;
  }
}

}  // namespace
}  // namespace antcd
