// Private: the section-4 query of one model pair in steps. random_detect() runs it in one call;
// a scene frame with a shared evaluation budget (scene/pair_query.cpp) runs one search step per
// round, so both are this one implementation.
#pragma once

#include <antcd/random.hpp>

namespace antcd::detail {

class PairDetection {
 public:
  /// Phase 1: the memory's witnesses (temporal coherence), then the preliminary detection at
  /// delta and the sampling. The request must have been validated (validate_detect). A pair
  /// decided here (a witness confirmed, or no leaf pair) is not pending.
  PairDetection(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
                const DetectRequest& request, ColonyMemory* memory);

  /// The request the steps use; a round scheduler changes its search's seed, stop criteria and
  /// restarts (and evaluations_per_leaf_pair) between steps.
  [[nodiscard]] DetectRequest& request() { return request_; }
  [[nodiscard]] bool pending() const { return pending_; }
  /// Evaluations spent so far (the memory's neighbourhood scan and every search).
  [[nodiscard]] std::uint64_t spent() const { return out_.search.evaluations; }

  /// One search of the current space. Without a witness in a partial space, builds the full
  /// space; with `then_full`, searches it at once too (else the next step does). A step that ends
  /// with a witness, or with a proof of separation, or (all_witnesses) after one search of the
  /// full space, leaves the pair no longer pending. Returns the evaluations it spent.
  std::uint64_t step(bool then_full);

  /// The result (a pair still pending is undecided); leaves the near-miss flag in the memory.
  DetectResult finish();

 private:
  SearchResult search_space(std::uint64_t seed);
  void build(std::uint32_t max_leaf_pairs);

  const Model& a_;
  const Model& b_;
  Transform pose_a_, pose_b_;
  DetectRequest request_;
  ColonyMemory* memory_;
  SamplingOptions sampling_;
  std::uint64_t sampling_seed_ = 0;
  FeatureSpace space_;
  DetectResult out_;
  bool pending_ = false;
  bool decided_ = false;  // a witness, or proves_separate on the searched space
};

/// Throws ArgumentError for an invalid DetectRequest (naming `caller` and the field).
void validate_detect(const DetectRequest& request, const char* caller);

}  // namespace antcd::detail
