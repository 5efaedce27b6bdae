// Figure 5's learned baselines in `antcd bench paper` (see learned.hpp).
#include "paper/learned.hpp"

#include <ostream>

#ifdef ANTCD_HAVE_LEARNED
#include <antcd/rng.hpp>
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/detector.hpp>

#include <algorithm>
#include <chrono>
#include <utility>
#endif

namespace antcd::experiments::paper {

#ifdef ANTCD_HAVE_LEARNED

bool learned_available() { return true; }

void measure_learned(const Scene& scene,
                     const std::function<bool(std::size_t, std::uint32_t, std::uint32_t)>& truth,
                     Results& R, std::ostream& log) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  // One set of generated, labelled scenes with BOX-LSTM's window; BOX-DNN takes each sample's
  // last frame.
  learned::TrainingSetOptions set;
  set.scenes = R.plan.learned_scenes;
  set.frames = R.plan.learned_frames;
  set.seed = mix_seed(R.options.seed ^ 0x4C4541524EULL);
  set.window = learned::default_window(learned::Kind::Lstm);
  const auto t0 = Clock::now();
  const learned::Dataset lstm_data = learned::training_set(set);
  const double data_seconds = seconds(t0);
  const learned::Dataset dnn_data = lstm_data.last_frame();
  for (const learned::Kind kind : {learned::Kind::Dnn, learned::Kind::Lstm}) {
    const std::string name(learned::kind_name(kind));
    const learned::Dataset& data = kind == learned::Kind::Dnn ? dnn_data : lstm_data;
    LearnedTraining& info = R.learned_training[name];
    info.scenes = set.scenes;
    info.frames = set.frames;
    info.data_seconds = data_seconds;
    info.samples = data.size();
    info.positives = data.positives();
    learned::TrainOptions train;
    train.kind = kind;
    train.seed = set.seed;
    train.epochs = R.plan.learned_epochs;
    const auto t1 = Clock::now();
    const learned::Classifier model = learned::Classifier::train(data, train);
    info.train_seconds = seconds(t1);
    log << "  " << name << ": trained on " << data.size() << " samples of " << set.scenes
        << " generated scenes (data " << info.data_seconds << " s, training " << info.train_seconds
        << " s)" << std::endl;
    learned::Detector detector(scene, model);
    Tally& tally = R.learned[name];
    for (const std::size_t f : R.scene_frames) {
      const FrameResult fr = detector.run_frame(f);
      const double per_pair =
          fr.candidates.empty() ? 0.0 : fr.time_ms / static_cast<double>(fr.candidates.size());
      for (const auto& [i, j] : fr.candidates) {
        const bool reported =
            std::binary_search(fr.pairs.begin(), fr.pairs.end(), std::make_pair(i, j));
        tally.add(reported, truth(f, i, j), per_pair);
      }
    }
  }
}

#else

bool learned_available() { return false; }

void measure_learned(const Scene&,
                     const std::function<bool(std::size_t, std::uint32_t, std::uint32_t)>&,
                     Results&, std::ostream& log) {
  log << "  box-dnn, box-lstm: not measured (antcd built without libtorch)" << std::endl;
}

#endif

}  // namespace antcd::experiments::paper
