// antcd/random.hpp — random (stochastic) collision detection: the paper's sections 3–4, the whole
// flow for one model pair. Its parts: random_features.hpp (the feature space), random_search.hpp
// (the searches). Part of antcd::random (link antcd::random).
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

#pragma once

#include <antcd/random_export.hpp>
#include <antcd/random_search.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace antcd {

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
ANTCD_RANDOM_API bool proves_separate(const FeatureSpace& space, const SearchResult& result);

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
ANTCD_RANDOM_API WitnessCheck confirm_witnesses(const Model& a, const Transform& pose_a,
                                                const Model& b, const Transform& pose_b,
                                                Scalar delta, ColonyMemory& memory,
                                                bool stop_at_first,
                                                std::uint32_t neighbourhood = 0);

/// The whole random query of one model pair (section 4): the memory's witnesses first (each
/// confirmed at the new poses by the exact test counts as a hit), else preliminary detection at
/// delta (no leaf pair => separate; first the `first_leaf_pairs` nearest), feature sampling,
/// search; without a witness in a partial space, the full one is built and searched. With a
/// memory, the colony continues from it and leaves its state, witnesses and near-miss flag there.
/// The scene runner (scene.hpp) runs exactly this per pair. `memory` may be null. Throws
/// antcd::ArgumentError on invalid arguments.
ANTCD_RANDOM_API DetectResult random_detect(const Model& a, const Transform& pose_a, const Model& b,
                                            const Transform& pose_b, const DetectRequest& request,
                                            ColonyMemory* memory = nullptr);

/// One call: build_feature_space(a, pose_a, b, pose_b, sampling, request.seed), then search.
ANTCD_RANDOM_API SearchResult random_collide(const Model& a, const Transform& pose_a,
                                             const Model& b, const Transform& pose_b,
                                             const SearchRequest& request = {},
                                             const SamplingOptions& sampling = {});

// ---- The same query in steps, for callers that share an evaluation budget ----

/// random_detect() cut into steps: a caller that detects many model pairs under one evaluation
/// budget (the scene runner's frame budget) runs phase 1 of every pair, then one search step per
/// pair per round, and hands each round's remaining budget out through request(). Run to the end
/// without changing request(), it is random_detect() exactly (random_detect is this class). One
/// object belongs to one thread; its models and memory must outlive it.
class ANTCD_RANDOM_API PairDetection {
 public:
  /// Phase 1: the memory's witnesses (temporal coherence), then the preliminary detection at
  /// delta and the sampling. Throws ArgumentError (naming "random_detect" and the field) for an
  /// invalid request. A pair decided here (a witness confirmed, or no leaf pair) is not pending.
  PairDetection(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
                const DetectRequest& request, ColonyMemory* memory);

  /// The request the steps use; a round scheduler may change its search's seed, stop criteria and
  /// restarts (and evaluations_per_leaf_pair) between steps.
  [[nodiscard]] DetectRequest& request() { return request_; }
  [[nodiscard]] bool pending() const { return pending_; }
  /// Evaluations spent so far (the memory's neighbourhood scan and every search).
  [[nodiscard]] std::uint64_t spent() const { return out_.search.evaluations; }

  /// One search of the current space. Without a witness in a partial space, builds the full
  /// space; with `then_full`, searches it at once too (else the next step does). A step that ends
  /// with a witness, or with a proof of separation, or (all_witnesses) after one search of the
  /// full space, leaves the pair no longer pending. Returns the evaluations it spent.
  std::uint64_t step(bool then_full);

  /// The result (a pair still pending is undecided); leaves the near-miss flag in the memory.
  DetectResult finish();

 private:
  SearchResult search_space(std::uint64_t seed);
  void build(std::uint32_t max_leaf_pairs);

  const Model& a_;
  const Model& b_;
  Transform pose_a_, pose_b_;
  DetectRequest request_;
  ColonyMemory* memory_;
  SamplingOptions sampling_;
  std::uint64_t sampling_seed_ = 0;
  FeatureSpace space_;
  DetectResult out_;
  bool pending_ = false;
  bool decided_ = false;  // a witness, or proves_separate on the searched space
};

/// Throws ArgumentError for an invalid DetectRequest, naming `caller` and the field (what
/// random_detect and PairDetection check).
ANTCD_RANDOM_API void check_detect_request(const DetectRequest& request, const char* caller);

}  // namespace antcd
