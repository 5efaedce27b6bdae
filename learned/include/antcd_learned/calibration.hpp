// antcd_learned/calibration.hpp — the decision threshold of a learned model, chosen by
// cross-validation by mesh (docs/learned-baselines.md), never on the held-out meshes.
//
// cross_validate() deals the training meshes into k folds (mesh_folds); for each fold it trains a
// model on scenes of the other folds' meshes and computes that model's probabilities on a scene
// made only of the fold's meshes, which it never saw. choose_threshold() then picks, over the
// pooled out-of-fold probabilities, the threshold that maximises min(recall, precision): the goal
// of the learned baselines is a bar both must clear (issue 40: both >= 0.8), and this criterion
// lifts the weaker of the two as far as the data allows (F1 would accept, say, recall 0.95 with
// precision 0.72). Everything is a deterministic function of the options and the seed. No torch
// header here.
#pragma once

#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/meshes.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace antcd::learned {

/// Seed of the evaluated mesh scene of fold `k` of a cross-validation seeded by `seed`;
/// `antcd learn train`'s held-out check uses k = ~0.
std::uint64_t evaluation_seed(std::uint64_t seed, std::uint64_t k);

/// Counts at "probability >= threshold".
Confusion confusion_at(std::span<const float> probabilities, std::span<const std::uint8_t> labels,
                       double threshold);

struct ThresholdChoice {
  double threshold = 0.5;
  Confusion at;  ///< the samples' counts at `threshold`
};

/// The threshold t, 0 < t < 1, maximising min(recall, precision) of "probability >= t" over the
/// samples. Only thresholds that split the samples are candidates (between two distinct
/// probabilities); within the best interval t is 0.5 when the interval holds it, else its
/// midpoint; between equally good intervals, the one whose t is nearest 0.5. When no threshold
/// splits the samples (all probabilities equal), 0.5. Throws std::invalid_argument when the
/// sizes differ, there are no samples, or no sample is positive.
ThresholdChoice choose_threshold(std::span<const float> probabilities,
                                 std::span<const std::uint8_t> labels);

/// One fold of a cross-validation by mesh.
struct FoldResult {
  std::vector<std::filesystem::path> meshes;  ///< kept out of the fold's training, then judged
  std::size_t train_samples = 0;
  std::vector<float> probabilities;  ///< the fold model's, on the scene of `meshes`
  std::vector<std::uint8_t> labels;  ///< the exact method's on that scene
};

struct CrossValidation {
  std::vector<FoldResult> folds;
  std::vector<float> probabilities;  ///< every fold's, pooled in fold order
  std::vector<std::uint8_t> labels;  ///< likewise
  ThresholdChoice choice;            ///< choose_threshold over the pooled samples
};

/// k-fold cross-validation by mesh over set.mesh_files (mesh_folds(set.mesh_files, k,
/// set.seed)): fold i's model trains on training_set(set) with fold i's meshes removed (the same
/// options otherwise) and is judged on mesh_scene_samples(fold i's meshes, set.frames,
/// evaluation_seed(set.seed, i), set.window, set.delta). `done` (when set) is called after each
/// fold. Throws std::invalid_argument for a bad k (mesh_folds), as training_set and
/// Classifier::train do for bad options, and when no judged sample collides.
CrossValidation cross_validate(
    const TrainingSetOptions& set, const TrainOptions& train, std::size_t k,
    const std::function<void(std::size_t, const FoldResult&)>& done = {});

}  // namespace antcd::learned
