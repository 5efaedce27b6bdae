// antcd_learned/features.hpp — the bounding-volume features of one object pair (the "BOX-" part
// of BOX-DNN and BOX-LSTM).
//
// A pair's feature vector is computed from the two hierarchies' bounding volumes only (no triangle
// is read): root spheres and OBBs, the 15 separating-axis margins of the root OBBs, the relative
// placement and orientation of the two root OBBs, their sizes and volume ratios, and, level by
// level down to kFeatureDepth, how many node pairs of the two trees still overlap. Everything is
// measured in A's model frame and lengths are divided by the sum of the root sphere radii, so the
// vector does not change when both objects undergo the same rigid motion (up to rounding), nor
// when the whole pair is scaled.
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
inline constexpr int kFeatureVersion = 1;
/// Deepest level of the two trees the per-level overlap counts reach (root = level 0).
inline constexpr int kFeatureDepth = 5;
/// Length of the feature vector.
inline constexpr std::size_t kFeatureCount = 58;

using FeatureVector = std::array<float, kFeatureCount>;

/// The features of models `a` and `b` at poses `pose_a`, `pose_b`, with the collision threshold
/// `delta` >= 0 (every overlap test is widened by it, as in the broad phase). Allocation-free.
FeatureVector pair_features(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, Scalar delta);

/// Short names of the features, in vector order (for reports and docs).
const std::array<std::string_view, kFeatureCount>& feature_names();

}  // namespace antcd::learned
