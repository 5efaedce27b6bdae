// Point-in-solid test for closed models (see volume.hpp).
#include "exact/volume.hpp"

#include <cmath>
#include <numbers>

namespace antcd::detail {

bool inside_closed(const Model& model, const Vec3& p) {
  // The root box contains the surface, hence the solid: a point beyond it is outside.
  const Obb box = model.root().obb();
  const Vec3 local = box.axes.transpose() * (p - box.center);
  if ((local.cwiseAbs() - box.half_extents).maxCoeff() > 0) return false;
  const LeafCorners verts = model.leaf_corners();
  Scalar total = 0;
  for (std::size_t t = 0; t < verts.size(); ++t) {
    total += geometry::solid_angle(p, verts(t, 0), verts(t, 1), verts(t, 2));
  }
  // ±1 inside (the sign is the orientation of the surface), 0 outside.
  return std::abs(total) > 2 * std::numbers::pi;
}

}  // namespace antcd::detail
