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

/// Runs `query.method` on one pair. Deterministic: random methods seed their stream from
/// (query.seed, frame, i, j) only.
PairOutcome narrow_phase(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                         const SceneQuery& query, std::size_t frame, std::uint32_t i,
                         std::uint32_t j);

}  // namespace antcd::detail
