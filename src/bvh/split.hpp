// Private: where a hierarchy node's triangles are cut in two (split.cpp).
#pragma once

#include <antcd/bvh.hpp>

#include "geometry/obb_fit.hpp"

#include <cstddef>
#include <span>

namespace antcd::detail {

/// From this depth on the split point is always the median, so the depth stays below
/// kMedianDepth + log2(n) + 1 whatever the triangle distribution, and the build O(n log n).
constexpr std::size_t kMedianDepth = 40;
// antcd/bvh.hpp's bound on the levels: the root, kMedianDepth levels of mean splits, then at most
// 32 median halvings of fewer than 2^32 triangles.
static_assert(kMaxTreeLevels >= 1 + kMedianDepth + 32);

/// Partitions `tris` (at least 2) of a node at `depth` into a left and a right part and returns
/// the size of the left part (0 < size < tris.size()).
std::size_t split_triangles(std::span<geometry::detail::FitTriangle> tris, std::size_t depth);

/// A triangle as the split sees it: its centroid only.
struct SplitCentroid {
  Vec3 centroid;
};

/// The same split of the same centroids in the same order: it moves the items exactly as the
/// FitTriangle overload moves the triangles, so a pass over these lighter items predicts the
/// tree's shape (the build counts its nodes this way before it writes them).
std::size_t split_triangles(std::span<SplitCentroid> tris, std::size_t depth);

}  // namespace antcd::detail
