// antcd/points.hpp — point queries against a posed model: inside/outside and signed distance,
// for batches of points.
//
// Conventions
// - Points are given and returned in WORLD coordinates; `pose` maps the model's frame to the
//   world (as everywhere in antcd). Triangle indices are indices into the model's mesh.
// - Inside/outside is defined for models whose mesh is closed and consistently oriented
//   (Model::is_closed()): the solid is the set of points of non-zero generalised winding number
//   of the surface (for a surface that does not cross itself: the region it encloses, whichever
//   way it is oriented). contains() on an open model throws ArgumentError.
// - signed_distance(): the distance from the point to the surface (the closest point on the union
//   of the non-degenerate triangles), NEGATIVE inside the solid and positive outside. On an open
//   model no solid is defined: the distances are unsigned (>= 0) and SignedDistanceResult::is_signed
//   is false, so the caller can tell.
//
// Accuracy
// - contains(): the winding number is summed through the hierarchy: a node whose box does not
//   contain the point contributes the solid angle of a fan spanning its patch's boundary edges
//   (equal to the patch's own, by Stokes), the others their triangles'. The sum is rounded to
//   the nearest integer, so the answer is exact for every point farther from the surface than the
//   rounding of the solid angles (about 1e-12 of the model's size); points closer than that may be
//   classified either way. No ray is cast: edges and vertices need no special case.
// - signed_distance(): the distance and closest point are exact up to the rounding of the
//   point–triangle distance (a few ulps of the coordinates). The sign is read from the
//   angle-weighted pseudo-normal of the closest feature (face, edge or vertex; Bærentzen and
//   Aanæs), which agrees with the winding number for a surface that does not cross itself; the
//   winding number decides instead when that test is ill-conditioned (the point within rounding
//   of the surface, or nearly tangent to the feature) and for every point when the mesh has
//   several connected pieces with overlapping bounding boxes (overlapping or nested shells; slower).
//   A single piece that crosses itself may get a sign that differs from contains() near the
//   crossing. A point on the surface gets distance 0.
// - Results do not depend on the number of threads: each point is computed on its own.
//
// Cost: the first point query on a closed model derives per-node boundary fans and pseudo-normals
// (O(n log n) in the triangles, kept by the Model); then each point costs O(log n) node visits
// for the distance, more for the winding number. Batches run in parallel over the points with
// oneTBB.
//
// Thread safety: both queries are const; any number of threads may query the same Model at once
// (the first-use data is built exactly once under a once-flag). Model::refit() is a mutation and
// must not run concurrently with queries on the same Model.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/error.hpp>
#include <antcd/export.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace antcd {

struct PointDistance {
  /// Distance to the surface: negative inside the solid, positive outside, 0 on the surface.
  /// Unsigned (>= 0) when the model is open (SignedDistanceResult::is_signed false).
  Scalar distance = 0;
  /// Closest point of the surface, world frame.
  Vec3 closest = Vec3::Zero();
  /// Mesh triangle that holds the closest point.
  std::uint32_t triangle = 0;
};

struct SignedDistanceResult {
  /// One entry per query point, in the same order.
  std::vector<PointDistance> points;
  /// The model is closed, so the distances carry a sign. False: unsigned distances.
  bool is_signed = false;
};

/// For each point (world frame): 1 when it lies inside the solid bounded by the posed model, else 0.
/// Throws ArgumentError when the model is not closed (Model::is_closed) or a point is not finite
/// (naming its index).
ANTCD_API std::vector<std::uint8_t> contains(const Model& model, const Transform& pose,
                                             std::span<const Vec3> points);

/// Signed distance, closest point and triangle of the posed model's surface for each point
/// (world frame); see the header comment for the sign. Throws ArgumentError when a point is not
/// finite (naming its index).
ANTCD_API SignedDistanceResult signed_distance(const Model& model, const Transform& pose,
                                               std::span<const Vec3> points);

}  // namespace antcd
