// shared/production_line/robot_arm.hpp — the robot cell's two-link arm: elbow-up inverse
// kinematics and smooth blends between joint poses (internal to the generator).
#pragma once

#include <antcd/math.hpp>

namespace antcd::shared::line {

/// Joint angles: yaw about z, then the elevations of the upper arm and forearm above horizontal.
struct ArmPose {
  Scalar yaw = 0;
  Scalar upper = 0;
  Scalar fore = 0;
};

/// Elbow-up inverse kinematics of the two links (kUpperArm, kForearm) for a tip at horizontal
/// reach r and height z (relative to the shoulder) in the vertical plane of `yaw`.
ArmPose solve_arm(Scalar yaw, Scalar r, Scalar z);

/// From a to b with a smoothstep in t in [0, 1].
ArmPose blend(const ArmPose& a, const ArmPose& b, Scalar t);

}  // namespace antcd::shared::line
