// antcd/bvh.hpp — the hybrid Sphere-OBB bounding-volume hierarchy (paper, section 2).
//
// A Model is a mesh plus its hierarchy. Every query is const and a Model may be queried from any
// number of threads at once. The one mutation is refit() (moved vertices, same triangles): it must
// not run while any query reads the same Model (a Model shared through a World or between threads
// is to be refitted only when no query is in flight, or replaced by a fresh one).
//
// Tree layout: nodes in depth-first order in one flat array. Node 0 is the root. For an internal
// node at index i the left child is i + 1 and the right child is `right`. A leaf owns the
// triangles leaf_triangles()[first .. first + count). Bounding volumes are in the model's frame.
#pragma once

#include <antcd/export.hpp>
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace antcd {

namespace detail {
struct ModelCache;
struct ModelCacheAccess;
}  // namespace detail

struct BuildOptions {
  /// Largest number of triangles in a leaf (>= 1).
  std::uint32_t leaf_size = 4;
  CovarianceMethod covariance = CovarianceMethod::AreaWeightedCentroid;
};

struct BvhNode {
  Obb obb;
  Sphere sphere;
  /// Internal node: index of the right child (the left one is this index + 1).
  /// Leaf: index of the first triangle in Model::leaf_triangles().
  std::uint32_t first_or_right = 0;
  /// Number of triangles of a leaf; 0 for an internal node.
  std::uint32_t count = 0;

  [[nodiscard]] bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 160, "BvhNode layout changed: check traversal cache behaviour");

struct BvhStats {
  std::size_t triangles = 0;             ///< triangles in the mesh
  std::size_t degenerate_triangles = 0;  ///< zero-area triangles left out of the tree
  std::size_t nodes = 0;
  std::size_t leaves = 0;
  std::size_t depth = 0;          ///< levels, a lone root counts 1
  std::size_t max_leaf_size = 0;  ///< largest leaf actually built
  double obb_volume_sum = 0;      ///< sum of every node's OBB volume (tightness measure)
  double build_ms = 0;            ///< wall time of the build
  std::size_t memory_bytes = 0;   ///< heap bytes owned by the Model (mesh + tree)
};

class ANTCD_API Model {
 public:
  /// Builds the hierarchy over `mesh`. Throws MeshError (named `source`) if the mesh is invalid
  /// (see validate_mesh) or has no triangle of non-zero area, or antcd::ArgumentError if
  /// options.leaf_size is 0. O(n log n) in the number of triangles.
  explicit Model(Mesh mesh, const BuildOptions& options = {}, std::string source = "mesh");

  [[nodiscard]] const Mesh& mesh() const { return mesh_; }
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] const BuildOptions& options() const { return options_; }
  [[nodiscard]] std::span<const BvhNode> nodes() const { return nodes_; }
  [[nodiscard]] const BvhNode& root() const { return nodes_.front(); }
  /// Mesh triangle indices in leaf order (degenerate triangles absent).
  [[nodiscard]] std::span<const std::uint32_t> leaf_triangles() const { return leaf_triangles_; }
  /// Vertex positions of leaf_triangles()[k], packed: 3 per triangle, model frame.
  [[nodiscard]] std::span<const Vec3> leaf_vertices() const { return leaf_vertices_; }
  [[nodiscard]] const BvhStats& stats() const { return stats_; }
  /// The mesh is closed and consistently oriented (antcd::is_closed, decided at construction):
  /// it bounds a solid, and volume queries (CollisionRequest::volume) apply to it.
  [[nodiscard]] bool is_closed() const { return closed_; }

  /// New positions for the mesh's vertices (same count and order, same triangles: a deforming
  /// mesh), model frame. Keeps the tree's topology and recomputes its volumes bottom-up in O(n):
  /// every box keeps its axes and gets the extents that hold its triangles (a leaf: from its
  /// vertices; an internal node: from its children's boxes, so possibly looser than a fresh fit);
  /// spheres are recomputed likewise. Every query answers afterwards exactly as on a Model built
  /// from the moved mesh (only traversal costs may differ). A mutation: not concurrent with queries
  /// on this Model. Throws ArgumentError (naming the model) for a wrong vertex count, a non-finite
  /// vertex (naming its index), or a triangle of zero area at build time that has an area now (it
  /// is not in the tree: build a new Model). On a throw the Model is unchanged.
  void refit(std::span<const Vec3> new_vertices);

 private:
  friend struct detail::ModelCacheAccess;
  Mesh mesh_;
  std::string source_;
  BuildOptions options_;
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> leaf_triangles_;
  std::vector<Vec3> leaf_vertices_;
  BvhStats stats_;
  bool closed_ = false;
  /// Data derived on first use by point queries (antcd/points.hpp), built once under a once-flag
  /// so that concurrent const queries stay safe.
  std::shared_ptr<detail::ModelCache> cache_;
};

/// Counters of one traversal, for tests and tuning.
struct TraversalStats {
  std::uint64_t node_pairs = 0;      ///< node pairs visited
  std::uint64_t sphere_rejects = 0;  ///< pairs culled by the sphere test
  std::uint64_t obb_rejects = 0;     ///< pairs culled by the OBB test (after passing spheres)
  std::uint64_t leaf_pairs = 0;      ///< leaf pairs whose volumes overlap
  /// Pairs culled because no triangle of a large leaf meets the other (smaller) node's box, each
  /// triangle tested alone (exact queries only; see collide.hpp).
  std::uint64_t triangle_rejects = 0;
};

/// A pair of leaves (node indices) whose bounding volumes overlap.
struct LeafPair {
  std::uint32_t node_a = 0;
  std::uint32_t node_b = 0;
};

/// Preliminary detection (paper, section 4 step 1): depth-first dual traversal of both trees, with
/// the sphere test first and the 15-axis OBB test second, both grown by `delta` >= 0. Appends to
/// `out` every leaf pair whose volumes are within delta; `out` is not cleared. Thread-safe.
ANTCD_API TraversalStats overlapping_leaves(const Model& a, const Transform& pose_a, const Model& b,
                                            const Transform& pose_b, Scalar delta,
                                            std::vector<LeafPair>& out);

/// The paper's Sphere-OBB baseline verdict: true when some pair of leaves has overlapping sphere
/// and OBB (grown by delta). Stops at the first such pair. Thread-safe.
ANTCD_API bool any_leaf_pair_overlaps(const Model& a, const Transform& pose_a, const Model& b,
                                      const Transform& pose_b, Scalar delta);

}  // namespace antcd
