// Model::refit: new vertex positions for the same triangles, the tree's topology kept and its
// bounding volumes recomputed bottom-up in O(n).
#include <antcd/bvh.hpp>

#include "bvh/model_cache.hpp"
#include "bvh/node_store.hpp"
#include "util/check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace antcd {

namespace {

/// The box with `axes` (the node's own) holding the points.
Obb fit_points(const Mat3& axes, std::span<const Vec3> points) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : points) {
    const Vec3 local = axes.transpose() * p;
    lo = lo.cwiseMin(local);
    hi = hi.cwiseMax(local);
  }
  return {axes * (0.5 * (lo + hi)), axes, 0.5 * (hi - lo)};
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

double Model::looseness() const {
  Scalar internal = 0, leaves = 0;
  for (const BvhNode& n : nodes_) {
    const Scalar e = Scalar{n.half[0]} + Scalar{n.half[1]} + Scalar{n.half[2]};
    (n.is_leaf() ? leaves : internal) += e;
  }
  return leaves > 0 ? internal / leaves : 1;
}

double Model::refit_growth() const {
  return built_looseness_ > 0 ? looseness() / built_looseness_ : 1;
}

void Model::rebuild() {
  Model fresh(mesh_, options_, source_);
  *this = std::move(fresh);
}

bool Model::refit(std::span<const Vec3> new_vertices, double rebuild_above) {
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

  if (!(rebuild_above >= 0)) {
    detail::argument_error(source_ + ": refit", "rebuild_above", ">= 0 (or +inf)",
                           number_text(rebuild_above));
  }
  if (built_looseness_ == 0) built_looseness_ = looseness();  // as built or loaded
  std::copy(new_vertices.begin(), new_vertices.end(), mesh_.vertices.begin());
  const LeafCorners corners_of = leaf_corners();
  // Children come after their parent in the depth-first layout: refit from the last node back.
  // Each box keeps its axes; a leaf's extents come from its vertices, an internal node's from its
  // children's box corners (a bound, possibly looser than a fresh fit); each sphere is the smaller
  // of the box's circumscribed sphere and (internal nodes) the one about the box centre holding
  // the children's spheres, or (leaves) the one through the farthest vertex.
  std::vector<Vec3> verts;
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    BvhNode& node = nodes_[i];
    const Mat3 axes = node.axes();
    if (node.is_leaf()) {
      verts.clear();
      for (std::uint32_t k = node.first_or_right; k < node.first_or_right + node.count; ++k) {
        for (int c = 0; c < 3; ++c) verts.push_back(corners_of(k, c));
      }
      const Obb box = fit_points(axes, verts);
      Scalar r2 = 0;
      for (const Vec3& v : verts) r2 = std::max(r2, (v - box.center).squaredNorm());
      detail::store_volumes(node, box, std::sqrt(r2));
      continue;
    }
    const BvhNode& left = nodes_[i + 1];
    const BvhNode& right = nodes_[node.first_or_right];
    std::array<Vec3, 16> points;
    const auto cl = corners(left.obb());
    const auto cr = corners(right.obb());
    std::copy(cl.begin(), cl.end(), points.begin());
    std::copy(cr.begin(), cr.end(), points.begin() + 8);
    const Obb box = fit_points(axes, points);
    const Scalar from_children = std::max((left.center - box.center).norm() + left.radius,
                                          (right.center - box.center).norm() + right.radius);
    detail::store_volumes(node, box, std::min(from_children, box.half_extents.norm()));
  }
  stats_.obb_volume_sum = 0;
  for (const BvhNode& node : nodes_) stats_.obb_volume_sum += node.obb().volume();
  // Data derived from the old positions (point-query pseudo-normals) is dropped; the self queries'
  // boundary data depends on the triangles and the tree's topology only, and is kept.
  cache_ = cache_->after_refit();
  if (rebuild_above > 0 && refit_growth() > rebuild_above) {
    try {
      rebuild();
    } catch (const MeshError&) {
      return false;  // no triangle of non-zero area left to build on: keep the refitted tree
    }
    return true;
  }
  return false;
}

}  // namespace antcd
