// antcd_learned/detector.hpp — BOX-DNN / BOX-LSTM run over a scene, frame by frame, like the
// library's own methods: the scene's broad phase (Scene::broad_phase), then the classifier on
// every candidate pair's features (features.hpp: bounding volumes, leaf pairs and a few leaves'
// triangles), all candidates of a frame in one batch.
//
// A learned method is not conservative: a pair it calls free may collide (a miss), and the
// reverse. Measure it against exact (recall, precision) before trusting it.
//
// A Detector keeps each pair's recent feature vectors (BOX-LSTM needs the last `window` frames),
// so run_frame is not const and a Detector serves one thread; frames run in increasing order
// reuse that history, any order gives the same answers. No torch header here.
#pragma once

#include <antcd/scene.hpp>
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>

#include <vector>

namespace antcd::learned {

class Detector {
 public:
  /// `scene` and `model` must outlive the detector. The run's collision threshold is the model's
  /// (Classifier::delta()).
  Detector(const Scene& scene, const Classifier& model);

  /// Candidates and the pairs the model calls colliding (both sorted, i < j); time_ms covers the
  /// broad phase, the features and the network. Throws std::out_of_range for a frame >= frames.
  FrameResult run_frame(std::size_t frame);

 private:
  const Scene* scene_;
  const Classifier* model_;
  PairHistory history_;
  std::vector<float> buffer_;
};

}  // namespace antcd::learned
