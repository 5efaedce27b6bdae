// experiments/paper/scene_figures.hpp — Figures 4-5 of `antcd bench paper`: every candidate
// object pair of sampled frames, decided by each method against the exact method's verdicts.
#pragma once

#include <antcd/scene.hpp>

#include <cstdint>
#include <iosfwd>
#include <utility>
#include <vector>

#include "paper/results.hpp"
#include "paper/run_util.hpp"

namespace antcd::experiments::paper {

/// The exact method's verdicts on one frame.
struct FrameTruth {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;       ///< colliding, sorted
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;  ///< broad phase, sorted
  double time_ms = 0;
};

/// Fills R.scene_frames, R.exact, R.sphere_obb, R.random (one series per kSceneSpecs entry and
/// budget), R.sensitivity and R.feature_delta_mean. Each random series runs the library's
/// section 4 flow per candidate pair (random_detect at delta = 0: preliminary detection, no leaf
/// pair => separate, sampling, search to the first colliding feature pair or the budget).
void measure_scene_figures(const Scene& scene, const std::vector<FrameTruth>& truth, Results& R,
                           std::ostream& log, Clock::time_point start);

}  // namespace antcd::experiments::paper
