// The turn's bounds (src/ccd/motion.hpp: ccd::Spin) and the per-pair step of the sweep's
// traversal (src/ccd/first_contact.hpp: ccd::pair_step), against the motion itself.
#include <antcd/ccd.hpp>
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ccd/first_contact.hpp"
#include "ccd/motion.hpp"
#include "ccd/swept_proximity.hpp"

namespace antcd {
namespace {

Mat3 random_rotation(std::mt19937_64& rng, Scalar max_angle) {
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  return Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), max_angle * unit(rng))
      .rotation;
}

TEST(Spin, ReachTimesTheAngleIsEveryPointsSpeed) {
  // The slerp moves a model point at theta |k x p| per unit time (k the model-frame axis): the
  // bound is met, not merely respected (a world-frame axis would miss it for a turned start).
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int i = 0; i < 40; ++i) {
    Transform p0, p1;
    p0.rotation = random_rotation(rng, 3);
    p1.rotation = random_rotation(rng, 3);
    const ccd::Spin s = ccd::spin(p0.rotation, p1.rotation);
    ASSERT_TRUE(s.about_axis) << i;
    for (int j = 0; j < 10; ++j) {
      const Vec3 p = 2 * Vec3(unit(rng), unit(rng), unit(rng));
      for (const Scalar t : {0.1, 0.5, 0.9}) {
        constexpr Scalar h = 1e-5;
        const Vec3 before = ccd::interpolate_pose(p0, p1, t - h).apply(p);
        const Vec3 after = ccd::interpolate_pose(p0, p1, t + h).apply(p);
        const Scalar speed = (after - before).norm() / (2 * h);
        EXPECT_NEAR(speed, s.theta * s.reach(p), 1e-6) << i << " " << j << " t " << t;
      }
    }
  }
  // Too small a turn for its axis: the distance from the origin.
  const Mat3 r0 = random_rotation(rng, 3);
  const Mat3 r1 = r0 * Transform::from_axis_angle(Vec3::UnitX(), 1e-12).rotation;
  const ccd::Spin tiny = ccd::spin(r0, r1);
  EXPECT_FALSE(tiny.about_axis);
  EXPECT_EQ(tiny.reach(Vec3(3, 4, 0)), 5);
}

/// The model-frame corners of every triangle under node `i`.
void corners_under(const Model& m, std::uint32_t i, std::vector<Vec3>& out) {
  const BvhNode& n = m.nodes()[i];
  if (n.is_leaf()) {
    const LeafCorners c = m.leaf_corners();
    for (std::uint32_t k = 0; k < n.count; ++k) {
      for (const Vec3& v : c.triangle(n.first_or_right + k)) out.push_back(v);
    }
    return;
  }
  corners_under(m, i + 1, out);
  corners_under(m, n.first_or_right, out);
}

TEST(Spin, NodeAndModelReachHoldEveryCorner) {
  // A long roller spinning about (nearly) its own axis: every node's corners lie within
  // node_reach of the axis through the node's centre, every corner within model_reach of the
  // axis, and the latter is the rim, not the far end.
  const Model roller(make_cylinder(0.05, 1.3, 32, 8), {}, "roller");
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int i = 0; i < 8; ++i) {
    const Mat3 r0 = random_rotation(rng, 3);
    const Mat3 r1 =
        r0 * Transform::from_axis_angle(Vec3(0.02 * unit(rng), 0.02 * unit(rng), 1), 2).rotation;
    const ccd::Spin s = ccd::spin(r0, r1);
    ASSERT_TRUE(s.about_axis);
    for (std::uint32_t k = 0; k < roller.nodes().size(); ++k) {
      const BvhNode& n = roller.nodes()[k];
      std::vector<Vec3> corners;
      corners_under(roller, k, corners);
      Scalar most = 0;
      for (const Vec3& v : corners) most = std::max(most, s.axis.cross(v - n.center).norm());
      EXPECT_LE(most, s.node_reach(n)) << "node " << k;
    }
    Scalar most = 0;
    for (const Vec3& v : roller.mesh().vertices) most = std::max(most, s.reach(v));
    const Scalar model = ccd::model_reach(roller, s);
    EXPECT_LE(most, model);
    EXPECT_LT(model, 0.1);  // the rim (0.05 and a wobble), not the ends (0.65)
    EXPECT_LT(s.node_reach(roller.root()), 0.15);  // against its radius, 0.65
  }
}

/// Two triangles' world corners at time t.
std::array<Vec3, 3> posed(const std::array<Vec3, 3>& x, const Transform& p) {
  return {p.apply(x[0]), p.apply(x[1]), p.apply(x[2])};
}

TEST(PairStep, TranslationAloneIsTheGapOverTheClosingSpeed) {
  const Model a(make_box({1, 1, 1}), {}, "a");
  const Model b(make_box({1, 1, 1}), {}, "b");
  const Transform id = Transform::identity();
  const Vec3 pa(1, 0, 0), pb(0, 0, 0);
  const Vec3 n(1, 0, 0);  // from B towards A
  const auto step = [&](const Vec3& v, Scalar n_error) {
    Transform a1 = id;
    a1.translation = v;  // A moves by v over the motion; B stays
    const ccd::RigidPair m = ccd::rigid_pair(a, id, a1, b, id, id);
    return ccd::pair_step(1, n, n_error, v, Mat3::Identity(), m, {&pa, 1}, {&pb, 1});
  };
  // Closing at 2: a gap of 1 lasts 0.5 (the turning terms of a 1e-15 rad "turn" aside).
  EXPECT_NEAR(step(Vec3(-2, 0, 0), 0), 0.5, 1e-9);
  // Moving apart, or sideways: it never closes within any time that matters.
  EXPECT_GT(step(Vec3(3, 0, 0), 0), 1e9);
  EXPECT_GT(step(Vec3(0, 5, 0), 0), 1e9);
  // A direction not known (n_error >= 0.5): the full speed, 5.
  EXPECT_NEAR(step(Vec3(3, 4, 0), 0.5), 0.2, 1e-9);
}

TEST(PairStep, ADiscSpinningInItsPlaneBesideAPlateStepsFarther) {
  // A's triangle lies in the plane x = 0.5 of a disc spinning about x at 3 rad; B's plate is the
  // plane x = 0.6: the spin moves A's points along the plate, never towards it.
  const Model a(make_box({1, 1, 1}), {}, "a");
  const Model b(make_box({1, 1, 1}), {}, "b");
  const Transform a0 = Transform::identity();
  const Transform a1 = Transform::from_axis_angle(Vec3::UnitX(), 3);
  const Transform b0 = Transform::identity();
  const ccd::RigidPair m = ccd::rigid_pair(a, a0, a1, b, b0, b0);
  const std::array<Vec3, 3> x{Vec3(0.5, 0.9, 0), Vec3(0.5, 1.0, 0), Vec3(0.5, 0.95, 0.1)};
  const std::array<Vec3, 3> y{Vec3(0.6, -2, -2), Vec3(0.6, 2, -2), Vec3(0.6, 0, 3)};
  const Vec3 n(-1, 0, 0);  // from B towards A
  const Scalar step = ccd::pair_step(0.1, n, 0, Vec3::Zero(), Mat3::Identity(), m, x, y);
  const Scalar tangent = 0.1 / (3 * 1.0);  // gap over theta times the rim's reach (about 1)
  EXPECT_GT(step, 3 * tangent);
  EXPECT_LE(step, std::sqrt(2 * 0.1 / (9 * 0.9)) * 1.01);  // the turn's curvature still counts
}

TEST(PairStep, NoSampledTimeWithinTheStepComesNearer) {
  // Random triangle pairs under random rigid motions (turns up to 3 rad, both bodies, started at
  // turned poses): over [0, step] the exact distance stays above distance - gap.
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const Model a(make_box({1, 1, 1}), {}, "a");
  const Model b(make_box({1, 1, 1}), {}, "b");
  int stepped = 0;
  for (int i = 0; i < 3000; ++i) {
    Transform a0, a1, b0, b1;
    a0.rotation = random_rotation(rng, 3);
    a1.rotation = random_rotation(rng, 3);
    b0.rotation = random_rotation(rng, 3);
    b1.rotation = random_rotation(rng, 3);
    a0.translation = 0.3 * Vec3(unit(rng), unit(rng), unit(rng));
    a1.translation = a0.translation + 0.5 * Vec3(unit(rng), unit(rng), unit(rng));
    b0.translation = Vec3(1.5 + unit(rng), unit(rng), unit(rng));
    b1.translation = b0.translation + 0.5 * Vec3(unit(rng), unit(rng), unit(rng));
    std::array<Vec3, 3> x, y;
    for (Vec3& v : x) v = Vec3(unit(rng), unit(rng), unit(rng));
    for (Vec3& v : y) v = Vec3(unit(rng), unit(rng), unit(rng));
    const ccd::RigidPair m = ccd::rigid_pair(a, a0, a1, b, b0, b1);
    const auto xa = posed(x, a0);
    const auto yb = posed(y, b0);
    const geometry::TriangleDistance d =
        geometry::triangle_distance(xa[0], xa[1], xa[2], yb[0], yb[1], yb[2]);
    if (!(d.distance > 1e-3)) continue;
    // The traversal's frame: everything in A's model frame at t = 0.
    const Mat3 to_a = a0.rotation.transpose();
    const Vec3 n = to_a * (d.pa - d.pb) / d.distance;
    const Vec3 v = to_a * ((a1.translation - a0.translation) - (b1.translation - b0.translation));
    const Mat3 b_to_a = to_a * b0.rotation;
    const Scalar gap = 0.9 * d.distance;
    const Scalar step = ccd::pair_step(gap, n, 1e-12, v, b_to_a, m, x, y);
    ASSERT_GE(step, 0) << i;
    ++stepped;
    const Scalar end = std::min<Scalar>(step, 1);
    for (int k = 1; k <= 100; ++k) {
      const Scalar t = end * k / 100;
      const auto xt = posed(x, ccd::interpolate_pose(a0, a1, t));
      const auto yt = posed(y, ccd::interpolate_pose(b0, b1, t));
      const Scalar dt =
          geometry::triangle_distance(xt[0], xt[1], xt[2], yt[0], yt[1], yt[2]).distance;
      ASSERT_GE(dt, d.distance - gap - 1e-9) << i << " at " << t << " of step " << step;
    }
  }
  EXPECT_GT(stepped, 1000);
}

}  // namespace
}  // namespace antcd
