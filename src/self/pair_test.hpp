// Private: the exact verdict on one pair of triangles of a mesh under the sharing rule of
// antcd/self.hpp, and the per-triangle exact facts the self queries start from (pair_test.cpp).
#pragma once

#include <antcd/mesh.hpp>

#include <cstdint>

namespace antcd::self_detail {

/// Exact facts about one triangle's normal n = (b - a) x (c - a): bit 2k is set only when n_k > 0
/// and bit 2k + 1 only when n_k < 0 (k = 0, 1, 2; exact signs). A nonzero n_k may leave its bits
/// clear when another component's sign is proved in floating point (the cone cull then has fewer
/// axes, never a wrong one). Zero exactly for a degenerate triangle. When `axis` is not null it
/// receives certificate_axis(a, b, c), found from the same floating-point components.
std::uint8_t normal_signs(const Vec3& a, const Vec3& b, const Vec3& c, int* axis = nullptr);

/// What a caller may already know about a pair; only the cost depends on it, never the verdict.
struct PairHint {
  /// The projection the certificates use for triangle i: the axis (0, 1, 2) a projection along
  /// which drops, any of the three (-1: the dominant axis of i's normal, found here).
  int axis = -1;
  /// A box filter ran already (the caller's boxes of the two triangles, which hold their exact
  /// boxes, overlap): the exact box test in front of the triangle test is skipped.
  bool boxes_tested = false;
};

/// The dominant axis of the floating-point normal (b - a) x (c - a): the projection the pair
/// test's certificates prefer (PairHint::axis).
int certificate_axis(const Vec3& a, const Vec3& b, const Vec3& c);

/// Whether triangles i and j (distinct, both of non-zero area) of `mesh` intersect beyond what
/// their shared vertex indices require (antcd/self.hpp). `shared` is set to the number of vertex
/// indices they share (0 to 3).
bool pair_intersects(const Mesh& mesh, std::uint32_t i, std::uint32_t j, int& shared,
                     PairHint hint = {});

/// The same for triangles with corners ti and tj (vertex indices into mesh.vertices), as a caller
/// that keeps the corners beside its boxes passes them.
bool pair_intersects(const Mesh& mesh, const TriangleIndices& ti, const TriangleIndices& tj,
                     int& shared, PairHint hint = {});

}  // namespace antcd::self_detail
