// Private: whether a point lies inside the solid bounded by a closed model.
#pragma once

#include <antcd/bvh.hpp>

namespace antcd::detail {

/// Winding-number test of `p` (model frame) against the closed, consistently oriented surface of
/// `model`: the solid angles of all its triangles sum to ±4π inside and to 0 outside, so the
/// rounded sum is robust wherever p is not within rounding distance of the surface (no ray, so no
/// special case for edges and vertices). Points outside the root box are outside at once.
bool inside_closed(const Model& model, const Vec3& p);

}  // namespace antcd::detail
