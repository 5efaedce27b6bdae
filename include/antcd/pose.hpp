// antcd/pose.hpp — the one rigid-pose check, for the library (World, sweeps, scenes) and its front
// ends (the CLI, Python, WebAssembly): a pose is accepted when its entries are finite and its
// rotation is orthonormal within tolerance::kRigid (antcd/tolerances.hpp) with determinant +1;
// a 4x4 matrix also needs its last row (0, 0, 0, 1) within tolerance::kRigid. Header only.
// check_pose allocates nothing (it runs for every pose of every frame); PoseCheck::problem()
// builds the message of a refused pose.
#pragma once

#include <antcd/math.hpp>
#include <antcd/tolerances.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace antcd {

struct PoseCheck {
  enum class Fault {
    None,            ///< a rigid pose
    NotFinite,       ///< an entry is NaN or infinite
    NotOrthonormal,  ///< max |R^T R - I| > tolerance::kRigid (a scale or a shear)
    Reflection,      ///< orthonormal, determinant -1
    NotAffine,       ///< a 4x4 matrix whose last row is not (0, 0, 0, 1)
  };
  Fault fault = Fault::None;
  /// max |R^T R - I| of the rotation (0 when an entry is not finite).
  Scalar orthonormality_error = 0;

  [[nodiscard]] bool rigid() const { return fault == Fault::None; }
  /// The fault as a phrase to follow the pose's name ("poses[3] is not finite ..."); empty for a
  /// rigid pose.
  [[nodiscard]] std::string problem() const {
    switch (fault) {
      case Fault::None:
        return {};
      case Fault::NotFinite:
        return "is not finite (NaN or infinity)";
      case Fault::NotOrthonormal: {
        char text[160];
        std::snprintf(text, sizeof text,
                      "is not a rigid motion: rotation is not orthonormal (max |R^T R - I| = %.3g "
                      "> %.3g): no scale or shear",
                      orthonormality_error, tolerance::kRigid);
        return text;
      }
      case Fault::Reflection:
        return "is not a rigid motion: rotation has determinant -1 (a reflection)";
      case Fault::NotAffine:
        return "is not a rigid motion: last row must be [0, 0, 0, 1] (no projective part)";
    }
    return {};
  }
};

/// Whether `pose` is a rigid motion (see the top of this file).
[[nodiscard]] inline PoseCheck check_pose(const Transform& pose) noexcept {
  PoseCheck c;
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    c.fault = PoseCheck::Fault::NotFinite;
    return c;
  }
  c.orthonormality_error = tolerance::orthonormality_error(pose.rotation);
  if (!(c.orthonormality_error <= tolerance::kRigid)) {
    c.fault = PoseCheck::Fault::NotOrthonormal;
  } else if (!(pose.rotation.determinant() > 0)) {
    c.fault = PoseCheck::Fault::Reflection;
  }
  return c;
}

/// check_pose of a 4x4 homogeneous matrix given as `pose` (its upper 3x4) and its last row.
[[nodiscard]] inline PoseCheck check_pose(const Transform& pose, Scalar r30, Scalar r31, Scalar r32,
                                          Scalar r33) noexcept {
  PoseCheck c = check_pose(pose);
  if (c.rigid() &&
      !(std::abs(r30) + std::abs(r31) + std::abs(r32) + std::abs(r33 - 1) <= tolerance::kRigid)) {
    const bool finite =
        std::isfinite(r30) && std::isfinite(r31) && std::isfinite(r32) && std::isfinite(r33);
    c.fault = finite ? PoseCheck::Fault::NotAffine : PoseCheck::Fault::NotFinite;
  }
  return c;
}

}  // namespace antcd
