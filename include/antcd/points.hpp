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
//   model no solid is defined: the distances are unsigned (>= 0) and
//   SignedDistanceResult::is_signed is false, so the caller can tell.
// - contains(p) is exactly (signed_distance(p) < 0): both read the sign the same way (below). A
//   point on the surface (distance 0) is not contained.
//
// How the sign is decided (both queries), in this order:
// 1. Away from the surface: a voxel grid over the model (about 8 cells per triangle) marks every
//    cell that the box of some triangle (grown by 1e-9 of the model's size) meets. The other cells
//    form connected regions the surface does not cross; the winding number of each is computed
//    once, exactly (far from the surface), and a point in such a cell, or outside the grid, takes
//    it (regions beyond a budget of about 1000 + n/16, n the triangles, are left to step 2). This
//    is the winding-number definition itself, with no approximation.
// 2. Near the surface (a point in a marked cell): the angle-weighted pseudo-normal of the closest
//    feature (face, edge or vertex; Bærentzen and Aanæs): inside when the point lies behind it.
//    For a closed surface that does not cross itself this equals the winding number.
// 3. The winding number, summed exactly through the hierarchy (a node whose box does not contain
//    the point contributes the solid angle of a fan over its patch's boundary edges), decides
//    instead of 2. when 2. is ambiguous: the offset from the closest point is within 1e-6
//    (relative) of perpendicular to the pseudo-normal, or the closest point lies on all three edges
//    of its triangle (within 1e-10 of its size and coordinates); and for every point near the
//    surface when the mesh has several connected pieces whose bounding boxes overlap (nested or
//    overlapping shells). The winding number is rounded to the nearest integer, so it is exact for
//    points farther from the surface than about 1e-12 of the model's size.
// Consequently a single piece that crosses itself may, within a grid cell of the crossing, get
// the side of its nearest sheet rather than its winding number. A point within rounding of the
// surface (about 1e-12 of the model's size) may be classified either way.
//
// Accuracy of the distance: the distance, closest point and triangle are those of the brute-force
// minimum over all triangles of the same point–triangle distance (a few ulps of the coordinates)
// in the model's frame; among equally near triangles, the first in the hierarchy's leaf order. The
// hierarchy only prunes with bounds compared at a margin far above their rounding, so it never
// changes the answer.
//
// Results do not depend on the number of threads, on the order of the points, or on the other
// points of the batch: each point's answer is the one above.
//
// Cost: the first point query on a model builds a compact axis-aligned copy of its hierarchy
// with per-triangle plane and edge data (O(n), about 160 bytes per triangle); on a closed model
// also the boundary fans, pseudo-normals and the grid (O(n log n)). Then a point costs one grid
// lookup (contains(), away from the surface), or a closest-point descent: O(log n) nodes for a
// point near the surface, more for a point far from it relative to the triangles' size (the number
// of triangles that come near to being closest grows with that ratio). Batches are visited along a
// Morton curve, each point's descent seeded with its predecessor's closest triangle, in parallel
// over blocks of points with oneTBB.
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

/// For each point (world frame): 1 when it lies inside the solid bounded by the posed model, else
/// 0. Throws ArgumentError when the model is not closed (Model::is_closed) or a point is not finite
/// (naming its index).
ANTCD_API std::vector<std::uint8_t> contains(const Model& model, const Transform& pose,
                                             std::span<const Vec3> points);

/// Signed distance, closest point and triangle of the posed model's surface for each point
/// (world frame); see the header comment for the sign. Throws ArgumentError when a point is not
/// finite (naming its index).
ANTCD_API SignedDistanceResult signed_distance(const Model& model, const Transform& pose,
                                               std::span<const Vec3> points);

}  // namespace antcd
