// Private: what point queries derive once per closed model (boundary fans of the hierarchy's
// patches, pseudo-normals), and the per-point queries built on it (model frame).
#pragma once

#include <antcd/bvh.hpp>

#include "points/point_tree.hpp"
#include "points/solid_grid.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace antcd::detail {

struct PointIndex {
  /// Boundary edges (mesh vertex indices, oriented as in their triangle) of node i's patch:
  /// fan_edges[fan_first[i] .. fan_first[i + 1]). The patch's solid angle seen from a point
  /// outside the node's box equals that of the fan from the first boundary vertex over them.
  std::vector<std::uint32_t> fan_first;
  std::vector<std::array<std::uint32_t, 2>> fan_edges;
  /// Angle-weighted pseudo-normals, pointing out of the solid (flipped when the whole surface
  /// faces inward, i.e. encloses a negative volume): per leaf triangle k (leaf order) its unit face
  /// normal and the (unnormalised) normal sums of its edges (v_i, v_{i+1}); per mesh vertex the
  /// angle-weighted sum of its triangles' normals.
  std::vector<Vec3> face_normal;
  std::vector<std::array<Vec3, 3>> edge_normal;
  std::vector<Vec3> vertex_normal;
  /// The surface has several connected pieces whose bounding boxes overlap (overlapping or nested
  /// shells): the nearest feature's pseudo-normal need not tell the winding number there, so the
  /// sign of a distance is always read from the winding number.
  bool sign_by_winding = false;
  /// Inside/outside at once for points away from the surface.
  SolidGrid grid;
};

/// Builds the index of a closed model (fans and pseudo-normals).
PointIndex build_point_index(const Model& model);

/// The model's index, built on first use (once, thread-safe) and kept by the model.
const PointIndex& point_index(const Model& model);

/// Winding number of the model's surface at p (model frame), rounded to the nearest integer.
int winding_number(const Model& model, const PointIndex& index, const Vec3& p);

/// Whether p (model frame) is inside the closed model, read from the pseudo-normal of the closest
/// feature of `c` (the winding number decides where that test is ill-conditioned).
/// Use solid_state() first: it answers most points without a closest point.
bool inside_from_closest(const Model& model, const PointIndex& index, const Vec3& p,
                         const ClosestPoint& c);

/// SolidGrid::kInside / kOutside from the grid, or kSurface: then closest_point() and
/// inside_from_closest() decide.
inline std::uint8_t solid_state(const PointIndex& index, const Vec3& p) {
  return index.grid.classify(p);
}

/// Whether p (model frame) lies inside the solid of a closed model: contains()'s answer for that
/// one point (antcd/points.hpp says how the sign is read), without its argument checks and without
/// allocating once the model's point data exist. The library's one point-in-solid test: collide()'s
/// volume test and the penetration layer's nested solids use it too. The model must be closed.
bool inside_solid(const Model& model, const Vec3& p);

}  // namespace antcd::detail
