// The compact axis-aligned tree for point distance, its branch-and-bound descent, and the
// Morton order of a batch of points.
#include "points/point_tree.hpp"

#include "bvh/model_cache.hpp"
#include "util/grid_cell.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace antcd::detail {

PointTree build_point_tree(const Model& model) {
  const auto nodes = model.nodes();
  const LeafCorners lv = model.leaf_corners();
  PointTree tree;
  const std::size_t n_tris = lv.size();
  tree.triangles.resize(n_tris);
  for (std::size_t k = 0; k < n_tris; ++k) {
    const auto v = lv.triangle(k);
    PointTree::Triangle& t = tree.triangles[k];
    t = {Vec3::Zero(), 0, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}, {0, 0, 0}};
    for (int i = 0; i < 3; ++i) {
      tree.coordinate_scale = std::max(tree.coordinate_scale, v[i].cwiseAbs().maxCoeff());
    }
    const Vec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    const Scalar longest = std::max({e[0].norm(), e[1].norm(), e[2].norm()});
    const Vec3 cross = e[0].cross(-e[2]);
    // Sine of the largest angle (at least that of every angle): below 1e-3 the normal's rounding
    // is too large for the bound's margin, and the triangle is always tested exactly.
    const Scalar sine = cross.norm() / (longest * longest);
    if (!(sine >= 1e-3)) continue;
    t.n = cross.normalized();
    t.nd = t.n.dot(v[0]);
    for (int i = 0; i < 3; ++i) {
      t.m[i] = t.n.cross(e[i]).normalized();  // points into the triangle
      t.md[i] = t.m[i].dot(v[i]);
    }
  }
  if (nodes[0].is_leaf()) {
    tree.root_leaf_count = nodes[0].count;
    tree.max_depth = 1;
    return tree;
  }
  // Boxes of every hierarchy node, children (higher indices) before parents.
  std::vector<Aabb> box(nodes.size());
  std::vector<std::uint32_t> depth(nodes.size(), 1);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const BvhNode& n = nodes[i];
    if (n.is_leaf()) {
      for (std::size_t k = n.first_or_right; k < std::size_t{n.first_or_right} + n.count; ++k) {
        for (int c = 0; c < 3; ++c) box[i].extend(lv(k, c));
      }
    } else {
      const Aabb& l = box[i + 1];
      const Aabb& r = box[n.first_or_right];
      box[i].min = l.min.cwiseMin(r.min);
      box[i].max = l.max.cwiseMax(r.max);
      depth[i] = 1 + std::max(depth[i + 1], depth[n.first_or_right]);
    }
  }
  tree.max_depth = depth[0];
  // Internal hierarchy nodes in index order (a parent before its children) become tree nodes.
  std::vector<std::uint32_t> slot(nodes.size(), 0);
  std::uint32_t internal = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].is_leaf()) slot[i] = internal++;
  }
  tree.nodes.resize(internal);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].is_leaf()) continue;
    PointTree::Node& out = tree.nodes[slot[i]];
    const std::size_t child[2] = {i + 1, nodes[i].first_or_right};
    for (int c = 0; c < 2; ++c) {
      const BvhNode& n = nodes[child[c]];
      for (int a = 0; a < 3; ++a) {
        out.lo[a][c] = box[child[c]].min[a];
        out.hi[a][c] = box[child[c]].max[a];
      }
      out.ref[c] = n.is_leaf() ? n.first_or_right : slot[child[c]];
      out.count[c] = n.count;
    }
  }
  return tree;
}

const PointTree& point_tree(const Model& model) {
  static const std::size_t slot = new_cache_slot();
  return derived<PointTree>(model, slot, [&] { return build_point_tree(model); });
}

namespace {

/// Lower bound of the squared distance from p to triangle t (see PointTree::Triangle).
Scalar triangle_bound_squared(const PointTree::Triangle& t, const Vec3& p) {
  const Scalar h = t.n.dot(p) - t.nd;
  const Scalar e = std::max(
      {t.md[0] - t.m[0].dot(p), t.md[1] - t.m[1].dot(p), t.md[2] - t.m[2].dot(p), Scalar{0}});
  return h * h + e * e;
}

struct Entry {
  std::uint32_t ref;
  std::uint32_t count;
  Scalar bound;
};

}  // namespace

ClosestPoint closest_point(const Model& model, const PointTree& tree, const Vec3& p,
                           std::uint32_t hint) {
  const LeafCorners lv = model.leaf_corners();
  ClosestPoint best;
  best.distance_squared = std::numeric_limits<Scalar>::infinity();
  best.leaf_triangle = kNoHint;
  // Bounds are compared with the best distance plus a margin that covers the rounding of the
  // bounds and of the exact distances (a few ulps of the coordinates): no triangle whose computed
  // distance could be the smallest is ever pruned, so the answer is the brute-force minimum.
  const Scalar margin = 1e-11 * (p.cwiseAbs().maxCoeff() + tree.coordinate_scale);
  Scalar cut = std::numeric_limits<Scalar>::infinity();  // (best distance + margin)^2
  auto test_triangle = [&](std::uint32_t k) {
    if (triangle_bound_squared(tree.triangles[k], p) > cut) return;
    const auto v = lv.triangle(k);
    Vec3 c;
    const Scalar d2 = geometry::point_triangle_distance_squared(p, v[0], v[1], v[2], &c);
    if (d2 < best.distance_squared || (d2 == best.distance_squared && k < best.leaf_triangle)) {
      best = {d2, c, k};
      const Scalar r = std::sqrt(d2) + margin;
      cut = r * r;
    }
  };
  if (hint != kNoHint) test_triangle(hint);
  if (tree.root_leaf_count != 0) {
    for (std::uint32_t k = 0; k < tree.root_leaf_count; ++k) test_triangle(k);
    return best;
  }
  DescentStack<Entry> storage(tree.max_depth);
  Entry* stack = storage.data();
  std::size_t top = 0;
  stack[top++] = {0, 0, 0};
  const Eigen::Array2d px = Eigen::Array2d::Constant(p.x());
  const Eigen::Array2d py = Eigen::Array2d::Constant(p.y());
  const Eigen::Array2d pz = Eigen::Array2d::Constant(p.z());
  using Pair = Eigen::Map<const Eigen::Array2d, Eigen::Aligned16>;
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.bound > cut) continue;
    if (e.count != 0) {
      for (std::uint32_t k = e.ref; k < e.ref + e.count; ++k) {
        if (k != hint) test_triangle(k);
      }
      continue;
    }
    const PointTree::Node& n = tree.nodes[e.ref];
    const Eigen::Array2d dx =
        (Pair(n.lo[0]) - px).max(px - Pair(n.hi[0])).max(Eigen::Array2d::Zero());
    const Eigen::Array2d dy =
        (Pair(n.lo[1]) - py).max(py - Pair(n.hi[1])).max(Eigen::Array2d::Zero());
    const Eigen::Array2d dz =
        (Pair(n.lo[2]) - pz).max(pz - Pair(n.hi[2])).max(Eigen::Array2d::Zero());
    const Eigen::Array2d d2 = dx * dx + dy * dy + dz * dz;
    // Nearer child on top of the stack, so it is searched first and tightens the bound.
    const int near = d2[1] < d2[0] ? 1 : 0;
    const int far = 1 - near;
    if (d2[far] <= cut) stack[top++] = {n.ref[far], n.count[far], d2[far]};
    if (d2[near] <= cut) stack[top++] = {n.ref[near], n.count[near], d2[near]};
  }
  return best;
}

std::vector<std::size_t> coherent_order(std::span<const Vec3> points) {
  Aabb box;
  for (const Vec3& p : points) box.extend(p);
  const Vec3 extent = box.extent();
  const Scalar size = std::max(extent.maxCoeff(), std::numeric_limits<Scalar>::min());
  constexpr std::uint64_t kTop = (1u << 21) - 1;
  const Scalar scale = static_cast<Scalar>(kTop) / size;
  // The order only steers the search, so coordinates whose arithmetic overflows (an extent past
  // the double range, a scale past it for coincident points) may share a cell.
  auto cell = [](Scalar q) { return clamped_cell<std::uint64_t>(q, 0, kTop); };
  // Spreads the low 21 bits of x three apart.
  auto spread = [](std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 q = (points[i] - box.min) * scale;
    keyed[i] = {spread(cell(q.x())) | spread(cell(q.y())) << 1 | spread(cell(q.z())) << 2, i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace antcd::detail
