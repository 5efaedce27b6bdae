// self_intersections (antcd/self.hpp): a self-traversal of the Model's own Sphere-OBB hierarchy,
// subtrees culled by their normal cones (cone.cpp), leaf pairs decided by the exact pair test
// (pair_test.cpp); triangles the hierarchy leaves out (numerically degenerate, yet of non-zero
// area) are tested against the tree and each other apart.
#include <antcd/error.hpp>
#include <antcd/self.hpp>
#include <antcd/tolerances.hpp>

#include "geometry/obb_sat.hpp"
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

/// What every task reads: the model, per-node normal-sign masks and the cone data.
struct Context {
  const Model& model;
  const Mesh& mesh;
  std::span<const BvhNode> nodes;
  std::span<const std::uint32_t> leaves;
  std::vector<std::uint8_t> leaf_signs;  ///< normal_signs of leaf_triangles()[k]
  std::vector<std::uint8_t> node_signs;  ///< AND of leaf_signs over the node's triangles
  std::shared_ptr<const self_detail::ConeTopology> cones;  ///< null: no cone culling
  Scalar margin = 0;
};

/// The closed bounding boxes of one leaf's triangles (exact: minima and maxima of corner
/// coordinates), found once per leaf visit instead of once per triangle pair. A leaf larger than
/// the buffer (a user's leaf_size above it) gets none: its pairs skip this filter.
class LeafBoxes {
 public:
  static constexpr std::uint32_t kCapacity = 16;
  LeafBoxes(const Context& cx, const BvhNode& leaf) : first_(leaf.first_or_right) {
    if (leaf.count > kCapacity) return;
    count_ = leaf.count;
    const auto& v = cx.mesh.vertices;
    for (std::uint32_t k = 0; k < count_; ++k) {
      const TriangleIndices& t = cx.mesh.triangles[cx.leaves[first_ + k]];
      lo_[k] = v[t[0]].cwiseMin(v[t[1]]).cwiseMin(v[t[2]]);
      hi_[k] = v[t[0]].cwiseMax(v[t[1]]).cwiseMax(v[t[2]]);
    }
  }
  /// Leaf triangle k (an index into leaf_triangles()) of this leaf and leaf triangle l of
  /// `other` have disjoint boxes, so they share no vertex and do not meet (false: not known).
  [[nodiscard]] bool apart(std::uint32_t k, const LeafBoxes& other, std::uint32_t l) const {
    if (count_ == 0 || other.count_ == 0) return false;
    const std::uint32_t i = k - first_, j = l - other.first_;
    return (hi_[i].array() < other.lo_[j].array()).any() ||
           (other.hi_[j].array() < lo_[i].array()).any();
  }

 private:
  std::uint32_t first_;
  std::uint32_t count_ = 0;
  std::array<Vec3, kCapacity> lo_;
  std::array<Vec3, kCapacity> hi_;
};

struct Collector {
  std::vector<Pair> pairs;
  SelfIntersectionStats stats;
  bool first_only = false;
  bool done = false;

  /// Leaf triangles k and l (indices into leaf_triangles()), with their leaves' boxes.
  void test(const Context& cx, std::uint32_t k, std::uint32_t l, const LeafBoxes& bk,
            const LeafBoxes& bl) {
    if (bk.apart(k, bl, l)) {
      ++stats.triangle_pairs;
      return;
    }
    test(cx, cx.leaves[k], cx.leaves[l]);
  }

  void test(const Context& cx, std::uint32_t ti, std::uint32_t tj) {
    ++stats.triangle_pairs;
    int shared = 0;
    const bool hit = self_detail::pair_intersects(cx.mesh, ti, tj, shared);
    if (shared != 0) ++stats.adjacent_pairs;
    if (hit) {
      pairs.push_back({std::min(ti, tj), std::max(ti, tj)});
      if (first_only) done = true;
    }
  }
};

bool volumes_disjoint(const BvhNode& a, const BvhNode& b, Scalar margin) {
  const Scalar r = Scalar{a.radius} + Scalar{b.radius} + margin;
  const Vec3 d = b.center - a.center;
  if (d.squaredNorm() > r * r) return true;
  const Mat3 ra = a.axes();
  const Mat3 rot = ra.transpose() * b.axes();
  // The six face axes only: the nine edge-edge axes rarely separate the touching neighbours a
  // self traversal meets, and skipping them only costs rejections, never a pair.
  return geometry::detail::obb_face_separated(a.half_extents().array() + margin, b.half_extents(),
                                              rot, geometry::detail::obb_abs_rotation(rot),
                                              ra.transpose() * d);
}

/// Expands one work item by one step, pushing its children with `push`; tests leaves directly.
template <class Push>
void step(const Context& cx, const Work& w, Collector& out, const Push& push) {
  const BvhNode& na = cx.nodes[w.a];
  if (w.self) {
    if (na.is_leaf()) {
      const LeafBoxes boxes(cx, na);
      const std::uint32_t f = na.first_or_right;
      for (std::uint32_t k = f; k < f + na.count && !out.done; ++k) {
        if (cx.leaf_signs[k] == 0) continue;  // exactly degenerate
        for (std::uint32_t l = k + 1; l < f + na.count && !out.done; ++l) {
          if (cx.leaf_signs[l] != 0) out.test(cx, k, l, boxes, boxes);
        }
      }
      return;
    }
    if (cx.cones && na.count == 0 && cx.node_signs[w.a] != 0) {
      if (const auto* entry = cx.cones->find(w.a)) {
        ++out.stats.cone_tests;
        if (self_detail::cone_culls(cx.model, *cx.cones, *entry, cx.node_signs[w.a])) {
          ++out.stats.cone_culled;
          return;
        }
      }
    }
    const std::uint32_t l = w.a + 1, r = na.first_or_right;
    push(Work{l, r, false});
    push(Work{r, r, true});
    push(Work{l, l, true});
    return;
  }
  const BvhNode& nb = cx.nodes[w.b];
  ++out.stats.node_pairs;
  if (volumes_disjoint(na, nb, cx.margin)) {
    ++out.stats.volume_rejects;
    return;
  }
  if (na.is_leaf() && nb.is_leaf()) {
    const LeafBoxes ba(cx, na), bb(cx, nb);
    for (std::uint32_t k = na.first_or_right; k < na.first_or_right + na.count && !out.done; ++k) {
      if (cx.leaf_signs[k] == 0) continue;
      for (std::uint32_t l = nb.first_or_right; l < nb.first_or_right + nb.count && !out.done;
           ++l) {
        if (cx.leaf_signs[l] != 0) out.test(cx, k, l, ba, bb);
      }
    }
    return;
  }
  if (nb.is_leaf() || (!na.is_leaf() && na.radius >= nb.radius)) {
    push(Work{na.first_or_right, w.b, false});
    push(Work{w.a + 1, w.b, false});
  } else {
    push(Work{w.a, nb.first_or_right, false});
    push(Work{w.a, w.b + 1, false});
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
  const auto& v = cx.mesh.vertices;
  const auto corner = [&](std::uint32_t t, int c) -> const Vec3& {
    return v[cx.mesh.triangles[t][static_cast<std::size_t>(c)]];
  };
  for (std::size_t s = 0; s < left_out.size() && !out.done; ++s) {
    const std::uint32_t t = left_out[s];
    const Vec3 centre = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3;
    Scalar radius = 0;
    for (int c = 0; c < 3; ++c) radius = std::max(radius, (corner(t, c) - centre).norm());
    radius = tolerance::widened(radius) + cx.margin;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty() && !out.done) {
      const BvhNode& n = cx.nodes[stack.back()];
      const std::uint32_t i = stack.back();
      stack.pop_back();
      const Scalar r = Scalar{n.radius} + radius;
      if ((n.center - centre).squaredNorm() > r * r) continue;
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

}  // namespace

SelfIntersectionResult self_intersections(const Model& model,
                                          const SelfIntersectionRequest& request) {
  SelfIntersectionResult result;
  const Mesh& mesh = model.mesh();
  Context cx{model, mesh, model.nodes(), model.leaf_triangles(), {}, {}, nullptr, 0};
  const auto& v = mesh.vertices;
  // Exact normal signs of the tree's triangles (zero: exactly degenerate), in leaf order.
  cx.leaf_signs.resize(cx.leaves.size());
  parallel::for_ranges(0, cx.leaves.size(), 4096, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) {
      const TriangleIndices& t = mesh.triangles[cx.leaves[k]];
      cx.leaf_signs[k] = self_detail::normal_signs(v[t[0]], v[t[1]], v[t[2]]);
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
  // The volumes' rounding allowance, as the two-model traversal takes it (bvh/traverse.hpp).
  cx.margin = tolerance::volume_allowance(Scalar{model.root().radius} + model.root().center.norm());
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
