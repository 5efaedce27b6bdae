// World continuous motion (World::sweep_poses / set_poses_continuous): against antcd::sweep on
// every admitted pair (brute force), the swept-box broad phase against dense sub-stepping, the
// filters, and argument errors.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

struct Fixture {
  World world;
  std::vector<ObjectId> ids;
  std::vector<Transform> from;
  std::vector<Transform> to;  ///< end poses of every object (unmoved ones: the same pose)
  std::vector<ObjectId> moving;
  std::vector<Transform> moving_to;
};

/// A small world of bars, sheets, tori and boxes in a 3-unit cube; about two thirds move fast (up
/// to 1.5 per step) and turn by up to 2.5 radians, so pairs that meet only between the poses and
/// rotations that swing a bar outside both end boxes both occur.
Fixture random_world(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const std::vector<std::shared_ptr<const Model>> models = {
      std::make_shared<const Model>(make_box({0.8, 0.05, 0.05}), BuildOptions{}, "bar"),
      std::make_shared<const Model>(make_box({0.4, 0.4, 0.005}), BuildOptions{}, "sheet"),
      std::make_shared<const Model>(make_torus(0.4, 0.1, 16, 8), BuildOptions{}, "torus"),
      std::make_shared<const Model>(make_box({0.2, 0.2, 0.2}), BuildOptions{}, "box")};
  Fixture f;
  for (int k = 0; k < 16; ++k) {
    const Transform p0 = test::random_pose(rng, 1.5);
    f.ids.push_back(f.world.add(models[static_cast<std::size_t>(k) % models.size()], p0));
    f.from.push_back(p0);
    Transform p1 = p0;
    if (k % 3 != 2) {
      const Vec3 axis(unit(rng), unit(rng), unit(rng));
      p1.rotation =
          Eigen::AngleAxis<Scalar>(2.5 * unit(rng), axis.normalized()).toRotationMatrix() *
          p0.rotation;
      p1.translation += 1.5 * Vec3(unit(rng), unit(rng), unit(rng));
      f.moving.push_back(f.ids.back());
      f.moving_to.push_back(p1);
    }
    f.to.push_back(p1);
  }
  return f;
}

TEST(WorldContinuous, MatchesPerPairSweepOnEveryPair) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    Fixture f = random_world(seed);
    f.world.ignore_pair(f.ids[0], f.ids[1]);
    SweepRequest req;
    req.min_separation = seed % 2 == 0 ? 0.05 : 0;
    const std::vector<PairToi> got = f.world.sweep_poses(f.moving, f.moving_to, req);
    std::vector<PairToi> want;
    for (std::size_t i = 0; i < f.ids.size(); ++i) {
      for (std::size_t j = i + 1; j < f.ids.size(); ++j) {
        if (!f.world.may_collide(f.ids[i], f.ids[j])) continue;
        const SweepResult r = sweep(f.world.model(f.ids[i]), f.from[i], f.to[i],
                                    f.world.model(f.ids[j]), f.from[j], f.to[j], req);
        if (r.hit) want.push_back({f.ids[i], f.ids[j], r});
      }
    }
    ASSERT_EQ(got.size(), want.size()) << "seed " << seed;
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].a, want[k].a);
      EXPECT_EQ(got[k].b, want[k].b);
      EXPECT_TRUE(got[k].sweep.hit);
      EXPECT_EQ(got[k].sweep.toi, want[k].sweep.toi);
      EXPECT_EQ(got[k].sweep.contact.triangle_a, want[k].sweep.contact.triangle_a);
    }
    EXPECT_GT(want.size(), 0U) << "seed " << seed << ": the world should see contacts";
    // The query changed nothing.
    for (std::size_t k = 0; k < f.ids.size(); ++k) {
      EXPECT_EQ(f.world.pose(f.ids[k]).translation, f.from[k].translation);
    }
  }
}

TEST(WorldContinuous, SweptBoxesNeverDropAPairThatMeets) {
  // Dense sub-stepping (100 steps) with the exact discrete query on every pair the swept-box
  // broad phase dropped: none may touch at any step.
  int dropped = 0, candidates = 0;
  for (std::uint64_t seed = 11; seed <= 16; ++seed) {
    const Fixture f = random_world(seed);
    const Scalar delta = 0.02;
    const std::vector<ObjectPair> pairs =
        f.world.swept_candidate_pairs(f.moving, f.moving_to, delta);
    candidates += static_cast<int>(pairs.size());
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    CollisionRequest cr;
    cr.delta = delta;
    for (std::size_t i = 0; i < f.ids.size(); ++i) {
      for (std::size_t j = i + 1; j < f.ids.size(); ++j) {
        if (std::binary_search(pairs.begin(), pairs.end(), ObjectPair{f.ids[i], f.ids[j]})) {
          continue;
        }
        ++dropped;
        for (int s = 0; s <= 100; ++s) {
          const Scalar t = s / 100.0;
          ASSERT_FALSE(
              collide(f.world.model(f.ids[i]), ccd::interpolate_pose(f.from[i], f.to[i], t),
                      f.world.model(f.ids[j]), ccd::interpolate_pose(f.from[j], f.to[j], t), cr)
                  .colliding)
              << "seed " << seed << " pair " << i << "," << j << " touches at t = " << t;
        }
      }
    }
  }
  EXPECT_GT(dropped, candidates);  // the broad phase does prune
}

TEST(WorldContinuous, SpinningBarOutsideBothEndBoxesIsCaught) {
  // A bar of half length 1 turns about z from -45 to +45 degrees; a small box sits where the
  // bar's tip passes at 0 degrees, outside the box of the bar's two end boxes (|x| <= 0.73).
  World world;
  const auto bar =
      std::make_shared<const Model>(make_box({1.0, 0.02, 0.02}), BuildOptions{}, "bar");
  const auto probe =
      std::make_shared<const Model>(make_box({0.02, 0.02, 0.02}), BuildOptions{}, "p");
  const Transform start = Transform::from_axis_angle(Vec3::UnitZ(), -M_PI / 4);
  const Transform end = Transform::from_axis_angle(Vec3::UnitZ(), M_PI / 4);
  const ObjectId b = world.add(bar, start);
  const ObjectId p = world.add(probe, Transform::from_axis_angle(Vec3::UnitZ(), 0, {0.95, 0, 0}));
  const std::vector<ObjectId> ids = {b};
  const std::vector<Transform> poses = {end};
  EXPECT_FALSE(collide(*bar, start, *probe, world.pose(p)).colliding);
  EXPECT_FALSE(collide(*bar, end, *probe, world.pose(p)).colliding);
  const std::vector<PairToi> hits = world.set_poses_continuous(ids, poses);
  ASSERT_EQ(hits.size(), 1U);
  EXPECT_EQ(hits[0].a, b);
  EXPECT_EQ(hits[0].b, p);
  // The bar's edge reaches the probe's corner about 0.042 rad before 0 degrees: t ~ 0.473.
  EXPECT_GT(hits[0].sweep.toi, 0.45);
  EXPECT_LT(hits[0].sweep.toi, 0.5);
  // The World now holds the end pose.
  EXPECT_TRUE(world.pose(b).rotation.isApprox(end.rotation));
  // Static pairs that touch count with toi 0; filtered pairs never.
  // (A pose of the World itself as add()'s argument: add() must copy it before growing.)
  const ObjectId q = world.add(probe, world.pose(p));
  const std::vector<PairToi> resting = world.sweep_poses({}, {});
  ASSERT_EQ(resting.size(), 1U);
  EXPECT_EQ(resting[0].a, p);
  EXPECT_EQ(resting[0].b, q);
  EXPECT_EQ(resting[0].sweep.toi, 0);
  world.set_filter(q, 2, 2);
  EXPECT_TRUE(world.sweep_poses({}, {}).empty());
}

TEST(WorldContinuous, RejectsBadArgumentsAndChangesNothing) {
  World world;
  const auto box = std::make_shared<const Model>(make_box({0.5, 0.5, 0.5}), BuildOptions{}, "box");
  const ObjectId a = world.add(box, Transform{}, {"a"});
  const ObjectId gone = world.add(box, Transform{});
  world.remove(gone);
  const Transform moved = Transform::from_axis_angle(Vec3::UnitX(), 0.1, {3, 0, 0});
  Transform skew = moved;
  skew.rotation(0, 1) = 0.5;
  const auto expect_error = [&](std::vector<ObjectId> ids, std::vector<Transform> poses,
                                SweepRequest req, const std::string& part) {
    try {
      (void)world.set_poses_continuous(ids, poses, req);
      ADD_FAILURE() << "no error for " << part;
    } catch (const ArgumentError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    EXPECT_EQ(world.pose(a).translation, Vec3::Zero());
  };
  expect_error({a}, {}, {}, "1 ids but 0 poses");
  expect_error({a, a}, {moved, moved}, {}, "ids[1] repeats ids[0]");
  expect_error({gone}, {moved}, {}, "ids[0]");
  expect_error({a}, {skew}, {}, "new_poses[0]");
  SweepRequest bad;
  bad.min_separation = -1;
  expect_error({a}, {moved}, bad, "min_separation");
  bad = {};
  bad.time_tolerance = 0;
  expect_error({a}, {moved}, bad, "time_tolerance");
  EXPECT_THROW((void)world.swept_candidate_pairs(std::vector<ObjectId>{a},
                                                 std::vector<Transform>{moved}, std::nan("")),
               ArgumentError);
}

}  // namespace
}  // namespace antcd
