#include "paper/scene_figures.hpp"

#include "paper/format.hpp"
#include "paper/plan.hpp"
#include "shared/rng.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>

#include <algorithm>
#include <atomic>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>

namespace antcd::experiments::paper {

void measure_scene_figures(const Scene& scene, const std::vector<FrameTruth>& truth, Results& R,
                           std::ostream& log, Clock::time_point start) {
  const Plan& P = R.plan;
  for (std::size_t k = 0; k < P.scene_frames && k < R.frames; ++k) {
    R.scene_frames.push_back((2 * k + 1) * R.frames / (2 * P.scene_frames));
  }
  R.scene_frames.erase(std::unique(R.scene_frames.begin(), R.scene_frames.end()),
                       R.scene_frames.end());
  struct Task {
    std::size_t frame;
    std::uint32_t i, j;
    bool truth;
  };
  std::vector<Task> tasks;
  for (const std::size_t f : R.scene_frames) {
    for (const auto& [i, j] : truth[f].candidates) {
      const bool t =
          std::binary_search(truth[f].pairs.begin(), truth[f].pairs.end(), std::make_pair(i, j));
      tasks.push_back({f, i, j, t});
    }
  }
  log << "[" << num(ms_since(start) / 1000, 1) << " s] Figures 4-5: " << R.scene_frames.size()
      << " frames, " << tasks.size() << " candidate pairs × " << std::size(kSceneSpecs)
      << " series × " << P.budgets.size() << " budgets" << std::endl;
  struct TaskResult {
    Tally exact, sphere;
    std::vector<Tally> random;  ///< [spec * budgets + budget]
    std::vector<Tally> sensitivity;
    double delta = 0;
  };
  std::vector<TaskResult> results(tasks.size());
  std::atomic<std::size_t> done{0};
  std::mutex log_mutex;
  parallel_for(tasks.size(), R.options.threads, [&](std::size_t idx) {
    const Task& t = tasks[idx];
    const Model& a = scene.model_of(t.i);
    const Model& b = scene.model_of(t.j);
    const Transform pa = scene.description().objects[t.i].pose(t.frame);
    const Transform pb = scene.description().objects[t.j].pose(t.frame);
    TaskResult& out = results[idx];
    {
      CollisionResult c;
      const auto t0 = Clock::now();
      const bool hit = collide(a, pa, b, pb, CollisionRequest{0.0, false, 0}, c);
      out.exact.add(hit, t.truth, ms_since(t0));
    }
    {
      const auto t0 = Clock::now();
      const bool hit = any_leaf_pair_overlaps(a, pa, b, pb, 0.0);
      out.sphere.add(hit, t.truth, ms_since(t0));
    }
    const std::uint64_t seed = shared::derive_seed(R.options.seed, 4, t.frame, t.i, t.j);
    out.delta = default_delta(a, b);
    // The library's section 4 flow for one pair: everything from the preliminary detection on is
    // in the time.
    auto detect = [&](Method method, Verdict verdict, std::uint64_t budget,
                      std::optional<double> centroid_delta, std::size_t salt) {
      DetectRequest req;
      req.delta = 0;
      req.samples_per_side = P.scene_samples;
      req.evaluations_per_leaf_pair = 0;  // the budget below is the only one
      req.first_leaf_pairs = 32;          // the figures' protocol since they were first measured
      req.triangle_masks = false;         // the paper's preliminary detection: sphere and OBB only
      req.search = paper_request(method, shared::derive_seed(seed, 5, salt));
      req.search.verdict = verdict;
      req.search.centroid_delta = centroid_delta;
      req.search.restarts = std::numeric_limits<std::uint32_t>::max();
      req.search.stop.max_evaluations = budget;
      const auto s0 = Clock::now();
      const DetectResult res = random_detect(a, pa, b, pb, req);
      Tally tally;
      tally.add(res.colliding, t.truth, ms_since(s0), static_cast<double>(res.search.evaluations));
      return tally;
    };
    for (std::size_t g = 0; g < std::size(kSceneSpecs); ++g) {
      for (const std::uint64_t budget : P.budgets) {
        out.random.push_back(
            detect(kSceneSpecs[g].method, kSceneSpecs[g].verdict, budget, std::nullopt, g));
      }
    }
    for (const double scale : P.delta_scales) {
      out.sensitivity.push_back(
          detect(Method::Maco, Verdict::PaperCentroid, P.budgets.back(), out.delta * scale, 0));
    }
    const std::size_t d = ++done;
    const std::lock_guard<std::mutex> lock(log_mutex);
    if (d % std::max<std::size_t>(1, tasks.size() / 10) == 0 || d == tasks.size()) {
      log << "  " << d << "/" << tasks.size() << " pairs done (" << num(ms_since(start) / 1000, 1)
          << " s)" << std::endl;
    }
  });
  double delta_sum = 0;
  for (const TaskResult& x : results) {
    R.exact.merge(x.exact);
    R.sphere_obb.merge(x.sphere);
    delta_sum += x.delta;
    for (std::size_t g = 0; g < std::size(kSceneSpecs); ++g) {
      for (std::size_t q = 0; q < P.budgets.size(); ++q) {
        R.random[{series_key(kSceneSpecs[g]), P.budgets[q]}].merge(
            x.random[g * P.budgets.size() + q]);
      }
    }
    for (std::size_t k = 0; k < P.delta_scales.size(); ++k) {
      R.sensitivity[P.delta_scales[k]].merge(x.sensitivity[k]);
    }
  }
  R.feature_delta_mean = results.empty() ? 0 : delta_sum / static_cast<double>(results.size());
  // Budgets that no pair was run with still get (empty) series.
  for (const SceneSeriesSpec& g : kSceneSpecs) {
    for (const std::uint64_t b : P.budgets) R.random[{series_key(g), b}];
  }
}

}  // namespace antcd::experiments::paper
