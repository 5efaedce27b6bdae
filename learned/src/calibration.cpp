// The decision threshold chosen by cross-validation by mesh (see calibration.hpp).
#include <antcd/rng.hpp>
#include <antcd_learned/calibration.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace antcd::learned {

std::uint64_t evaluation_seed(std::uint64_t seed, std::uint64_t k) {
  return mix_seed(seed ^ 0x4556414CULL ^ mix_seed(k));
}

Confusion confusion_at(std::span<const float> probabilities, std::span<const std::uint8_t> labels,
                       double threshold) {
  std::vector<std::uint8_t> predicted(probabilities.size());
  for (std::size_t i = 0; i < probabilities.size(); ++i) {
    predicted[i] = static_cast<double>(probabilities[i]) >= threshold ? 1 : 0;
  }
  return confusion(predicted, std::vector<std::uint8_t>(labels.begin(), labels.end()));
}

ThresholdChoice choose_threshold(std::span<const float> probabilities,
                                 std::span<const std::uint8_t> labels) {
  const std::size_t n = labels.size();
  if (probabilities.size() != n) {
    throw std::invalid_argument("probabilities and labels differ in number");
  }
  if (n == 0) throw std::invalid_argument("no samples to choose a decision threshold on");
  const std::size_t positives = static_cast<std::size_t>(
      std::count_if(labels.begin(), labels.end(), [](std::uint8_t y) { return y != 0; }));
  if (positives == 0) {
    throw std::invalid_argument("no colliding sample to choose a decision threshold on");
  }
  // Highest probability first; "top m" is "probability >= t" for t in (p[m], p[m - 1]].
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return probabilities[a] != probabilities[b] ? probabilities[a] > probabilities[b] : a < b;
  });
  double best_score = -1;
  double best_t = 0.5;
  std::size_t tp = 0;
  for (std::size_t m = 0; m < n;) {
    const float upper = probabilities[order[m]];
    while (m < n && probabilities[order[m]] == upper) tp += labels[order[m++]] != 0 ? 1 : 0;
    if (m == n) break;  // everything positive: no split
    const float lower = probabilities[order[m]];
    const double recall = static_cast<double>(tp) / static_cast<double>(positives);
    const double precision = static_cast<double>(tp) / static_cast<double>(m);
    const double score = std::min(recall, precision);
    const double t = lower < 0.5F && upper >= 0.5F
                         ? 0.5
                         : (static_cast<double>(lower) + static_cast<double>(upper)) / 2;
    if (score > best_score || (score == best_score && std::abs(t - 0.5) < std::abs(best_t - 0.5))) {
      best_score = score;
      best_t = t;
    }
  }
  ThresholdChoice c;
  c.threshold = best_t;
  c.at = confusion_at(probabilities, labels, best_t);
  return c;
}

CrossValidation cross_validate(const TrainingSetOptions& set, const TrainOptions& train,
                               std::size_t k,
                               const std::function<void(std::size_t, const FoldResult&)>& done) {
  const auto folds = mesh_folds(set.mesh_files, k, set.seed);
  CrossValidation cv;
  for (std::size_t i = 0; i < folds.size(); ++i) {
    TrainingSetOptions fold_set = set;
    fold_set.mesh_files.clear();
    for (std::size_t j = 0; j < folds.size(); ++j) {
      if (j != i) {
        fold_set.mesh_files.insert(fold_set.mesh_files.end(), folds[j].begin(), folds[j].end());
      }
    }
    const Dataset data = training_set(fold_set);
    const Classifier model = Classifier::train(data, train);
    const Dataset test = mesh_scene_samples(folds[i], set.frames, evaluation_seed(set.seed, i),
                                            set.window, set.delta);
    FoldResult fold;
    fold.meshes = folds[i];
    fold.train_samples = data.size();
    fold.probabilities = model.probabilities(test.features, test.size());
    fold.labels = test.labels;
    cv.probabilities.insert(cv.probabilities.end(), fold.probabilities.begin(),
                            fold.probabilities.end());
    cv.labels.insert(cv.labels.end(), fold.labels.begin(), fold.labels.end());
    cv.folds.push_back(std::move(fold));
    if (done) done(i, cv.folds.back());
  }
  cv.choice = choose_threshold(cv.probabilities, cv.labels);
  return cv;
}

}  // namespace antcd::learned
