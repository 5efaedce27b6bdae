// Private: writing a fitted box and sphere into a BvhNode's compact storage (build.cpp, refit.cpp).
#pragma once

#include <antcd/bvh.hpp>

#include <cmath>
#include <limits>

namespace antcd::detail {

/// The smallest float >= x (x >= 0 or +inf; +inf past the float range).
inline float float_at_least(Scalar x) {
  if (!(x <= static_cast<Scalar>(std::numeric_limits<float>::max()))) {
    return std::numeric_limits<float>::infinity();
  }
  float f = static_cast<float>(x);
  if (static_cast<Scalar>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

/// The axes a node can store: `axes` with its third column replaced by the cross product of the
/// first two, computed as BvhNode::axes() computes it. Fit the extents along these.
inline Mat3 storable_axes(const Mat3& axes) {
  BvhNode node;
  node.axis0 = axes.col(0);
  node.axis1 = axes.col(1);
  return node.axes();
}

/// Stores `box` (whose axes are storable_axes of themselves) and the sphere about its centre of
/// `radius`; extents and radius are rounded up, so the node's volumes contain the given ones.
inline void store_volumes(BvhNode& node, const Obb& box, Scalar radius) {
  node.center = box.center;
  node.axis0 = box.axes.col(0);
  node.axis1 = box.axes.col(1);
  for (int k = 0; k < 3; ++k) node.half[k] = float_at_least(box.half_extents[k]);
  node.radius = float_at_least(radius);
}

}  // namespace antcd::detail
