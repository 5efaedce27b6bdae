// Private: the narrow phase of one object pair, for every scene method.
#pragma once

#include <antcd/scene.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace antcd::detail {

struct PairOutcome {
  bool colliding = false;
  std::uint64_t feature_hits = 0;   ///< random methods: distinct colliding feature pairs found
  std::uint64_t feature_truth = 0;  ///< random methods: colliding feature pairs in the space
  std::uint64_t evaluations = 0;    ///< random methods: fitness evaluations spent
  bool undecided = false;           ///< random methods: budget spent without a witness
};

/// One object of a candidate pair: its model, its pose this frame, its model's feature radius
/// (random.hpp, cached by the scene) and its object index.
struct PairSide {
  const Model* model = nullptr;
  Transform pose;
  Scalar feature_radius = 0;
  std::uint32_t index = 0;
};

/// Runs an exact method (Exact, SphereObb) on one pair.
PairOutcome query_pair(const PairSide& a, const PairSide& b, const SceneQuery& query);

/// Calls body(k) for k in [0, count), possibly in parallel.
using ForEach = std::function<void(std::size_t, const std::function<void(std::size_t)>&)>;

/// Runs a random method on every candidate pair of a frame: random_detect's query per pair
/// (PairDetection, antcd/random.hpp), whole, or with a frame budget in steps that share the budget
/// in rounds. `memory` is empty or holds one ColonyMemory per pair. Deterministic: each pair's
/// random stream depends on (query.seed, frame, a.index, b.index, round) and its memory only.
void random_frame(const std::vector<std::pair<PairSide, PairSide>>& pairs, const SceneQuery& query,
                  std::size_t frame, const std::vector<ColonyMemory*>& memory,
                  std::vector<PairOutcome>& out, const ForEach& for_each);

}  // namespace antcd::detail
