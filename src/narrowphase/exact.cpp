// Exact detection: the dual traversal's overlapping leaves, then triangle–triangle tests.
#include <antcd/collide.hpp>

#include "bvh/traverse.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace antcd {

bool collide(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
             const CollisionRequest& request, CollisionResult& result) {
  if (!(request.delta >= 0) || !std::isfinite(request.delta)) {
    throw std::invalid_argument("collision threshold delta must be finite and >= 0, got " +
                                std::to_string(request.delta));
  }
  result.clear();
  const detail::PairFrame frame(a, pose_a, b, pose_b, request.delta);
  const auto verts_a = a.leaf_vertices();
  const auto verts_b = b.leaf_vertices();
  const auto tris_a = a.leaf_triangles();
  const auto tris_b = b.leaf_triangles();
  const auto nodes_a = a.nodes();
  const auto nodes_b = b.nodes();
  const Scalar delta = request.delta;
  const std::size_t limit = request.all_contacts ? request.max_contacts : 1;

  result.traversal = detail::dual_traverse(a, b, frame, [&](std::uint32_t la, std::uint32_t lb) {
    const BvhNode& na = nodes_a[la];
    const BvhNode& nb = nodes_b[lb];

    // for the default sizes and falls back to per-triangle transforms for large leaves.
    for (std::uint32_t jb = nb.first_or_right; jb < nb.first_or_right + nb.count; ++jb) {
      const Vec3 b0 = frame.b_to_a.apply(verts_b[3 * jb]);
      const Vec3 b1 = frame.b_to_a.apply(verts_b[3 * jb + 1]);
      const Vec3 b2 = frame.b_to_a.apply(verts_b[3 * jb + 2]);
      for (std::uint32_t ia = na.first_or_right; ia < na.first_or_right + na.count; ++ia) {
        ++result.triangle_tests;
        Vec3 point;
        Scalar distance = 0;
        if (geometry::triangles_within(verts_a[3 * ia], verts_a[3 * ia + 1], verts_a[3 * ia + 2],
                                       b0, b1, b2, delta, &point, &distance)) {
          result.colliding = true;
          result.contacts.push_back({tris_a[ia], tris_b[jb], pose_a.apply(point), distance});
          if (limit != 0 && result.contacts.size() >= limit) return true;
        }
      }
    }
    return false;
  });
  return result.colliding;
}

CollisionResult collide(const Model& a, const Transform& pose_a, const Model& b,
                        const Transform& pose_b, const CollisionRequest& request) {
  CollisionResult result;
  collide(a, pose_a, b, pose_b, request, result);
  return result;
}

}  // namespace antcd
