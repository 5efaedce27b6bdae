#include "bvh/traverse.hpp"

namespace antcd {

TraversalStats overlapping_leaves(const Model& a, const Transform& pose_a, const Model& b,
                                  const Transform& pose_b, Scalar delta,
                                  std::vector<LeafPair>& out) {
  const detail::PairFrame frame(a, pose_a, b, pose_b, delta);
  return detail::dual_traverse(a, b, frame, [&](std::uint32_t la, std::uint32_t lb) {
    out.push_back({la, lb});
    return false;
  });
}

bool any_leaf_pair_overlaps(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, Scalar delta) {
  const detail::PairFrame frame(a, pose_a, b, pose_b, delta);
  bool found = false;
  detail::dual_traverse(a, b, frame, [&](std::uint32_t, std::uint32_t) { return found = true; });
  return found;
}

}  // namespace antcd
