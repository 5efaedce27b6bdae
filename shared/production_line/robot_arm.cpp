#include "shared/production_line/robot_arm.hpp"

#include "shared/production_line/equipment.hpp"
#include "shared/production_line/poses.hpp"

#include <algorithm>
#include <cmath>

namespace antcd::shared::line {

/// Elbow-up inverse kinematics of the two links for a tip at horizontal reach r and height z
/// (relative to the shoulder) in the vertical plane of `yaw`.
ArmPose solve_arm(Scalar yaw, Scalar r, Scalar z) {
  const Scalar d = std::clamp(std::hypot(r, z), std::abs(kUpperArm - kForearm) + 1e-6,
                              kUpperArm + kForearm - 1e-6);
  const Scalar phi = std::atan2(z, r);
  const Scalar beta = std::acos(std::clamp(
      (kUpperArm * kUpperArm + d * d - kForearm * kForearm) / (2 * kUpperArm * d), -1.0, 1.0));
  ArmPose a;
  a.yaw = yaw;
  a.upper = phi + beta;
  a.fore = std::atan2(z - kUpperArm * std::sin(a.upper), r - kUpperArm * std::cos(a.upper));
  return a;
}

ArmPose blend(const ArmPose& a, const ArmPose& b, Scalar t) {
  const Scalar s = smoothstep(t);
  return {lerp(a.yaw, b.yaw, s), lerp(a.upper, b.upper, s), lerp(a.fore, b.fore, s)};
}

}  // namespace antcd::shared::line
