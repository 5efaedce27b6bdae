// Private: normal-cone culling of a self query (Volino & Magnenat-Thalmann 1994; Provot 1997),
// shared by the static self test (self/cone.cpp) and the deforming sweep (deform_sweep.cpp):
// - the position-independent subtree boundaries (ConeTopology, built once per Model and kept by
//   refit);
// - the sweep over a boundary cycle's edge boxes that both simplicity tests run (cycle_is_simple),
//   with the static or the continuous pair predicates;
// - the continuous cull of a deforming subtree (DeformCones, deform_cone_culls; normal_cone.cpp
//   holds its proof).
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace antcd::detail {

/// Subtrees of at least this many triangles may be culled whole (smaller ones are cheaper to
/// traverse than to test, and their boundaries would cost memory).
inline constexpr std::uint32_t kConeMinTriangles = 64;

/// Position-independent data of the cull, built once per Model (and kept by refit): for each
/// subtree of at least kConeMinTriangles triangles whose edges are each used by at most two of its
/// triangles, in opposite directions, and whose boundary edges form one directed cycle, that cycle.
/// A boundary edge is stored as 3 t + k: edge k of mesh triangle t, from corner k to corner k + 1.
struct ConeTopology {
  struct Entry {
    std::uint32_t node;
    std::uint32_t begin;  ///< into edges
    std::uint32_t end;
  };
  std::vector<Entry> entries;  ///< ascending by node
  std::vector<std::uint32_t> edges;
  /// The entry of `node`, or null.
  [[nodiscard]] const Entry* find(std::uint32_t node) const;
  [[nodiscard]] std::size_t bytes() const {
    return entries.capacity() * sizeof(Entry) + edges.capacity() * sizeof(std::uint32_t);
  }
  [[nodiscard]] std::span<const std::uint32_t> cycle(const Entry& e) const {
    return {edges.data() + e.begin, e.end - e.begin};
  }
};

/// The model's ConeTopology, built on first use (thread-safe).
std::shared_ptr<const ConeTopology> cone_topology(const Model& model);

/// Tail and head vertex of boundary edge code e (3 t + k).
inline std::uint32_t edge_tail(const Mesh& m, std::uint32_t e) { return m.triangles[e / 3][e % 3]; }
inline std::uint32_t edge_head(const Mesh& m, std::uint32_t e) {
  return m.triangles[e / 3][(e % 3 + 1) % 3];
}

/// The 2-D box (projected coordinates u, v) of boundary edge `pos` of a cycle: of its segment
/// (static) or of everything it sweeps (continuous).
struct EdgeBox {
  double lo_u, hi_u, lo_v, hi_v;
  std::uint32_t pos;  ///< position in the cycle
};

/// The sweep of the simplicity tests over the n = boxes.size() edges of a closed cycle (boxes
/// sorted here): every pair of edges whose boxes overlap is handed to `apart(x, y)` (positions x <
/// y, not consecutive: must prove the edges never meet) or to `no_fold(first, second)`
/// (consecutive, first's head is second's tail: must prove they meet only at that vertex). True
/// when every call proves it; edges whose boxes are apart never meet, so the cycle is then simple.
template <class Apart, class NoFold>
bool cycle_is_simple(std::vector<EdgeBox>& boxes, const Apart& apart, const NoFold& no_fold) {
  const std::size_t n = boxes.size();
  std::sort(boxes.begin(), boxes.end(), [](const EdgeBox& x, const EdgeBox& y) {
    return x.lo_u < y.lo_u || (x.lo_u == y.lo_u && x.pos < y.pos);
  });
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n && boxes[j].lo_u <= boxes[i].hi_u; ++j) {
      if (boxes[j].lo_v > boxes[i].hi_v || boxes[j].hi_v < boxes[i].lo_v) continue;
      std::size_t x = boxes[i].pos, y = boxes[j].pos;
      if (x > y) std::swap(x, y);
      const bool consecutive = y == x + 1 || (x == 0 && y == n - 1);
      if (!consecutive) {
        if (!apart(x, y)) return false;
        continue;
      }
      const std::size_t first = (y == x + 1) ? x : y;
      const std::size_t second = (y == x + 1) ? y : x;
      if (!no_fold(first, second)) return false;
    }
  }
  return true;
}

/// Per-call data of the continuous cull: node_signs[i] (for each node i of the model's tree) has
/// bit 2k set when, for every triangle under node i, normal component k is certified > 0 at every
/// t in [0, 1] of the motion V0 -> V1, and bit 2k + 1 when certified < 0 (normal_cone.cpp, (i)).
struct DeformCones {
  std::shared_ptr<const ConeTopology> topology;  ///< null: no subtree can be culled
  std::vector<std::uint8_t> node_signs;
  /// The tree's root (node 0) is culled: then node_signs holds the root's signs only (every other
  /// node 0), as no other node is tested.
  bool root_culled = false;
  [[nodiscard]] std::size_t bytes() const { return node_signs.capacity(); }
};

/// The cull data of `model`'s tree for the motion V0 -> V1 (one finite position per vertex).
/// O(n); topology is null when the model has no cone entry. The root is tried first, along one
/// axis (that of the first triangle's largest normal component at t = 0: a choice, not a
/// certificate), stopping at the first triangle without a certified sign along it; only when
/// the root is not culled are all the nodes' signs computed.
/// max_coordinate: the largest |coordinate| of V0 and V1.
DeformCones make_deform_cones(const Model& model, std::span<const Vec3> V0,
                              std::span<const Vec3> V1, Scalar max_coordinate);

/// Whether no self pair (antcd/deform_ccd.hpp) of triangles under tree node `node` comes into
/// contact (distance 0) at any t in [0, 1]: the node has a cone entry, a certified direction, and
/// its boundary cycle projected along that direction's axis stays simple over the whole step
/// (normal_cone.cpp). `scratch` is reused between calls.
bool deform_cone_culls(const Model& model, const DeformCones& cones, std::uint32_t node,
                       std::span<const Vec3> V0, std::span<const Vec3> V1,
                       std::vector<EdgeBox>& scratch);

}  // namespace antcd::detail
