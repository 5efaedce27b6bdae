#include "scene/pair_query.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>
#include <antcd/rng.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace antcd::detail {

namespace {

std::uint64_t pair_seed(const SceneQuery& query, std::size_t frame, const PairSide& a,
                        const PairSide& b, std::uint64_t round) {
  const std::uint64_t base =
      mix_seed(mix_seed(mix_seed(query.seed) ^ frame) ^ (std::uint64_t{a.index} << 32 | b.index));
  return round == 0 ? base : mix_seed(base ^ round);
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

void random_frame(const std::vector<std::pair<PairSide, PairSide>>& pairs,
                  const SceneQuery& query, std::size_t frame,
                  const std::vector<ColonyMemory*>& memory, std::vector<PairOutcome>& out,
                  const ForEach& for_each) {
  const std::size_t m = pairs.size();
  out.assign(m, PairOutcome{});
  const bool all = query.search_all || query.count_feature_truth;
  const bool witness = query.verdict == Verdict::Witness;
  std::vector<FeatureSpace> spaces(m);
  std::vector<char> pending(m, 0);

  SearchRequest base;
  base.method = query.method;
  base.verdict = query.verdict;
  base.iterations = query.iterations;
  base.ant.ants = query.agents;
  base.ant.scan_covered_spaces = query.scan_covered_spaces;
  base.pso.particles = query.agents;
  base.ga.population = query.agents;
  base.stop.first_hit = !all;

  // Phase 1, per pair: the memory's witnesses (temporal coherence), then the preliminary
  // detection at delta and the sampling. A pair without a leaf pair is separate, with no search.
  for_each(m, [&](std::size_t k) {
    const auto& [a, b] = pairs[k];
    ColonyMemory* mem = memory.empty() ? nullptr : memory[k];
    if (mem != nullptr && witness && !all && !mem->witnesses.empty()) {
      const WitnessCheck check = confirm_witnesses(*a.model, a.pose, *b.model, b.pose,
                                                   query.delta, *mem, true,
                                                   query.witness_neighbourhood);
      out[k].evaluations += check.evaluations;
      if (check.valid > 0) {
        out[k].colliding = true;
        return;
      }
    }
    SamplingOptions sampling;
    sampling.samples_per_side = static_cast<std::uint32_t>(query.samples_per_side);
    sampling.delta = query.delta;
    // default_delta(a, b), from the radii the scene cached (random.hpp).
    sampling.centroid_delta =
        query.feature_delta > 0
            ? query.feature_delta
            : default_delta(a.feature_radius, b.feature_radius);
    // A pair left undecided last frame is most likely still a near miss: the partial pass would
    // only be repeated by the full one.
    const bool straight_to_full = all || (mem != nullptr && mem->undecided);
    sampling.max_leaf_pairs = straight_to_full ? 0 : query.first_leaf_pairs;
    spaces[k] = build_feature_space(*a.model, a.pose, *b.model, b.pose, sampling,
                                    pair_seed(query, frame, a, b, 0));
    if (spaces[k].leaf_pairs == 0) {
      if (mem != nullptr) mem->witnesses.clear();
      return;
    }
    if (query.count_feature_truth) out[k].feature_truth = count_colliding(spaces[k], base.verdict);
    pending[k] = 1;
  });

  // Phase 2: the searches. Without a frame budget each pair gets its own (evaluations per leaf
  // pair, and N iterations). With one, the frame's budget is shared in rounds: each round splits
  // what is left equally over the pairs still undecided, whose colonies continue from their
  // memory. The split depends only on counts, so the answer is the same at any thread count.
  const bool frame_budget = query.frame_evaluations > 0 || query.frame_seconds > 0;
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t left = query.frame_evaluations;
  constexpr std::uint64_t kMaxRounds = 8;
  std::vector<std::uint64_t> spent(m, 0);
  // The witness scans of phase 1 count against the frame budget too.
  for (std::size_t k = 0; k < m; ++k) left -= std::min(left, out[k].evaluations);
  for (std::uint64_t round = 0; round < (frame_budget ? kMaxRounds : 1); ++round) {
    std::vector<std::size_t> todo;
    for (std::size_t k = 0; k < m; ++k) {
      if (pending[k] != 0) todo.push_back(k);
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
      SearchRequest request = base;
      request.seed = pair_seed(query, frame, a, b, round);
      if (frame_budget) {
        request.stop.max_evaluations = share;
        request.stop.max_seconds = seconds;
        // The frame budget replaces the per-run limit: the colony keeps going (a restart keeps
        // its pheromone and N_c) until its share is spent.
        request.restarts = std::numeric_limits<std::uint32_t>::max() - 1;
      } else if (query.evaluations_per_leaf_pair > 0) {
        request.stop.max_evaluations = query.evaluations_per_leaf_pair * spaces[k].leaf_pairs;
      }
      ColonyMemory* mem = memory.empty() ? nullptr : memory[k];
      SearchResult found = search(spaces[k], request, mem);
      // Decided: a witness, or a complete scan of every overlapping leaf pair's triangles (judged
      // on the space that was searched, before any rebuild below replaces it).
      bool decided = found.found || proves_separate(spaces[k], found);
      if (!found.found && !spaces[k].complete) {
        // Nothing among the leaf pairs met first: every leaf pair, and (without a frame budget)
        // search again; with one, the next round searches the full space.
        SamplingOptions sampling;
        sampling.samples_per_side = static_cast<std::uint32_t>(query.samples_per_side);
        sampling.delta = query.delta;
        sampling.centroid_delta = spaces[k].centroid_delta;
        spaces[k] = build_feature_space(*a.model, a.pose, *b.model, b.pose, sampling,
                                        pair_seed(query, frame, a, b, 0));
        if (!frame_budget) {
          const std::uint64_t partial = found.evaluations;
          if (query.evaluations_per_leaf_pair > 0) {
            request.stop.max_evaluations =
                query.evaluations_per_leaf_pair * spaces[k].leaf_pairs;
          }
          found = search(spaces[k], request, mem);
          decided = found.found || proves_separate(spaces[k], found);
          found.evaluations += partial;
        }
      }
      spent[k] = found.evaluations;
      out[k].evaluations += found.evaluations;
      out[k].feature_hits += found.hits.size();
      if (found.found) out[k].colliding = true;
      // A verdict needs one witness; collecting them all (search_all) takes one round.
      if (decided || all || !frame_budget) pending[k] = 0;
      if (!decided && !frame_budget) out[k].undecided = true;
    });
    for (const std::size_t k : todo) left -= std::min(left, spent[k]);
  }
  for (std::size_t k = 0; k < m; ++k) {
    if (pending[k] != 0 || (all && frame_budget && !out[k].colliding && spaces[k].leaf_pairs > 0)) {
      out[k].undecided = true;
    }
    // The hint for the next frame: leaves overlapped and no witness (undecided, or proven
    // separate by a scan); either way a near miss, whose next contact is a new one.
    if (!memory.empty() && memory[k] != nullptr) {
      memory[k]->undecided = !out[k].colliding && spaces[k].leaf_pairs > 0;
    }
  }
}

}  // namespace antcd::detail
