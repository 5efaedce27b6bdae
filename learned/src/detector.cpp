// BOX-DNN / BOX-LSTM over a scene (see detector.hpp).
#include <antcd_learned/detector.hpp>

#include <chrono>

namespace antcd::learned {

Detector::Detector(const Scene& scene, const Classifier& model)
    : scene_(&scene), model_(&model), history_(scene, model.window(), model.delta()) {}

FrameResult Detector::run_frame(std::size_t frame) {
  const auto start = std::chrono::steady_clock::now();
  FrameResult result;
  result.frame = frame;
  result.candidates = scene_->broad_phase(frame, model_->delta());
  const std::size_t n = result.candidates.size();
  const std::size_t floats = model_->window() * kFeatureCount;
  buffer_.resize(n * floats);
  for (std::size_t k = 0; k < n; ++k) {
    const auto [i, j] = result.candidates[k];
    history_.window_features(i, j, frame, buffer_.data() + k * floats);
  }
  history_.forget_before(frame + 1);
  const std::vector<std::uint8_t> verdict = model_->predict(buffer_, n);
  for (std::size_t k = 0; k < n; ++k) {
    if (verdict[k] != 0) result.pairs.push_back(result.candidates[k]);
  }
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace antcd::learned
