// antcd_learned/classifier.hpp — BOX-DNN and BOX-LSTM: learned collide / not-collide classifiers
// over the bounding-volume features of a candidate pair (our construction of the paper's names;
// see docs/learned-baselines.md).
//
// - BOX-DNN: a multilayer perceptron (kFeatureCount → 64 → 32 → 1, ReLU) on one frame's features.
// - BOX-LSTM: a one-layer LSTM (hidden 32) over the features of the pair's last `window` frames,
//   its last output through a linear layer.
// Both are PyTorch modules (libtorch's C++ API); inputs are standardised with the training set's
// per-feature mean and deviation, stored in the model file. Output: the probability that the pair
// collides; predict() calls a pair colliding when it reaches the model's decision threshold: 0.5
// unless one was set (antcd learn train --folds K chooses it on out-of-fold probabilities of a
// cross-validation by mesh, calibration.hpp), stored in the model file.
//
// Determinism: train() seeds libtorch (torch::manual_seed), shuffles with its own generator and
// runs on one intra-op thread, so the same data and seed give the same weights; see
// docs/learned-baselines.md for what libtorch does not promise.
//
// Model file: a libtorch archive (zip) holding the format tag "antcd-learned/2", the feature
// version, the kind, the window, delta, the standardisation, the decision threshold, the training
// record, the network's parameters and a checksum of the standardisation, the parameters and the
// threshold. save() writes it atomically; load() refuses any file that is not such an archive,
// whose checksum does not match, whose threshold is not inside (0, 1), or that was made for
// another feature version, with ModelError naming the file. Files of format "antcd-learned/1"
// (before thresholds were stored) load with the threshold 0.5 they were used with.
//
// Thread safety: a Classifier is immutable after train()/load(); probabilities() and predict() are
// const and may be called from several threads. No torch header here (the network lives in the
// implementation file).
#pragma once

#include <antcd/mesh.hpp>
#include <antcd_learned/dataset.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace antcd::learned {

/// A model file is missing, unreadable, not a model, or made for another feature version.
/// what() is "<file>: <problem>", one line.
class ModelError : public Error {
 public:
  using Error::Error;
};

enum class Kind { Dnn, Lstm };

/// "box-dnn" or "box-lstm".
std::string_view kind_name(Kind kind);
/// Parses "box-dnn" / "box-lstm"; throws Error naming the value otherwise.
Kind parse_kind(std::string_view name);
/// The feature window each kind is trained with: 1 for BOX-DNN, 8 frames for BOX-LSTM.
std::size_t default_window(Kind kind);

struct TrainOptions {
  Kind kind = Kind::Dnn;
  std::uint64_t seed = 1;
  std::size_t epochs = 40;
  std::size_t batch = 256;
  double learning_rate = 2e-3;
  /// Progress lines (one per few epochs) when set.
  std::function<void(const std::string&)> log;
};

/// What a model was trained on and how long it took (stored in the model file).
struct TrainingRecord {
  std::uint64_t seed = 0;
  std::uint64_t scenes = 0;  ///< generated scenes (0 when trained on a given data set)
  std::uint64_t frames = 0;  ///< frames per scene
  std::uint64_t samples = 0;
  std::uint64_t positives = 0;
  std::uint64_t epochs = 0;
  double final_loss = 0;      ///< mean training loss of the last epoch
  double train_accuracy = 0;  ///< on the training samples, after training
  double data_seconds = 0;    ///< generating and labelling the scenes
  double train_seconds = 0;   ///< the optimisation alone
  std::string meshes;         ///< training mesh files (names, ", "-separated; empty: none)
  std::string held_out;       ///< the mesh files held out of training (names)
  /// How the decision threshold was chosen ("" : the default 0.5), e.g. the criterion and the
  /// cross-validation it was chosen on.
  std::string threshold_source;
};

class Classifier {
 public:
  Classifier(Classifier&&) noexcept;
  Classifier& operator=(Classifier&&) noexcept;
  ~Classifier();

  /// Trains on `data` (window must be 1 for Kind::Dnn). Throws std::invalid_argument for an
  /// empty data set, a bad option or a window that does not fit the kind.
  static Classifier train(const Dataset& data, const TrainOptions& options);
  /// Loads a model file. Throws ModelError (one line, naming the file).
  static Classifier load(const std::filesystem::path& path);
  /// Writes the model file atomically (temporary file, then rename). Throws Error.
  void save(const std::filesystem::path& path) const;

  [[nodiscard]] Kind kind() const;
  [[nodiscard]] std::size_t window() const;
  [[nodiscard]] Scalar delta() const;
  [[nodiscard]] int feature_version() const;
  [[nodiscard]] const TrainingRecord& record() const;
  /// Sets what the model was trained on (scenes, frames, data time) before save().
  void set_record(const TrainingRecord& record);
  /// The decision threshold of predict(): a pair collides when its probability is >= it.
  [[nodiscard]] double threshold() const;
  /// Sets the decision threshold; throws std::invalid_argument unless 0 < threshold < 1.
  void set_threshold(double threshold);

  /// Collision probabilities of `count` samples laid out as in Dataset::features.
  [[nodiscard]] std::vector<float> probabilities(std::span<const float> samples,
                                                 std::size_t count) const;
  /// probabilities() >= threshold(), as 0/1.
  [[nodiscard]] std::vector<std::uint8_t> predict(std::span<const float> samples,
                                                  std::size_t count) const;

 private:
  struct Impl;
  explicit Classifier(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace antcd::learned
