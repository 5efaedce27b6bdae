// Private: bounds on a rigid motion (antcd/ccd.hpp's interpolation) shared by the mesh sweep and
// the World's continuous queries.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/error.hpp>
#include <antcd/math.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "util/check.hpp"

namespace antcd::ccd {

/// Throws ArgumentError "<function>: <argument>[ <what>] is beyond the continuous queries'
/// coordinate range (+-1e+100), got <value>" when |value| > kSweepCoordinateRange (or NaN).
inline void require_sweep_range(std::string_view function, std::string_view argument,
                                std::string_view what, Scalar value) {
  if (std::abs(value) <= kSweepCoordinateRange) return;
  std::string msg(function);
  msg.append(": ").append(argument);
  if (!what.empty()) msg.append(" ").append(what);
  msg.append(" is beyond the continuous queries' coordinate range (+-");
  msg.append(number_text(kSweepCoordinateRange)).append("), got ");
  msg.append(number_text(value));
  throw ArgumentError(msg);
}

/// require_sweep_range on the largest entry of the pose's translation.
inline void require_sweep_translation(std::string_view function, std::string_view argument,
                                      const Transform& pose) {
  int k = 0;
  pose.translation.cwiseAbs().maxCoeff(&k);
  require_sweep_range(function, argument, "translation", pose.translation[k]);
}

/// Angle of the rotation from r0 to r1 along the shorter arc (the slerp's total angle), rounded up.
inline Scalar rotation_angle(const Mat3& r0, const Mat3& r1) {
  const Scalar angle = Quat(r0).angularDistance(Quat(r1));
  return tolerance::widened(angle) + 1e-15;
}

/// Radius about the model origin holding every vertex of the model's tree (root sphere).
inline Scalar origin_radius(const Model& m) {
  return m.root().center.norm() + static_cast<Scalar>(m.root().radius);
}

/// The turn of one model over a motion from rotation r0 to r1 (the slerp of
/// ccd::interpolate_pose): R(t) = R0 exp(t theta [k]), k a unit axis in the model frame. A model
/// point p stays on a circle about that axis through the model origin, of radius |k x p| (its
/// distance from the axis), so the turn moves it at theta |k x p| per unit time and its path's
/// second derivative is theta^2 |k x p|: a wheel, roller or fan spinning about its own axis moves
/// its rim, not its far ends. reach(p) bounds that radius, allowing for the computed axis's
/// rounding; where the turn is too small for its axis to be known, reach(p) = |p|.
struct Spin {
  Scalar theta = 0;          ///< >= the rotation angle (ccd::rotation_angle)
  Vec3 axis = Vec3::Zero();  ///< the computed unit axis (model frame), when about_axis
  Scalar axis_error = 0;     ///< >= |computed axis - true axis|
  bool about_axis = false;   ///< false: no axis known, reach is the distance from the origin

  /// >= the distance of model point p (model frame) from the turn's axis through the origin (not
  /// rounded up: callers widen their sums).
  [[nodiscard]] Scalar reach(const Vec3& p) const {
    if (!about_axis) return p.norm();
    return axis.cross(p).norm() + axis_error * p.cwiseAbs().sum();  // |p| <= |p|_1
  }

  /// >= the distance from the axis of every offset d of a point of the node from its centre (the
  /// turn moves such a point about the centre by at most theta |k x d| per unit time): its
  /// radius, or through its box, the sum of its half extents times |k x box axis| where less
  /// (a long node along the axis, a roller's, hardly turns about its centre).
  [[nodiscard]] Scalar node_reach(const BvhNode& n) const {
    const Scalar radius = n.radius;
    if (!about_axis) return radius;
    const Vec3 axis2 = n.axis0.cross(n.axis1);
    const Scalar box = n.half[0] * axis.cross(n.axis0).norm() +
                       n.half[1] * axis.cross(n.axis1).norm() +
                       n.half[2] * axis.cross(axis2).norm() +
                       axis_error * (Scalar{n.half[0]} + n.half[1] + n.half[2]);
    return std::min(radius, tolerance::widened(box));
  }
};

/// The unit quaternion q0 of r0 and the rotation q0^-1 q1 from it to r1's (w >= 0: the shorter
/// arc, as the slerp of ccd::interpolate_pose takes): the turn is q(t) = q0 (q0^-1 q1)^t.
struct TurnDelta {
  Quat q0;
  Quat delta;
};
inline TurnDelta turn_delta(const Mat3& r0, const Mat3& r1) {
  TurnDelta d{Quat(r0).normalized(), Quat::Identity()};
  d.delta = d.q0.conjugate() * Quat(r1).normalized();
  if (d.delta.w() < 0) d.delta.coeffs() = -d.delta.coeffs();
  return d;
}

/// The turn from r0 to r1. The axis is the vector part of q0^-1 q1 (turn_delta), normalised: each
/// of its components is a sum of four products of unit components, wrong by a few 1e-16 after the
/// two normalisations; kAxisRounding bounds that error with room to spare, and normalising a vector
/// of length s errs by at most 2 e / s in direction. Below kAxisFloor (turns under 2e-9 rad) the
/// axis is not used.
inline Spin spin(const Mat3& r0, const Mat3& r1) {
  constexpr Scalar kAxisRounding = 1e-13;
  constexpr Scalar kAxisFloor = 1e-9;
  Spin s;
  s.theta = rotation_angle(r0, r1);
  const Quat delta = turn_delta(r0, r1).delta;
  const Scalar length = delta.vec().norm();
  if (length > kAxisFloor) {
    s.axis = delta.vec() / length;
    s.axis_error = 2 * kAxisRounding / length;
    s.about_axis = true;
  }
  return s;
}

/// >= spin.reach(p) over every point p of the model's tree: the root sphere's bound (reach of its
/// centre plus its radius), or the largest reach of the root box's corners where less (reach is
/// convex in p, so a box's largest is at a corner; the box's float extents are rounded outwards,
/// the corners' arithmetic is covered by kVolume of their size).
inline Scalar model_reach(const Model& m, const Spin& s) {
  const BvhNode& root = m.root();
  const Scalar sphere = s.reach(root.center) + static_cast<Scalar>(root.radius);
  if (!s.about_axis) return sphere;
  const Mat3 axes = root.axes();
  const Vec3 half = root.half_extents();
  Scalar box = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 sign((corner & 1) != 0 ? 1 : -1, (corner & 2) != 0 ? 1 : -1,
                    (corner & 4) != 0 ? 1 : -1);
    box = std::max(box, s.reach(root.center + axes * sign.cwiseProduct(half)));
  }
  box += tolerance::kVolume * (root.center.norm() + half.sum());
  return std::min(sphere, box);
}

/// The turn of model `m` from r0 to r1 (ccd::spin) in a pair whose relative translation is
/// `speed`, keeping its axis only where the turn is at least as fast as that translation
/// (theta origin_radius >= speed: a roller, wheel or fan spinning in place, a robot link turning
/// about its joint). Elsewhere the axis is dropped and every bound uses |p| again: the axis
/// costs a cross product or more per bound, and with tighter margins the interval proofs go on
/// to succeed at the leaves where they used to fail at once and hand over (a thin sheet turning
/// about an axis in its plane, a frame ending just before contact: +41 % instructions).
/// Callgrind (sweeps only), this rule against keeping the axis also where it tightens the
/// model's own bound by a fifth: bench/ccd_bench frame_sweep sheets apart / sheets touching /
/// torus apart / torus touching 7.8 / 11.1 / 52.5 / 70.7 M against 11.0 / 11.7 / 52.5 / 70.7 M
/// (main before the axis: 7.8 / 10.9 / 51.8 / 68.4 M); the 12-frame production line 1.25 G
/// against 1.32 G (before: 1.73 G); the 60-frame assimp scene 4.43 G both (before: 6.52 G).
inline Spin model_spin(const Model& m, const Mat3& r0, const Mat3& r1, Scalar speed) {
  Spin s = spin(r0, r1);
  if (s.about_axis && s.theta * origin_radius(m) < speed) {
    s.about_axis = false;
    s.axis = Vec3::Zero();
    s.axis_error = 0;
  }
  return s;
}

}  // namespace antcd::ccd
