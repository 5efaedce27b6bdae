// Per-model data for point queries and the per-point queries: winding number through the
// hierarchy (boundary fans), pseudo-normal sign of the closest feature.
#include "points/point_index.hpp"

#include <antcd/tolerances.hpp>

#include "bvh/model_cache.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace antcd::detail {

namespace {

using Edge = std::array<std::uint32_t, 2>;

/// Cancels edges traversed both ways: what remains is the boundary of the patch the edges came
/// from (a non-manifold edge may remain several times). Deterministic order.
void reduce_boundary(std::vector<Edge>& edges) {
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    const auto ka = std::minmax(a[0], a[1]);
    const auto kb = std::minmax(b[0], b[1]);
    return ka != kb ? ka < kb : a < b;
  });
  std::size_t out = 0;
  for (std::size_t i = 0; i < edges.size();) {
    const auto key = std::minmax(edges[i][0], edges[i][1]);
    long net = 0;  // forward (low -> high) minus backward
    std::size_t j = i;
    for (; j < edges.size() && std::minmax(edges[j][0], edges[j][1]) == key; ++j) {
      net += edges[j][0] < edges[j][1] ? 1 : -1;
    }
    const Edge kept = net > 0 ? Edge{key.first, key.second} : Edge{key.second, key.first};
    for (long n = std::abs(net); n > 0; --n) edges[out++] = kept;
    i = j;
  }
  edges.resize(out);
}

/// p lies outside the node's box by more than the rounding of the box's fit.
bool outside_box(const BvhNode& node, const Vec3& p) {
  const Vec3 local = node.axes().transpose() * (p - node.center);
  const Vec3 half = node.half_extents();
  const Scalar margin = tolerance::kPoint * (node.center.cwiseAbs().maxCoeff() + half.maxCoeff());
  return ((local.cwiseAbs() - half).array() > margin).any();
}

/// Whether two connected pieces of the hierarchy's triangles (joined through shared vertex
/// indices) have overlapping bounding boxes.
bool pieces_overlap(const Model& model) {
  const Mesh& mesh = model.mesh();
  std::vector<std::uint32_t> parent(mesh.vertices.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const std::uint32_t t : model.leaf_triangles()) {
    const TriangleIndices& tri = mesh.triangles[t];
    for (int i = 1; i < 3; ++i) {
      const std::uint32_t a = find(tri[0]), b = find(tri[i]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<Aabb> boxes(mesh.vertices.size());
  std::vector<std::uint32_t> roots;
  for (const std::uint32_t t : model.leaf_triangles()) {
    for (const std::uint32_t v : mesh.triangles[t]) {
      const std::uint32_t r = find(v);
      if (boxes[r].empty()) roots.push_back(r);
      boxes[r].extend(mesh.vertices[v]);
    }
  }
  if (roots.size() < 2) return false;
  std::sort(roots.begin(), roots.end(),
            [&](std::uint32_t a, std::uint32_t b) { return boxes[a].min.x() < boxes[b].min.x(); });
  // Sweep along x: each box against the following ones that start before it ends.
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const Aabb& a = boxes[roots[i]];
    for (std::size_t j = i + 1; j < roots.size() && boxes[roots[j]].min.x() <= a.max.x(); ++j) {
      const Aabb& b = boxes[roots[j]];
      if ((a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all()) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

PointIndex build_point_index(const Model& model) {
  PointIndex index;
  const auto nodes = model.nodes();
  const auto leaf_tris = model.leaf_triangles();
  const LeafCorners lv = model.leaf_corners();
  const Mesh& mesh = model.mesh();

  // Boundary of each node's patch, children before parents (a child's index exceeds its parent's).
  std::vector<std::vector<Edge>> boundary(nodes.size());
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const BvhNode& node = nodes[i];
    std::vector<Edge>& b = boundary[i];
    if (node.is_leaf()) {
      for (std::uint32_t k = node.first_or_right; k < node.first_or_right + node.count; ++k) {
        const TriangleIndices& t = mesh.triangles[leaf_tris[k]];
        b.push_back({t[0], t[1]});
        b.push_back({t[1], t[2]});
        b.push_back({t[2], t[0]});
      }
    } else {
      const auto& left = boundary[i + 1];
      const auto& right = boundary[node.first_or_right];
      b.reserve(left.size() + right.size());
      b.insert(b.end(), left.begin(), left.end());
      b.insert(b.end(), right.begin(), right.end());
    }
    reduce_boundary(b);
  }
  index.fan_first.reserve(nodes.size() + 1);
  index.fan_first.push_back(0);
  for (auto& b : boundary) {
    index.fan_edges.insert(index.fan_edges.end(), b.begin(), b.end());
    index.fan_first.push_back(static_cast<std::uint32_t>(index.fan_edges.size()));
    std::vector<Edge>().swap(b);
  }

  // Pseudo-normals (Bærentzen and Aanæs): faces, edges as the sum of their two faces' normals,
  // vertices as the sum of their faces' normals weighted by the angle at the vertex.
  const std::size_t n = leaf_tris.size();
  index.face_normal.resize(n);
  index.edge_normal.assign(n, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  index.vertex_normal.assign(mesh.vertices.size(), Vec3::Zero());
  struct EdgeSlot {
    std::uint32_t lo, hi, k, slot;
  };
  // The normals are made to point out of the solid: an inward-facing surface (negative enclosed
  // volume) has them all flipped.
  Scalar volume6 = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto v = lv.triangle(k);
    volume6 += v[0].dot(v[1].cross(v[2]));
  }
  const Scalar outward = volume6 < 0 ? -1 : 1;
  std::vector<EdgeSlot> slots;
  slots.reserve(3 * n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const auto v = lv.triangle(k);
    const Vec3 nrm = outward * (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    index.face_normal[k] = nrm;
    const TriangleIndices& t = mesh.triangles[leaf_tris[k]];
    for (std::uint32_t i = 0; i < 3; ++i) {
      const Vec3 e1 = v[(i + 1) % 3] - v[i];
      const Vec3 e2 = v[(i + 2) % 3] - v[i];
      const Scalar angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      index.vertex_normal[t[i]] += angle * nrm;
      const auto [lo, hi] = std::minmax(t[i], t[(i + 1) % 3]);
      slots.push_back({lo, hi, k, i});
    }
  }
  std::sort(slots.begin(), slots.end(), [](const EdgeSlot& a, const EdgeSlot& b) {
    return std::tie(a.lo, a.hi, a.k, a.slot) < std::tie(b.lo, b.hi, b.k, b.slot);
  });
  for (std::size_t i = 0; i < slots.size();) {
    std::size_t j = i;
    Vec3 sum = Vec3::Zero();
    for (; j < slots.size() && slots[j].lo == slots[i].lo && slots[j].hi == slots[i].hi; ++j) {
      sum += index.face_normal[slots[j].k];
    }
    for (std::size_t m = i; m < j; ++m) index.edge_normal[slots[m].k][slots[m].slot] = sum;
    i = j;
  }
  index.sign_by_winding = pieces_overlap(model);
  index.grid = SolidGrid(model, [&](const Vec3& p) { return winding_number(model, index, p); });
  return index;
}

const PointIndex& point_index(const Model& model) {
  static const std::size_t slot = new_cache_slot();
  return derived<PointIndex>(model, slot, [&] { return build_point_index(model); });
}

int winding_number(const Model& model, const PointIndex& index, const Vec3& p) {
  const auto nodes = model.nodes();
  if (outside_box(nodes[0], p)) return 0;  // the root box holds the whole surface
  const LeafCorners lv = model.leaf_corners();
  const auto& verts = model.mesh().vertices;
  Scalar total = 0;
  DescentStack<std::uint32_t> storage(model.stats().depth);
  std::uint32_t* stack = storage.data();
  std::size_t top = 0;
  stack[top++] = 0;
  auto leaf_sum = [&](const BvhNode& node) {
    for (std::size_t k = node.first_or_right; k < node.first_or_right + node.count; ++k) {
      total += geometry::solid_angle(p, lv(k, 0), lv(k, 1), lv(k, 2));
    }
  };
  while (top > 0) {
    const std::uint32_t i = stack[--top];
    const BvhNode& node = nodes[i];
    if (node.is_leaf()) {
      leaf_sum(node);
      continue;
    }
    if (i != 0 && outside_box(node, p)) {
      const std::uint32_t f0 = index.fan_first[i];
      const std::uint32_t f1 = index.fan_first[i + 1];
      if (f0 == f1) continue;
      const Vec3& apex = verts[index.fan_edges[f0][0]];
      for (std::uint32_t f = f0; f < f1; ++f) {
        total += geometry::solid_angle(p, apex, verts[index.fan_edges[f][0]],
                                       verts[index.fan_edges[f][1]]);
      }
      continue;
    }
    stack[top++] = node.first_or_right;
    stack[top++] = i + 1;
  }
  return static_cast<int>(std::lround(total / (4 * std::numbers::pi)));
}

bool inside_from_closest(const Model& model, const PointIndex& index, const Vec3& p,
                         const ClosestPoint& c) {
  if (index.sign_by_winding) return winding_number(model, index, p) != 0;
  const std::uint32_t k = c.leaf_triangle;
  const auto v = model.leaf_corners().triangle(k);
  const Vec3 d = p - c.point;
  const Scalar dn = d.norm();
  if (dn == 0) return true;  // on the surface (the caller reports distance 0)
  Scalar scale = 0;
  for (int i = 0; i < 3; ++i) {
    scale = std::max({scale, (v[(i + 1) % 3] - v[i]).norm(), v[i].cwiseAbs().maxCoeff()});
  }
  const Scalar tol = tolerance::kPoint * scale;
  bool on_edge[3];
  int edges = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = v[(i + 1) % 3] - v[i];
    on_edge[i] = (c.point - v[i]).cross(e).norm() <= tol * e.norm();
    edges += on_edge[i] ? 1 : 0;
  }
  Vec3 normal;
  if (edges == 0) {
    normal = index.face_normal[k];
  } else if (edges == 1) {
    normal = index.edge_normal[k][on_edge[0] ? 0 : on_edge[1] ? 1 : 2];
  } else if (edges == 2) {
    // Edge i runs from vertex i to i + 1: the two touched edges meet at the vertex after the
    // untouched one's end.
    const int untouched = !on_edge[0] ? 0 : !on_edge[1] ? 1 : 2;
    const int shared = (untouched + 2) % 3;
    normal = index.vertex_normal[model.mesh().triangles[model.leaf_triangles()[k]][shared]];
  } else {
    normal = Vec3::Zero();
  }
  const Scalar dot = d.dot(normal);
  if (std::abs(dot) > 1e-6 * dn * normal.norm()) return dot < 0;
  return winding_number(model, index, p) != 0;
}

}  // namespace antcd::detail
