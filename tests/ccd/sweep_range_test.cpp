// Sweeps at every finite scale (issue 41): a motion within the continuous queries' coordinate
// range (kSweepCoordinateRange) is answered conservatively, one beyond it is refused with an
// ArgumentError naming the argument; never a proven miss for a motion that touches. Random motions
// from 1e-300 to 1e300 in scale against dense sub-stepping, the World's continuous motion too.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ccd/continuous_support.hpp"

namespace antcd {
namespace {

/// kSweepCoordinateRange (antcd/sweep.hpp), as documented.
constexpr Scalar kRange = 1e100;

/// The message of the ArgumentError `f` throws ("" when it throws none).
template <class F>
std::string argument_error(const F& f) {
  try {
    f();
  } catch (const ArgumentError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

Transform at(Scalar x) { return Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0, 0)); }

// A unit box from x = -s to x = +s through a ball at the origin: contact at t = 0.5. At 1e155 and
// beyond the motion bound overflowed and the sweep answered a proven miss; at 1e154 it failed
// naming distance's abs_tolerance, an option the caller never gave.
TEST(SweepRange, PassThroughAtAnyScaleIsAHitOrRefused) {
  const Model box(make_box({0.5, 0.5, 0.5}), {}, "box");
  const Model ball(make_sphere(0.5, 16, 8), {}, "ball");
  const Transform id = Transform::identity();
  const Scalar big = std::numeric_limits<Scalar>::max();
  for (const Scalar s : {1.0, 1e20, 1e50, 1e100, 1e154, 1e155, 1e200, 1e300, big / 2}) {
    SweepResult r;
    const std::string error = argument_error([&] { r = sweep(box, at(-s), at(s), ball, id, id); });
    if (error.empty()) {
      // Answered: never a miss, never after the contact.
      EXPECT_TRUE(r.hit) << s << ": a proven miss (lower bound " << r.distance << ")";
      EXPECT_LE(r.toi, 0.5) << s;
      EXPECT_TRUE(std::isfinite(r.motion_bound)) << s;
      EXPECT_LE(s, kRange) << s << ": answered beyond the range";
    } else {
      EXPECT_GT(s, kRange) << s << ": refused within the range";
      EXPECT_TRUE(contains(error,
                           "sweep: pose_a0 translation is beyond the continuous queries' "
                           "coordinate range"))
          << s << ": " << error;
    }
  }
  // B moving instead, min_separation and a model too far out, a huge time tolerance.
  EXPECT_TRUE(contains(argument_error([&] { (void)sweep(box, id, id, ball, at(1e155), id); }),
                       "pose_b0 translation"));
  SweepRequest req;
  req.min_separation = 1e300;
  EXPECT_TRUE(contains(argument_error([&] { (void)sweep(box, id, id, ball, id, id, req); }),
                       "sweep: min_separation is beyond"));
  // (A model farther out than 1e100 cannot be built: its triangles' areas overflow. Its root
  // radius is a float, +inf beyond 3.4e38.)
  const Model far(make_box({1e40, 1e40, 1e40}), {}, "huge box");
  EXPECT_TRUE(contains(argument_error([&] { (void)sweep(far, id, id, ball, id, id); }),
                       "sweep: model a reach from its origin is beyond"));
  req = {};
  req.time_tolerance = 1e300;
  const SweepResult r = sweep(box, at(-3), at(3), ball, id, id, req);
  EXPECT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
}

// The property of issue 41: random finite motions spanning 1e-300 to 1e300 in scale; dense
// sub-stepping (1000 steps, exact collide) never finds a contact before a reported toi or in a
// reported miss, and a motion is refused only when a translation lies beyond the range.
TEST(SweepRange, RandomMotionsAtEveryScaleNeverBeatDenseStepping) {
  const Model box(make_box({0.4, 0.3, 0.2}), {}, "box");
  const Model torus(make_torus(0.6, 0.15, 16, 8), {}, "torus");
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::uniform_real_distribution<Scalar> exponent(-300, 300);
  std::uniform_int_distribution<int> step(0, 1000);
  int refused = 0, hits = 0, dense_hits = 0, motions = 0;
  for (int i = 0; i < 160; ++i) {
    const Scalar s = std::pow(10.0, exponent(rng));
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    // At time tc (a sub-step) A's origin is at `near`, within reach of the torus or not.
    const Scalar tc = step(rng) / 1000.0;
    const Vec3 near = 0.9 * Vec3(unit(rng), unit(rng), unit(rng));
    const Transform a0 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)),
                                                    unit(rng), near - tc * s * dir);
    const Transform a1 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)),
                                                    unit(rng), near + (1 - tc) * s * dir);
    const Transform b0 = Transform::from_axis_angle(Vec3::UnitX(), 0.3 * unit(rng));
    const Transform b1 = Transform::from_axis_angle(Vec3::UnitY(), 0.3 * unit(rng));
    SweepRequest req;
    req.min_separation = i % 4 == 0 ? 0.01 : 0;
    const Scalar largest =
        std::max(a0.translation.cwiseAbs().maxCoeff(), a1.translation.cwiseAbs().maxCoeff());
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.3g", s);
    const std::string what = "motion " + std::to_string(i) + " at scale " + scale;
    SweepResult r;
    const std::string error = argument_error([&] { r = sweep(box, a0, a1, torus, b0, b1, req); });
    ++motions;
    if (largest > kRange) {
      EXPECT_TRUE(contains(error, "translation is beyond the continuous queries' coordinate range"))
          << what << ": " << error;
      ++refused;
      continue;
    }
    ASSERT_EQ(error, "") << what;
    EXPECT_TRUE(std::isfinite(r.motion_bound)) << what;
    hits += r.hit ? 1 : 0;
    const auto dense = test::first_substep_contact(box, a0, a1, torus, b0, b1, req.min_separation);
    if (dense) {
      ++dense_hits;
      EXPECT_TRUE(r.hit) << what << ": dense stepping touches at " << *dense;
      if (r.hit) {
        EXPECT_LE(r.toi, *dense) << what;
      }
    }
  }
  std::cout << "motions " << motions << ", refused " << refused << ", hits " << hits
            << ", dense-stepping contacts " << dense_hits << '\n';
  EXPECT_GT(refused, 0);
  EXPECT_GT(dense_hits, 10);
}

// World::set_poses_continuous at huge translations: refused naming the argument (it answered no
// contact at 1e155), nothing moved.
TEST(SweepRange, WorldContinuousMotionBeyondTheRangeIsRefused) {
  World world;
  const auto box = std::make_shared<const Model>(make_box({0.5, 0.5, 0.5}), BuildOptions{}, "box");
  const auto ball = std::make_shared<const Model>(make_sphere(0.5, 16, 8), BuildOptions{}, "ball");
  const ObjectId a = world.add(box, at(-1e155));
  (void)world.add(ball, Transform::identity());
  const std::vector<ObjectId> ids = {a};
  const std::vector<Transform> to = {at(1e155)};
  const std::string error = argument_error([&] { (void)world.set_poses_continuous(ids, to); });
  EXPECT_TRUE(contains(error, "World::sweep_poses: new_poses[0] translation is beyond")) << error;
  EXPECT_EQ(world.pose(a).translation.x(), -1e155);
  // Within the range the pass-through is found.
  world.set_pose(a, at(-1e100));
  const std::vector<Transform> within = {at(1e100)};
  const std::vector<PairToi> hits = world.set_poses_continuous(ids, within);
  ASSERT_EQ(hits.size(), 1U);
  EXPECT_LE(hits[0].sweep.toi, 0.5);
}

}  // namespace
}  // namespace antcd
