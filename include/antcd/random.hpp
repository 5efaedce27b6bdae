// antcd/random.hpp — random (stochastic) collision detection: the paper's sections 3–4.
//
// Flow (the paper's section 4, Figure 2):
//  1. Preliminary detection: the Sphere-OBB dual traversal at the collision threshold delta (the
//     same delta as collide()) reports the leaf pairs whose volumes are within delta. None: the
//     models are separate, with no search at all.
//  2. Feature sampling: the triangles of those leaves, per side, give FEATURES (their centroids,
//     section 3.2). A feature space is the 2-D grid of feature pairs (i, j), i indexing A's
//     features and j B's; its fitness is the centroid distance f(i, j) (Eq. 6).
//  3. Search: an ant colony (or a baseline) walks the grid looking for colliding feature pairs.
//
// What a colliding feature pair is (Verdict):
// - Verdict::Witness (default): the exact triangle test at delta (collide()'s definition)
//   confirms the two triangles. The centroid distance only orders the search and decides which
//   pairs are worth that test: two triangles can be within delta only if
//   f(i, j) <= r_i + r_j + delta, with r the triangle's circumradius about its centroid. Every
//   reported pair is a real contact (precision 1 by construction); misses are the only
//   approximation.
// - Verdict::PaperCentroid: the paper literally (Eq. 5 on Eq. 6): a centroid pair within the
//   centroid threshold delta_c. A proximity test, not contact: near misses count.
//
// Conventions
// - Frames: a FeatureSpace holds its centroids and triangles in the WORLD frame (pose applied).
//   Centroids are floats (structure of arrays); the witness test runs on doubles.
// - Feature order: each side's features follow the hierarchy's leaf order (or a Morton curve), so
//   neighbouring indices are neighbours in space and the grid is a landscape a local search can
//   walk.
// - Determinism: every random choice comes from a small xoshiro256** stream seeded from the seed
//   passed in. Same inputs, seed and memory => same result, bit for bit, on any thread.
//   StopCriteria::max_seconds is the only criterion that depends on the clock.
// - Memory across frames: a ColonyMemory (optional) carries one model pair's pheromone, its
//   iteration count N_c and the last witnesses from one search to the next (temporal coherence).
//   A memory must not be used by two searches at once.
// - Thread safety: no global state. FeatureSpace and Model are only read, so any number of threads
//   may search the same space at once (each with its own memory, or none).
// - Errors: invalid arguments throw antcd::ArgumentError naming the parameter.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/method.hpp>

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
ANTCD_API std::string_view to_string(Verdict verdict);
/// The inverse of to_string; throws ArgumentError naming the text and the accepted names.
ANTCD_API Verdict parse_verdict(std::string_view text);

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
struct ANTCD_API FeatureSpace {
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
ANTCD_API Scalar feature_radius(const Model& model);

/// Default centroid threshold of Verdict::PaperCentroid: feature_radius(a) + feature_radius(b).
/// Two touching triangles of at most median size have centroids within it. Always > 0.
ANTCD_API Scalar default_delta(const Model& a, const Model& b);
/// default_delta from radii already computed with feature_radius (a scene caches them per model).
ANTCD_API Scalar default_delta(Scalar radius_a, Scalar radius_b);

/// Preliminary detection then sampling: runs overlapping_leaves(a, pose_a, b, pose_b,
/// options.delta), takes the triangles of the reported leaves of each side in leaf order, samples
/// options.samples_per_side of them per side (stratified: one uniformly random triangle from each
/// of that many equal runs of the leaf order), computes centroids, radii and vertices in the world
/// frame and orders them (options.order). `seed` drives the sampling only. Models with no leaf
/// pair give an empty space. Throws antcd::ArgumentError if samples_per_side is 0, delta is
/// negative or not finite, or a set centroid_delta is not finite and > 0.
ANTCD_API FeatureSpace build_feature_space(const Model& a, const Transform& pose_a, const Model& b,
                                 const Transform& pose_b, const SamplingOptions& options = {},
                                 std::uint64_t seed = 0);

// ---- Searches (sections 3.3–4) ----


/// Readings of Eq. 12, eta = 1 / (d_oj + d_ij + d_js) (docs/random-detection.md argues them).
enum class PathHeuristic {
  /// Default. d_oj = the length of the ant's path so far, d_ij = the step from the current cell
  /// to j, d_js = the distance still missing to a collision, max(0, f(j) - reach(j)) (reach =
  /// r_i + r_j + delta for Witness, delta_c for PaperCentroid): the fitness stays the signal.
  Remaining,
  /// The first reading: d_ij = f(j), d_oj = cell distance from the tour's start, d_js = cell
  /// distance to the best cell so far (kept for the ablation).
  Corridor,
};

/// The four improvements of section 3.4; each can be switched off alone (ablation). Used only by
/// Method::Maco (Aco runs with all four off).
struct MacoSwitches {
  bool adaptive_exponents = true;    ///< (1) alpha' = alpha Nc/n, beta' = beta Nc/n (Eqs. 9–10)
  bool adaptive_evaporation = true;  ///< (2) rho = N / (Nc + N) (Eq. 11)
  bool path_heuristic = true;        ///< (3) eta = 1 / (d_oj + d_ij + d_js) (Eq. 12)
  bool reward_punishment = true;  ///< (4) reward/punish against the best evaluation (Eqs. 13–15)
  /// Reading of Eq. 12 when path_heuristic is on.
  PathHeuristic heuristic = PathHeuristic::Remaining;
  /// Section 3.4 (1), "select the route with the highest probability": move to the candidate of
  /// largest tau^alpha' eta^beta' instead of drawing by roulette (Eq. 7). Off by default (a
  /// greedy ant re-walks the same cells; see docs/random-detection.md); an option for the study.
  bool greedy_moves = false;
};

/// Where the ants start each tour.
enum class AntStart {
  /// Default: a uniformly random cell of a uniformly random reported leaf pair (section 4:
  /// "the primitive patches between the collision nodes" are where to look).
  LeafPairs,
  /// A uniformly random cell of the whole grid (the classic colony's random cities).
  Uniform,
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
  /// Pheromone lives on a coarse grid of at most this many blocks per side (>= 1) over each
  /// model's leaf order (FeatureSide::position), so it survives pose changes. 64 gives 4096 cells.
  std::uint32_t pheromone_resolution = 64;
  AntStart start = AntStart::LeafPairs;
  MacoSwitches maco;
  /// A colony never evaluates more candidates than there are cells that can collide: when a
  /// first-hit search (StopCriteria::first_hit, no target share or progress marks) has an
  /// evaluation limit above FeatureSpace::leaf_pair_cells() (plus the memory's witnesses), those
  /// cells are scanned instead, leaf pair by leaf pair (SearchResult::scanned). Every triangle
  /// pair within delta lies in an overlapping leaf pair, so the scan tests once each cell the
  /// colony could usefully visit, and it is complete. The memory's witnesses are tested first and
  /// kept as for a colony; the pheromone is left as it was. false: the colony always runs (the
  /// paper's method; ablations and reproduction).
  bool scan_covered_spaces = true;
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
/// (Exhaustive and Grid: after the last row).
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

/// A colliding feature pair: grid cell (i, j), the mesh triangles, the centroid distance.
struct FeaturePair {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  std::uint32_t triangle_a = 0;
  std::uint32_t triangle_b = 0;
  Scalar distance = 0;
};

/// What an ant colony carries from one search of a model pair to the next (temporal coherence,
/// section 3.1: "the position of the optimal solution ... [is] constantly changing"): the
/// pheromone (on blocks of the models' leaf order, so it means the same regions at every pose),
/// the iteration count N_c of Eqs. 9–11 (so a later search does not fall back to the random walks
/// of N_c = 1; Eq. 11's rho then acts as the forgetting rate), and the last search's witnesses
/// (mesh triangle pairs), which the next search tests first. Empty = a fresh colony.
struct ColonyMemory {
  std::uint32_t grid_a = 0;  ///< pheromone blocks per side (0 = not initialised)
  std::uint32_t grid_b = 0;
  std::vector<float> log_tau;          ///< log2 of the pheromone, grid_a x grid_b
  std::uint64_t iterations = 0;        ///< N_c: iterations run so far
  double best_evaluation = 0;          ///< Eq. 13's bt (0 = none yet)
  /// Witnesses as positions in the two models' leaf order (Model::leaf_triangles() indices,
  /// pose-independent, like FeatureSide::position), most recent first.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> witnesses;
  /// The last query of this pair (a scene frame) ended without a witness while its leaves
  /// overlapped (undecided, or proven separate by a complete scan: a near miss). Its contact, if one appears, is new, so the next query traverses the
  /// whole hierarchy at once instead of trying the nearest leaf pairs first.
  bool undecided = false;
  /// Largest number of witnesses kept.
  static constexpr std::size_t kMaxWitnesses = 64;

  void clear() { *this = ColonyMemory{}; }
};

struct SearchRequest {
  Method method = Method::Maco;
  Verdict verdict = Verdict::Witness;
  /// Centroid threshold of Verdict::PaperCentroid (finite, > 0). Unset: the space's
  /// FeatureSpace::centroid_delta. (Witness uses the space's delta.)
  std::optional<Scalar> centroid_delta = std::nullopt;
  /// N: iterations (generations) of one run; also the N of Eq. 11. Exhaustive and Grid ignore it.
  std::uint32_t iterations = 100;
  /// Further runs when a run ends its N iterations without meeting another stop criterion. PSO and
  /// GA start fresh (new swarm / population); the colonies continue with their pheromone and N_c
  /// (a restart re-places the ants, it does not reset Eqs. 9–11). Hits and best accumulate.
  std::uint32_t restarts = 0;
  /// Progress marks, for experiments: shares in (0, 1] of the space's colliding pairs (the truth
  /// as for StopCriteria::target_share). SearchResult::progress tells when each was reached.
  std::vector<double> progress_marks;
  AntParams ant;
  PsoParams pso;
  GaParams ga;
  StopCriteria stop;
  std::uint64_t seed = 0;

  /// The population of every engine at once: ant.ants, pso.particles and ga.population (the
  /// paper's m; a scene run's --agents).
  void set_agents(std::uint32_t agents) {
    ant.ants = agents;
    pso.particles = agents;
    ga.population = agents;
  }
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
  Iterations,   ///< N iterations ran (or Exhaustive / Grid enumerated every pair)
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
  std::uint64_t evaluations = 0;     ///< fitness (centroid distance) evaluations, repeats included
  std::uint64_t witness_tests = 0;   ///< exact triangle tests run (Verdict::Witness)
  std::uint32_t iterations = 0;  ///< iterations begun, over all runs (Exhaustive: rows visited;
                                 ///< a leaf-pair scan: leaf pairs visited)
  std::uint32_t runs = 0;        ///< runs begun (1 + restarts used)
  std::vector<ProgressMark> progress;  ///< one per SearchRequest::progress_marks, same order
  StopReason stop = StopReason::EmptySpace;
  /// The search enumerated the cells that can collide: Exhaustive and Grid (the whole space), or a
  /// colony whose budget covered the overlapping leaf pairs' cells (AntParams::scan_covered_spaces).
  /// With stop == Iterations, every such cell was tested.
  bool scanned = false;
  Verdict verdict = Verdict::Witness;
  Scalar centroid_delta = 0;  ///< the centroid threshold used (PaperCentroid)
};

/// Runs one search over `space`. With a memory (colonies only; others ignore it), the colony
/// starts from the memory's pheromone and N_c, tests the memory's witnesses first (they count as
/// evaluations), and leaves its state and this search's witnesses in it. Throws
/// antcd::ArgumentError on an invalid request.
ANTCD_API SearchResult search(const FeatureSpace& space, const SearchRequest& request,
                    ColonyMemory* memory = nullptr);

/// Number of colliding pairs in the space under `verdict` (centroid threshold `centroid_delta`,
/// unset: the space's), by enumeration: the truth a detection rate is measured against.
ANTCD_API std::uint64_t count_colliding(const FeatureSpace& space,
                                        Verdict verdict = Verdict::Witness,
                                        std::optional<Scalar> centroid_delta = std::nullopt);

// ---- One model pair, the whole flow ----

struct DetectRequest {
  /// collide()'s threshold delta (>= 0).
  Scalar delta = 0;
  /// The search: method, verdict, centroid threshold (unset: default_delta(a, b), which costs a
  /// pass over both meshes; a caller that queries the same models often can pass it resolved),
  /// engine parameters and seed (the sampling's seed too). Its stop criteria bound EACH search of
  /// a space: the partial pass and, when that finds nothing, the full pass. stop.first_hit is
  /// forced on (a verdict needs one witness) unless `all_witnesses` is set.
  SearchRequest search;
  /// Run the search to its budget and return every colliding feature pair it meets.
  bool all_witnesses = false;
  /// Also count the colliding feature pairs of the searched space by enumeration
  /// (DetectResult::feature_truth, the paper's A/B). Implies all_witnesses.
  bool count_truth = false;
  std::uint32_t samples_per_side = 1000;
  FeatureOrder order = FeatureOrder::Leaf;
  /// Leaf pairs of the first, partial preliminary detection (nearest first;
  /// SamplingOptions::max_leaf_pairs; 0 = all at once). Without a witness there, the space is
  /// rebuilt with every leaf pair. Skipped (all at once) when the memory says the last query of
  /// the pair was a near miss (ColonyMemory::undecided).
  std::uint32_t first_leaf_pairs = 8;
  /// SamplingOptions::triangle_masks.
  bool triangle_masks = true;
  /// Positions around each remembered witness scanned before any traversal
  /// (confirm_witnesses); 0 = the witnesses alone.
  std::uint32_t witness_neighbourhood = 4;
  /// Budget per reported leaf pair, in evaluations, for each search of a space, combined with the
  /// search's own stop.max_evaluations (the smaller; 0 = none). A pair of models whose leaves
  /// overlap but whose surfaces do not meet costs about as many centroid distances as the exact
  /// test would test triangle pairs. When it covers every cell of the overlapping leaf pairs, the
  /// colonies scan those cells instead (AntParams::scan_covered_spaces): complete, so a pair
  /// without a witness is then proven separate.
  std::uint64_t evaluations_per_leaf_pair = 32;
};

struct DetectResult {
  bool colliding = false;
  /// Decided by the memory's witnesses alone (no traversal, no search).
  bool by_memory = false;
  /// No leaf pair at delta: separate without a search.
  bool no_leaf_pair = false;
  /// Leaves overlapped, no witness was found, and the search did not prove the pair separate
  /// (proves_separate): "separate" is then a guess, not a proof.
  bool undecided = false;
  std::size_t leaf_pairs = 0;
  /// Fitness evaluations the whole query spent (the memory's neighbourhood scan and every search).
  std::uint64_t spent = 0;
  /// Distinct colliding feature pairs the searches found.
  std::uint64_t feature_hits = 0;
  /// With count_truth: colliding feature pairs in the searched space.
  std::uint64_t feature_truth = 0;
  /// The last search; its evaluations and witness_tests count the whole query.
  SearchResult search;
};

/// Whether `result`, a Verdict::Witness search of `space` without a witness, proves the pair
/// separate at the space's delta: the space came from a preliminary detection that ran to the end
/// and kept every candidate triangle (no sampling), and the search tested every cell (an
/// exhaustive or grid search that ran out its rows, or a colony that scanned a covered space).
/// Every triangle pair within delta lies in two overlapping leaves and so in that space.
ANTCD_API bool proves_separate(const FeatureSpace& space, const SearchResult& result);

/// What confirm_witnesses did.
struct WitnessCheck {
  std::size_t valid = 0;          ///< witnesses confirmed at the new poses
  std::uint64_t evaluations = 0;  ///< centroid distances computed (neighbourhood scan)
  std::uint64_t tests = 0;        ///< exact triangle tests
};

/// Tests the memory's witnesses at these poses with collide()'s exact triangle test at delta.
/// When none is still valid and `neighbourhood` > 0, scans the cells around each remembered
/// witness, up to `neighbourhood` positions away in each model's leaf order (the grid moves an ant
/// makes), with the reach filter f <= r_i + r_j + delta and the exact test: a contact that slid
/// to a neighbouring triangle is found again without a traversal. stop_at_first: stops at the
/// first valid pair, moved to the front (the other witnesses stay, untested); else keeps only
/// the valid witnesses. Throws antcd::ArgumentError for a negative or non-finite delta.
ANTCD_API WitnessCheck confirm_witnesses(const Model& a, const Transform& pose_a, const Model& b,
                               const Transform& pose_b, Scalar delta, ColonyMemory& memory,
                               bool stop_at_first, std::uint32_t neighbourhood = 0);

/// The whole random query of one model pair (section 4): the memory's witnesses first (each
/// confirmed at the new poses by the exact test counts as a hit), else preliminary detection at
/// delta (no leaf pair => separate; first the `first_leaf_pairs` nearest), feature sampling,
/// search; without a witness in a partial space, the full one is built and searched. With a
/// memory, the colony continues from it and leaves its state, witnesses and near-miss flag there.
/// The scene runner (scene.hpp) runs exactly this per pair. `memory` may be null. Throws
/// antcd::ArgumentError on invalid arguments.
ANTCD_API DetectResult random_detect(const Model& a, const Transform& pose_a, const Model& b,
                           const Transform& pose_b, const DetectRequest& request,
                           ColonyMemory* memory = nullptr);

/// One call: build_feature_space(a, pose_a, b, pose_b, sampling, request.seed), then search.
ANTCD_API SearchResult random_collide(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, const SearchRequest& request = {},
                            const SamplingOptions& sampling = {});

}  // namespace antcd
