// The normal-cone cull of self_intersections (Volino & Magnenat-Thalmann 1994; Provot 1997):
// a subtree whose triangles all face one way and whose boundary does not cross itself in
// projection cannot intersect itself. The sufficient condition implemented, for the set R of a
// subtree's triangles and a coordinate axis direction d (one of ±x, ±y, ±z), and why it is exact:
//
// (a) every triangle of R projects along d onto a triangle of exactly positive orientation (the
//     sign of its normal's d component, an exact 2-D orientation: pair_test.cpp, normal_signs);
// (b) every edge (pair of vertex indices) is used by at most two triangles of R, and by two only
//     in opposite directions;
// (c) the boundary edges of R (used by one triangle of R), directed as in that triangle, form one
//     directed cycle, and their projections form a simple polygon: edges that do not share an
//     index do not meet, and consecutive edges meet only at their common vertex (exact 2-D
//     orientations and coordinate comparisons).
//
// Proof. Let f be the projection. For a point p of the plane on no projected edge, the number of
// triangles of R whose projection holds p (its degree) is the sum of their boundary winding
// numbers about p (each is 1 or 0 by (a)); by (b) interior edges cancel in that sum, leaving the
// winding number of the projected boundary cycle, which is 0 or ±1 for a simple polygon (c). So
// no two projected triangles of R overlap in an open set. Suppose A, B in R meet at a point x
// their sharing does not require, q = f(x). Around q each triangle of R holding q covers a
// closed sector, with disjoint interiors. Crossing a sector's bounding ray along an edge e of its
// triangle T (e passes through x in space, f being one-to-one on T), either e is interior and its
// other triangle T' (opposite side by (a) and (b)) covers the next sector with the same point x
// over q, or e is a boundary edge. Walking from A both ways either closes around q (then A's
// chain covers all of it and B's sector overlaps it, unless B is in the chain) or ends on two
// boundary rays. B's chain likewise. A simple polygon has at most two boundary rays at q, each
// of one boundary edge, and a boundary edge has one triangle, so A and B lie in one chain. In a
// chain A = T0, ..., Tm = B consecutive triangles share an edge through x; for m = 1 that edge
// is A and B's shared edge and holds x; for m >= 2 each inner triangle has q at a projected
// corner, so x is that corner and every edge of the chain holds its vertex, which A and B then
// share, at x. Either way the sharing requires x: a contradiction. Hence no pair of R
// intersects beyond its sharing; the cull never drops a pair. Conditions (b) and the cycle of
// (c) depend on the triangles only and are found once (cone_topology); (a) and the polygon test
// are decided per query on the current positions.
#include "self/cone.hpp"

#include "bvh/model_cache.hpp"
#include "geometry/intersection.hpp"
#include "geometry/predicates.hpp"

#include <algorithm>
#include <mutex>
#include <numeric>
#include <utility>

namespace antcd::self_detail {

using geometry::detail::orient2d;
using geometry::detail::Projection;

const ConeTopology::Entry* ConeTopology::find(std::uint32_t node) const {
  const auto it = std::lower_bound(entries.begin(), entries.end(), node,
                                   [](const Entry& e, std::uint32_t n) { return e.node < n; });
  return it != entries.end() && it->node == node ? &*it : nullptr;
}

namespace {

std::uint32_t tail(const Mesh& m, std::uint32_t e) { return m.triangles[e / 3][e % 3]; }
std::uint32_t head(const Mesh& m, std::uint32_t e) { return m.triangles[e / 3][(e % 3 + 1) % 3]; }
std::uint64_t edge_key(const Mesh& m, std::uint32_t e) {
  const std::uint64_t u = tail(m, e), v = head(m, e);
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
            [&](std::uint32_t a, std::uint32_t b) { return tail(m, a) < tail(m, b); });
  for (std::size_t i = 1; i < by_tail.size(); ++i) {
    if (tail(m, by_tail[i]) == tail(m, by_tail[i - 1])) return false;
  }
  std::vector<std::uint32_t> cycle;
  cycle.reserve(codes.size());
  std::uint32_t e = by_tail.front();
  for (std::size_t step = 0; step < by_tail.size(); ++step) {
    cycle.push_back(e);
    const std::uint32_t h = head(m, e);
    const auto it =
        std::lower_bound(by_tail.begin(), by_tail.end(), h,
                         [&](std::uint32_t c, std::uint32_t v) { return tail(m, c) < v; });
    if (it == by_tail.end() || tail(m, *it) != h) return false;
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
    const bool two_opposite = j - i == 2 && tail(m, all[i].code) != tail(m, all[i + 1].code);
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
  static const std::size_t slot = detail::new_kept_slot();
  return detail::kept<ConeTopology>(model, slot, [&] { return build_topology(model); });
}

bool cone_culls(const Model& model, const ConeTopology& topology, const ConeTopology::Entry& entry,
                std::uint8_t signs) {
  if (signs == 0) return false;
  int bit = 0;
  while ((signs >> bit & 1u) == 0) ++bit;
  // Along -axis the orientations are all negative: the mirror image of the positive case.
  const Projection pr(bit / 2);
  const Mesh& m = model.mesh();
  const auto& v = m.vertices;
  const std::span<const std::uint32_t> cycle(topology.edges.data() + entry.begin,
                                             entry.end - entry.begin);
  const std::size_t n = cycle.size();
  struct Seg {
    double lo_u, hi_u, lo_v, hi_v;
    std::uint32_t pos;  // position in the cycle
  };
  std::vector<Seg> segs(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = v[tail(m, cycle[k])];
    const Vec3& b = v[head(m, cycle[k])];
    segs[k] = {std::min(a[pr.u], b[pr.u]), std::max(a[pr.u], b[pr.u]), std::min(a[pr.v], b[pr.v]),
               std::max(a[pr.v], b[pr.v]), static_cast<std::uint32_t>(k)};
  }
  std::sort(segs.begin(), segs.end(), [](const Seg& x, const Seg& y) {
    return x.lo_u < y.lo_u || (x.lo_u == y.lo_u && x.pos < y.pos);
  });
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n && segs[j].lo_u <= segs[i].hi_u; ++j) {
      if (segs[j].lo_v > segs[i].hi_v || segs[j].hi_v < segs[i].lo_v) continue;
      std::size_t x = segs[i].pos, y = segs[j].pos;
      if (x > y) std::swap(x, y);
      const bool consecutive = y == x + 1 || (x == 0 && y == n - 1);
      if (!consecutive) {
        if (geometry::detail::segments_meet_2d(v[tail(m, cycle[x])], v[head(m, cycle[x])],
                                               v[tail(m, cycle[y])], v[head(m, cycle[y])], pr,
                                               nullptr)) {
          return false;
        }
        continue;
      }
      // Consecutive: first -> shared -> second. They overlap beyond the shared vertex only when
      // collinear with both far ends on one side of it.
      const std::uint32_t first = (y == x + 1) ? cycle[x] : cycle[y];
      const std::uint32_t second = (y == x + 1) ? cycle[y] : cycle[x];
      const Vec3& a = v[tail(m, first)];
      const Vec3& s = v[head(m, first)];
      const Vec3& c = v[head(m, second)];
      if (orient2d(a, s, c, pr) != 0) continue;
      const int axis = a[pr.u] != s[pr.u] ? pr.u : pr.v;
      if ((a[axis] > s[axis]) == (c[axis] > s[axis]) && c[axis] != s[axis]) return false;
    }
  }
  return true;
}

}  // namespace antcd::self_detail
