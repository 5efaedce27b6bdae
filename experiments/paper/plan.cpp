#include "paper/plan.hpp"

#include <limits>

namespace antcd::experiments::paper {

int feature_row(std::uint32_t n) {
  for (int r = 0; r < 5; ++r) {
    if (kPaperFeatures[r] == n) return r;
  }
  return -1;
}

double paper_table1(std::uint32_t features, std::size_t rate) {
  const int row = feature_row(features);
  return row < 0 ? std::numeric_limits<double>::quiet_NaN() : kPaperTable1[row][rate];
}
double paper_table2(std::uint32_t features, std::size_t rate) {
  const int row = feature_row(features);
  return row < 0 ? std::numeric_limits<double>::quiet_NaN() : kPaperTable2[row][rate] / 100;
}

Plan make_plan(bool quick) {
  Plan p;
  if (quick) {
    p.features = {1000, 2000};
    p.pair_frames = 2;
    p.pair_seeds = 2;
    p.table_cap = 8'000'000;
    p.colony_sizes = {20, 40, 60, 80, 100};
    p.fig3_frames = 1;
    p.fig3_seeds = 1;
    p.scene_frames = 3;
    p.budgets = {1600, 25600, 409600};
    p.delta_scales = {0.5};
    p.learned_scenes = 2;
    p.learned_frames = 60;
    p.learned_epochs = 15;
    p.ablation_features = 1000;
  } else {
    p.features = {1000, 2000, 3000, 4000, 5000};
    p.pair_frames = 4;
    p.pair_seeds = 3;
    p.table_cap = 40'000'000;
    p.colony_sizes = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
    p.fig3_frames = 2;
    p.fig3_seeds = 2;
    p.scene_frames = 30;
    p.budgets = {400, 1600, 6400, 25600, 102400, 409600, 1638400};
    p.delta_scales = {0.5, 0.25};
  }
  return p;
}

std::string method_key(Method m) { return std::string(method_name(m)); }

std::string series_key(const SceneSeriesSpec& spec) {
  return method_key(spec.method) +
         (spec.verdict == Verdict::PaperCentroid ? " (paper centroid)" : "");
}

SearchRequest paper_request(Method method, std::uint64_t seed) {
  SearchRequest r;
  r.method = method;
  r.iterations = 100;
  r.ant.ants = 60;
  r.ant.alpha = 1;
  r.ant.beta = 1;
  r.ant.n = 50;
  // The paper's colony alone: no leaf-pair scan when a budget covers the cells that can collide.
  r.ant.scan_covered_spaces = false;
  r.pso.particles = 60;
  r.ga.population = 60;
  r.seed = seed;
  return r;
}

}  // namespace antcd::experiments::paper
