// antcd_learned/dataset.hpp — labelled samples for the learned baselines, and the feature
// history of a scene's object pairs.
//
// A sample is one broad-phase candidate pair (i < j) at one frame: the pair's feature vectors
// (features.hpp) over the `window` frames ending at that frame, oldest first (frames before 0
// repeat frame 0), labelled 1 when the exact method says the pair collides at that frame. BOX-DNN
// uses window 1; BOX-LSTM a longer window, so that the motion is part of its input.
//
// Training data is generated, never taken from the evaluated scene: training_set() builds
// production-line scenes (antcd scene generate), pairs of generated shapes and, given training
// mesh files (meshes.hpp: split by mesh), pairs of those meshes, from seeds derived from its own
// seed, labels them with the exact method and removes its temporary folder. No torch header here.
#pragma once

#include <antcd/scene.hpp>
#include <antcd_learned/features.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace antcd::learned {

struct Dataset {
  std::size_t window = 1;  ///< frames per sample
  Scalar delta = 0;        ///< collision threshold of the labels and the features
  /// size() × window × kFeatureCount values, sample by sample, frame by frame (oldest first).
  std::vector<float> features;
  std::vector<std::uint8_t> labels;  ///< 1 = the exact method reports a collision

  [[nodiscard]] std::size_t size() const { return labels.size(); }
  [[nodiscard]] std::size_t sample_floats() const { return window * kFeatureCount; }
  [[nodiscard]] std::size_t positives() const;
  /// Appends `other`'s samples; throws Error when window or delta differ.
  void append(const Dataset& other);
  /// The same samples with only their last (current) frame: window-1 data for BOX-DNN.
  [[nodiscard]] Dataset last_frame() const;
  /// Sets features [first, first + count) of every frame of every sample to 0 (to measure what a
  /// feature group adds: a constant feature carries nothing). Throws std::out_of_range past the
  /// vector.
  void zero_features(std::size_t first, std::size_t count);
};

/// Feature vectors of a scene's object pairs over recent frames, kept so that a run over
/// consecutive frames computes each pair's features once per frame. Not thread-safe (one per
/// thread or per run).
class PairHistory {
 public:
  PairHistory(const Scene& scene, std::size_t window, Scalar delta);

  /// Writes the window × kFeatureCount features of pair (i, j) ending at `frame` to `out`.
  void window_features(std::uint32_t i, std::uint32_t j, std::size_t frame, float* out);
  /// Drops cached vectors of frames that no window ending at `frame` or later needs.
  void forget_before(std::size_t frame);

 private:
  const Scene* scene_;
  std::size_t window_;
  Scalar delta_;
  /// (i, j, frame) → features.
  struct Key {
    std::uint32_t i, j;
    std::size_t frame;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  std::unordered_map<Key, FeatureVector, KeyHash> cache_;
};

/// Samples of frames [first, last) of `scene`: every broad-phase candidate pair of each frame,
/// labelled by the exact method with threshold `delta`. Throws std::out_of_range for last > frames.
Dataset scene_samples(const Scene& scene, std::size_t first, std::size_t last, std::size_t window,
                      Scalar delta);

struct TrainingSetOptions {
  std::size_t scenes = 6;    ///< generated scenes (>= 1)
  std::size_t frames = 150;  ///< frames of each scene (>= 1)
  std::uint64_t seed = 1;    ///< every scene's seed is derived from it
  std::size_t window = 1;
  Scalar delta = 0;
  /// Production-line scenes get between min_objects and max_objects objects.
  std::size_t min_objects = 40;
  std::size_t max_objects = 90;
  /// Training meshes (mesh files, meshes.hpp). When not empty, scene k with k % 3 == 1 is a
  /// row of mesh pairs instead of a production line: five of these meshes (drawn from the
  /// scene's seed; all when fewer) and two generated shapes, each passing through both of its
  /// neighbours. No other mesh file is read.
  std::vector<std::filesystem::path> mesh_files;
};

/// Describes scene k of a training set (layout, objects, vertices, seed) for the log.
std::string training_scene_label(const TrainingSetOptions& options, std::size_t k);

/// Generates the training scenes described above and returns their samples. Scene k is a
/// production line (objects and tessellation drawn from the seed) except every third one, which
/// is a row of pairs of generated shapes (tori, spheres, boxes, cylinders, compound parts) passing
/// through each other, and, with mesh_files, the one after each production line (k % 3 == 1), a
/// row of mesh pairs. `log` (when set) receives one line per scene. Throws std::invalid_argument
/// for bad options, Error when the temporary folder cannot be written.
Dataset training_set(const TrainingSetOptions& options,
                     const std::function<void(const std::string&)>& log = {});

}  // namespace antcd::learned
