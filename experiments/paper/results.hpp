// experiments/paper/results.hpp — everything `antcd bench paper` measured, and the aggregates
// the tables, plots and report are written from.
#pragma once

#include "paper/paper_bench.hpp"
#include "paper/plan.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace antcd::experiments::paper {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Tables 1-2 and Figure 3: runs on the measured pair ----

struct MarkResult {
  bool reached = false;
  double ms = kInf;
  double evaluations = kInf;
  std::size_t found_contacts = 0;  ///< A: hits up to the mark confirmed by the exact test
};

struct PairRun {
  std::uint32_t features = 0;
  std::size_t frame = 0;
  std::uint32_t space_a = 0, space_b = 0;
  std::size_t candidates_a = 0, candidates_b = 0;  ///< triangles of the kept leaves, per side
  std::uint64_t truth = 0;                         ///< colliding feature pairs in the space
  std::size_t contacts = 0;           ///< B: colliding triangle pairs of the two objects
  std::size_t contacts_in_space = 0;  ///< of B, those whose two triangles were both sampled
  double build_ms = 0;
  /// [search][rate]: kTableMethods first, then (at Plan::ablation_features only) the variants of
  /// shared::maco_ablation() in order.
  std::vector<std::vector<MarkResult>> marks;
};

struct Fig3Run {
  std::uint32_t features = 0;
  std::uint32_t ants = 0;
  double rate = 0;
  double ms = 0;
  double evaluations = 0;
};

// ---- Figures 4-5: verdicts on the scene's candidate pairs ----

/// Verdicts against the exact method's, and the time they took.
struct Tally {
  std::uint64_t tp = 0, fp = 0, fn = 0, tn = 0;
  double ms = 0;           ///< summed over the candidate pairs
  double evaluations = 0;  ///< fitness evaluations, summed (random methods)
  void add(bool reported, bool truth, double t, double evals = 0) {
    if (reported && truth) ++tp;
    if (reported && !truth) ++fp;
    if (!reported && truth) ++fn;
    if (!reported && !truth) ++tn;
    ms += t;
    evaluations += evals;
  }
  void merge(const Tally& o) {
    tp += o.tp;
    fp += o.fp;
    fn += o.fn;
    tn += o.tn;
    ms += o.ms;
    evaluations += o.evaluations;
  }
  [[nodiscard]] std::uint64_t total() const { return tp + fp + fn + tn; }
  [[nodiscard]] double recall() const {
    return tp + fn == 0 ? 1.0 : static_cast<double>(tp) / static_cast<double>(tp + fn);
  }
  [[nodiscard]] double precision() const {
    return tp + fp == 0 ? 1.0 : static_cast<double>(tp) / static_cast<double>(tp + fp);
  }
  [[nodiscard]] double accuracy() const {
    return total() == 0 ? 1.0 : static_cast<double>(tp + tn) / static_cast<double>(total());
  }
  [[nodiscard]] double pair_ms() const {
    return total() == 0 ? 0.0 : ms / static_cast<double>(total());
  }
  [[nodiscard]] double pair_evaluations() const {
    return total() == 0 ? 0.0 : evaluations / static_cast<double>(total());
  }
};

struct SceneSeries {
  std::string method;
  std::uint64_t budget = 0;  ///< 0 for exact and sphere-obb
  Tally tally;
};

/// How a learned baseline was trained (reported apart from its detection time).
struct LearnedTraining {
  std::size_t scenes = 0, frames = 0, samples = 0, positives = 0;
  double data_seconds = 0;   ///< generating and labelling the training scenes
  double train_seconds = 0;  ///< the optimisation
};

// ---- Everything measured ----

struct Results {
  Plan plan;
  PaperBenchOptions options;
  // scene
  std::size_t objects = 0, meshes = 0, frames = 0;
  double average_vertices = 0;
  std::uint64_t scene_colliding = 0, scene_candidates = 0;
  double exact_frame_ms = 0;
  // measured pair
  std::string name_a, name_b;
  std::size_t contact_frames = 0;
  std::vector<std::size_t> pair_frames;
  std::size_t fine_vertices = 0;  ///< the tessellation finally used (Plan::fine_vertices refined)
  std::vector<std::size_t> fine_tried;  ///< every tessellation tried, in order
  /// Fewest candidate triangles at delta = 0 per side over the measured frames.
  std::size_t fine_candidates_a = 0, fine_candidates_b = 0;
  std::size_t fine_triangles_a = 0, fine_triangles_b = 0;
  double fine_delta = 0;
  std::vector<PairRun> runs;
  std::vector<Fig3Run> fig3;
  // figures 4-5
  std::vector<std::size_t> scene_frames;
  double feature_delta_mean = 0;
  Tally exact, sphere_obb;
  std::map<std::pair<std::string, std::uint64_t>, Tally> random;  ///< (method, budget)
  std::map<double, Tally> sensitivity;  ///< delta_c scale → maco (paper centroid), top budget
  /// Figure 5's learned baselines ("box-dnn", "box-lstm"); empty without libtorch.
  std::map<std::string, Tally> learned;
  std::map<std::string, LearnedTraining> learned_training;
  double seconds = 0;
};

// ---- Aggregates ----

/// One cell of Tables 1-2: medians over the runs of one feature count for one search and rate.
struct TableCell {
  std::size_t runs = 0, reached = 0;
  double ms = kInf, evaluations = kInf, build_ms = 0;
  double space_a = 0, space_b = 0, candidates_a = 0, candidates_b = 0;
  double a = std::numeric_limits<double>::quiet_NaN(), b = 0, ab = 0, coverage = 0;
};

/// The cell of search `method` (an index into PairRun::marks: kTableMethods, then the ablation
/// variants) at `features` and rate index `rate`. Runs without that search are skipped.
TableCell table_cell(const Results& r, std::size_t method, std::uint32_t features,
                     std::size_t rate);

/// Cost of one fitness evaluation of search `method` (PairRun::marks index), ns: the median over
/// every run that reached a mark of (time / evaluations) at the highest mark it reached.
double ns_per_evaluation(const Results& r, std::size_t method);

/// Figure 3: the mean rate of colony size m at n features; NaN without runs.
double fig3_mean(const Results& r, std::uint32_t n, std::uint32_t m);

/// The series of Figure 4 (Sphere-OBB, ACO and MACO in both verdict modes, exact) and of
/// Figure 5 (MACO in both modes, PSO, GA, the learned baselines when built, exact).
std::vector<std::string> fig4_series(const Results& r);
std::vector<std::string> fig5_series(const Results& r);

/// Figures 4-5: the tallies of `methods` ("exact", "sphere-obb", or one series per budget).
std::vector<SceneSeries> scene_series(const Results& r, const std::vector<std::string>& methods);

}  // namespace antcd::experiments::paper
