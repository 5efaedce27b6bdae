// antcd/math.hpp — scalar type, vector aliases and rigid transforms.
//
// antcd uses one scalar type everywhere (double). A Transform maps points from a model's own frame
// ("local" or "model" frame) into the world frame: p_world = R * p_local + t. R is a proper
// rotation (orthonormal, det = +1). All lengths are in the units of the mesh files; antcd never
// rescales.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace antcd {

using Scalar = double;
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
using Mat3 = Eigen::Matrix<Scalar, 3, 3>;
using Quat = Eigen::Quaternion<Scalar>;

/// A rigid motion: rotation then translation. p_world = rotation * p_local + translation.
struct Transform {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  static Transform identity() { return {}; }

  /// From a translation and a unit quaternion (w, x, y, z). The quaternion is normalised here;
  /// callers that must reject non-unit input (file parsers) check it before.
  static Transform from_quaternion(const Vec3& t, Scalar w, Scalar x, Scalar y, Scalar z) {
    Transform tr;
    tr.rotation = Quat(w, x, y, z).normalized().toRotationMatrix();
    tr.translation = t;
    return tr;
  }

  /// Rotation of `angle` radians about `axis` (need not be unit), then translation.
  static Transform from_axis_angle(const Vec3& axis, Scalar angle, const Vec3& t = Vec3::Zero()) {
    Transform tr;
    tr.rotation = Eigen::AngleAxis<Scalar>(angle, axis.normalized()).toRotationMatrix();
    tr.translation = t;
    return tr;
  }

  [[nodiscard]] Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
  [[nodiscard]] Vec3 apply_vector(const Vec3& v) const { return rotation * v; }

  [[nodiscard]] Transform inverse() const {
    Transform inv;
    inv.rotation = rotation.transpose();
    inv.translation = -(inv.rotation * translation);
    return inv;
  }

  /// (*this) ∘ other: first `other`, then `*this`.
  [[nodiscard]] Transform operator*(const Transform& other) const {
    Transform out;
    out.rotation = rotation * other.rotation;
    out.translation = rotation * other.translation + translation;
    return out;
  }
};

/// Axis-aligned box, used for bounds reports and broad phases.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<Scalar>::infinity());

  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  [[nodiscard]] bool empty() const { return (min.array() > max.array()).any(); }
  [[nodiscard]] Vec3 extent() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
};

}  // namespace antcd
