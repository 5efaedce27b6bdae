// self_intersections (antcd/self.hpp): a self-traversal of the Model's own hierarchy, its
// subtrees bounded per call by exact axis-aligned boxes of the current corners (the tree's
// spheres and boxes are not read: between the touching neighbours a self traversal meets they
// cost more than they cull, and a box of the corners themselves is never loosened by a refit),
// subtrees culled by their normal cones (cone.cpp), leaf pairs decided by the exact pair test
// (pair_test.cpp); triangles the hierarchy leaves out (numerically degenerate, yet of non-zero
// area) are tested against the tree and each other apart.
#include <antcd/error.hpp>
#include <antcd/self.hpp>

#include "self/cone.hpp"
#include "self/pair_test.hpp"
#include "util/parallel.hpp"

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

/// A closed axis-aligned box: the exact minima and maxima of corner coordinates (of a triangle,
/// or of a subtree's triangles). Point sets in disjoint boxes do not meet.
struct Box {
  // User-provided, so that the per-call vectors of boxes are not zero-filled before being set.
  Box() {}  // NOLINT(modernize-use-equals-default)
  Box(const Vec3& l, const Vec3& h) : lo(l), hi(h) {}
  Vec3 lo;
  Vec3 hi;
  [[nodiscard]] bool apart(const Box& o) const {
    return (hi.array() < o.lo.array()).any() || (o.hi.array() < lo.array()).any();
  }
};

/// The box of mesh triangle t.
inline Box box_of(const Mesh& mesh, std::uint32_t t) {
  const auto& v = mesh.vertices;
  const TriangleIndices& c = mesh.triangles[t];
  const Vec3 &p = v[c[0]], &q = v[c[1]], &r = v[c[2]];
  Box b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = std::min({p[k], q[k], r[k]});
    b.hi[k] = std::max({p[k], q[k], r[k]});
  }
  return b;
}

/// What every task reads: the model, per-node normal-sign masks and the cone data.
struct Context {
  const Model& model;
  const Mesh& mesh;
  std::span<const BvhNode> nodes;
  std::span<const std::uint32_t> leaves;
  std::vector<std::uint8_t> leaf_signs;  ///< normal_signs of leaf_triangles()[k]
  std::vector<std::uint8_t> node_signs;  ///< AND of leaf_signs over the node's triangles
  std::vector<Box> leaf_boxes;           ///< box of leaf_triangles()[k]
  std::vector<std::uint8_t> leaf_axes;   ///< self_detail::certificate_axis of leaf_triangles()[k]
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
    if (cx.leaf_boxes[k].apart(cx.leaf_boxes[l])) {
      ++stats.triangle_pairs;
      return;
    }
    test(cx, cx.leaves[k], cx.leaves[l], {cx.leaf_axes[k], true});
  }

  void test(const Context& cx, std::uint32_t ti, std::uint32_t tj,
            self_detail::PairHint hint = {}) {
    ++stats.triangle_pairs;
    int shared = 0;
    const bool hit = self_detail::pair_intersects(cx.mesh, ti, tj, shared, hint);
    if (shared != 0) ++stats.adjacent_pairs;
    if (hit) {
      pairs.push_back({std::min(ti, tj), std::max(ti, tj)});
      if (first_only) done = true;
    }
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
        if (cx.leaf_signs[k] == 0) continue;  // exactly degenerate
        for (std::uint32_t l = k + 1; l < f + na.count && !out.done; ++l) {
          if (cx.leaf_signs[l] != 0) out.test_leaf(cx, k, l);
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
      if (cx.leaf_signs[k] == 0) continue;
      for (std::uint32_t l = nb.first_or_right; l < nb.first_or_right + nb.count && !out.done;
           ++l) {
        if (cx.leaf_signs[l] != 0) out.test_leaf(cx, k, l);
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
    const Box box = box_of(cx.mesh, t);
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty() && !out.done) {
      const BvhNode& n = cx.nodes[stack.back()];
      const std::uint32_t i = stack.back();
      stack.pop_back();
      if (cx.node_boxes[i].apart(box)) continue;
      if (n.is_leaf()) {
        for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count && !out.done; ++k) {
          if (cx.leaf_signs[k] != 0) out.test(cx, t, cx.leaves[k]);
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
  cx.leaf_boxes.resize(cx.leaves.size());
  parallel::for_ranges(0, cx.leaves.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) cx.leaf_boxes[k] = box_of(cx.mesh, cx.leaves[k]);
  });
  // The nodes' boxes, children before parents (a node's children follow it).
  cx.node_boxes.resize(cx.nodes.size());
  for (std::size_t i = cx.nodes.size(); i-- > 0;) {
    const BvhNode& n = cx.nodes[i];
    Box& b = cx.node_boxes[i];
    if (n.is_leaf()) {
      b = cx.leaf_boxes[n.first_or_right];
      for (std::uint32_t k = n.first_or_right + 1; k < n.first_or_right + n.count; ++k) {
        b.lo = b.lo.cwiseMin(cx.leaf_boxes[k].lo);
        b.hi = b.hi.cwiseMax(cx.leaf_boxes[k].hi);
      }
    } else {
      const Box& l = cx.node_boxes[i + 1];
      const Box& r = cx.node_boxes[n.first_or_right];
      b = {l.lo.cwiseMin(r.lo), l.hi.cwiseMax(r.hi)};
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
  Context cx{model, mesh, model.nodes(), model.leaf_triangles(), {}, {}, {}, {}, {}, nullptr};
  const auto& v = mesh.vertices;
  // Exact normal signs of the tree's triangles (zero: exactly degenerate), in leaf order.
  cx.leaf_signs.resize(cx.leaves.size());
  cx.leaf_axes.resize(cx.leaves.size());
  parallel::for_ranges(0, cx.leaves.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) {
      const TriangleIndices& t = mesh.triangles[cx.leaves[k]];
      int axis = 0;
      cx.leaf_signs[k] = self_detail::normal_signs(v[t[0]], v[t[1]], v[t[2]], &axis);
      cx.leaf_axes[k] = static_cast<std::uint8_t>(axis);
    }
  });
  // The triangles the tree leaves out: degenerate exactly, or thin but with an area.
  std::vector<bool> in_tree(mesh.triangles.size(), false);
  for (std::size_t k = 0; k < cx.leaves.size(); ++k) {
    in_tree[cx.leaves[k]] = true;
    if (cx.leaf_signs[k] == 0) result.degenerate_triangles.push_back(cx.leaves[k]);
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
            s &= cx.leaf_signs[k];
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
