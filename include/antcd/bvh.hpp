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

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace antcd {

namespace detail {
struct ModelCache;
struct ModelCacheAccess;
struct ModelFile;
}  // namespace detail

struct BuildOptions {
  /// Largest number of triangles in a leaf (>= 1).
  std::uint32_t leaf_size = 4;
  CovarianceMethod covariance = CovarianceMethod::AreaWeightedCentroid;
};

/// One node of the hierarchy: an oriented box and a sphere about the same centre, both holding
/// every vertex of the node's triangles (model frame). 96 bytes: the centre and two box axes in
/// double; the third axis is axis0 x axis1, computed the same way wherever it is used (the build
/// fits the extents along exactly that vector); half extents and radius in float, rounded up
/// (towards +infinity) from the double fit, so the stored volumes only ever contain the double
/// ones. Read them through obb() and sphere().
struct BvhNode {
  // What the sphere test and the descent read comes first (36 bytes). The array is not aligned
  // to cache lines, so on some nodes these bytes straddle two lines; aligning it was not tried.
  Vec3 center = Vec3::Zero();  ///< centre of the box and of the sphere
  float radius = 0;            ///< sphere radius
  /// Number of triangles of a leaf; 0 for an internal node.
  std::uint32_t count = 0;
  /// Internal node: index of the right child (the left one is this index + 1).
  /// Leaf: index of the first triangle in Model::leaf_triangles().
  std::uint32_t first_or_right = 0;
  std::array<float, 3> half = {0, 0, 0};  ///< box half extents along axis0, axis1, axes()[2]
  Vec3 axis0 = Vec3::UnitX();             ///< first box axis (unit)
  Vec3 axis1 = Vec3::UnitY();             ///< second box axis (unit, orthogonal to axis0)

  [[nodiscard]] bool is_leaf() const { return count != 0; }
  /// The box axes as columns: axis0, axis1, axis0 x axis1 (right-handed).
  [[nodiscard]] Mat3 axes() const {
    Mat3 m;
    m.col(0) = axis0;
    m.col(1) = axis1;
    m.col(2) = axis0.cross(axis1);
    return m;
  }
  [[nodiscard]] Vec3 half_extents() const { return {half[0], half[1], half[2]}; }
  [[nodiscard]] Obb obb() const { return {center, axes(), half_extents()}; }
  [[nodiscard]] Sphere sphere() const { return {center, radius}; }
};
static_assert(sizeof(BvhNode) == 96, "BvhNode layout changed: check traversal cache behaviour");

/// The corners of the triangles in leaf order, read through the model's mesh (the model keeps no
/// copy of them): corner c (0, 1, 2) of leaf triangle k is
/// mesh().vertices[mesh().triangles[leaf_triangles()[k]][c]], model frame. Valid while its Model
/// lives and is not refitted.
class LeafCorners {
 public:
  LeafCorners(const Mesh& mesh, std::span<const std::uint32_t> leaf_triangles)
      : vertices_(mesh.vertices.data()),
        triangles_(mesh.triangles.data()),
        leaf_(leaf_triangles.data()),
        size_(leaf_triangles.size()) {}
  /// Corner c of leaf triangle k (k < size(), c < 3).
  [[nodiscard]] const Vec3& operator()(std::size_t k, int c) const {
    return vertices_[triangles_[leaf_[k]][static_cast<std::size_t>(c)]];
  }
  /// The three corners of leaf triangle k (k < size()).
  [[nodiscard]] std::array<Vec3, 3> triangle(std::size_t k) const {
    const TriangleIndices& t = triangles_[leaf_[k]];
    return {vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]};
  }
  /// Number of triangles.
  [[nodiscard]] std::size_t size() const { return size_; }

 private:
  const Vec3* vertices_;
  const TriangleIndices* triangles_;
  const std::uint32_t* leaf_;
  std::size_t size_;
};

/// The most levels a hierarchy has (a lone root counts 1): the build splits at the mean of the
/// centroids for its first 40 levels (each split leaves at least one triangle per side), then at
/// the median, halving what is left, so fewer than 2^32 triangles take at most 40 + 32 levels
/// below the root. Every traversal's stack is sized for this (a pair traversal holds at most
/// 3 (depth(A) + depth(B)) + 1 pairs: 433 for two trees this deep), and a model file with a deeper
/// tree is refused (docs/model_file.md).
inline constexpr std::size_t kMaxTreeLevels = 73;

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
  /// Corners of leaf_triangles()[k], model frame (read through the mesh).
  [[nodiscard]] LeafCorners leaf_corners() const { return {mesh_, leaf_triangles_}; }
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
  ///
  /// `rebuild_above` > 0 adds the rebuild rule: when refit_growth() exceeds it after the refit,
  /// the hierarchy is rebuilt (rebuild()) and refit returns true (false when it was not, or when
  /// no triangle has an area left to build on: the refitted tree is kept). 0 (the default):
  /// never. A negative or NaN value throws ArgumentError before anything changes.
  bool refit(std::span<const Vec3> new_vertices, double rebuild_above = 0);

  /// How much looser refit() has made the hierarchy since it was last built (or loaded):
  /// L_now / L_built, where L is the sum of the internal nodes' box half extents (x + y + z)
  /// over the leaves' sum. Leaves are refitted to their vertices; internal boxes keep their old
  /// axes and are fitted around their children's boxes, so they loosen as the mesh deforms away
  /// from the shape the tree was built for: L grows. 1 for a built hierarchy. (Extents, not
  /// volumes: flat meshes keep L finite.) Not yet a calibrated predictor of query cost: on the
  /// twisted 100k sheet of bench/self_bench.cpp (built flat, refitted to a twist of 15-360
  /// degrees) it read 1.54-1.69 while the self test on the refitted tree cost 0.93-1.37x that on
  /// a fresh one (one contended run), so no default threshold is set.
  [[nodiscard]] double refit_growth() const;

  /// Builds the hierarchy afresh for the current vertices (same triangles, options and source):
  /// the Model then holds what Model(mesh(), options(), source()) holds. O(n log n). For a
  /// deforming model whose refitted volumes have grown loose, or whose zero-area triangles have
  /// gained an area. Throws MeshError as the constructor does (no triangle of non-zero area left);
  /// on a throw the Model is unchanged. A mutation: not concurrent with queries on this Model.
  void rebuild();

  // ---- Model files (.antcd; the format is docs/model_file.md) ----
  // A model file holds the mesh, the source name, the build options and the built hierarchy,
  // field by field, little-endian, with a format version and a checksum of its payload. Loading
  // validates everything before use (sizes against the file size before any allocation, every
  // index, finite coordinates, the tree's shape) and rebuilds nothing: a loaded Model answers
  // every query bit for bit as the saved one. Point-query and penetration caches are not saved:
  // they are derived again on first use, as on a built Model. stats() is the saved model's
  // (build_ms is the original build's time; memory_bytes is this process's). Thread-safe
  // (save/to_bytes are const; load/from_bytes touch nothing shared).

  /// Writes the model file to `path` atomically (temporary file, then rename). Throws antcd::Error
  /// naming `path` when it cannot be written.
  void save(const std::filesystem::path& path) const;
  /// The model file's bytes (what save() writes).
  [[nodiscard]] std::vector<std::uint8_t> to_bytes() const;
  /// Reads a model file written by save(); the Model's source() is `path`. Throws MeshError naming
  /// `path` for a file that is not a model file, truncated, corrupted (checksum), of another
  /// format version, or inconsistent (an index out of range, a non-finite coordinate, a malformed
  /// tree); antcd::Error when it is missing or unreadable.
  [[nodiscard]] static Model load(const std::filesystem::path& path);
  /// The Model whose to_bytes() are `bytes`; its source() is the saved model's. Errors as load(),
  /// named `name`.
  [[nodiscard]] static Model from_bytes(std::span<const std::uint8_t> bytes,
                                        std::string_view name = "model bytes");

 private:
  friend struct detail::ModelCacheAccess;
  friend struct detail::ModelFile;
  /// An empty model for detail::ModelFile to fill.
  Model();
  /// stats_ from the mesh, the nodes and the leaves (all but depth, degenerate_triangles and
  /// build_ms).
  void count_stats();
  Mesh mesh_;
  std::string source_;
  BuildOptions options_;
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> leaf_triangles_;
  BvhStats stats_;
  bool closed_ = false;
  /// L of refit_growth() for the hierarchy as built or loaded (0 until first needed).
  double built_looseness_ = 0;
  [[nodiscard]] double looseness() const;
  /// Data derived on first use by point queries (antcd/points.hpp), built once under a once-flag
  /// so that concurrent const queries stay safe.
  std::shared_ptr<detail::ModelCache> cache_;
};

/// True when `path` names a model file by its extension: ".antcd" (any letter case). The
/// loaders (antcd::load_mesh, the CLI, the scene files, Python) read such paths with Model::load.
ANTCD_API bool is_model_path(const std::filesystem::path& path);

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
