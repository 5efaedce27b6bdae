// Private: the narrow phase of one object pair, for every scene method.
#pragma once

#include <antcd/scene.hpp>

#include <cstdint>

namespace antcd::detail {

struct PairOutcome {
  bool colliding = false;
  std::uint64_t feature_hits = 0;   ///< random methods: distinct colliding feature pairs found
  std::uint64_t feature_truth = 0;  ///< random methods: colliding feature pairs in the space
};

/// One object of a candidate pair: its model, its pose this frame, its model's feature radius
/// (random.hpp, cached by the scene) and its object index.
struct PairSide {
  const Model* model = nullptr;
  Transform pose;
  Scalar feature_radius = 0;
  std::uint32_t index = 0;
};

/// Runs `query.method` on one pair. Deterministic: random methods seed their stream from
/// (query.seed, frame, a.index, b.index) only.
PairOutcome query_pair(const PairSide& a, const PairSide& b, const SceneQuery& query,
                       std::size_t frame);

}  // namespace antcd::detail
