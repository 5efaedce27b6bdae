// antcd_learned/features.hpp — the bounding-volume features of one object pair (the "BOX-" part
// of BOX-DNN and BOX-LSTM).
//
// A pair's feature vector has two parts (docs/learned-baselines.md lists every value):
// - bounding volumes: root spheres and OBBs, the 15 separating-axis margins of the root OBBs, the
//   relative placement and orientation of the two root OBBs, their sizes and volume ratios, and,
//   level by level down to kFeatureDepth, how many node pairs of the two trees overlap. The
//   descent carries a front of at most kFeatureFront node pairs (when more overlap, an evenly
//   spread subset of them, so that the front covers the whole overlap region) down to the leaves;
//   pairs of two leaves leave it and are counted apart (kFeatureSamples of them kept, spread
//   likewise);
// - shape (version 2): those kept leaf pairs read through their triangles' corners: the smallest
//   corner-to-corner distance, whether triangle pairs straddle each other's planes (the plane
//   step of a triangle-triangle test, not the test itself), how close the straddling ones are,
//   and the spread of the leaves' normals.
// Everything is measured in A's model frame and lengths are divided by the sum of the root sphere
// radii (the leaf-pair distances by the two leaves' radii), so the vector does not change when
// both objects undergo the same rigid motion (up to rounding), nor when the whole pair is scaled.
//
// The definition is versioned: kFeatureVersion changes whenever a feature is added, removed,
// reordered or computed differently, and a saved model records the version it was trained with.
//
// Pure functions of their arguments: reentrant and thread-safe. No torch header here.
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <cstddef>
#include <string_view>

namespace antcd::learned {

/// Version of the feature definition below.
inline constexpr int kFeatureVersion = 2;
/// Deepest level of the two trees the per-level overlap counts reach (root = level 0).
inline constexpr int kFeatureDepth = 10;
/// Most node pairs carried from one level to the next (the most deeply overlapping ones); beyond
/// it the counts of the deeper levels cover only those, and a flag says so. The descent goes on
/// below kFeatureDepth, until no node pair is left, to collect leaf pairs.
inline constexpr std::size_t kFeatureFront = 128;
/// Most leaf pairs whose triangles are read (the most deeply overlapping ones found).
inline constexpr std::size_t kFeatureSamples = 64;
/// Length of the feature vector.
inline constexpr std::size_t kFeatureCount = 76;

using FeatureVector = std::array<float, kFeatureCount>;

/// The features of models `a` and `b` at poses `pose_a`, `pose_b`, with the collision threshold
/// `delta` >= 0 (every overlap test is widened by it, as in the broad phase). Allocation-free.
FeatureVector pair_features(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, Scalar delta);

/// Short names of the features, in vector order (for reports and docs).
const std::array<std::string_view, kFeatureCount>& feature_names();

/// A run of consecutive features measuring one thing (the rows of the docs' feature table).
struct FeatureGroup {
  std::string_view name;
  std::size_t first = 0;
  std::size_t count = 0;
};
inline constexpr std::size_t kFeatureGroups = 5;
/// The groups in vector order, covering it exactly: root volumes (v1), levels 1-5 (v1), levels
/// 6-10, leaf pairs and shape (v2).
const std::array<FeatureGroup, kFeatureGroups>& feature_groups();

}  // namespace antcd::learned
