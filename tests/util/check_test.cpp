// The argument check of util/check.hpp and the named tolerances of antcd/tolerances.hpp: one
// message format ("<function>: <argument> must be <requirement>, got <value>") from the helpers
// and from the library calls that use them, and the tolerance functions' definitions.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>
#include <antcd/pose.hpp>
#include <antcd/tolerances.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "util/check.hpp"

namespace antcd {
namespace {

std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const ArgumentError& e) {
    return e.what();
  }
  return "(no ArgumentError)";
}

constexpr Scalar kNaN = std::numeric_limits<Scalar>::quiet_NaN();
constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();

TEST(ArgumentCheck, OneFormatPerRequirement) {
  using namespace detail;
  EXPECT_EQ(message([] { require_non_negative("f", "x", -0.5); }),
            "f: x must be finite and >= 0, got -0.5");
  EXPECT_EQ(message([] { require_non_negative("f", "x", kInf); }),
            "f: x must be finite and >= 0, got inf");
  EXPECT_EQ(message([] { require_positive("f", "x", 0); }), "f: x must be finite and > 0, got 0");
  EXPECT_EQ(message([] { require_finite("f", "x", kNaN); }), "f: x must be finite, got nan");
  EXPECT_EQ(message([] { require_bound("f", "x", -1); }), "f: x must be >= 0 (or +inf), got -1");
  EXPECT_EQ(message([] { require_in_range("f", "x", 1, 0, 1, true, "[0, 1)"); }),
            "f: x must be in [0, 1), got 1");
  EXPECT_EQ(message([] { require_at_least("f", "n", 0U, 1); }), "f: n must be >= 1, got 0");
  // Accepted values, boundaries included.
  EXPECT_EQ(message([] {
              require_non_negative("f", "x", 0);
              require_positive("f", "x", 1e-300);
              require_bound("f", "x", kInf);
              require_in_range("f", "x", 1, 0, 1, false, "[0, 1]");
              require_at_least("f", "n", std::uint64_t{1}, 1);
            }),
            "(no ArgumentError)");
}

TEST(ArgumentCheck, LibraryCallsUseIt) {
  const auto ball = std::make_shared<const Model>(make_sphere(1, 8, 4));
  const Transform id = Transform::identity();
  EXPECT_EQ(message([] { World w(WorldOptions{-1}); }),
            "World: options.fat_fraction must be finite and >= 0, got -1");
  EXPECT_EQ(message([&] {
              DistanceRequest r;
              r.rel_tolerance = 1.5;
              (void)distance(*ball, id, *ball, id, r);
            }),
            "distance: rel_tolerance must be in [0, 1), got 1.5");
  EXPECT_EQ(message([&] {
              CollisionRequest r;
              r.delta = kNaN;
              (void)collide(*ball, id, *ball, id, r);
            }),
            "collide: request.delta must be finite and >= 0, got nan");
  EXPECT_EQ(message([&] {
              PenetrationRequest r;
              r.max_evaluations = 0;
              (void)penetration(*ball, id, *ball, id, r);
            }),
            "penetration: max_evaluations must be >= 1, got 0");
  EXPECT_EQ(message([] { (void)World().pairs_within(-2); }),
            "World::pairs_within: distance must be finite and >= 0, got -2");
}

TEST(Tolerances, Definitions) {
  EXPECT_EQ(tolerance::volume_allowance(0), tolerance::kFloor);
  EXPECT_GT(tolerance::volume_allowance(0), 0);
  EXPECT_EQ(tolerance::volume_allowance(2), 2 * tolerance::kVolume + tolerance::kFloor);
  EXPECT_GT(tolerance::widened(1), 1);
  EXPECT_EQ(tolerance::widened(0), 0);
  const Mat3 turn = Eigen::AngleAxis<Scalar>(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_LT(tolerance::orthonormality_error(turn), 1e-15);
  const auto fault = [](const Mat3& r) { return check_pose(Transform(r, Vec3(1, 2, 3))).fault; };
  using Fault = PoseCheck::Fault;
  EXPECT_EQ(fault(turn), Fault::None);
  EXPECT_EQ(fault(-turn), Fault::Reflection);
  EXPECT_EQ(fault(turn * (1 + 2 * tolerance::kRigid)), Fault::NotOrthonormal);  // a scale
  EXPECT_EQ(fault(turn * (1 + 0.25 * tolerance::kRigid)), Fault::None);
  EXPECT_EQ(fault(Mat3::Constant(kNaN)), Fault::NotFinite);
  EXPECT_EQ(check_pose(Transform(turn, Vec3(0, kNaN, 0))).fault, Fault::NotFinite);
  // A 4x4 matrix's last row: within kRigid of (0, 0, 0, 1), else not affine; NaN: not finite.
  const Transform t(turn, Vec3(1, 2, 3));
  EXPECT_TRUE(check_pose(t, 0, 0, 0.25 * tolerance::kRigid, 1).rigid());
  EXPECT_EQ(check_pose(t, 0.1, 0, 0, 1).fault, Fault::NotAffine);
  EXPECT_EQ(check_pose(t, 0, 0, 0, 2).fault, Fault::NotAffine);
  EXPECT_EQ(check_pose(t, 0, kNaN, 0, 1).fault, Fault::NotFinite);
  EXPECT_EQ(check_pose(t, 1e308, 1e308, 0, 1).fault, Fault::NotAffine);  // finite, sum overflows
  // Each fault names itself; a rigid pose has no problem.
  EXPECT_EQ(check_pose(t).problem(), "");
  EXPECT_NE(check_pose(Transform(-turn, Vec3::Zero())).problem().find("reflection"),
            std::string::npos);
  EXPECT_NE(check_pose(Transform(2 * turn, Vec3::Zero())).problem().find("not orthonormal"),
            std::string::npos);
  EXPECT_NE(check_pose(t, 0, 0, 0, 2).problem().find("last row"), std::string::npos);
  // The written-out error against its definition, and one NaN entry anywhere propagating.
  Mat3 skew = turn;
  skew(0, 1) += 3e-7;
  skew(2, 0) -= 1e-6;
  EXPECT_NEAR(tolerance::orthonormality_error(skew),
              (skew.transpose() * skew - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_GT(tolerance::orthonormality_error(skew), 5e-7);
  for (int k = 0; k < 9; ++k) {
    Mat3 r = turn;
    r(k % 3, k / 3) = kNaN;
    EXPECT_TRUE(std::isnan(tolerance::orthonormality_error(r))) << k;
    EXPECT_EQ(fault(r), Fault::NotFinite) << k;
  }
}

}  // namespace
}  // namespace antcd
