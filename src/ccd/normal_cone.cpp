// Normal-cone culling shared by the static self test and the deforming sweep
// (ccd/normal_cone.hpp): the subtree boundaries (position-independent), and the continuous cull.
//
// The continuous cull (deform_cone_culls). Let R be the triangles under a tree node with a cone
// entry (so conditions (b) and the cycle of (c) of the static cull, self/cone.cpp, hold: they
// depend on the triangles only), k an axis and every vertex moving linearly, x(t) = (1 - t) x(0)
// + t x(1). It culls R when, for one sign s of axis k:
//
// (i) every triangle of R has s n_k(t) > 0 for every t in [0, 1]. With e1 = b - a, e2 = c - a
//     (both linear in t), n(t) = e1(t) x e2(t) = (1 - t)^2 n0 + 2 t (1 - t) n01 + t^2 n1, where
//     n0 = n(0), n1 = n(1) and n01 = (e1(0) x e2(1) + e1(1) x e2(0)) / 2 (expand the product:
//     this is exact, a quadratic Bezier curve with control points n0, n01, n1). The three
//     Bernstein weights are >= 0 and sum to 1, so s n_k(t) > 0 on [0, 1] when s n0_k, s n01_k and
//     s n1_k are all > 0. Each is evaluated in floating point with a bound on its rounding (the
//     differences, the products and the sum: at most 7 u times the sum of the products'
//     magnitudes, u = 2^-53; 16 u is used, plus 16 DBL_MIN for underflow) and counts only when it
//     exceeds that bound (bernstein_sign): a certified sign, never an estimate.
// (ii) at every t in [0, 1] the boundary cycle of R, projected along axis k, is a simple polygon.
//     An edge (p, q) at time t is (1 - w) p(t) + w q(t), a convex combination of p(0), p(1),
//     q(0), q(1): it stays in the convex hull of those four points over the whole step. Two
//     edges with no common vertex never meet when those hulls, projected, are strictly separated
//     by a line (tested on the 12 directions normal to a pair of one hull's points, which hold
//     the separating axis of two convex polygons when one exists, each projection with a bound
//     on its rounding; hulls_apart). Two consecutive edges a -> s -> c meet beyond s only when
//     a, s, c are collinear with a and c on one side of s: excluded at every t when the cross
//     product (a - s) x (c - s), quadratic in t as n above, has certified Bernstein coefficients
//     of one strict sign, or the dot product (a - s) . (c - s) has all three certified < 0.
//
// Then at every t the static conditions (a) (mirrored when s < 0), (b) and (c) hold, and the
// static theorem (self/cone.cpp) says no two triangles A, B of R meet beyond what their shared
// vertices require: A and B meet at most in the hull S of their shared vertices. A self pair
// (antcd/deform_ccd.hpp) queried from A and B in contact at t has a common point x of A and B,
// hence x in S: for a vertex v of A against B (v not a corner of B), x = v(t) would be a corner
// of the non-degenerate A on the hull of A's other corners; for edges of A and B with no common
// vertex, x in S on both edges would make x an end of each (two edges of one non-degenerate
// triangle meet only at a common end, or are the same edge), a common vertex. Both are
// impossible, so no self pair under the node ever touches (distance 0) over [0, 1], and none is
// lost by skipping the node's self traversal. The pairs between R and the rest are not culled.
#include "ccd/normal_cone.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <utility>

#include "bvh/model_cache.hpp"
#include "util/parallel.hpp"

namespace antcd::detail {

const ConeTopology::Entry* ConeTopology::find(std::uint32_t node) const {
  const auto it = std::lower_bound(entries.begin(), entries.end(), node,
                                   [](const Entry& e, std::uint32_t n) { return e.node < n; });
  return it != entries.end() && it->node == node ? &*it : nullptr;
}

namespace {

std::uint64_t edge_key(const Mesh& m, std::uint32_t e) {
  const std::uint64_t u = edge_tail(m, e), v = edge_head(m, e);
  return std::min(u, v) << 32 | std::max(u, v);
}

struct KeyedEdge {
  std::uint64_t key;
  std::uint32_t code;
};

/// Sorted by key, with pairs of equal keys removed (interior edges; opposite by (b)).
void cancel_pairs(std::vector<KeyedEdge>& v) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < v.size();) {
    if (i + 1 < v.size() && v[i + 1].key == v[i].key) {
      i += 2;
    } else {
      v[out++] = v[i++];
    }
  }
  v.resize(out);
}

/// The edges as one directed cycle (each vertex the tail of one and the head of one, all reached
/// from the first), in cycle order; false when they are not.
bool one_cycle(const Mesh& m, std::vector<std::uint32_t>& codes) {
  std::vector<std::uint32_t> by_tail = codes;
  std::sort(by_tail.begin(), by_tail.end(),
            [&](std::uint32_t a, std::uint32_t b) { return edge_tail(m, a) < edge_tail(m, b); });
  for (std::size_t i = 1; i < by_tail.size(); ++i) {
    if (edge_tail(m, by_tail[i]) == edge_tail(m, by_tail[i - 1])) return false;
  }
  std::vector<std::uint32_t> cycle;
  cycle.reserve(codes.size());
  std::uint32_t e = by_tail.front();
  for (std::size_t step = 0; step < by_tail.size(); ++step) {
    cycle.push_back(e);
    const std::uint32_t h = edge_head(m, e);
    const auto it =
        std::lower_bound(by_tail.begin(), by_tail.end(), h,
                         [&](std::uint32_t c, std::uint32_t v) { return edge_tail(m, c) < v; });
    if (it == by_tail.end() || edge_tail(m, *it) != h) return false;
    e = *it;
  }
  if (e != cycle.front()) return false;  // closed early: a shorter cycle, more edges left
  codes = std::move(cycle);
  return true;
}

std::shared_ptr<const ConeTopology> build_topology(const Model& model) {
  auto topo = std::make_shared<ConeTopology>();
  const Mesh& m = model.mesh();
  const auto nodes = model.nodes();
  const auto leaves = model.leaf_triangles();
  // (b) over the whole tree: an edge used more than twice, or twice in one direction, excludes
  // every subtree holding a triangle of it.
  std::vector<KeyedEdge> all;
  all.reserve(leaves.size() * 3);
  for (const std::uint32_t t : leaves) {
    for (std::uint32_t k = 0; k < 3; ++k) all.push_back({edge_key(m, 3 * t + k), 3 * t + k});
  }
  std::sort(all.begin(), all.end(),
            [](const KeyedEdge& a, const KeyedEdge& b) { return a.key < b.key; });
  std::vector<bool> bad(m.triangles.size(), false);
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    const bool two_opposite =
        j - i == 2 && edge_tail(m, all[i].code) != edge_tail(m, all[i + 1].code);
    if (j - i > 2 || (j - i == 2 && !two_opposite)) {
      for (std::size_t k = i; k < j; ++k) bad[all[k].code / 3] = true;
    }
    i = j;
  }
  all = {};
  // Bottom-up boundaries (children follow their parent in the depth-first layout). A subtree is
  // given up (and so are its ancestors) when it holds a bad triangle or its boundary has more
  // edges than 2 per triangle + 16 (not a surface patch worth a polygon test).
  std::vector<std::vector<KeyedEdge>> boundary(nodes.size());
  std::vector<bool> given_up(nodes.size(), false);
  std::vector<std::uint32_t> count(nodes.size(), 0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const BvhNode& n = nodes[i];
    std::vector<KeyedEdge>& b = boundary[i];
    if (n.is_leaf()) {
      count[i] = n.count;
      for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
        const std::uint32_t t = leaves[k];
        if (bad[t]) given_up[i] = true;
        for (std::uint32_t c = 0; c < 3; ++c) b.push_back({edge_key(m, 3 * t + c), 3 * t + c});
      }
      std::sort(b.begin(), b.end(),
                [](const KeyedEdge& x, const KeyedEdge& y) { return x.key < y.key; });
    } else {
      const std::size_t l = i + 1, r = n.first_or_right;
      count[i] = count[l] + count[r];
      given_up[i] = given_up[l] || given_up[r];
      if (!given_up[i]) {
        b.resize(boundary[l].size() + boundary[r].size());
        std::merge(boundary[l].begin(), boundary[l].end(), boundary[r].begin(), boundary[r].end(),
                   b.begin(), [](const KeyedEdge& x, const KeyedEdge& y) { return x.key < y.key; });
      }
      boundary[l] = {};
      boundary[r] = {};
    }
    if (given_up[i]) {
      b = {};
      continue;
    }
    cancel_pairs(b);
    if (b.size() > 2 * std::size_t{count[i]} + 16) {
      given_up[i] = true;
      b = {};
      continue;
    }
    if (count[i] >= kConeMinTriangles && !b.empty()) {
      std::vector<std::uint32_t> codes(b.size());
      for (std::size_t k = 0; k < b.size(); ++k) codes[k] = b[k].code;
      if (one_cycle(m, codes)) {
        const auto begin = static_cast<std::uint32_t>(topo->edges.size());
        topo->edges.insert(topo->edges.end(), codes.begin(), codes.end());
        topo->entries.push_back(
            {static_cast<std::uint32_t>(i), begin, static_cast<std::uint32_t>(topo->edges.size())});
      }
    }
  }
  std::reverse(topo->entries.begin(), topo->entries.end());  // ascending by node
  topo->entries.shrink_to_fit();
  topo->edges.shrink_to_fit();
  return topo;
}

}  // namespace

std::shared_ptr<const ConeTopology> cone_topology(const Model& model) {
  static const std::size_t slot = new_kept_slot();
  return kept<ConeTopology>(model, slot, [&] { return build_topology(model); });
}

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;
constexpr double kTiny = 16 * std::numeric_limits<double>::min();

enum class Form { Cross, Dot };

/// A coefficient is a signed sum of products of two coordinate differences, each difference at
/// most 2 m in magnitude (m: the largest coordinate magnitude of the points), so each product at
/// most 4 m^2: bounds on the rounding of the two-product (end) and four-product (middle)
/// coefficients that hold for every triangle of the call (the error bound of bernstein_sign with
/// every product at its largest), with room for the rounding of the bound itself.
struct StaticBound {
  double end = std::numeric_limits<double>::infinity();
  double middle = std::numeric_limits<double>::infinity();
};
StaticBound static_bound(double m) {
  const double p = 4 * m * m * (1 + 8 * kUnitRoundoff);
  return {16 * kUnitRoundoff * 2 * p + kTiny, 16 * kUnitRoundoff * 4 * p + kTiny};
}

/// The certified sign over t in [0, 1] of x(t) x y(t) (Cross) or x(t) . y(t) (Dot) in the
/// coordinates (u, v), x = p - o and y = q - o of three linearly moving points (o0 -> o1, ...):
/// +1 (-1) when its three Bernstein coefficients are certified > 0 (< 0), else 0 (header comment,
/// (i)). The middle coefficient is taken doubled (same sign). `sb` (when its points' magnitudes
/// are within its m) decides first; the coefficients' own bound, smaller, decides the rest.
template <Form kForm>
int bernstein_sign(const Vec3& o0, const Vec3& p0, const Vec3& q0, const Vec3& o1, const Vec3& p1,
                   const Vec3& q1, int u, int v, const StaticBound& sb = {}) {
  const double x0u = p0[u] - o0[u], x0v = p0[v] - o0[v], y0u = q0[u] - o0[u], y0v = q0[v] - o0[v];
  const double x1u = p1[u] - o1[u], x1v = p1[v] - o1[v], y1u = q1[u] - o1[u], y1v = q1[v] - o1[v];
  // Each coefficient is a signed sum of products x_i y_j (l - r for Cross, l + r for Dot).
  constexpr double kS = kForm == Form::Cross ? -1 : 1;
  const std::array<double, 8> l =
      kForm == Form::Cross ? std::array<double, 8>{x0u * y0v, x0v * y0u, x1u * y1v, x1v * y1u,
                                                   x0u * y1v, x0v * y1u, x1u * y0v, x1v * y0u}
                           : std::array<double, 8>{x0u * y0u, x0v * y0v, x1u * y1u, x1v * y1v,
                                                   x0u * y1u, x0v * y1v, x1u * y0u, x1v * y0v};
  const double b0 = l[0] + kS * l[1];
  const double b2 = l[2] + kS * l[3];
  const double b1 = (l[4] + kS * l[5]) + (l[6] + kS * l[7]);
  if (b0 > sb.end && b1 > sb.middle && b2 > sb.end) return 1;
  if (b0 < -sb.end && b1 < -sb.middle && b2 < -sb.end) return -1;
  // The coefficients' own bounds: 16 u times the sum of their products' magnitudes.
  const double e0 = 16 * kUnitRoundoff * (std::abs(l[0]) + std::abs(l[1])) + kTiny;
  const double e2 = 16 * kUnitRoundoff * (std::abs(l[2]) + std::abs(l[3])) + kTiny;
  const double e1 =
      16 * kUnitRoundoff * (std::abs(l[4]) + std::abs(l[5]) + std::abs(l[6]) + std::abs(l[7])) +
      kTiny;
  if (b0 > e0 && b1 > e1 && b2 > e2) return 1;
  if (b0 < -e0 && b1 < -e1 && b2 < -e2) return -1;
  return 0;
}

struct Point2 {
  double u, v;
};

/// Whether the computed projections of a and b on direction (du, dv) are apart by more than their
/// rounding: |fl(du x + dv y) - (du x + dv y)| <= 2.01 u (|du| + |dv|) m, m the largest
/// coordinate magnitude.
bool apart_along(const std::array<Point2, 4>& a, const std::array<Point2, 4>& b, double du,
                 double dv, double m) {
  const double err = 4 * kUnitRoundoff * (std::abs(du) + std::abs(dv)) * m + kTiny;
  double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a;
  double lo_b = lo_a, hi_b = hi_a;
  for (int k = 0; k < 4; ++k) {
    const double pa = du * a[k].u + dv * a[k].v;
    const double pb = du * b[k].u + dv * b[k].v;
    lo_a = std::min(lo_a, pa);
    hi_a = std::max(hi_a, pa);
    lo_b = std::min(lo_b, pb);
    hi_b = std::max(hi_b, pb);
  }
  return hi_a + 2 * err < lo_b || hi_b + 2 * err < lo_a;
}

/// Whether the convex hulls of the point sets a and b (4 points each) are strictly separated by
/// a line, tested on the directions normal and parallel to each pair of points of one set (the
/// normals hold a separating axis of two convex polygons when one exists; the parallels cover
/// hulls flat on one line), after each projection's rounding (header comment, (ii)). The
/// directions need no exactness: any direction that separates the projections proves it.
bool hulls_apart(const std::array<Point2, 4>& a, const std::array<Point2, 4>& b) {
  double m = 0;
  for (const auto* set : {&a, &b}) {
    for (const Point2& p : *set) m = std::max({m, std::abs(p.u), std::abs(p.v)});
  }
  for (const auto* set : {&a, &b}) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const double du = (*set)[j].u - (*set)[i].u;
        const double dv = (*set)[j].v - (*set)[i].v;
        if (du == 0 && dv == 0) continue;
        if (apart_along(a, b, -dv, du, m) || apart_along(a, b, du, dv, m)) return true;
      }
    }
  }
  return false;
}

/// The continuous simplicity test (ii) of the node's boundary cycle projected along axis k.
bool cycle_stays_simple(const Mesh& m, std::span<const std::uint32_t> cycle, int k,
                        std::span<const Vec3> V0, std::span<const Vec3> V1,
                        std::vector<EdgeBox>& boxes) {
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  const std::size_t n = cycle.size();
  auto points = [&](std::size_t pos) {
    const std::uint32_t t = edge_tail(m, cycle[pos]), h = edge_head(m, cycle[pos]);
    return std::array<Point2, 4>{Point2{V0[t][u], V0[t][v]}, Point2{V1[t][u], V1[t][v]},
                                 Point2{V0[h][u], V0[h][v]}, Point2{V1[h][u], V1[h][v]}};
  };
  boxes.resize(n);
  for (std::size_t pos = 0; pos < n; ++pos) {
    const std::array<Point2, 4> p = points(pos);
    EdgeBox& b = boxes[pos];
    b = {p[0].u, p[0].u, p[0].v, p[0].v, static_cast<std::uint32_t>(pos)};
    for (int i = 1; i < 4; ++i) {
      b.lo_u = std::min(b.lo_u, p[i].u);
      b.hi_u = std::max(b.hi_u, p[i].u);
      b.lo_v = std::min(b.lo_v, p[i].v);
      b.hi_v = std::max(b.hi_v, p[i].v);
    }
  }
  return cycle_is_simple(
      boxes, [&](std::size_t x, std::size_t y) { return hulls_apart(points(x), points(y)); },
      [&](std::size_t first, std::size_t second) {
        const std::uint32_t a = edge_tail(m, cycle[first]);
        const std::uint32_t s = edge_head(m, cycle[first]);
        const std::uint32_t c = edge_head(m, cycle[second]);
        if (bernstein_sign<Form::Cross>(V0[s], V0[a], V0[c], V1[s], V1[a], V1[c], u, v) != 0) {
          return true;  // never collinear
        }
        return bernstein_sign<Form::Dot>(V0[s], V0[a], V0[c], V1[s], V1[a], V1[c], u, v) < 0;
      });
}

}  // namespace

/// swept_normal_signs with the call's static bound.
std::uint8_t swept_normal_signs(const Vec3& a0, const Vec3& b0, const Vec3& c0, const Vec3& a1,
                                const Vec3& b1, const Vec3& c1, const StaticBound& sb) {
  std::uint8_t bits = 0;
  for (int k = 0; k < 3; ++k) {
    // Dropping axis k leaves the cyclic pair (k + 1, k + 2): the 2-D cross product is n_k.
    const int s = bernstein_sign<Form::Cross>(a0, b0, c0, a1, b1, c1, (k + 1) % 3, (k + 2) % 3, sb);
    if (s > 0) bits = static_cast<std::uint8_t>(bits | (1u << (2 * k)));
    if (s < 0) bits = static_cast<std::uint8_t>(bits | (1u << (2 * k + 1)));
  }
  return bits;
}

DeformCones make_deform_cones(const Model& model, std::span<const Vec3> V0,
                              std::span<const Vec3> V1, Scalar max_coordinate) {
  DeformCones c;
  const StaticBound sb = static_bound(max_coordinate);
  std::shared_ptr<const ConeTopology> topology = cone_topology(model);
  if (topology->entries.empty()) return c;
  const Mesh& mesh = model.mesh();
  const std::span<const BvhNode> nodes = model.nodes();
  const std::span<const std::uint32_t> leaves = model.leaf_triangles();
  c.node_signs.assign(nodes.size(), 0);
  if (topology->find(0) != nullptr && !leaves.empty()) {
    // The root along one axis, until a triangle has no certified sign along it.
    const TriangleIndices& f = mesh.triangles[leaves[0]];
    const Vec3 n = (V0[f[1]] - V0[f[0]]).cross(V0[f[2]] - V0[f[0]]).cwiseAbs();
    const int k = n.x() >= n.y() && n.x() >= n.z() ? 0 : (n.y() >= n.z() ? 1 : 2);
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    int sign = 2;  // 2: none yet
    for (std::size_t i = 0; i < leaves.size() && sign != 0; ++i) {
      const TriangleIndices& t = mesh.triangles[leaves[i]];
      const int s = bernstein_sign<Form::Cross>(V0[t[0]], V0[t[1]], V0[t[2]], V1[t[0]], V1[t[1]],
                                                V1[t[2]], u, v, sb);
      sign = (sign == 2 || s == sign) ? s : 0;
    }
    if (sign == 1 || sign == -1) {
      c.node_signs[0] = static_cast<std::uint8_t>(1u << (2 * k + (sign < 0 ? 1 : 0)));
      c.topology = topology;
      std::vector<EdgeBox> scratch;
      if (deform_cone_culls(model, c, 0, V0, V1, scratch)) {
        c.root_culled = true;
        return c;
      }
    }
  }
  // Leaves in parallel (independent), then the internal nodes bottom-up (children follow their
  // parent in the depth-first layout).
  parallel::for_ranges(0, nodes.size(), 1024, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const BvhNode& n = nodes[i];
      if (!n.is_leaf()) continue;
      std::uint8_t s = 0x3f;
      for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count && s != 0; ++k) {
        const TriangleIndices& t = mesh.triangles[leaves[k]];
        s &= swept_normal_signs(V0[t[0]], V0[t[1]], V0[t[2]], V1[t[0]], V1[t[1]], V1[t[2]], sb);
      }
      c.node_signs[i] = s;
    }
  });
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const BvhNode& n = nodes[i];
    if (!n.is_leaf()) c.node_signs[i] = c.node_signs[i + 1] & c.node_signs[n.first_or_right];
  }
  c.topology = std::move(topology);
  return c;
}

bool deform_cone_culls(const Model& model, const DeformCones& cones, std::uint32_t node,
                       std::span<const Vec3> V0, std::span<const Vec3> V1,
                       std::vector<EdgeBox>& scratch) {
  if (!cones.topology || node >= cones.node_signs.size()) return false;
  const std::uint8_t signs = cones.node_signs[node];
  if (signs == 0) return false;
  const ConeTopology::Entry* entry = cones.topology->find(node);
  if (entry == nullptr) return false;
  for (int k = 0; k < 3; ++k) {  // each axis with a certified sign
    if ((signs >> (2 * k) & 3u) == 0) continue;
    if (cycle_stays_simple(model.mesh(), cones.topology->cycle(*entry), k, V0, V1, scratch)) {
      return true;
    }
  }
  return false;
}

}  // namespace antcd::detail
