// The one rigid-pose check of the library (World::set_pose, sweep(), the WebAssembly bindings):
// finite entries, a rotation orthonormal within tolerance::kRigid (antcd/tolerances.hpp) with
// determinant +1.
#pragma once

#include <antcd/math.hpp>
#include <antcd/tolerances.hpp>

namespace antcd::detail {

/// Largest |R^T R - I| entry a pose's rotation may have: tolerance::kRigid, under the name the
/// WebAssembly bindings use (not a second definition).
inline constexpr Scalar kPoseTolerance = tolerance::kRigid;

/// The problem with `pose` as a short phrase ("is not finite ...", "is not a rigid motion ..."),
/// or nullptr for a rigid pose. `err` receives the orthonormality error (0 when not finite).
/// No allocation: it runs for every pose of every frame.
inline const char* pose_problem(const Transform& pose, Scalar& err) {
  err = 0;
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    return "is not finite (NaN or infinity)";
  }
  err = tolerance::orthonormality_error(pose.rotation);
  if (!(err <= tolerance::kRigid) || !(pose.rotation.determinant() > 0)) {
    return "is not a rigid motion (rotation not orthonormal with determinant +1)";
  }
  return nullptr;
}

}  // namespace antcd::detail
