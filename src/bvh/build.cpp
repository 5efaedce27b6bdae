// Top-down construction of the hybrid Sphere-OBB hierarchy (paper, section 2): each node gets
// the OBB of its triangles (geometry/obb_fit.cpp, Eqs. 1–3) and a sphere about the box centre,
// then its triangles are cut in two (split.cpp) until at most leaf_size remain.
#include <antcd/bvh.hpp>

#include "bvh/model_cache.hpp"
#include "bvh/node_store.hpp"
#include "bvh/split.hpp"
#include "geometry/obb_fit.hpp"
#include "util/check.hpp"
#include "util/huge_pages.hpp"
#include "util/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include <memory>

namespace antcd {

namespace {

using BuildTriangle = geometry::detail::FitTriangle;
using detail::SplitCentroid;

// Large trees are built by parallel tasks (oneTBB) over the subtrees of the top levels. A node's
// box and sphere are fitted from its triangles in the order they have when the node is reached,
// and the split that orders them is decided by the centroids alone, so each subtree is the same
// whatever thread builds it, and the tree is the same as a one-thread build, bit for bit. Each
// task writes its nodes straight into their final places: a first pass over the centroids alone
// (the same splits, 24 bytes per triangle instead of 112) counts every top subtree's nodes.
constexpr std::size_t kTaskLevels = 6;       // tasks for the nodes of depth < 6 (64 subtrees)
constexpr std::size_t kTaskMinimum = 16384;  // smaller ranges are built by the task that has them

/// Triangle `i` of `mesh` for the build; area 0 marks a triangle left out (zero area).
BuildTriangle make_build_triangle(const Mesh& mesh, std::size_t i) {
  const auto& t = mesh.triangles[i];
  BuildTriangle bt{static_cast<std::uint32_t>(i),
                   {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]},
                   Vec3::Zero(),
                   0};
  if (geometry::is_degenerate_triangle(bt.v[0], bt.v[1], bt.v[2])) return bt;
  // The centroid of a triangle (its static moments over its area) is its vertex mean.
  bt.centroid = (bt.v[0] + bt.v[1] + bt.v[2]) / 3.0;
  bt.area = 0.5 * (bt.v[1] - bt.v[0]).cross(bt.v[2] - bt.v[0]).norm();
  return bt;
}

/// body(begin, end) over [0, n): in oneTBB tasks for a large model, on this thread otherwise
/// (a small model gains nothing from tasks, and stays out of oneTBB's scheduler entirely).
template <class Body>
void for_blocks(std::size_t n, const Body& body) {
  if (n < kTaskMinimum) {
    body(std::size_t{0}, n);
    return;
  }
  parallel::for_ranges(0, n, 4096, body);
}

/// f() and g(), at once in oneTBB tasks when `large`.
template <class F, class G>
void invoke_both(bool large, const F& f, const G& g) {
  if (large) {
    parallel::invoke(f, g);
  } else {
    f();
    g();
  }
}

bool is_task_node(std::size_t size, std::size_t depth, std::size_t leaf_size) {
  return depth < kTaskLevels && size >= kTaskMinimum && size > leaf_size;
}

/// Nodes of the subtree over `items` at `depth`, counted with the build's own splits.
std::size_t count_nodes(std::span<SplitCentroid> items, std::size_t depth, std::size_t leaf_size) {
  if (items.size() <= leaf_size) return 1;
  const std::size_t mid = detail::split_triangles(items, depth);
  return 1 + count_nodes(items.first(mid), depth + 1, leaf_size) +
         count_nodes(items.subspan(mid), depth + 1, leaf_size);
}

/// The node counts of the top levels' subtrees, indexed like a heap (root 0, children 2h+1 and
/// 2h+2), for the nodes the build splits in tasks and their children.
class NodeCounts {
 public:
  NodeCounts(std::span<SplitCentroid> items, std::size_t leaf_size)
      : leaf_size_(leaf_size), counts_((std::size_t{2} << kTaskLevels) - 1, 0) {
    total_ = count(items, 0, 0);
  }
  [[nodiscard]] std::size_t total() const { return total_; }
  [[nodiscard]] std::size_t operator[](std::size_t heap) const { return counts_[heap]; }

 private:
  std::size_t count(std::span<SplitCentroid> items, std::size_t depth, std::size_t heap) {
    std::size_t n = 0;
    if (!is_task_node(items.size(), depth, leaf_size_)) {
      n = count_nodes(items, depth, leaf_size_);
    } else {
      const std::size_t mid = detail::split_triangles(items, depth);
      std::size_t left = 0;
      std::size_t right = 0;
      parallel::invoke([&] { left = count(items.first(mid), depth + 1, 2 * heap + 1); },
                       [&] { right = count(items.subspan(mid), depth + 1, 2 * heap + 2); });
      n = 1 + left + right;
    }
    counts_[heap] = n;
    return n;
  }

  std::size_t leaf_size_;
  std::vector<std::size_t> counts_;
  std::size_t total_ = 0;
};

class Builder {
 public:
  Builder(std::span<BuildTriangle> tris, const BuildOptions& options, const NodeCounts& counts,
          std::vector<BvhNode>& nodes)
      : tris_(tris), options_(options), counts_(counts), nodes_(nodes) {}

  /// Builds the subtree over tris[begin, end) at `depth` (heap position `heap` while in the top
  /// levels) into nodes [index, index + its node count). Returns its height.
  std::size_t build_task(std::size_t begin, std::size_t end, std::size_t depth, std::size_t heap,
                         std::size_t index) const {
    if (!is_task_node(end - begin, depth, options_.leaf_size)) {
      std::size_t cursor = index;
      const std::size_t height = build(begin, end, depth, cursor);
      if (cursor - index != counts_[heap]) {
        throw std::logic_error("hierarchy build: a subtree's node count differs from its count");
      }
      return height;
    }
    BvhNode node = fit_node(begin, end);
    const std::size_t mid = begin + detail::split_triangles(range(begin, end), depth);
    const std::size_t right_index = index + 1 + counts_[2 * heap + 1];
    std::size_t left_height = 0;
    std::size_t right_height = 0;
    parallel::invoke(
        [&] { left_height = build_task(begin, mid, depth + 1, 2 * heap + 1, index + 1); },
        [&] { right_height = build_task(mid, end, depth + 1, 2 * heap + 2, right_index); });
    node.first_or_right = static_cast<std::uint32_t>(right_index);
    nodes_[index] = node;
    return 1 + std::max(left_height, right_height);
  }

 private:
  /// One task's subtree, depth first: the node at `cursor`, then its left subtree, then its
  /// right one; `cursor` ends past the subtree's last node.
  std::size_t build(std::size_t begin, std::size_t end, std::size_t depth,
                    std::size_t& cursor) const {
    const std::size_t index = cursor++;
    BvhNode node = fit_node(begin, end);
    std::size_t height = 1;
    if (end - begin <= options_.leaf_size) {
      node.first_or_right = static_cast<std::uint32_t>(begin);
      node.count = static_cast<std::uint32_t>(end - begin);
    } else {
      const std::size_t mid = begin + detail::split_triangles(range(begin, end), depth);
      const std::size_t left_height = build(begin, mid, depth + 1, cursor);
      node.first_or_right = static_cast<std::uint32_t>(cursor);
      const std::size_t right_height = build(mid, end, depth + 1, cursor);
      height += std::max(left_height, right_height);
    }
    nodes_[index] = node;
    return height;
  }

  std::span<BuildTriangle> range(std::size_t begin, std::size_t end) const {
    return tris_.subspan(begin, end - begin);
  }

  BvhNode fit_node(std::size_t begin, std::size_t end) const {
    const std::span<const BuildTriangle> tris = range(begin, end);
    const Obb box = geometry::detail::fit_obb(
        tris, detail::storable_axes(geometry::detail::fit_obb_axes(tris, options_.covariance)));
    // Sphere about the box centre through the farthest vertex: never larger than the box's
    // circumscribed sphere, and a cheap first reject in the traversal.
    Scalar r2 = 0;
    for (const BuildTriangle& t : tris) {
      for (const Vec3& v : t.v) r2 = std::max(r2, (v - box.center).squaredNorm());
    }
    BvhNode node;
    detail::store_volumes(node, box, std::sqrt(r2));
    return node;
  }

  std::span<BuildTriangle> tris_;
  const BuildOptions& options_;
  const NodeCounts& counts_;
  std::vector<BvhNode>& nodes_;
};

}  // namespace

Model::Model(Mesh mesh, const BuildOptions& options, std::string source)
    : mesh_(std::move(mesh)),
      source_(std::move(source)),
      options_(options),
      cache_(std::make_shared<detail::ModelCache>()) {
  const auto start = std::chrono::steady_clock::now();
  detail::require_at_least(source_, "options.leaf_size", options_.leaf_size, 1);
  validate_mesh(mesh_, source_);

  // Every triangle with its corners, centroid and area; zero-area ones are left out of the tree.
  // The large arrays below are filled by parallel loops (each element on its own, so the result
  // does not depend on the threads) and allocated without being written first, so that their
  // first-write page faults, a large part of a multi-million-triangle build, are shared too.
  const std::size_t n = mesh_.triangles.size();
  std::unique_ptr<BuildTriangle[]> tris_storage(new BuildTriangle[n]);
  std::size_t kept = n;
  std::atomic<bool> some_zero_area{false};
  invoke_both(
      n >= kTaskMinimum,
      // Independent of the tree: decided while the triangles are prepared.
      [&] { closed_ = antcd::is_closed(mesh_); },
      [&] {
        detail::advise_huge_pages(tris_storage.get(), n);
        for_blocks(n, [&](std::size_t begin, std::size_t end) {
          bool zero = false;
          for (std::size_t i = begin; i < end; ++i) {
            tris_storage[i] = make_build_triangle(mesh_, i);
            zero = zero || tris_storage[i].area == 0;
          }
          if (zero) some_zero_area.store(true, std::memory_order_relaxed);
        });
        if (!some_zero_area.load()) return;
        // Left-packing of the triangles with an area, in mesh order.
        kept = 0;
        for (std::size_t i = 0; i < n; ++i) {
          if (tris_storage[i].area == 0) continue;
          if (kept != i) tris_storage[kept] = tris_storage[i];
          ++kept;
        }
      });
  stats_.degenerate_triangles = n - kept;
  if (kept == 0) {
    throw MeshError(source_, "has no triangle of non-zero area");
  }
  const std::span<BuildTriangle> tris(tris_storage.get(), kept);

  {
    std::unique_ptr<SplitCentroid[]> centroids(new SplitCentroid[kept]);
    detail::advise_huge_pages(centroids.get(), kept);
    for_blocks(kept, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) centroids[i].centroid = tris[i].centroid;
    });
    const NodeCounts counts(std::span<SplitCentroid>(centroids.get(), kept), options_.leaf_size);
    centroids.reset();
    nodes_.reserve(counts.total());
    detail::advise_huge_pages(nodes_.data(), nodes_.capacity());
    nodes_.resize(counts.total());
    const Builder builder(tris, options_, counts, nodes_);
    stats_.depth = builder.build_task(0, kept, 0, 0, 0);
  }
  // The traversals' stacks are sized for this bound (antcd/bvh.hpp, split.hpp).
  if (stats_.depth > kMaxTreeLevels) {
    throw std::logic_error("Model: the build made a tree of " + std::to_string(stats_.depth) +
                           " levels, more than kMaxTreeLevels");
  }

  // The leaf order; the triangles' corners are read through the mesh (LeafCorners).
  leaf_triangles_.resize(kept);
  for (std::size_t i = 0; i < kept; ++i) leaf_triangles_[i] = tris[i].index;
  tris_storage.reset();

  count_stats();
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void Model::count_stats() {
  stats_.triangles = mesh_.triangles.size();
  stats_.nodes = nodes_.size();
  stats_.leaves = 0;
  stats_.max_leaf_size = 0;
  stats_.obb_volume_sum = 0;
  for (const BvhNode& node : nodes_) {
    stats_.obb_volume_sum += node.obb().volume();
    if (node.is_leaf()) {
      ++stats_.leaves;
      stats_.max_leaf_size = std::max<std::size_t>(stats_.max_leaf_size, node.count);
    }
  }
  stats_.memory_bytes = mesh_.vertices.capacity() * sizeof(Vec3) +
                        mesh_.triangles.capacity() * sizeof(TriangleIndices) +
                        nodes_.capacity() * sizeof(BvhNode) +
                        leaf_triangles_.capacity() * sizeof(std::uint32_t);
}

}  // namespace antcd
