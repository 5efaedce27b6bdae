// shared/production_line/flexible.hpp — the flexible veneer sheets of `antcd scene generate
// --flexible` (internal to the production-line generator): a tessellated sheet of zero thickness
// whose vertices follow its support frame by frame.
//
// - Sag: over a roller conveyor the sheet rests on the rollers (its surface kContact plus the
//   tessellation's sag into each) and sags between them, kSagDepth at mid-pitch (a sin^2 profile
//   from the roller's edge to mid-pitch).
// - Droop: past the first or the last roller the sheet droops, kDroopRate * d^2 below the rollers
//   at a distance d beyond the last roller's edge (vertical displacement; lengths not preserved).
// - Fold: one sheet of the line (the first flexible one) folds onto itself, period after period:
//   its trailing flap (kFlapLength) curls up over a bend of radius kFoldRadius until it lies back
//   over the sheet, then tilts down until its tip is kFoldPress below the sheet's top (the flap
//   passes through the sheet there: a self-intersection), holds, and unfolds.
// The offsets are functions of the vertex's world x (the pose's x plus its own), so a folded flap
// sags and droops with the part of the sheet under it.
#pragma once

#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <cstddef>
#include <vector>

namespace antcd::shared::line {

inline constexpr Scalar kSagDepth = 0.008;
inline constexpr Scalar kDroopRate = 0.6;  ///< 1/m
inline constexpr Scalar kFlapLength = 0.35;
inline constexpr Scalar kFoldRadius = 0.02;
inline constexpr Scalar kFoldPress = 0.004;

/// The rollers a flexible sheet lies on: axes at first_axis + pitch * i, i < rollers.
struct RollerSupport {
  Scalar first_axis = 0;
  std::size_t rollers = 1;
  Scalar pitch = 0.25;
  Scalar radius = 0.05;
  /// The height of the sheet's surface at world x, relative to its height on a roller (<= 0).
  [[nodiscard]] Scalar offset(Scalar x) const;
};

/// The fold of the folding sheet at phase u in [0, 1) of its period: the flap's curl angle (0 to
/// pi) and its tilt below the horizontal once curled.
struct Fold {
  Scalar curl = 0;
  Scalar tilt = 0;
};
Fold fold_at(Scalar u);

/// The vertices of `rest` (a flat sheet in its z = 0 plane, flexible_sheet_mesh) when its frame is
/// at world x `world_x` on `support`, with `fold` applied (Fold{} for none).
std::vector<Vec3> sheet_frame(const Mesh& rest, const RollerSupport& support, Scalar world_x,
                              const Fold& fold);

}  // namespace antcd::shared::line
