// experiments/paper/plan.hpp — what `antcd bench paper` measures: the paper's published numbers
// (section 5), the plan of each mode (quick or full) and the searches with the paper's settings.
#pragma once

#include <antcd/method.hpp>
#include <antcd/random.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace antcd::experiments::paper {

// ---- The paper's numbers (section 5) ----

inline constexpr std::uint32_t kPaperFeatures[] = {1000, 2000, 3000, 4000, 5000};
inline constexpr double kRates[] = {0.2, 0.4, 0.6, 0.8};
/// Table 1: duration (ms) at detection rate 20/40/60/80 %, one row per feature count.
inline constexpr double kPaperTable1[5][4] = {{5.1, 8.4, 10.6, 13.4},
                                              {7.0, 11.1, 12.9, 16.4},
                                              {9.2, 13.4, 16.1, 20.8},
                                              {12.3, 15.6, 18.5, 22.0},
                                              {14.1, 17.2, 20.5, 27.3}};
/// Table 2: A/B in percent.
inline constexpr double kPaperTable2[5][4] = {{7.3, 15.2, 22.1, 30.2},
                                              {10.0, 21.2, 34.3, 45.6},
                                              {13.3, 27.8, 39.6, 51.2},
                                              {16.2, 35.9, 55.1, 62.7},
                                              {20.0, 44.1, 65.4, 85.3}};
/// Figure 3 (text): the colony size with the highest detection rate per feature count.
inline constexpr std::uint32_t kPaperBestAnts[5] = {40, 50, 50, 60, 60};

/// The row of kPaperFeatures holding `n`, or -1.
int feature_row(std::uint32_t n);
/// The paper's Table 1 (ms) at `features` and rate index 0..3; NaN when the paper has no row.
double paper_table1(std::uint32_t features, std::size_t rate);
/// The paper's Table 2 (A/B as a fraction) at `features` and rate index 0..3; NaN likewise.
double paper_table2(std::uint32_t features, std::size_t rate);

// ---- Plan: what each mode measures ----

struct Plan {
  std::vector<std::uint32_t> features;  ///< features per side (Tables 1-2, Figure 3)
  std::size_t pair_frames = 0;          ///< frames of the measured pair (Tables 1-2)
  std::size_t pair_seeds = 0;           ///< seeds per frame (Tables 1-2)
  std::uint64_t table_cap = 0;          ///< evaluation cap of one Table 1 search
  std::vector<std::uint32_t> colony_sizes;
  std::size_t fig3_frames = 0;
  std::size_t fig3_seeds = 0;
  std::size_t scene_frames = 0;        ///< frames sampled for Figures 4-5
  std::vector<std::uint64_t> budgets;  ///< evaluation budgets per pair (Figures 4-5)
  /// First tessellation tried for the measured pair (vertices per mesh); it is refined until
  /// each side of the pair has at least max(features) candidate triangles at delta = 0 (so the
  /// largest row's space is truly n x n), up to max_fine_vertices.
  std::size_t fine_vertices = 3000;
  std::size_t max_fine_vertices = 120000;
  /// The ablation of MACO's switches (shared/maco_ablation.hpp) runs on the Table 1 spaces of
  /// this feature count.
  std::uint32_t ablation_features = 2000;
  std::uint32_t scene_samples = 5000;  ///< features per side in Figures 4-5 (paper: 5000)
  std::vector<double> delta_scales;    ///< centroid-threshold sensitivity (Figure 4 note)
  // Figure 5's learned baselines (box-dnn, box-lstm): their generated training scenes.
  std::size_t learned_scenes = 6;
  std::size_t learned_frames = 150;
  std::size_t learned_epochs = 40;
};

Plan make_plan(bool quick);

// ---- The searches ----

/// Tables 1-2 measure every search, MACO first; Figures 4-5 the heuristic ones.
inline constexpr Method kTableMethods[] = {Method::Maco, Method::Aco, Method::Pso, Method::Ga,
                                           Method::Exhaustive};
/// Index of the exhaustive scan in kTableMethods.
inline constexpr std::size_t kExhaustiveIndex = 4;

/// One series of Figures 4-5: a search with a verdict mode (antcd/random.hpp, Verdict).
struct SceneSeriesSpec {
  Method method;
  Verdict verdict;
};
/// Every search with the default (witness) verdict; the colonies also with the paper's centroid
/// verdict, where the two modes differ.
inline constexpr SceneSeriesSpec kSceneSpecs[] = {
    {Method::Maco, Verdict::Witness},       {Method::Aco, Verdict::Witness},
    {Method::Pso, Verdict::Witness},        {Method::Ga, Verdict::Witness},
    {Method::Maco, Verdict::PaperCentroid}, {Method::Aco, Verdict::PaperCentroid}};
/// The name of a series in files: "maco", …, "maco (paper centroid)".
std::string series_key(const SceneSeriesSpec& spec);

/// The method's name in files ("maco", …, antcd/method.hpp).
std::string method_key(Method m);

/// The paper's settings (section 5, experiment 3): m = 60, alpha = beta = 1, N = 100, n = 50; the
/// swarm and the population of the baselines have the same size.
SearchRequest paper_request(Method method, std::uint64_t seed);

}  // namespace antcd::experiments::paper
