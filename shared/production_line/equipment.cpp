#include "shared/production_line/equipment.hpp"

#include "shared/production_line/poses.hpp"

#include <algorithm>

namespace antcd::shared::line {

std::vector<Part> roller_parts() {
  return {cylinder_part(kRollerRadius, kRollerLength, z_to_y(), Vec3::Zero())};
}

std::vector<Part> sheet_parts() {
  return {box_part(Vec3(kSheetHalfX, kSheetHalfY, kSheetHalfZ), Vec3::Zero())};
}

/// Conveyor bed under `rollers` rollers, centred on x = 0, floor at z = 0: two side rails with a
/// 2 cm gap to the roller ends, cross members below the rollers, four legs.
std::vector<Part> bed_parts(std::size_t rollers, bool simple) {
  const Scalar half = static_cast<Scalar>(rollers) * kRollerPitch / 2;
  std::vector<Part> parts;
  for (const Scalar y : {-kRailY, kRailY}) {
    parts.push_back(box_part(Vec3(half, kRailHalfY, 0.06), Vec3(0, y, kRollerAxisZ)));
  }
  if (simple) return parts;
  // Cross members between two rollers, 2 cm below them.
  const Scalar cross_z = kRollerAxisZ - kRollerRadius - 0.02 - 0.03;
  std::vector<std::size_t> gaps{1};
  if (rollers >= 4) gaps.push_back(rollers / 2);
  if (rollers >= 3) gaps.push_back(rollers - 1);
  gaps.erase(std::unique(gaps.begin(), gaps.end()), gaps.end());
  for (const std::size_t g : gaps) {
    const Scalar x = -half + kRollerPitch * static_cast<Scalar>(g);
    parts.push_back(box_part(Vec3(0.03, kRailY + kRailHalfY, 0.03), Vec3(x, 0, cross_z)));
  }
  const Scalar leg_half_z = (kRollerAxisZ - 0.06) / 2;
  for (const Scalar x : {-half + 0.06, half - 0.06}) {
    for (const Scalar y : {-kRailY, kRailY}) {
      parts.push_back(box_part(Vec3(0.04, 0.04, leg_half_z), Vec3(x, y, leg_half_z)));
    }
  }
  return parts;
}

/// Portal frame across a conveyor: two columns 0.1 m outside the rails and a beam at 1.66 m.
std::vector<Part> portal_parts(bool simple) {
  std::vector<Part> parts;
  if (!simple) {
    for (const Scalar y : {-0.9, 0.9}) {
      parts.push_back(box_part(Vec3(0.06, 0.06, 0.8), Vec3(0, y, 0.8)));
    }
  }
  parts.push_back(box_part(Vec3(0.06, 0.96, 0.06), Vec3(0, 0, 1.66)));
  return parts;
}

/// Drying tunnel over a conveyor of `rollers` rollers: roof and two side walls.
std::vector<Part> dryer_parts(std::size_t rollers, bool simple) {
  const Scalar half = static_cast<Scalar>(rollers) * kRollerPitch / 2 + 0.1;
  std::vector<Part> parts{box_part(Vec3(half, 1.0, 0.05), Vec3(0, 0, 1.65))};
  if (simple) return parts;
  for (const Scalar y : {-0.95, 0.95}) {
    parts.push_back(box_part(Vec3(half, 0.05, 0.8), Vec3(0, y, 0.8)));
  }
  return parts;
}

/// Press frame: base, four columns 6 cm clear of the platens, crown.
std::vector<Part> press_frame_parts(bool simple) {
  std::vector<Part> parts{box_part(Vec3(0.8, 0.8, 0.08), Vec3(0, 0, 1.98))};
  if (simple) return parts;
  parts.push_back(box_part(Vec3(0.8, 0.8, 0.15), Vec3(0, 0, 0.15)));
  for (const Scalar x : {-0.72, 0.72}) {
    for (const Scalar y : {-0.68, 0.68}) {
      parts.push_back(box_part(Vec3(0.06, 0.06, 0.95), Vec3(x, y, 0.95)));
    }
  }
  return parts;
}

std::vector<Part> press_plate_parts() {
  return {box_part(Vec3(kPlatenHalfX, 0.55, kPlatenHalfZ), Vec3::Zero())};
}

/// Pallet 1.2 × 1.0 × 0.122, origin at the bottom centre: three runners along x, five top slats.
std::vector<Part> pallet_parts(bool simple) {
  if (simple) {
    return {box_part(Vec3(kPalletHalfX, 0.5, kPalletHeight / 2), Vec3(0, 0, kPalletHeight / 2))};
  }
  std::vector<Part> parts;
  for (const Scalar y : {-0.44, 0.0, 0.44}) {
    parts.push_back(box_part(Vec3(kPalletHalfX, 0.05, 0.05), Vec3(0, y, 0.05)));
  }
  for (const Scalar x : {-0.52, -0.26, 0.0, 0.26, 0.52}) {
    parts.push_back(box_part(Vec3(0.07, 0.5, 0.011), Vec3(x, 0, 0.111)));
  }
  return parts;
}

/// Robot pedestal (0.7 m) with a floor flange; the shoulder sphere (on the upper arm) clears its
/// top by 5 cm.
std::vector<Part> robot_base_parts(bool simple) {
  std::vector<Part> parts{cylinder_part(0.2, 0.7, Mat3::Identity(), Vec3(0, 0, 0.35))};
  if (!simple) parts.push_back(cylinder_part(0.32, 0.04, Mat3::Identity(), Vec3(0, 0, 0.02)));
  return parts;
}

/// Upper arm along +x from the shoulder: shoulder sphere and a tube that stops 2 cm short of the
/// elbow sphere (which belongs to the forearm).
std::vector<Part> upper_arm_parts(bool simple) {
  const Scalar tube = kUpperArm - 0.11 - 0.02;
  std::vector<Part> parts{cylinder_part(0.06, tube, z_to_x(), Vec3(tube / 2, 0, 0))};
  if (!simple) parts.push_back(sphere_part(0.15, Vec3::Zero()));
  return parts;
}

/// Forearm along +x from the elbow: elbow sphere, tube, and the tip sphere (the gripper) at 1 m.
std::vector<Part> forearm_parts(bool simple) {
  std::vector<Part> parts{sphere_part(kTipRadius, Vec3(kForearm, 0, 0))};
  if (simple) return parts;
  parts.push_back(cylinder_part(0.045, kForearm, z_to_x(), Vec3(kForearm / 2, 0, 0)));
  parts.push_back(sphere_part(0.11, Vec3::Zero()));
  return parts;
}

std::vector<Part> column_parts() { return {box_part(Vec3(0.1, 0.1, 1.0), Vec3(0, 0, 1.0))}; }

}  // namespace antcd::shared::line
