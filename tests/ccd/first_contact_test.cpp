// The sweep's traversal (src/ccd/first_contact.hpp) on its own, started at t = 0, where every
// node pair and triangle pair must advance on its own bounds from the start: fine meshes whose
// motion is mostly turning (a ball on a long arm about its model origin), against dense
// sub-stepping with the exact discrete query.
#include <antcd/collide.hpp>
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>

#include "ccd/continuous_support.hpp"
#include "ccd/first_contact.hpp"
#include "ccd/motion.hpp"
#include "ccd/swept_proximity.hpp"

namespace antcd {
namespace {

/// first_contact() from t = 0 with the sweep's allowances (src/ccd/sweep.cpp).
ccd::FirstContact first_contact_of(const Model& a, const Transform& a0, const Transform& a1,
                                   const Model& b, const Transform& b0, const Transform& b1,
                                   Scalar separation, Scalar tol,
                                   const ccd::FirstContactLimits& limits = {}) {
  const ccd::RigidPair m = ccd::rigid_pair(a, a0, a1, b, b0, b1);
  const Scalar ra = ccd::origin_radius(a);
  const Scalar rb = ccd::origin_radius(b);
  const Scalar mu = ccd::motion_bound(m);
  const Scalar scale = ra + rb + separation + a0.translation.norm() + a1.translation.norm() +
                       b0.translation.norm() + b1.translation.norm();
  return ccd::first_contact(m, 0, separation, tolerance::kArithmetic * scale,
                            tolerance::kVolume * scale, mu * tol / 2, limits);
}

/// A fine ball of radius 0.25 whose centre is `arm` from its model origin: turning the model
/// swings it along an arc (its motion is almost all turning).
Model ball_on_arm(const Vec3& arm, int slices = 48, int stacks = 24) {
  Mesh m = make_sphere(0.25, slices, stacks);
  for (Vec3& v : m.vertices) v += arm;
  return Model(std::move(m), {}, "ball on arm");
}

TEST(FirstContact, TurningFineMeshesNeverPassTheirFirstContact) {
  const Model ball = ball_on_arm({2, 0, 0});
  const Model torus(make_torus(0.5, 0.15, 60, 30), {}, "torus");
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  constexpr Scalar kTol = 1e-6;
  int hits = 0, misses = 0;
  for (int i = 0; i < 24; ++i) {
    const std::string what = "motion " + std::to_string(i);
    // The ball swings by 0.6-1.4 rad about (nearly) z, drifting by at most 0.05; the torus waits
    // on the arc's circle (radius 2) at a random height and tilt, mostly inside the swing.
    const Scalar phi0 = unit(rng);
    const Scalar swing = 1.0 + 0.4 * unit(rng);
    const Transform a0 = Transform::from_axis_angle(Vec3(0.05 * unit(rng), 0.05 * unit(rng), 1),
                                                    phi0, 0.05 * Vec3(unit(rng), 0, 0));
    const Transform a1 = Transform::from_axis_angle(Vec3(0.05 * unit(rng), 0.05 * unit(rng), 1),
                                                    phi0 + swing, 0.05 * Vec3(0, unit(rng), 0));
    const Scalar psi = phi0 + swing * (0.5 + 0.6 * unit(rng));
    const Transform b =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 3 * unit(rng),
                                   Vec3(2 * std::cos(psi), 2 * std::sin(psi), 0.9 * unit(rng)));
    const Scalar separation = i % 2 == 0 ? 0.0 : 0.01;
    // A budget far above what any of these motions takes (the worst, a near miss, about 42 000).
    ccd::FirstContactLimits limits;
    limits.pairs = 1000000;
    const ccd::FirstContact r =
        first_contact_of(ball, a0, a1, torus, b, b, separation, kTol, limits);
    ASSERT_NE(r.outcome, ccd::FirstContact::Outcome::gave_up) << what;
    const auto dense = test::first_substep_contact(ball, a0, a1, torus, b, b, separation);
    const bool hit = r.outcome == ccd::FirstContact::Outcome::hit;
    if (dense) {
      ASSERT_TRUE(hit) << what << ": dense stepping touches at " << *dense;
      EXPECT_LE(r.toi, *dense) << what;
    }
    if (!hit) {
      ++misses;
      continue;
    }
    ++hits;
    // Nothing within the separation over [0.97 toi, toi).
    CollisionRequest cr;
    cr.delta = separation;
    CollisionResult res;
    for (int k = 0; k < 300 && r.toi > 0; ++k) {
      const Scalar t = r.toi * (1 - 0.03 * (1 - k / 300.0));
      EXPECT_FALSE(collide(ball, ccd::interpolate_pose(a0, a1, t), torus, b, cr, res))
          << what << ": touches at " << t << " before toi " << r.toi;
    }
    // The pair that stopped is within the separation and the tolerance's reach at toi.
    const auto tri = [](const Model& m, const Transform& p, std::uint32_t t) {
      const auto& idx = m.mesh().triangles[t];
      const auto& v = m.mesh().vertices;
      return std::array<Vec3, 3>{p.apply(v[idx[0]]), p.apply(v[idx[1]]), p.apply(v[idx[2]])};
    };
    const auto x = tri(ball, ccd::interpolate_pose(a0, a1, r.toi), r.triangle_a);
    const auto y = tri(torus, b, r.triangle_b);
    const Scalar d = geometry::triangle_distance(x[0], x[1], x[2], y[0], y[1], y[2]).distance;
    EXPECT_NEAR(d, r.distance, 1e-9) << what;
    EXPECT_LE(d, separation + 4.0 * kTol) << what;  // mu < 8 here
  }
  std::cout << "turning fine meshes: " << hits << " hits, " << misses << " misses\n";
  EXPECT_GE(hits, 6);
  EXPECT_GE(misses, 2);
}

TEST(FirstContact, AProbeInsideTheArcIsNotSkippedByAChord) {
  // The ball on its arm swings about z; a small probe waits inside the arc's circle, near enough
  // for the ball's inner side to graze it. In A's frame the probe runs on an arc that bulges
  // outwards of its chords (towards the ball): a chord test without its bend jumps the contact.
  // Fine meshes, then coarse ones (few, large triangles).
  const Model ball = ball_on_arm({2, 0, 0});
  const Model probe(make_sphere(0.05, 24, 12), {}, "probe");
  const Model coarse_ball = ball_on_arm({2, 0, 0}, 8, 6);
  const Model coarse_probe(make_sphere(0.05, 6, 4), {}, "coarse probe");
  int hits = 0;
  for (int i = 0; i < 16; ++i) {
    const bool coarse = i >= 8;
    const Model& a = coarse ? coarse_ball : ball;
    const Model& p = coarse ? coarse_probe : probe;
    const Scalar at = 0.3 + 0.1 * (i % 8);
    // The probe's outer side at 1.77 - 0.002 i (fine); the coarse ones sit nearer.
    const Scalar inside = coarse ? 1.74 - 0.005 * (i % 8) : 1.72 - 0.002 * i;
    const Transform a0 = Transform::identity();
    const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), 1.2);
    const Transform b = Transform::from_axis_angle(
        Vec3::UnitZ(), 0, Vec3(inside * std::cos(at), inside * std::sin(at), 0));
    const ccd::FirstContact r = first_contact_of(a, a0, a1, p, b, b, 0, 1e-6);
    const auto dense = test::first_substep_contact(a, a0, a1, p, b, b, 0);
    const std::string what = "probe " + std::to_string(i);
    ASSERT_TRUE(dense.has_value()) << what;
    ASSERT_EQ(r.outcome, ccd::FirstContact::Outcome::hit) << what;
    EXPECT_LE(r.toi, *dense) << what;
    ++hits;
  }
  EXPECT_EQ(hits, 16);
}

TEST(FirstContact, AProbeCrossingAPlateIsNotSkippedByATriangleChord) {
  // In A's frame a probe runs on a circle of radius 0.987 about A's origin while a large triangle
  // of A faces it at x = 0.995 (a second triangle far to the side makes their leaf box enclose
  // the probe, so the triangle pairs are examined from the start). The probe's outer face reaches
  // x = 0.997 near the circle's top only: a chord of the path from well before to well after that
  // crossing stays below the plate, the arc does not. Without the chord's bend the triangle pairs
  // jump over the contact.
  Mesh plate;
  plate.vertices = {{0.995, -1, -1}, {0.995, -1, 1}, {0.995, 1.5, 0},
                    {0.5, -1, -1},   {0.5, -1, 1},   {0.6, -0.9, 0}};
  plate.triangles = {{0, 1, 2}, {3, 4, 5}};
  const Model a(std::move(plate), {}, "plate");
  const Model probe(make_box({0.01, 0.01, 0.01}), {}, "probe");
  const Transform b = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(0.987, 0, 0));
  for (const Scalar swing : {0.7, 0.8, 0.9}) {
    const Transform a0 = Transform::from_axis_angle(Vec3::UnitZ(), -swing);
    const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), swing);
    const auto dense = test::first_substep_contact(a, a0, a1, probe, b, b, 0);
    ASSERT_TRUE(dense.has_value()) << swing;
    const ccd::FirstContact r = first_contact_of(a, a0, a1, probe, b, b, 0, 1e-6);
    ASSERT_EQ(r.outcome, ccd::FirstContact::Outcome::hit) << swing;
    EXPECT_LE(r.toi, *dense) << swing;
  }
}

TEST(FirstContact, GivesUpAfterItsPairBudget) {
  const Model ball = ball_on_arm({2, 0, 0});
  const Model torus(make_torus(0.5, 0.15, 60, 30), {}, "torus");
  const Transform a0 = Transform::identity();
  const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), 1.0);
  const Transform b =
      Transform::from_axis_angle(Vec3::UnitX(), 0.3, Vec3(2 * std::cos(0.5), 2 * std::sin(0.5), 0));
  const ccd::FirstContact full = first_contact_of(ball, a0, a1, torus, b, b, 0, 1e-6);
  ASSERT_EQ(full.outcome, ccd::FirstContact::Outcome::hit);
  ASSERT_GT(full.pairs, 20u);
  ccd::FirstContactLimits limits;
  limits.pairs = 20;
  const ccd::FirstContact cut = first_contact_of(ball, a0, a1, torus, b, b, 0, 1e-6, limits);
  EXPECT_EQ(cut.outcome, ccd::FirstContact::Outcome::gave_up);
  // The time it reached is proven free: at most the time of impact, and nothing touches before.
  EXPECT_GE(cut.toi, 0.0);
  EXPECT_LE(cut.toi, full.toi);
  const auto dense = test::first_substep_contact(ball, a0, a1, torus, b, b, 0);
  ASSERT_TRUE(dense.has_value());
  EXPECT_LE(cut.toi, *dense);
}

TEST(FirstContact, SpinningRollersNeverPassTheirFirstContact) {
  // A fine roller spinning fast about its own axis (in a random orientation, so that its model
  // axis is not a world axis) while a thin plate, its face parallel to the roller's axis, comes
  // at it sideways: a line contact where the turn moves the rim along the plate, not towards it
  // (the directional step of pair_step) and the long roller hardly turns about its nodes'
  // centres (Spin::node_reach). Half the plates stop short of the roller or pass beside it.
  const Model roller(make_cylinder(0.05, 1.3, 48, 12), {}, "roller");
  const Model plate(make_box({0.3, 0.3, 0.005}, 12), {}, "plate");
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  constexpr Scalar kTol = 1e-6;
  int hits = 0, misses = 0;
  for (int i = 0; i < 16; ++i) {
    const std::string what = "motion " + std::to_string(i);
    const Transform orient =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 3 * unit(rng));
    const Transform a0 = orient;
    // A spin of 1-3 rad about the model z axis, with a slight wobble.
    Transform a1 = orient * Transform::from_axis_angle(Vec3(0.01 * unit(rng), 0.01 * unit(rng), 1),
                                                       2 + unit(rng));
    a1.translation = 0.005 * Vec3(unit(rng), unit(rng), unit(rng));
    // The plate's face normal is the roller's x axis, its long side along the roller; it moves
    // along -x from 0.1 beyond the rim to a stop 0.02 short of it or 0.02 into it, offset along y
    // (beside the rim for some).
    const Vec3 x_axis = orient.rotation.col(0);
    const Vec3 y_axis = orient.rotation.col(1);
    const Mat3 plate_rot =
        orient.rotation *
        Transform::from_axis_angle(Vec3::UnitY(), std::numbers::pi / 2 + 0.02 * unit(rng)).rotation;
    const Scalar stop = i % 2 == 0 ? 0.03 : -0.015;
    const Scalar side = i % 4 < 2 ? 0.02 * unit(rng) : 0.06 + 0.02 * unit(rng);
    Transform b0, b1;
    b0.rotation = b1.rotation = plate_rot;
    b0.translation = (0.05 + 0.005 + 0.1) * x_axis + side * y_axis;
    b1.translation = (0.05 + 0.005 + stop) * x_axis + side * y_axis;
    const Scalar separation = i % 3 == 0 ? 0.01 : 0.0;
    const auto dense = test::first_substep_contact(roller, a0, a1, plate, b0, b1, separation);
    SweepRequest request;
    request.min_separation = separation;
    request.time_tolerance = kTol;
    const SweepResult swept = sweep(roller, a0, a1, plate, b0, b1, request);
    ccd::FirstContactLimits limits;
    limits.pairs = 1000000;
    const ccd::FirstContact r =
        first_contact_of(roller, a0, a1, plate, b0, b1, separation, kTol, limits);
    ASSERT_NE(r.outcome, ccd::FirstContact::Outcome::gave_up) << what;
    const bool hit = r.outcome == ccd::FirstContact::Outcome::hit;
    if (dense) {
      ASSERT_TRUE(hit) << what << ": dense stepping touches at " << *dense;
      ASSERT_TRUE(swept.hit) << what << ": dense stepping touches at " << *dense;
      EXPECT_LE(r.toi, *dense) << what;
      EXPECT_LE(swept.toi, *dense) << what;
    }
    if (!hit) {
      ++misses;
      EXPECT_FALSE(swept.hit) << what;
      continue;
    }
    ++hits;
    ASSERT_TRUE(swept.hit) << what;
    EXPECT_NEAR(swept.toi, r.toi, 4 * kTol) << what;
    // Nothing within the separation just before either toi.
    CollisionRequest cr;
    cr.delta = separation;
    CollisionResult res;
    for (const Scalar toi : {r.toi, swept.toi}) {
      for (int k = 0; k < 200 && toi > 0; ++k) {
        const Scalar t = toi * (1 - 0.02 * (1 - k / 200.0));
        EXPECT_FALSE(collide(roller, ccd::interpolate_pose(a0, a1, t), plate,
                             ccd::interpolate_pose(b0, b1, t), cr, res))
            << what << ": touches at " << t << " before toi " << toi;
      }
    }
  }
  std::cout << "spinning rollers: " << hits << " hits, " << misses << " misses\n";
  EXPECT_GE(hits, 4);
  EXPECT_GE(misses, 4);
}

}  // namespace
}  // namespace antcd
