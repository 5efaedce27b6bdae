// Model::refit: new vertex positions for the same triangles, the tree's topology kept and its
// bounding volumes recomputed bottom-up in O(n).
#include <antcd/bvh.hpp>

#include "bvh/model_cache.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace antcd {

namespace {

/// The box with `axes` holding the points, and the sphere about its centre through the farthest.
void fit_points(BvhNode& node, const Mat3& axes, std::span<const Vec3> points) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : points) {
    const Vec3 local = axes.transpose() * p;
    lo = lo.cwiseMin(local);
    hi = hi.cwiseMax(local);
  }
  node.obb.axes = axes;
  node.obb.center = axes * (0.5 * (lo + hi));
  node.obb.half_extents = 0.5 * (hi - lo);
}

std::array<Vec3, 8> corners(const Obb& box) {
  std::array<Vec3, 8> out;
  for (int i = 0; i < 8; ++i) {
    const Vec3 s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    out[i] = box.center + box.axes * s.cwiseProduct(box.half_extents);
  }
  return out;
}

}  // namespace

void Model::refit(std::span<const Vec3> new_vertices) {
  if (new_vertices.size() != mesh_.vertices.size()) {
    throw ArgumentError(source_ + ": refit: got " + std::to_string(new_vertices.size()) +
                        " vertices, the mesh has " + std::to_string(mesh_.vertices.size()));
  }
  for (std::size_t i = 0; i < new_vertices.size(); ++i) {
    if (!new_vertices[i].allFinite()) {
      throw ArgumentError(source_ + ": refit: vertex " + std::to_string(i) + " is not finite");
    }
  }
  // The tree holds the triangles that had non-zero area when it was built: one that gains an area
  // now would be missing from every query, so that needs a rebuild.
  std::vector<bool> in_tree(mesh_.triangles.size(), false);
  for (const std::uint32_t t : leaf_triangles_) in_tree[t] = true;
  for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
    if (in_tree[t]) continue;
    const auto& tri = mesh_.triangles[t];
    if (!geometry::is_degenerate_triangle(new_vertices[tri[0]], new_vertices[tri[1]],
                                          new_vertices[tri[2]])) {
      throw ArgumentError(source_ + ": refit: triangle " + std::to_string(t) +
                          " had zero area when the model was built and has not now; build a new "
                          "Model instead");
    }
  }

  std::copy(new_vertices.begin(), new_vertices.end(), mesh_.vertices.begin());
  for (std::size_t k = 0; k < leaf_triangles_.size(); ++k) {
    const auto& tri = mesh_.triangles[leaf_triangles_[k]];
    for (int i = 0; i < 3; ++i) leaf_vertices_[3 * k + i] = mesh_.vertices[tri[i]];
  }
  // Children come after their parent in the depth-first layout: refit from the last node back.
  // Each box keeps its axes; a leaf's extents come from its vertices, an internal node's from its
  // children's box corners (a bound, possibly looser than a fresh fit); each sphere is the smaller
  // of the box's circumscribed sphere and (internal nodes) the one about the box centre holding
  // the children's spheres, or (leaves) the one through the farthest vertex.
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    BvhNode& node = nodes_[i];
    if (node.is_leaf()) {
      const std::span<const Vec3> verts(leaf_vertices_.data() + 3 * std::size_t{node.first_or_right},
                                        3 * std::size_t{node.count});
      fit_points(node, node.obb.axes, verts);
      Scalar r2 = 0;
      for (const Vec3& v : verts) r2 = std::max(r2, (v - node.obb.center).squaredNorm());
      node.sphere = {node.obb.center, std::sqrt(r2)};
      continue;
    }
    const BvhNode& left = nodes_[i + 1];
    const BvhNode& right = nodes_[node.first_or_right];
    std::array<Vec3, 16> points;
    const auto cl = corners(left.obb);
    const auto cr = corners(right.obb);
    std::copy(cl.begin(), cl.end(), points.begin());
    std::copy(cr.begin(), cr.end(), points.begin() + 8);
    fit_points(node, node.obb.axes, points);
    const Scalar from_children =
        std::max((left.sphere.center - node.obb.center).norm() + left.sphere.radius,
                 (right.sphere.center - node.obb.center).norm() + right.sphere.radius);
    node.sphere = {node.obb.center, std::min(from_children, node.obb.half_extents.norm())};
  }
  stats_.obb_volume_sum = 0;
  for (const BvhNode& node : nodes_) stats_.obb_volume_sum += node.obb.volume();
  // Data derived from the old positions (point-query pseudo-normals) is dropped.
  cache_ = std::make_shared<detail::ModelCache>();
}

}  // namespace antcd
