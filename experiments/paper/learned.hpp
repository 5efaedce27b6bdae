// experiments/paper/learned.hpp — Figure 5's learned baselines BOX-DNN and BOX-LSTM (our
// construction, docs/learned-baselines.md) inside `antcd bench paper`.
#pragma once

#include <antcd/scene.hpp>

#include <cstdint>
#include <functional>
#include <iosfwd>

#include "paper/results.hpp"

namespace antcd::experiments::paper {

/// Whether this build has the learned baselines (antcd_learned, libtorch).
bool learned_available();

/// Trains BOX-DNN and BOX-LSTM on generated scenes (seeds derived from the bench seed, never the
/// bench scene; R.plan.learned_scenes scenes of R.plan.learned_frames frames), then runs each over
/// R.scene_frames of `scene` with the scene's broad phase and tallies every candidate pair against
/// `truth(frame, i, j)`; a frame's time (broad phase, features, network) is spread evenly over its
/// candidates. Fills R.learned and R.learned_training. Without libtorch it does nothing.
void measure_learned(const Scene& scene,
                     const std::function<bool(std::size_t, std::uint32_t, std::uint32_t)>& truth,
                     Results& R, std::ostream& log);

}  // namespace antcd::experiments::paper
