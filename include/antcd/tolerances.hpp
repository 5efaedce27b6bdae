// antcd/tolerances.hpp — the named tolerances every antcd query shares, one definition each.
//
// None of these is a tolerance on an ANSWER: exact predicates decide every verdict. They are
// rounding allowances by which conservative filters (bounding volumes, broad-phase boxes, cell
// grids) are widened so that rounding in double arithmetic never rejects something an exact test
// would accept, plus the one input check of what counts as a rigid rotation. Filters that must
// agree use the same constant: the World's broad phase keeps every pair that the hierarchy
// traversal (collide(), distance()) might accept only because its boxes are widened by at least
// the traversal's allowance, kVolume times a scale no smaller than the traversal's.
//
// Like Box2D's B2_LINEAR_SLOP or Jolt's cDefaultCollisionTolerance, but relative: antcd's meshes
// have no unit, so each allowance is the constant times a scale of the coordinates involved (the
// magnitudes of centres, radii and translations of the query), named where it is computed.
//
// Header-only constants and functions; thread-safe.
#pragma once

#include <antcd/math.hpp>

#include <cmath>

namespace antcd::tolerance {

/// Relative rounding allowance of bounding-volume tests: a volume test rejects only when apart by
/// more than kVolume * scale. The hierarchy traversal (bvh/traverse.hpp), the World's broad phase
/// and its posed boxes (world), ray casts against hierarchies, and the solid grid of point
/// queries. Why 1e-9: the arithmetic of one test (a box fit, a pose, a separating axis) is a few
/// dozen operations of relative rounding 1.1e-16 each, so about 1e-14 of the scale; 1e-9 leaves
/// five orders of magnitude of room and is still far below any gap that matters in mesh units.
inline constexpr Scalar kVolume = 1e-9;

/// Absolute floor added to relative allowances so that they stay positive for a scale of 0 (a
/// point-sized model at the origin). Far below any coordinate, above the smallest normal double.
inline constexpr Scalar kFloor = 1e-300;

/// Relative rounding allowance of a short computation (a handful of operations of relative
/// rounding 1.1e-16 each): a user's distance threshold (collide()'s delta, a World query's delta)
/// before it is compared with computed gaps, the slabs of a ray–box test, a sweep's motion bound
/// and its allowance on the scene's size (sweep.hpp).
inline constexpr Scalar kArithmetic = 1e-12;

/// Relative rounding allowance of point queries: a point against a triangle (on an edge, on the
/// surface), a node box, or a solid's surface (points.hpp, penetration.hpp's depth probes), on the
/// scale of the coordinates and sizes involved. A point query's arithmetic (a projection, a
/// barycentric split) rounds to about 1e-15 of that scale; 1e-10 is far above it and below any
/// offset a caller would mean.
inline constexpr Scalar kPoint = 1e-10;

/// A rotation is rigid when every entry of R^T R - I is at most this in magnitude (and det R > 0).
/// Loose on purpose: poses from single-precision sources, quaternion products or a 4x4 matrix
/// printed with 7 digits are accepted; a scale or shear of a millionth is not.
inline constexpr Scalar kRigid = 1e-6;

/// A quaternion given as text (scene files' rotation_wxyz, the CLI's --pose) is normalised when its
/// length is within this of 1, and refused otherwise: loose enough for values printed with 4
/// digits, tight enough that a typo (a missing sign, a digit too many) is caught.
inline constexpr Scalar kUnitQuaternion = 1e-3;

/// The rounding allowance of a volume test on coordinates of magnitude `scale`.
[[nodiscard]] inline Scalar volume_allowance(Scalar scale) { return kVolume * scale + kFloor; }

/// A computed quantity rounded up by kArithmetic (a threshold, a bound on a motion).
[[nodiscard]] inline Scalar widened(Scalar value) { return value * (1 + kArithmetic); }

/// The largest |(R^T R - I)_ij| of a rotation matrix (0 for an exact rotation); NaN when an entry
/// is NaN. Every pose check runs it (World::set_pose per object and frame, each WebAssembly
/// query's poses), so the six distinct entries of the symmetric R^T R are written out: Eigen's
/// general 3x3 product and reduction were a third of a culled WebAssembly query's time.
[[nodiscard]] inline Scalar orthonormality_error(const Mat3& r) {
  Scalar err = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const Scalar e =
          std::abs(r(0, i) * r(0, j) + r(1, i) * r(1, j) + r(2, i) * r(2, j) - (i == j ? 1 : 0));
      if (e > err || e != e) err = e;  // a NaN stays: nothing compares greater than it
    }
  }
  return err;
}

}  // namespace antcd::tolerance
