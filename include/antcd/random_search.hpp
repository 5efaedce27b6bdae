// antcd/random_search.hpp — the searches over a feature space (the paper's sections 3.3–4): the
// classic and improved ant colonies (ACO, MACO), PSO and GA, their parameters, stop criteria and
// memory across frames. The flow and the conventions are random.hpp's. Part of antcd::random.
#pragma once

#include <antcd/method.hpp>
#include <antcd/random_export.hpp>
#include <antcd/random_features.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace antcd {

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
  std::vector<float> log_tau;    ///< log2 of the pheromone, grid_a x grid_b
  std::uint64_t iterations = 0;  ///< N_c: iterations run so far
  double best_evaluation = 0;    ///< Eq. 13's bt (0 = none yet)
  /// Witnesses as positions in the two models' leaf order (Model::leaf_triangles() indices,
  /// pose-independent, like FeatureSide::position), most recent first.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> witnesses;
  /// The last query of this pair (a scene frame) ended without a witness while its leaves
  /// overlapped (undecided, or proven separate by a complete scan: a near miss). Its contact, if
  /// one appears, is new, so the next query traverses the whole hierarchy at once instead of trying
  /// the nearest leaf pairs first.
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
  std::uint64_t evaluations = 0;    ///< fitness (centroid distance) evaluations, repeats included
  std::uint64_t witness_tests = 0;  ///< exact triangle tests run (Verdict::Witness)
  std::uint32_t iterations = 0;     ///< iterations begun, over all runs (Exhaustive: rows visited;
                                    ///< a leaf-pair scan: leaf pairs visited)
  std::uint32_t runs = 0;           ///< runs begun (1 + restarts used)
  std::vector<ProgressMark> progress;  ///< one per SearchRequest::progress_marks, same order
  StopReason stop = StopReason::EmptySpace;
  /// The search enumerated the cells that can collide: Exhaustive and Grid (the whole space), or a
  /// colony whose budget covered the overlapping leaf pairs' cells
  /// (AntParams::scan_covered_spaces). With stop == Iterations, every such cell was tested.
  bool scanned = false;
  Verdict verdict = Verdict::Witness;
  Scalar centroid_delta = 0;  ///< the centroid threshold used (PaperCentroid)
};

/// Runs one search over `space`. With a memory (colonies only; others ignore it), the colony
/// starts from the memory's pheromone and N_c, tests the memory's witnesses first (they count as
/// evaluations), and leaves its state and this search's witnesses in it. Throws
/// antcd::ArgumentError on an invalid request.
ANTCD_RANDOM_API SearchResult search(const FeatureSpace& space, const SearchRequest& request,
                                     ColonyMemory* memory = nullptr);

/// Number of colliding pairs in the space under `verdict` (centroid threshold `centroid_delta`,
/// unset: the space's), by enumeration: the truth a detection rate is measured against.
ANTCD_RANDOM_API std::uint64_t count_colliding(const FeatureSpace& space,
                                               Verdict verdict = Verdict::Witness,
                                               std::optional<Scalar> centroid_delta = std::nullopt);

}  // namespace antcd
