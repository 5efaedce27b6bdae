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
// are decided per query on the current positions. The topology and the sweep over the boundary's
// edge boxes are shared with the deforming sweep's continuous cull (ccd/normal_cone.hpp).
#include "self/cone.hpp"

#include "geometry/intersection.hpp"
#include "geometry/predicates.hpp"

#include <algorithm>
#include <vector>

namespace antcd::self_detail {

using detail::edge_head;
using detail::edge_tail;
using geometry::detail::orient2d;
using geometry::detail::Projection;

bool cone_culls(const Model& model, const ConeTopology& topology, const ConeTopology::Entry& entry,
                std::uint8_t signs, std::vector<detail::EdgeBox>& boxes) {
  if (signs == 0) return false;
  int bit = 0;
  while ((signs >> bit & 1u) == 0) ++bit;
  // Along -axis the orientations are all negative: the mirror image of the positive case.
  const Projection pr(bit / 2);
  const Mesh& m = model.mesh();
  const auto& v = m.vertices;
  const std::span<const std::uint32_t> cycle = topology.cycle(entry);
  const std::size_t n = cycle.size();
  boxes.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = v[edge_tail(m, cycle[k])];
    const Vec3& b = v[edge_head(m, cycle[k])];
    boxes[k] = {std::min(a[pr.u], b[pr.u]), std::max(a[pr.u], b[pr.u]), std::min(a[pr.v], b[pr.v]),
                std::max(a[pr.v], b[pr.v]), static_cast<std::uint32_t>(k)};
  }
  return detail::cycle_is_simple(
      boxes,
      [&](std::size_t x, std::size_t y) {
        return !geometry::detail::segments_meet_2d(
            v[edge_tail(m, cycle[x])], v[edge_head(m, cycle[x])], v[edge_tail(m, cycle[y])],
            v[edge_head(m, cycle[y])], pr, nullptr);
      },
      [&](std::size_t first, std::size_t second) {
        // first -> shared -> second overlap beyond the shared vertex only when collinear with
        // both far ends on one side of it.
        const Vec3& a = v[edge_tail(m, cycle[first])];
        const Vec3& s = v[edge_head(m, cycle[first])];
        const Vec3& c = v[edge_head(m, cycle[second])];
        if (orient2d(a, s, c, pr) != 0) return true;
        const int axis = a[pr.u] != s[pr.u] ? pr.u : pr.v;
        return !((a[axis] > s[axis]) == (c[axis] > s[axis]) && c[axis] != s[axis]);
      });
}

}  // namespace antcd::self_detail
