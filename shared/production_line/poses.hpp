// shared/production_line/poses.hpp — the small pose and easing helpers of the production-line
// generator (internal).
#pragma once

#include <antcd/math.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace antcd::shared::line {

inline constexpr Scalar kPi = std::numbers::pi;

inline Scalar smoothstep(Scalar t) {
  t = std::clamp(t, Scalar{0}, Scalar{1});
  return t * t * (3 - 2 * t);
}

inline Scalar lerp(Scalar a, Scalar b, Scalar t) { return a + (b - a) * t; }

/// Fractional part in [0, 1).
inline Scalar fraction(Scalar x) {
  const Scalar f = x - std::floor(x);
  return f < 1 ? f : 0;
}

/// Translations are rounded to the micrometre: the file stays compact, and contact depths are
/// millimetres.
inline Vec3 round_um(const Vec3& v) {
  return {std::round(v.x() * 1e6) / 1e6, std::round(v.y() * 1e6) / 1e6,
          std::round(v.z() * 1e6) / 1e6};
}

inline Transform pose(const Mat3& rotation, const Vec3& translation) {
  Transform t;
  t.rotation = rotation;
  t.translation = round_um(translation);
  return t;
}

inline Transform at(const Vec3& translation) { return pose(Mat3::Identity(), translation); }

inline Mat3 rot(const Vec3& axis, Scalar angle) {
  return Eigen::AngleAxis<Scalar>(angle, axis.normalized()).toRotationMatrix();
}

/// Exact quarter turns (no rounding in cos(π/2)): the generators' z axis onto x or y.
inline Mat3 z_to_x() {
  Mat3 r;
  r << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // rotation of +90° about y
  return r;
}
inline Mat3 z_to_y() {
  Mat3 r;
  r << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // rotation of +90° about x (z → -y; the axis is what matters)
  return r;
}

}  // namespace antcd::shared::line
