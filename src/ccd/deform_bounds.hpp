// Private: the per-call bounds of a deforming mesh's hierarchy and the primitive ownership that
// lets each vertex–face and edge–edge pair be queried from one triangle pair only
// (antcd/deform_ccd.hpp, "Broad phase").
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace antcd::detail {

/// A hierarchy node's swept bounds: the boxes at t = 0 and t = 1 and the largest displacement of
/// its vertices towards -axis (dneg) and +axis (dpos), both >= 0. Leaf: count > 0 triangles at
/// DeformBounds::triangles[first, first + count). Internal: children left and right.
struct SweptNode {
  Vec3 lo0, hi0, lo1, hi1, dneg, dpos;
  std::uint32_t left = 0, right = 0, first = 0, count = 0;
  [[nodiscard]] bool is_leaf() const { return count != 0; }
};

/// Bit k (0..2): the triangle owns its corner k; bit 3 + k: it owns its edge (corner k, k + 1).
using OwnerMask = std::uint8_t;

struct DeformBounds {
  std::vector<SweptNode> nodes;
  std::vector<std::uint32_t> triangles;  ///< leaf order, then the zero-area triangles
  std::uint32_t root = 0;
  std::vector<OwnerMask> owner;   ///< per mesh triangle
  Scalar max_coordinate = 0;      ///< largest |coordinate| of V0 and V1
  Scalar max_displacement = 0;    ///< largest |V1 - V0| per axis
  std::size_t scratch_bytes = 0;  ///< peak bytes held while building and after
};

/// The bounds of `model`'s hierarchy (its node topology; the zero-area triangles it leaves out in
/// one extra leaf beside the root) for the motion V0 -> V1, and the ownership masks. O(n).
/// V0 and V1 must hold one finite position per mesh vertex (checked by the caller).
DeformBounds make_deform_bounds(const Model& model, std::span<const Vec3> V0,
                                std::span<const Vec3> V1);

/// Box over [0, s] of a node (or of a point set with the same fields), padded by `pad`.
inline void swept_box(const SweptNode& n, Scalar s, Scalar pad, Vec3& lo, Vec3& hi) {
  if (s >= 1) {
    lo = n.lo0.cwiseMin(n.lo1).array() - pad;
    hi = n.hi0.cwiseMax(n.hi1).array() + pad;
    return;
  }
  lo = (n.lo0 - s * n.dneg).cwiseMax(n.lo0.cwiseMin(n.lo1)).array() - pad;
  hi = (n.hi0 + s * n.dpos).cwiseMin(n.hi0.cwiseMax(n.hi1)).array() + pad;
}

}  // namespace antcd::detail
