// antcd/random_features.hpp — the feature space of the random detection (the paper's sections
// 3.1–3.2): features sampled from the leaves the preliminary detection keeps, the grid of feature
// pairs and its fitness, and what counts as a colliding feature pair. The flow and the conventions
// (frames, determinism, thread safety, errors) are random.hpp's. Part of antcd::random.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/random_export.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace antcd {

// ---- Feature space (sections 3.1–3.2) ----

/// What counts as a colliding feature pair (see the top of this file).
enum class Verdict {
  Witness,        ///< the exact triangle test at delta confirms the pair (default)
  PaperCentroid,  ///< the paper literally: centroid distance <= the centroid threshold
};

/// "witness" or "paper-centroid".
ANTCD_RANDOM_API std::string_view to_string(Verdict verdict);
/// The inverse of to_string; throws ArgumentError naming the text and the accepted names.
ANTCD_RANDOM_API Verdict parse_verdict(std::string_view text);

/// How each side's sampled features are ordered along their index.
enum class FeatureOrder {
  /// The hierarchy's leaf order (depth-first), which keeps spatially close triangles together.
  Leaf,
  /// A 30-bit Morton (Z-order) curve over the side's centroid bounding box.
  Morton,
};

struct SamplingOptions {
  /// Features sampled on each side (>= 1). When a side has fewer candidate triangles, all of them
  /// are taken.
  std::uint32_t samples_per_side = 1000;
  /// The collision threshold delta of collide() (>= 0, mesh units): the preliminary detection
  /// runs with it, and Verdict::Witness confirms pairs with it.
  Scalar delta = 0;
  /// The centroid threshold delta_c of Verdict::PaperCentroid (finite, > 0: it is also the
  /// colony's length unit). Unset: default_delta(a, b). It does not widen the preliminary
  /// detection.
  std::optional<Scalar> centroid_delta = std::nullopt;
  FeatureOrder order = FeatureOrder::Leaf;
  /// Stop the preliminary detection after this many leaf pairs (0 = all). The traversal then
  /// visits the nearer children first, so the space holds the leaf pairs met first; a search that
  /// finds nothing there must rebuild the space with every leaf pair (FeatureSpace::complete).
  std::uint32_t max_leaf_pairs = 0;
  /// Leave out leaf pairs that the exact query's traversal culls triangle by triangle (collide.hpp,
  /// TraversalStats::triangle_rejects): a leaf of 2 to 32 triangles whose sphere is more than
  /// twice the other node's, none of whose triangles meets that node's box grown by delta. Such a
  /// pair holds no triangle pair within delta, so no collision is lost, but it is a test beyond
  /// the paper's sphere and OBB: `antcd bench paper` turns it off, so that Table 1 and Figures 4-5
  /// sample the paper's leaf pairs. On real meshes of very different sizes (a large spider's
  /// leaves around a small model) it removes most of the spaces of pairs that do not touch.
  bool triangle_masks = true;
};

/// One side of a feature space: centroids (world frame, float structure of arrays), the
/// triangles' circumradii about them, their world vertices, and where each came from.
struct FeatureSide {
  std::vector<float> x, y, z;
  /// Largest centroid-to-vertex distance, rounded up to cover the float centroids' rounding.
  std::vector<float> radius;
  /// Vertices, 3 per feature, in model A's frame (the frame collide() tests in; B's are mapped
  /// into it), for the witness test.
  std::vector<Vec3> vertices;
  /// Mesh triangle index of each feature.
  std::vector<std::uint32_t> triangle;
  /// Index of each feature's triangle in Model::leaf_triangles(): pose-independent, so pheromone
  /// kept on it stays meaningful from frame to frame.
  std::vector<std::uint32_t> position;
  /// Triangles in the model's hierarchy (the range of `position`).
  std::uint32_t model_triangles = 0;
  /// Features of each reported leaf of this side (local leaf k: leaf_features[leaf_start[k] ..
  /// leaf_start[k + 1])); a leaf whose triangles were all left out by sampling is empty.
  std::vector<std::uint32_t> leaf_start;
  std::vector<std::uint32_t> leaf_features;

  [[nodiscard]] std::uint32_t size() const { return static_cast<std::uint32_t>(triangle.size()); }
  [[nodiscard]] Vec3 centroid(std::uint32_t i) const { return {x[i], y[i], z[i]}; }
};

/// The discrete 2-D search space of one model pair at one pose pair. Immutable once built.
struct ANTCD_RANDOM_API FeatureSpace {
  FeatureSide a;  ///< features of model A, index i
  FeatureSide b;  ///< features of model B, index j
  /// collide()'s delta the space was built for (culling and witness test).
  Scalar delta = 0;
  /// Centroid threshold of Verdict::PaperCentroid (SamplingOptions::centroid_delta, resolved);
  /// also the length unit of the colony's path lengths. Always > 0.
  Scalar centroid_delta = 0;
  /// Leaf pairs reported by the preliminary detection.
  std::size_t leaf_pairs = 0;
  /// Whether the preliminary detection ran to the end (false: SamplingOptions::max_leaf_pairs cut
  /// it, and other leaf pairs may exist).
  bool complete = true;
  /// The reported leaf pairs as local leaf indices into a.leaf_start / b.leaf_start (the cells
  /// where the colony places its ants, section 4 step 3).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> overlaps;
  /// Candidate triangles per side (in the reported leaves) before sampling.
  std::size_t candidates_a = 0;
  std::size_t candidates_b = 0;

  [[nodiscard]] std::uint64_t cells() const { return std::uint64_t{a.size()} * b.size(); }
  /// Cells (i, j) whose features lie in an overlapping leaf pair (`overlaps`): the only ones that
  /// can hold a triangle pair within delta. At most cells().
  [[nodiscard]] std::uint64_t leaf_pair_cells() const;
  [[nodiscard]] bool empty() const { return a.size() == 0 || b.size() == 0; }
  /// Fitness f(i, j) of Eq. 6: distance between the two centroids (float arithmetic).
  [[nodiscard]] float distance(std::uint32_t i, std::uint32_t j) const;
  /// Whether cell (i, j) collides under `verdict` (centroid threshold `centroid_delta`, unset:
  /// the space's). The witness test is exact (collide()'s triangle test at delta).
  [[nodiscard]] bool collides(std::uint32_t i, std::uint32_t j, Verdict verdict,
                              std::optional<Scalar> centroid_delta = std::nullopt) const;
};

/// Median over A's non-degenerate triangles of the largest centroid-to-vertex distance ("feature
/// radius"), model frame (poses do not change it). O(n) in the triangles.
ANTCD_RANDOM_API Scalar feature_radius(const Model& model);

/// Default centroid threshold of Verdict::PaperCentroid: feature_radius(a) + feature_radius(b).
/// Two touching triangles of at most median size have centroids within it. Always > 0.
ANTCD_RANDOM_API Scalar default_delta(const Model& a, const Model& b);
/// default_delta from radii already computed with feature_radius (a scene caches them per model).
ANTCD_RANDOM_API Scalar default_delta(Scalar radius_a, Scalar radius_b);

/// Preliminary detection then sampling: runs overlapping_leaves(a, pose_a, b, pose_b,
/// options.delta), takes the triangles of the reported leaves of each side in leaf order, samples
/// options.samples_per_side of them per side (stratified: one uniformly random triangle from each
/// of that many equal runs of the leaf order), computes centroids, radii and vertices in the world
/// frame and orders them (options.order). `seed` drives the sampling only. Models with no leaf
/// pair give an empty space. Throws antcd::ArgumentError if samples_per_side is 0, delta is
/// negative or not finite, or a set centroid_delta is not finite and > 0.
ANTCD_RANDOM_API FeatureSpace build_feature_space(const Model& a, const Transform& pose_a,
                                                  const Model& b, const Transform& pose_b,
                                                  const SamplingOptions& options = {},
                                                  std::uint64_t seed = 0);

}  // namespace antcd
