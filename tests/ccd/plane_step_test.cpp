// The sweep's plane step for convex pairs (src/ccd/plane_step.hpp) on its own, against the gap
// of the two vertex sets sampled densely over the interval it proves; and mesh sweeps of convex
// pairs (a spinning roller and a sheet sliding onto it, boxes and balls turning fast) against dense
// sub-stepping with the exact discrete query.
#include <antcd/ccd.hpp>
#include <antcd/distance.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "ccd/continuous_support.hpp"
#include "ccd/plane_step.hpp"
#include "ccd/swept_proximity.hpp"

namespace antcd {
namespace {

Transform pose_of(const Vec3& t, const Quat& q) {
  Transform p;
  p.translation = t;
  p.rotation = q.normalized().toRotationMatrix();
  return p;
}

Quat random_turn(std::mt19937_64& rng, Scalar max_angle) {
  std::normal_distribution<Scalar> g(0, 1);
  const Vec3 axis = Vec3(g(rng), g(rng), g(rng)).normalized();
  std::uniform_real_distribution<Scalar> angle(0, max_angle);
  return Quat(Eigen::AngleAxis<Scalar>(angle(rng), axis));
}

/// min over A's vertices of n . a less max over B's of n . b, at time s.
Scalar vertex_gap(const Model& a, const Transform& a0, const Transform& a1, const Model& b,
                  const Transform& b0, const Transform& b1, const Vec3& n, Scalar s) {
  const Transform pa = ccd::interpolate_pose(a0, a1, s);
  const Transform pb = ccd::interpolate_pose(b0, b1, s);
  Scalar low = std::numeric_limits<Scalar>::infinity();
  Scalar high = -std::numeric_limits<Scalar>::infinity();
  for (const Vec3& p : a.mesh().vertices) low = std::min(low, n.dot(pa.apply(p)));
  for (const Vec3& q : b.mesh().vertices) high = std::max(high, n.dot(pb.apply(q)));
  return low - high;
}

// A roller off its model origin spinning fast and a box turning and sliding past it: every
// interval the step proves keeps the vertex sets more than the margin apart along n at 4000
// sampled times (the chord's stray is what a spinning polygon's vertices need: a step without it
// is caught here).
TEST(PlaneStep, ProvenIntervalsKeepTheVertexSetsApart) {
  Mesh roller_mesh = make_cylinder(0.3, 2.0, 20);
  for (Vec3& v : roller_mesh.vertices) v += Vec3(0.4, 0, 0);  // turning about an axis off it
  const Model roller(roller_mesh);
  const Model box(make_box(Vec3(0.6, 0.4, 0.2)));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  int proven = 0;
  int partial = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Transform a0 = pose_of(Vec3(0, 0, 0), random_turn(rng, std::numbers::pi));
    const Transform a1 =
        pose_of(Vec3(0.05 * u(rng), 0.05 * u(rng), 0), Quat(a0.rotation) * random_turn(rng, 2.5));
    const Transform b0 = pose_of(Vec3(2.0 + u(rng), 1.5 * u(rng), 1.2 + 0.3 * u(rng)),
                                 random_turn(rng, std::numbers::pi));
    const Transform b1 = pose_of(b0.translation + Vec3(-1.5 + 0.5 * u(rng), u(rng), -0.5),
                                 Quat(b0.rotation) * random_turn(rng, 1.0));
    const ccd::RigidPair m = ccd::rigid_pair(roller, a0, a1, box, b0, b1);
    const Scalar t = 0.5 * (u(rng) + 1) / 2;
    const DistanceResult d =
        distance(roller, ccd::interpolate_pose(a0, a1, t), box, ccd::interpolate_pose(b0, b1, t));
    if (!(d.distance > 0)) continue;
    const Vec3 n = (d.point_a - d.point_b) / d.distance;
    const Scalar margin = 0.05 * d.distance;
    const Scalar tau = ccd::plane_step(m, n, t, margin, 1 - t);
    ASSERT_GE(tau, 0);
    ASSERT_LE(tau, 1 - t);
    if (tau == 0) continue;
    ++(tau == 1 - t ? proven : partial);
    for (int k = 0; k <= 4000; ++k) {
      const Scalar s = std::min<Scalar>(t + tau * k / 4000, 1);
      ASSERT_GT(vertex_gap(roller, a0, a1, box, b0, b1, n, s), margin)
          << "trial " << trial << " t " << t << " tau " << tau << " s " << s;
    }
  }
  // The test must see both kinds of answer to mean anything.
  EXPECT_GT(proven, 20);
  EXPECT_GT(partial, 20);
}

// Convex pairs through the sweep (the plane step on): a sheet sliding onto a spinning roller at
// the roller's top height (a grazing landing), and boxes and balls turning fast into each other:
// no contact is found by 1000-step sub-stepping before any toi, and every miss is one.
TEST(PlaneStep, ConvexSweepsAreNeverLate) {
  const Model roller(make_cylinder(0.05, 1.2, 64));
  const Model sheet(make_box(Vec3(0.4, 0.5, 0.002), 8));
  const Model ball(make_sphere(0.3, 24, 12));
  const Model box(make_box(Vec3(0.3, 0.2, 0.1)));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  int hits = 0;
  int misses = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const Model* a = nullptr;
    const Model* b = nullptr;
    Transform a0, a1, b0, b1;
    if (trial % 2 == 0) {
      // The roller lies along y and spins about it; the sheet's bottom sits within 1 mm of the
      // roller's top and slides along x, its front edge arriving over the roller.
      a = &roller;
      b = &sheet;
      const Quat lie(Eigen::AngleAxis<Scalar>(std::numbers::pi / 2, Vec3::UnitX()));
      const Scalar spin = 0.6 * (u(rng) + 1);
      a0 = pose_of(Vec3::Zero(), lie);
      a1 = pose_of(Vec3::Zero(), Quat(Eigen::AngleAxis<Scalar>(spin, Vec3::UnitY())) * lie);
      const Scalar z = 0.05 + 0.002 + 1e-3 * u(rng);
      const Scalar x0 = -0.45 - 0.03 * (u(rng) + 1);
      b0 = pose_of(Vec3(x0, 0, z), Quat::Identity());
      b1 = pose_of(Vec3(x0 + 0.05 + 0.02 * u(rng), 0, z), Quat::Identity());
    } else {
      a = trial % 4 == 1 ? &ball : &box;
      b = &box;
      a0 = pose_of(Vec3(-0.8, 0.3 * u(rng), 0.3 * u(rng)), random_turn(rng, std::numbers::pi));
      a1 = pose_of(Vec3(0.2 * u(rng), 0.3 * u(rng), 0.3 * u(rng)),
                   Quat(a0.rotation) * random_turn(rng, 2.5));
      b0 = pose_of(Vec3(0.5, 0.2 * u(rng), 0.2 * u(rng)), random_turn(rng, std::numbers::pi));
      b1 = pose_of(Vec3(0.5 + 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)),
                   Quat(b0.rotation) * random_turn(rng, 1.5));
    }
    const SweepResult r = sweep(*a, a0, a1, *b, b0, b1);
    const auto first = test::first_substep_contact(*a, a0, a1, *b, b0, b1, 0);
    if (first) {
      ASSERT_TRUE(r.hit) << "trial " << trial << ": a contact at " << *first << " missed";
      ASSERT_LE(r.toi, *first) << "trial " << trial;
    }
    ++(r.hit ? hits : misses);
  }
  EXPECT_GT(hits, 20);
  EXPECT_GT(misses, 10);
}

}  // namespace
}  // namespace antcd
