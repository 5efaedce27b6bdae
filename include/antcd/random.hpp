// antcd/random.hpp — random (stochastic) collision detection: the paper's sections 3–4.
//
// The exact query (collide.hpp) tests triangles. The random query works on FEATURES instead: the
// centroids of triangles sampled from the leaves that the Sphere-OBB traversal reports as
// overlapping. A feature space is the 2-D grid of feature pairs (i, j), i indexing A's sampled
// features and j B's; its fitness is the centroid distance f(i, j) (Eq. 6). A feature pair
// COLLIDES when f(i, j) <= delta (Eq. 5). A search (ant colony, improved ant colony, particle
// swarm, genetic algorithm or exhaustive enumeration) looks for colliding feature pairs.
//
// Conventions
// - Frames: a FeatureSpace holds its centroids in the WORLD frame (pose applied). Distances are
//   Euclidean, in mesh units.
// - delta here is a CENTROID distance threshold. It is not collide()'s delta (an exact
//   triangle-to-triangle distance): two triangles that cross each other can have centroids far
//   apart, and two triangles whose centroids are within delta need not touch. default_delta()
//   derives a threshold from the triangles' sizes (see there). The random query is approximate by
//   design; collide() is the exact one.
// - Feature order: each side's features are ordered so that neighbouring indices are neighbours in
//   space (the hierarchy's leaf order, or a Morton curve), so the grid is a landscape a local
//   search can walk, not noise.
// - Determinism: every random choice (sampling, search) comes from a std::mt19937_64 seeded from
//   the seed passed in. Same inputs and seed => same result, bit for bit, on any thread.
//   The only exception is StopCriteria::max_seconds, which makes the stopping point depend on the
//   clock.
// - Thread safety: no global state. Every function is reentrant; FeatureSpace and Model are only
//   read, so any number of threads may search the same space at once.
// - Memory: search() allocates its working set once (pheromone on at most 64 x 64 blocks, paths,
//   swarm or population); after that only the hit list and the distinct-hit set grow, with the
//   number of hits. Nothing is proportional to the number of feature pairs.
// - Errors: invalid arguments throw antcd::ArgumentError naming the parameter.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/method.hpp>

#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace antcd {

// ---- Feature space (sections 3.1–3.2) ----

/// How each side's sampled features are ordered along their index.
enum class FeatureOrder {
  /// The hierarchy's leaf order (depth-first), which keeps spatially close triangles together.
  Leaf,
  /// A 30-bit Morton (Z-order) curve over the side's centroid bounding box.
  Morton,
};

struct SamplingOptions {
  /// Features sampled on each side (>= 1). When a side has fewer candidate triangles, all of them
  /// are taken. The paper runs 1000 to 5000 per side.
  std::uint32_t samples_per_side = 1000;
  /// Centroid threshold the space is built for (also the preliminary detection's culling margin).
  /// Negative: default_delta(a, b). Every feature pair with centroid distance <= delta lies in
  /// a leaf pair the traversal reports, so culling with it loses no colliding pair.
  Scalar delta = -1;
  FeatureOrder order = FeatureOrder::Leaf;
};

/// One side of a feature space: centroids (world frame, structure of arrays) and, for each, the
/// index of its triangle in the mesh.
struct FeatureSide {
  std::vector<Scalar> x, y, z;
  std::vector<std::uint32_t> triangle;

  [[nodiscard]] std::uint32_t size() const { return static_cast<std::uint32_t>(triangle.size()); }
  [[nodiscard]] Vec3 centroid(std::uint32_t i) const { return {x[i], y[i], z[i]}; }
};

/// The discrete 2-D search space of one model pair at one pose pair. Immutable once built.
struct ANTCD_API FeatureSpace {
  FeatureSide a;  ///< features of model A, index i
  FeatureSide b;  ///< features of model B, index j
  /// The centroid threshold the space was built for (SamplingOptions::delta, resolved).
  Scalar delta = 0;
  /// Leaf pairs reported by the preliminary detection.
  std::size_t leaf_pairs = 0;
  /// Candidate triangles per side (in the reported leaves) before sampling.
  std::size_t candidates_a = 0;
  std::size_t candidates_b = 0;

  [[nodiscard]] std::uint64_t cells() const { return std::uint64_t{a.size()} * b.size(); }
  [[nodiscard]] bool empty() const { return a.size() == 0 || b.size() == 0; }
  /// Fitness f(i, j) of Eq. 6: distance between the two centroids.
  [[nodiscard]] Scalar distance(std::uint32_t i, std::uint32_t j) const;
};

/// Median over A's non-degenerate triangles of the largest centroid-to-vertex distance ("feature
/// radius"), model frame (poses do not change it). O(n) in the triangles.
ANTCD_API Scalar feature_radius(const Model& model);

/// Default centroid threshold: feature_radius(a) + feature_radius(b). Any point of a triangle lies
/// within its radius of its centroid, so two touching triangles of at most median size always have
/// centroids within this distance: for typical triangles the threshold misses no touching pair
/// (it does admit near misses; random detection is approximate). Always > 0.
ANTCD_API Scalar default_delta(const Model& a, const Model& b);
/// default_delta from radii already computed with feature_radius (a scene caches them per model).
ANTCD_API Scalar default_delta(Scalar radius_a, Scalar radius_b);

/// Preliminary detection then sampling: runs overlapping_leaves(a, pose_a, b, pose_b, delta), takes
/// the triangles of the reported leaves of each side in leaf order, samples
/// options.samples_per_side of them per side (stratified: one uniformly random triangle from each
/// of that many equal runs of the leaf order, so the sample covers every region), computes their
/// centroids in the world frame and orders them (options.order). `seed` drives the sampling only.
/// Separated models (no leaf pair) give an empty space. Throws antcd::ArgumentError if
/// samples_per_side is 0 or delta is NaN.
ANTCD_API FeatureSpace build_feature_space(const Model& a, const Transform& pose_a, const Model& b,
                                           const Transform& pose_b,
                                           const SamplingOptions& options = {},
                                           std::uint64_t seed = 0);

// ---- Searches (sections 3.3–4) ----

/// The four improvements of section 3.4; each can be switched off alone (ablation). Used only by
/// Method::Maco (Aco runs with all four off).
struct MacoSwitches {
  bool adaptive_exponents = true;    ///< (1) alpha' = alpha Nc/n, beta' = beta Nc/n (Eqs. 9–10)
  bool adaptive_evaporation = true;  ///< (2) rho = N / (Nc + N) (Eq. 11)
  bool path_heuristic = true;        ///< (3) eta = 1 / (d_oj + d_ij + d_js) (Eq. 12)
  bool reward_punishment = true;  ///< (4) reward/punish against the best evaluation (Eqs. 13–15)
};

/// Ant colony parameters (both Aco and Maco). See docs/random-detection.md for what a city, a path
/// and L_k are on the feature grid.
struct AntParams {
  std::uint32_t ants = 60;  ///< m
  double alpha = 1;         ///< pheromone exponent (base value for Eq. 9)
  double beta = 1;          ///< heuristic exponent (base value for Eq. 10)
  double rho = 0.5;         ///< fixed evaporation of Eq. 8 (Aco, or Maco without switch 2)
  double q = 1;        ///< deposit constant Q: an ant deposits Q / L_k on each cell of its path
  double tau0 = 1;     ///< initial pheromone c
  double n = 50;       ///< the constant n of Eqs. 9–10
  double theta = 0.5;  ///< reward factor of Eq. 15
  double mu = -0.5;    ///< punishment factor of Eq. 15
  std::uint32_t steps = 16;  ///< moves per ant per iteration (path length minus one)
  /// Pheromone lives on a coarse grid of at most this many blocks per side (>= 1); a block is
  /// ceil(size / resolution) features wide. 64 gives 4096 cells (32 KiB) whatever the space size.
  std::uint32_t pheromone_resolution = 64;
  MacoSwitches maco;
};

struct PsoParams {
  std::uint32_t particles = 60;
  double inertia = 0.7298;           ///< w
  double cognitive = 1.49618;        ///< c1
  double social = 1.49618;           ///< c2
  double max_velocity = 0.1;         ///< per axis, as a fraction of the side's size
  std::uint32_t stall_restart = 10;  ///< reseed a particle whose own best has not improved for
                                     ///< this many iterations (0 = never)
};

struct GaParams {
  std::uint32_t population = 60;  ///< >= 2
  double crossover = 0.9;         ///< probability of one-point crossover per couple
  double mutation = -1;           ///< per-bit flip probability; negative: 1 / chromosome bits
  std::uint32_t tournament = 2;   ///< tournament size (>= 1)
  std::uint32_t elites = 2;       ///< best individuals copied unchanged (capped at population - 1)
};

/// When a search stops: at the first criterion met, else after (restarts + 1) x N iterations
/// (Exhaustive: after the last row).
struct StopCriteria {
  bool first_hit = false;  ///< stop at the first colliding feature pair
  /// Stop once this share (0, 1] of the space's truly colliding pairs is found. The truth is
  /// reference_count when non-zero; otherwise it is counted by enumerating the space before the
  /// search starts (that enumeration is not in the result's evaluations). 0 = off.
  double target_share = 0;
  std::uint64_t reference_count = 0;
  std::uint64_t max_evaluations = 0;  ///< fitness evaluations (0 = no limit)
  double max_seconds = 0;             ///< wall time (0 = no limit; breaks determinism)
};

struct SearchRequest {
  Method method = Method::Maco;
  /// Centroid threshold. Negative: the space's delta. NaN is rejected. A value above the space's
  /// delta may find pairs outside the culled leaves missing from the space.
  Scalar delta = -1;
  /// N: iterations (generations) of one run; also the N of Eq. 11. Exhaustive ignores it.
  std::uint32_t iterations = 100;
  /// Independent runs started after the first one when it ends its N iterations without meeting
  /// another stop criterion: fresh pheromone / swarm / population, the random stream continues,
  /// hits and best accumulate. Use with max_evaluations or max_seconds to search "until a budget"
  /// without stretching N (which would change Eqs. 9–11). Exhaustive ignores it.
  std::uint32_t restarts = 0;
  /// Progress marks, for experiments: shares in (0, 1] of the space's colliding pairs (the truth
  /// as for StopCriteria::target_share). SearchResult::progress tells when each was reached.
  std::vector<double> progress_marks;
  AntParams ant;
  PsoParams pso;
  GaParams ga;
  StopCriteria stop;
  std::uint64_t seed = 0;
};

/// A colliding feature pair: grid cell (i, j), the mesh triangles, the centroid distance.
struct FeaturePair {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  std::uint32_t triangle_a = 0;
  std::uint32_t triangle_b = 0;
  Scalar distance = 0;
};

/// When a search had found a given share of the space's colliding pairs.
struct ProgressMark {
  double share = 0;        ///< as requested
  std::uint64_t hits = 0;  ///< ceil(share x truth): the distinct pairs needed
  bool reached = false;
  std::uint64_t evaluations = 0;  ///< evaluations done when reached
  double seconds = 0;             ///< wall time since the search began when reached
};

enum class StopReason {
  EmptySpace,   ///< nothing to search
  FirstHit,     ///< StopCriteria::first_hit
  Target,       ///< StopCriteria::target_share reached
  Iterations,   ///< N iterations ran (or Exhaustive enumerated every pair)
  Evaluations,  ///< StopCriteria::max_evaluations
  Time,         ///< StopCriteria::max_seconds
};

struct SearchResult {
  bool found = false;
  /// Every distinct colliding feature pair evaluated, in the order found.
  std::vector<FeaturePair> hits;
  /// Smallest centroid distance evaluated (+inf if nothing was evaluated) and its cell.
  Scalar best_distance = std::numeric_limits<Scalar>::infinity();
  FeaturePair best;
  std::uint64_t evaluations = 0;  ///< fitness evaluations, repeats included
  std::uint32_t iterations = 0;   ///< iterations begun, over all runs (Exhaustive: rows visited)
  std::uint32_t runs = 0;         ///< runs begun (1 + restarts used)
  std::vector<ProgressMark> progress;  ///< one per SearchRequest::progress_marks, same order
  StopReason stop = StopReason::EmptySpace;
  Scalar delta = 0;  ///< the threshold used
};

/// Runs one search over `space`. Throws antcd::ArgumentError on an invalid request.
ANTCD_API SearchResult search(const FeatureSpace& space, const SearchRequest& request);

/// Number of colliding pairs in the space at threshold delta (negative: the space's), by
/// enumeration: the truth against which a detection rate is measured.
ANTCD_API std::uint64_t count_colliding(const FeatureSpace& space, Scalar delta = -1);

/// One call: build_feature_space(a, pose_a, b, pose_b, sampling, request.seed), then search. When
/// request.delta is set (>= 0) the space is built for it, overriding sampling.delta.
ANTCD_API SearchResult random_collide(const Model& a, const Transform& pose_a, const Model& b,
                                      const Transform& pose_b, const SearchRequest& request = {},
                                      const SamplingOptions& sampling = {});

}  // namespace antcd
