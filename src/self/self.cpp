// self_intersections (antcd/self.hpp): a self-traversal of the Model's own hierarchy, its
// subtrees bounded per call by axis-aligned float boxes of the current corners, rounded outward
// (the tree's spheres and boxes are not read: between the touching neighbours a self traversal
// meets they cost more than they cull, and a box of the corners themselves is never loosened by a
// refit),
// subtrees culled by their normal cones (cone.cpp), leaf pairs decided by the exact pair test
// (pair_test.cpp); triangles the hierarchy leaves out (numerically degenerate, yet of non-zero
// area) are tested against the tree and each other apart.
#include <antcd/error.hpp>
#include <antcd/self.hpp>

#include "self/cone.hpp"
#include "self/pair_test.hpp"
#include "util/float_bounds.hpp"
#include "util/parallel.hpp"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace antcd {

namespace {

using Pair = std::array<std::uint32_t, 2>;

/// One unit of traversal work: the self test of one subtree, or the test of two disjoint ones.
struct Work {
  std::uint32_t a;
  std::uint32_t b;
  bool self;
};

/// A closed axis-aligned box of floats, rounded outward from the exact minima and maxima of corner
/// coordinates (of a triangle, or of a subtree's triangles), so that it holds the exact box: point
/// sets in boxes found apart do not meet. Lane 3 is 0 in both corners (a four-lane comparison then
/// ignores it). Floats halve the traversal's box traffic against doubles; the boxes only filter,
/// so the slightly larger ones change counts, never a verdict.
struct alignas(16) Box {
  // User-provided, so that the per-call vectors of boxes are not zero-filled before being set.
  Box() {}  // NOLINT(modernize-use-equals-default)
  float lo[4];
  float hi[4];
  [[nodiscard]] bool apart(const Box& o) const {
#if defined(__SSE2__)
    const __m128 below = _mm_cmplt_ps(_mm_load_ps(hi), _mm_load_ps(o.lo));
    const __m128 above = _mm_cmplt_ps(_mm_load_ps(o.hi), _mm_load_ps(lo));
    return _mm_movemask_ps(_mm_or_ps(below, above)) != 0;
#else
    bool out = false;
    for (int k = 0; k < 3; ++k) out = out || hi[k] < o.lo[k] || o.hi[k] < lo[k];
    return out;
#endif
  }
  /// The smallest box holding a and b.
  [[nodiscard]] static Box merged(const Box& a, const Box& b) {
    Box m;
    for (int k = 0; k < 4; ++k) {
      m.lo[k] = std::min(a.lo[k], b.lo[k]);
      m.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
    return m;
  }
};

/// The box of the triangle with corners c.
inline Box box_of(const Mesh& mesh, const TriangleIndices& c) {
  const auto& v = mesh.vertices;
  const Vec3 &p = v[c[0]], &q = v[c[1]], &r = v[c[2]];
  Box b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = detail::float_below(std::min({p[k], q[k], r[k]}));
    b.hi[k] = detail::float_above(std::max({p[k], q[k], r[k]}));
  }
  b.lo[3] = 0;
  b.hi[3] = 0;
  return b;
}

/// What a leaf pair test reads of one tree triangle, side by side: its box, corners, exact
/// normal signs (self_detail::normal_signs; zero: exactly degenerate) and certificate axis.
struct Slot {
  Slot() {}  // NOLINT(modernize-use-equals-default): not zero-filled, as Box
  Box box;
  TriangleIndices corners;
  std::uint8_t sign;
  std::uint8_t axis;
};

/// What every task reads: the model, per-node normal-sign masks and the cone data.
struct Context {
  const Model& model;
  const Mesh& mesh;
  std::span<const BvhNode> nodes;
  std::span<const std::uint32_t> leaves;
  std::vector<Slot> slots;               ///< of leaf_triangles()[k]
  std::vector<std::uint8_t> node_signs;  ///< AND of the slots' signs over the node's triangles
  std::vector<Box> node_boxes;           ///< box of each node's triangles
  std::shared_ptr<const self_detail::ConeTopology> cones;  ///< null: no cone culling
};

struct Collector {
  std::vector<Pair> pairs;
  SelfIntersectionStats stats;
  bool first_only = false;
  bool done = false;
  std::vector<detail::EdgeBox> edge_boxes;  ///< room of the cone tests, reused

  /// Leaf triangles k and l (indices into leaf_triangles()).
  void test_leaf(const Context& cx, std::uint32_t k, std::uint32_t l) {
    ++stats.triangle_pairs;
    const Slot& a = cx.slots[k];
    const Slot& b = cx.slots[l];
    if (a.box.apart(b.box)) return;
    int shared = 0;
    const bool hit =
        self_detail::pair_intersects(cx.mesh, a.corners, b.corners, shared, {a.axis, true});
    if (shared != 0) ++stats.adjacent_pairs;
    if (hit) found(cx.leaves[k], cx.leaves[l]);
  }

  void test(const Context& cx, std::uint32_t ti, std::uint32_t tj) {
    ++stats.triangle_pairs;
    int shared = 0;
    const bool hit = self_detail::pair_intersects(cx.mesh, ti, tj, shared);
    if (shared != 0) ++stats.adjacent_pairs;
    if (hit) found(ti, tj);
  }

  void found(std::uint32_t ti, std::uint32_t tj) {
    pairs.push_back({std::min(ti, tj), std::max(ti, tj)});
    if (first_only) done = true;
  }
};

/// Expands one work item by one step, pushing its children with `push`; tests leaves directly.
template <class Push>
void step(const Context& cx, const Work& w, Collector& out, const Push& push) {
  const BvhNode& na = cx.nodes[w.a];
  // A pair of subtrees is pushed only when their boxes overlap (tested here, once).
  const auto push_pair = [&](std::uint32_t a, std::uint32_t b) {
    ++out.stats.node_pairs;
    if (cx.node_boxes[a].apart(cx.node_boxes[b])) {
      ++out.stats.volume_rejects;
      return;
    }
    push(Work{a, b, false});
  };
  if (w.self) {
    if (na.is_leaf()) {
      const std::uint32_t f = na.first_or_right;
      for (std::uint32_t k = f; k < f + na.count && !out.done; ++k) {
        if (cx.slots[k].sign == 0) continue;  // exactly degenerate
        for (std::uint32_t l = k + 1; l < f + na.count && !out.done; ++l) {
          if (cx.slots[l].sign != 0) out.test_leaf(cx, k, l);
        }
      }
      return;
    }
    if (cx.cones && na.count == 0 && cx.node_signs[w.a] != 0) {
      if (const auto* entry = cx.cones->find(w.a)) {
        ++out.stats.cone_tests;
        if (self_detail::cone_culls(cx.model, *cx.cones, *entry, cx.node_signs[w.a],
                                    out.edge_boxes)) {
          ++out.stats.cone_culled;
          return;
        }
      }
    }
    const std::uint32_t l = w.a + 1, r = na.first_or_right;
    push_pair(l, r);
    push(Work{r, r, true});
    push(Work{l, l, true});
    return;
  }
  const BvhNode& nb = cx.nodes[w.b];
  if (na.is_leaf() && nb.is_leaf()) {
    for (std::uint32_t k = na.first_or_right; k < na.first_or_right + na.count && !out.done; ++k) {
      if (cx.slots[k].sign == 0) continue;
      for (std::uint32_t l = nb.first_or_right; l < nb.first_or_right + nb.count && !out.done;
           ++l) {
        if (cx.slots[l].sign != 0) out.test_leaf(cx, k, l);
      }
    }
    return;
  }
  if (!na.is_leaf() && !nb.is_leaf()) {
    push_pair(na.first_or_right, nb.first_or_right);
    push_pair(na.first_or_right, w.b + 1);
    push_pair(w.a + 1, nb.first_or_right);
    push_pair(w.a + 1, w.b + 1);
    return;
  }
  if (nb.is_leaf() || (!na.is_leaf() && na.radius >= nb.radius)) {
    push_pair(na.first_or_right, w.b);
    push_pair(w.a + 1, w.b);
  } else {
    push_pair(w.a, nb.first_or_right);
    push_pair(w.a, w.b + 1);
  }
}

/// Depth-first from `start` until done.
void run(const Context& cx, const Work& start, Collector& out) {
  std::vector<Work> stack{start};
  while (!stack.empty() && !out.done) {
    const Work w = stack.back();
    stack.pop_back();
    step(cx, w, out, [&](const Work& next) { stack.push_back(next); });
  }
}

void add(SelfIntersectionStats& to, const SelfIntersectionStats& s) {
  to.node_pairs += s.node_pairs;
  to.volume_rejects += s.volume_rejects;
  to.triangle_pairs += s.triangle_pairs;
  to.adjacent_pairs += s.adjacent_pairs;
  to.cone_culled += s.cone_culled;
  to.cone_tests += s.cone_tests;
}

/// Triangles left out of the hierarchy that have a non-zero area, against the tree's triangles
/// and each other.
void test_left_out(const Context& cx, const std::vector<std::uint32_t>& left_out, Collector& out) {
  for (std::size_t s = 0; s < left_out.size() && !out.done; ++s) {
    const std::uint32_t t = left_out[s];
    const Box box = box_of(cx.mesh, cx.mesh.triangles[t]);
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty() && !out.done) {
      const BvhNode& n = cx.nodes[stack.back()];
      const std::uint32_t i = stack.back();
      stack.pop_back();
      if (cx.node_boxes[i].apart(box)) continue;
      if (n.is_leaf()) {
        for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count && !out.done; ++k) {
          if (cx.slots[k].sign != 0) out.test(cx, t, cx.leaves[k]);
        }
      } else {
        stack.push_back(n.first_or_right);
        stack.push_back(i + 1);
      }
    }
    for (std::size_t s2 = s + 1; s2 < left_out.size() && !out.done; ++s2) {
      out.test(cx, t, left_out[s2]);
    }
  }
}

/// The boxes of the tree's triangles and of its nodes.
void add_boxes(Context& cx) {
  parallel::for_ranges(0, cx.slots.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) cx.slots[k].box = box_of(cx.mesh, cx.slots[k].corners);
  });
  // The nodes' boxes, children before parents (a node's children follow it).
  cx.node_boxes.resize(cx.nodes.size());
  for (std::size_t i = cx.nodes.size(); i-- > 0;) {
    const BvhNode& n = cx.nodes[i];
    Box& b = cx.node_boxes[i];
    if (n.is_leaf()) {
      b = cx.slots[n.first_or_right].box;
      for (std::uint32_t k = n.first_or_right + 1; k < n.first_or_right + n.count; ++k) {
        b = Box::merged(b, cx.slots[k].box);
      }
    } else {
      b = Box::merged(cx.node_boxes[i + 1], cx.node_boxes[n.first_or_right]);
    }
  }
}

/// The cone test culls the whole tree (the traversal's first step would stop there).
bool root_culled(const Context& cx) {
  if (!cx.cones || cx.nodes[0].is_leaf() || cx.node_signs[0] == 0) return false;
  const auto* entry = cx.cones->find(0);
  std::vector<detail::EdgeBox> boxes;
  return entry != nullptr &&
         self_detail::cone_culls(cx.model, *cx.cones, *entry, cx.node_signs[0], boxes);
}

}  // namespace

SelfIntersectionResult self_intersections(const Model& model,
                                          const SelfIntersectionRequest& request) {
  SelfIntersectionResult result;
  const Mesh& mesh = model.mesh();
  Context cx{model, mesh, model.nodes(), model.leaf_triangles(), {}, {}, {}, nullptr};
  const auto& v = mesh.vertices;
  // Exact normal signs of the tree's triangles (zero: exactly degenerate), in leaf order.
  cx.slots.resize(cx.leaves.size());
  parallel::for_ranges(0, cx.leaves.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) {
      Slot& s = cx.slots[k];
      s.corners = mesh.triangles[cx.leaves[k]];
      int axis = 0;
      s.sign = self_detail::normal_signs(v[s.corners[0]], v[s.corners[1]], v[s.corners[2]], &axis);
      s.axis = static_cast<std::uint8_t>(axis);
    }
  });
  // The triangles the tree leaves out: degenerate exactly, or thin but with an area.
  std::vector<bool> in_tree(mesh.triangles.size(), false);
  for (std::size_t k = 0; k < cx.leaves.size(); ++k) {
    in_tree[cx.leaves[k]] = true;
    if (cx.slots[k].sign == 0) result.degenerate_triangles.push_back(cx.leaves[k]);
  }
  std::vector<std::uint32_t> left_out;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    if (in_tree[t]) continue;
    const TriangleIndices& tri = mesh.triangles[t];
    if (self_detail::normal_signs(v[tri[0]], v[tri[1]], v[tri[2]]) == 0) {
      result.degenerate_triangles.push_back(t);
    } else {
      left_out.push_back(t);
    }
  }
  std::sort(result.degenerate_triangles.begin(), result.degenerate_triangles.end());
  if (request.normal_cones) {
    cx.cones = self_detail::cone_topology(model);
    result.stats.cone_cache_bytes = cx.cones->bytes();
    if (cx.cones->entries.empty()) {
      cx.cones = nullptr;
    } else {
      cx.node_signs.assign(cx.nodes.size(), 0);
      for (std::size_t i = cx.nodes.size(); i-- > 0;) {
        const BvhNode& n = cx.nodes[i];
        if (n.is_leaf()) {
          std::uint8_t s = 0x3f;
          for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
            s &= cx.slots[k].sign;
          }
          cx.node_signs[i] = s;
        } else {
          cx.node_signs[i] = cx.node_signs[i + 1] & cx.node_signs[n.first_or_right];
        }
      }
    }
  }

  if (left_out.empty() && root_culled(cx)) {
    // Nothing to traverse: the boxes are not needed (a deforming sheet's common case).
    result.stats.cone_tests = 1;
    result.stats.cone_culled = 1;
    return result;
  }
  add_boxes(cx);

  if (request.first_only) {
    Collector out;
    out.first_only = true;
    run(cx, Work{0, 0, true}, out);
    if (!out.done) test_left_out(cx, left_out, out);
    out.stats.cone_cache_bytes = result.stats.cone_cache_bytes;
    result.stats = out.stats;
    result.pairs = std::move(out.pairs);
    result.intersecting = !result.pairs.empty();
    return result;
  }

  // Split the traversal at fixed points: expand breadth-first on this thread until enough work
  // items exist, then run each item depth-first in parallel. The items, and so every counter,
  // depend on the tree alone, never on the thread count.
  constexpr std::size_t kTasks = 512;
  Collector serial;
  std::vector<Work> frontier{Work{0, 0, true}};
  while (!frontier.empty() && frontier.size() < kTasks) {
    std::vector<Work> next;
    bool expanded = false;
    for (const Work& w : frontier) {
      const bool leafy =
          w.self ? cx.nodes[w.a].is_leaf() : cx.nodes[w.a].is_leaf() && cx.nodes[w.b].is_leaf();
      if (leafy) {
        next.push_back(w);
        continue;
      }
      expanded = true;
      step(cx, w, serial, [&](const Work& c) { next.push_back(c); });
    }
    frontier = std::move(next);
    if (!expanded) break;
  }
  std::vector<Collector> parts(frontier.size());
  parallel::for_each_index(0, frontier.size(),
                           [&](std::size_t k) { run(cx, frontier[k], parts[k]); });
  Collector left;
  test_left_out(cx, left_out, left);
  serial.stats.cone_cache_bytes = result.stats.cone_cache_bytes;
  result.stats = serial.stats;
  std::size_t total = serial.pairs.size() + left.pairs.size();
  for (const Collector& p : parts) total += p.pairs.size();
  result.pairs.reserve(total);
  result.pairs.insert(result.pairs.end(), serial.pairs.begin(), serial.pairs.end());
  for (const Collector& p : parts) {
    add(result.stats, p.stats);
    result.pairs.insert(result.pairs.end(), p.pairs.begin(), p.pairs.end());
  }
  add(result.stats, left.stats);
  result.pairs.insert(result.pairs.end(), left.pairs.begin(), left.pairs.end());
  std::sort(result.pairs.begin(), result.pairs.end());
  result.intersecting = !result.pairs.empty();
  return result;
}

}  // namespace antcd
