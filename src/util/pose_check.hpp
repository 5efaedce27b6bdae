// The one rigid-pose check of the library (World::set_pose, sweep(), the WebAssembly bindings):
// finite entries, a rotation orthonormal within kPoseTolerance with determinant +1.
#pragma once

#include <antcd/math.hpp>

namespace antcd::detail {

/// Largest |R^T R - I| entry a pose's rotation may have.
inline constexpr Scalar kPoseTolerance = 1e-6;

/// The problem with `pose` as a short phrase ("is not finite ...", "is not a rigid motion ..."),
/// or nullptr for a rigid pose. `err` receives the orthonormality error (0 when not finite).
/// No allocation: it runs for every pose of every frame.
inline const char* pose_problem(const Transform& pose, Scalar& err) {
  err = 0;
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    return "is not finite (NaN or infinity)";
  }
  err = (pose.rotation.transpose() * pose.rotation - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (!(err <= kPoseTolerance) || !(pose.rotation.determinant() > 0)) {
    return "is not a rigid motion (rotation not orthonormal with determinant +1)";
  }
  return nullptr;
}

}  // namespace antcd::detail
