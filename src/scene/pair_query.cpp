#include "scene/pair_query.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>
#include <antcd/rng.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace antcd {

std::uint64_t scene_pair_seed(std::uint64_t seed, std::size_t frame, std::uint32_t i,
                              std::uint32_t j) {
  return mix_seed(mix_seed(mix_seed(seed) ^ frame) ^ (std::uint64_t{i} << 32 | j));
}

}  // namespace antcd

namespace antcd::detail {
namespace {

/// Round r > 0 of a frame budget: a derived, unrelated stream.
std::uint64_t round_seed(std::uint64_t pair_seed, std::uint64_t round) {
  return round == 0 ? pair_seed : mix_seed(pair_seed ^ round);
}

DetectRequest pair_request(const SceneQuery& query, const PairSide& a, const PairSide& b,
                           std::size_t frame) {
  DetectRequest request = query.random;
  request.delta = query.delta;
  request.search.method = query.method;
  request.search.seed = scene_pair_seed(query.seed, frame, a.index, b.index);
  // default_delta(a, b), from the radii the scene cached (random.hpp).
  if (!request.search.centroid_delta) {
    request.search.centroid_delta = default_delta(a.feature_radius, b.feature_radius);
  }
  return request;
}

}  // namespace

PairOutcome query_pair(const PairSide& a, const PairSide& b, const SceneQuery& query) {
  PairOutcome out;
  if (query.method == Method::Exact) {
    CollisionResult result;
    CollisionRequest request{query.delta, false, 0};
    request.volume = query.volume;
    out.colliding = collide(*a.model, a.pose, *b.model, b.pose, request, result);
  } else {
    out.colliding = any_leaf_pair_overlaps(*a.model, a.pose, *b.model, b.pose, query.delta);
  }
  return out;
}

void random_frame(const std::vector<std::pair<PairSide, PairSide>>& pairs, const SceneQuery& query,
                  std::size_t frame, const std::vector<ColonyMemory*>& memory,
                  std::vector<PairOutcome>& out, const ForEach& for_each) {
  const std::size_t m = pairs.size();
  out.assign(m, PairOutcome{});
  const bool frame_budget = query.frame_evaluations > 0 || query.frame_seconds > 0;
  std::vector<std::optional<PairDetection>> detections(m);
  auto result_of = [&](std::size_t k) {
    const DetectResult r = detections[k]->finish();
    out[k].colliding = r.colliding;
    out[k].feature_hits = r.feature_hits;
    out[k].feature_truth = r.feature_truth;
    out[k].evaluations = r.spent;
    out[k].undecided = r.undecided;
  };

  // Without a frame budget each pair is random_detect's query, whole.
  if (!frame_budget) {
    for_each(m, [&](std::size_t k) {
      const auto& [a, b] = pairs[k];
      detections[k].emplace(*a.model, a.pose, *b.model, b.pose, pair_request(query, a, b, frame),
                            memory.empty() ? nullptr : memory[k]);
      if (detections[k]->pending()) detections[k]->step(true);
      result_of(k);
    });
    return;
  }

  // With one, phase 1 (witnesses, preliminary detection, sampling) per pair, then the frame's
  // budget shared in rounds: each round splits what is left equally over the pairs still
  // undecided, each of which runs one search step with its share (its colony continuing from its
  // memory). The split depends only on counts, so the answer is the same at any thread count.
  const auto start = std::chrono::steady_clock::now();
  for_each(m, [&](std::size_t k) {
    const auto& [a, b] = pairs[k];
    detections[k].emplace(*a.model, a.pose, *b.model, b.pose, pair_request(query, a, b, frame),
                          memory.empty() ? nullptr : memory[k]);
  });
  std::uint64_t left = query.frame_evaluations;
  // The witness scans of phase 1 count against the frame budget too.
  for (std::size_t k = 0; k < m; ++k) left -= std::min(left, detections[k]->spent());
  constexpr std::uint64_t kMaxRounds = 8;
  std::vector<std::uint64_t> spent(m, 0);
  std::vector<std::size_t> todo;
  for (std::uint64_t round = 0; round < kMaxRounds; ++round) {
    todo.clear();
    for (std::size_t k = 0; k < m; ++k) {
      if (detections[k]->pending()) todo.push_back(k);
    }
    if (todo.empty()) break;
    std::uint64_t share = 0;
    double seconds = 0;
    if (query.frame_evaluations > 0) {
      share = left / todo.size();
      if (share == 0) break;
    }
    if (query.frame_seconds > 0) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double remaining = query.frame_seconds - elapsed;
      if (remaining <= 0) break;
      const double waves = std::ceil(static_cast<double>(todo.size()) /
                                     static_cast<double>(std::max(1, query.threads)));
      seconds = remaining / waves;
    }
    for_each(todo.size(), [&](std::size_t t) {
      const std::size_t k = todo[t];
      const auto& [a, b] = pairs[k];
      DetectRequest& request = detections[k]->request();
      request.search.seed = round_seed(scene_pair_seed(query.seed, frame, a.index, b.index), round);
      // The frame budget replaces the per-leaf-pair limit: the colony keeps going (a restart
      // keeps its pheromone and N_c) until its share is spent.
      request.evaluations_per_leaf_pair = 0;
      request.search.stop.max_evaluations = share;
      request.search.stop.max_seconds = seconds;
      request.search.restarts = std::numeric_limits<std::uint32_t>::max() - 1;
      spent[k] = detections[k]->step(false);
    });
    for (const std::size_t k : todo) left -= std::min(left, spent[k]);
  }
  for (std::size_t k = 0; k < m; ++k) result_of(k);
}

}  // namespace antcd::detail
