// self_proximity (antcd/self.hpp): each vertex and each edge descends the Model's hierarchy to the
// leaves within delta; triangles the hierarchy leaves out are scanned apart.
#include <antcd/error.hpp>
#include <antcd/geometry.hpp>
#include <antcd/self.hpp>
#include <antcd/tolerances.hpp>

#include "util/check.hpp"
#include "util/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace antcd {

namespace {

using Edge = std::array<std::uint32_t, 2>;

/// on_triangle(mesh triangle) for every tree triangle in a leaf whose sphere comes within
/// `radius` of `centre`.
template <class F>
void near_triangles(const Model& model, const Vec3& centre, Scalar radius,
                    std::vector<std::uint32_t>& stack, const F& on_triangle) {
  const auto nodes = model.nodes();
  const auto leaves = model.leaf_triangles();
  stack.assign(1, 0);
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    const BvhNode& n = nodes[i];
    const Scalar r = Scalar{n.radius} + radius;
    if ((n.center - centre).squaredNorm() > r * r) continue;
    if (n.is_leaf()) {
      for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
        on_triangle(leaves[k]);
      }
    } else {
      stack.push_back(n.first_or_right);
      stack.push_back(i + 1);
    }
  }
}

constexpr std::size_t kChunk = 512;

}  // namespace

SelfProximityResult self_proximity(const Model& model, Scalar delta) {
  if (!std::isfinite(delta) || delta < 0) {
    detail::argument_error("self_proximity (" + model.source() + ")", "delta", "finite and >= 0",
                           number_text(delta));
  }
  SelfProximityResult result;
  const Mesh& mesh = model.mesh();
  const auto& v = mesh.vertices;
  const auto& tris = mesh.triangles;
  for (const TriangleIndices& t : tris) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = t[static_cast<std::size_t>(c)];
      const std::uint32_t b = t[static_cast<std::size_t>((c + 1) % 3)];
      if (a != b) result.edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(result.edges.begin(), result.edges.end());
  result.edges.erase(std::unique(result.edges.begin(), result.edges.end()), result.edges.end());
  const auto& edges = result.edges;
  const auto edge_id = [&](std::uint32_t a, std::uint32_t b) {
    const Edge e{std::min(a, b), std::max(a, b)};
    return static_cast<std::uint32_t>(std::lower_bound(edges.begin(), edges.end(), e) -
                                      edges.begin());
  };
  std::vector<bool> in_tree(tris.size(), false);
  for (const std::uint32_t t : model.leaf_triangles()) in_tree[t] = true;
  std::vector<std::uint32_t> left_out;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    if (!in_tree[t]) left_out.push_back(t);
  }
  // The spheres' rounding allowance, as the traversals take it.
  const Scalar margin =
      delta + tolerance::volume_allowance(Scalar{model.root().radius} + model.root().center.norm());
  const Scalar d2 = delta * delta;

  // Vertex-triangle pairs, per chunk of vertices (fixed chunks: the same output at any thread
  // count).
  const std::size_t vchunks = (v.size() + kChunk - 1) / kChunk;
  std::vector<std::vector<SelfProximityPair>> vparts(vchunks);
  parallel::for_each_index(0, vchunks, [&](std::size_t c) {
    std::vector<std::uint32_t> stack, found;
    for (std::size_t p = c * kChunk; p < std::min(v.size(), (c + 1) * kChunk); ++p) {
      found.clear();
      const auto consider = [&](std::uint32_t t) {
        const TriangleIndices& tri = tris[t];
        if (tri[0] == p || tri[1] == p || tri[2] == p) return;
        found.push_back(t);
      };
      near_triangles(model, v[p], margin, stack, consider);
      for (const std::uint32_t t : left_out) consider(t);
      std::sort(found.begin(), found.end());
      for (const std::uint32_t t : found) {
        const TriangleIndices& tri = tris[t];
        Vec3 closest;
        const Scalar s2 = geometry::point_triangle_distance_squared(v[p], v[tri[0]], v[tri[1]],
                                                                    v[tri[2]], &closest);
        if (s2 <= d2) {
          vparts[c].push_back({SelfProximityPair::Kind::vertex_triangle,
                               static_cast<std::uint32_t>(p), t, std::sqrt(s2), v[p], closest});
        }
      }
    }
  });
  // Edge-edge pairs (a < b), per chunk of edges.
  const std::size_t echunks = (edges.size() + kChunk - 1) / kChunk;
  std::vector<std::vector<SelfProximityPair>> eparts(echunks);
  parallel::for_each_index(0, echunks, [&](std::size_t c) {
    std::vector<std::uint32_t> stack, found;
    for (std::size_t e = c * kChunk; e < std::min(edges.size(), (c + 1) * kChunk); ++e) {
      found.clear();
      const Vec3& p0 = v[edges[e][0]];
      const Vec3& p1 = v[edges[e][1]];
      const auto consider = [&](std::uint32_t t) {
        const TriangleIndices& tri = tris[t];
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t a = tri[static_cast<std::size_t>(k)];
          const std::uint32_t b = tri[static_cast<std::size_t>((k + 1) % 3)];
          if (a == b) continue;
          const std::uint32_t f = edge_id(a, b);
          if (f <= e) continue;
          const Edge& ef = edges[f];
          if (ef[0] == edges[e][0] || ef[0] == edges[e][1] || ef[1] == edges[e][0] ||
              ef[1] == edges[e][1]) {
            continue;
          }
          found.push_back(f);
        }
      };
      const Vec3 mid = 0.5 * (p0 + p1);
      near_triangles(model, mid, tolerance::widened(0.5 * (p1 - p0).norm()) + margin, stack,
                     consider);
      for (const std::uint32_t t : left_out) consider(t);
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      for (const std::uint32_t f : found) {
        Vec3 cp, cq;
        const Scalar s2 = geometry::segment_segment_distance_squared(p0, p1, v[edges[f][0]],
                                                                     v[edges[f][1]], &cp, &cq);
        if (s2 <= d2) {
          eparts[c].push_back({SelfProximityPair::Kind::edge_edge, static_cast<std::uint32_t>(e), f,
                               std::sqrt(s2), cp, cq});
        }
      }
    }
  });
  for (const auto& part : vparts) result.pairs.insert(result.pairs.end(), part.begin(), part.end());
  for (const auto& part : eparts) result.pairs.insert(result.pairs.end(), part.begin(), part.end());
  return result;
}

}  // namespace antcd
