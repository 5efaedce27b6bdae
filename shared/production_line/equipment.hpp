// shared/production_line/equipment.hpp — the equipment of the veneer line: dimensions (metres)
// and the primitives each kind of equipment is made of (internal to the generator).
#pragma once

#include "shared/production_line/tessellation.hpp"

#include <cstddef>
#include <vector>

namespace antcd::shared::line {

inline constexpr Scalar kContact = 0.002;  ///< interpenetration of resting contacts beyond the sag
inline constexpr Scalar kRollerRadius = 0.05;
inline constexpr Scalar kRollerLength = 1.30;
inline constexpr Scalar kRollerPitch = 0.25;
inline constexpr Scalar kRollerAxisZ = 0.80;
inline constexpr Scalar kRollerTop = kRollerAxisZ + kRollerRadius;
inline constexpr Scalar kRailHalfY = 0.04;
inline constexpr Scalar kRailY =
    kRollerLength / 2 + 0.02 + kRailHalfY;  // 2 cm gap to the roller ends
inline constexpr Scalar kSheetHalfX = 0.45;
inline constexpr Scalar kSheetHalfY = 0.45;
inline constexpr Scalar kSheetHalfZ = 0.005;
inline constexpr Scalar kPalletHalfX = 0.60;
inline constexpr Scalar kPalletHeight = 0.122;
inline constexpr Scalar kStationGap = 1.2;  ///< plus 0–0.3 m from the seed

// Hot press: platens 1.2 × 1.1 × 0.1, lower platen top at the conveyor's sheet level.
inline constexpr Scalar kPlatenHalfX = 0.60;
inline constexpr Scalar kPlatenHalfZ = 0.05;
inline constexpr Scalar kPressLength = 3.2;
inline constexpr Scalar kPressSheetTravel =
    1.10;  ///< sheet centre: from -travel (off the platen) to 0
inline constexpr Scalar kPressOpening = 0.40;

// Robot: shoulder 0.9 m above the floor, both links 1 m.
inline constexpr Scalar kShoulderZ = 0.90;
inline constexpr Scalar kUpperArm = 1.0;
inline constexpr Scalar kForearm = 1.0;
inline constexpr Scalar kTipRadius = 0.08;
inline constexpr Scalar kRobotY = -1.5;        ///< base, beside the pallet conveyor
inline constexpr Scalar kRobotTargetY = -2.7;  ///< the pallet the robot touches
inline constexpr Scalar kRobotCellLength = 2.6;

// Each function gives the parts of one kind of equipment in its own frame; `simple` is a version
// with fewer primitives, used when the vertex budget is too small for the full one.

std::vector<Part> roller_parts();

std::vector<Part> sheet_parts();

/// Conveyor bed under `rollers` rollers, centred on x = 0, floor at z = 0: two side rails with a
/// 2 cm gap to the roller ends, cross members below the rollers, four legs.
std::vector<Part> bed_parts(std::size_t rollers, bool simple);

/// Portal frame across a conveyor: two columns 0.1 m outside the rails and a beam at 1.66 m.
std::vector<Part> portal_parts(bool simple);

/// Drying tunnel over a conveyor of `rollers` rollers: roof and two side walls.
std::vector<Part> dryer_parts(std::size_t rollers, bool simple);

/// Press frame: base, four columns 6 cm clear of the platens, crown.
std::vector<Part> press_frame_parts(bool simple);

std::vector<Part> press_plate_parts();

/// Pallet 1.2 × 1.0 × 0.122, origin at the bottom centre: three runners along x, five top slats.
std::vector<Part> pallet_parts(bool simple);

/// Robot pedestal (0.7 m) with a floor flange; the shoulder sphere (on the upper arm) clears its
/// top by 5 cm.
std::vector<Part> robot_base_parts(bool simple);

/// Upper arm along +x from the shoulder: shoulder sphere and a tube that stops 2 cm short of the
/// elbow sphere (which belongs to the forearm).
std::vector<Part> upper_arm_parts(bool simple);

/// Forearm along +x from the elbow: elbow sphere, tube, and the tip sphere (the gripper) at 1 m.
std::vector<Part> forearm_parts(bool simple);

std::vector<Part> column_parts();

}  // namespace antcd::shared::line
