// random_detect() and PairDetection (antcd/random.hpp): the section-4 query of one model pair, in
// steps or in one call.
#include <antcd/error.hpp>
#include <antcd/random.hpp>

#include "util/check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "random/recorder.hpp"

namespace antcd {

void check_detect_request(const DetectRequest& request, const char* caller) {
  detail::validate_search(request.search, caller);
  detail::require_non_negative(caller, "delta", request.delta);
  detail::require_at_least(caller, "samples_per_side", request.samples_per_side, 1);
}

PairDetection::PairDetection(const Model& a, const Transform& pose_a, const Model& b,
                             const Transform& pose_b, const DetectRequest& request,
                             ColonyMemory* memory)
    : a_(a), b_(b), pose_a_(pose_a), pose_b_(pose_b), request_(request), memory_(memory) {
  check_detect_request(request_, "random_detect");
  const bool all = request_.all_witnesses || request_.count_truth;
  if (memory_ != nullptr && request_.search.verdict == Verdict::Witness && !all &&
      !memory_->witnesses.empty()) {
    const WitnessCheck check = confirm_witnesses(a_, pose_a_, b_, pose_b_, request_.delta, *memory_,
                                                 true, request_.witness_neighbourhood);
    out_.search.evaluations = check.evaluations;
    out_.search.witness_tests = check.tests;
    if (check.valid > 0) {
      out_.colliding = true;
      out_.by_memory = true;
      decided_ = true;
      return;
    }
  }
  sampling_.samples_per_side = request_.samples_per_side;
  sampling_.delta = request_.delta;
  sampling_.centroid_delta = request_.search.centroid_delta;
  sampling_.order = request_.order;
  sampling_.triangle_masks = request_.triangle_masks;
  sampling_seed_ = request_.search.seed;
  // A pair left without a witness last time is most likely still a near miss: the partial pass
  // would only be repeated by the full one.
  const bool straight_to_full = all || (memory_ != nullptr && memory_->undecided);
  build(straight_to_full ? 0 : request_.first_leaf_pairs);
  if (space_.leaf_pairs == 0) {
    out_.no_leaf_pair = true;
    decided_ = true;
    if (memory_ != nullptr) memory_->witnesses.clear();
    return;
  }
  if (request_.count_truth) {
    out_.feature_truth = count_colliding(space_, request_.search.verdict);
  }
  pending_ = true;
}

void PairDetection::build(std::uint32_t max_leaf_pairs) {
  sampling_.max_leaf_pairs = max_leaf_pairs;
  space_ = build_feature_space(a_, pose_a_, b_, pose_b_, sampling_, sampling_seed_);
  // Later searches (and the rebuild) use the threshold the space resolved: no second default.
  sampling_.centroid_delta = space_.centroid_delta;
  out_.leaf_pairs = space_.leaf_pairs;
}

SearchResult PairDetection::search_space(std::uint64_t seed) {
  SearchRequest request = request_.search;
  request.seed = seed;
  request.stop.first_hit = !(request_.all_witnesses || request_.count_truth);
  if (request_.evaluations_per_leaf_pair != 0) {
    const std::uint64_t budget = request_.evaluations_per_leaf_pair * space_.leaf_pairs;
    std::uint64_t& limit = request.stop.max_evaluations;
    limit = limit == 0 ? budget : std::min(limit, budget);
  }
  SearchResult found = search(space_, request, memory_);
  decided_ = found.found || proves_separate(space_, found);
  out_.feature_hits += found.hits.size();
  if (found.found) out_.colliding = true;
  return found;
}

std::uint64_t PairDetection::step(bool then_full) {
  const std::uint64_t before_evaluations = out_.search.evaluations;
  const std::uint64_t before_tests = out_.search.witness_tests;
  SearchResult found = search_space(request_.search.seed);
  std::uint64_t evaluations = found.evaluations;
  std::uint64_t tests = found.witness_tests;
  if (!found.found && !space_.complete) {
    // Nothing among the leaf pairs met first: every leaf pair (searched now, or next step).
    build(0);
    if (then_full) {
      found = search_space(request_.search.seed);
      evaluations += found.evaluations;
      tests += found.witness_tests;
    }
  }
  out_.search = std::move(found);
  out_.search.evaluations = before_evaluations + evaluations;
  out_.search.witness_tests = before_tests + tests;
  // A verdict needs one witness; collecting them all (all_witnesses) takes one full search.
  const bool all = request_.all_witnesses || request_.count_truth;
  if (decided_ || (all && space_.complete)) pending_ = false;
  return evaluations;
}

DetectResult PairDetection::finish() {
  out_.spent = out_.search.evaluations;
  out_.undecided = !out_.colliding && out_.leaf_pairs > 0 && !decided_;
  // The hint for the next query: leaves overlapped and no witness (undecided, or proven
  // separate by a scan); either way a near miss, whose next contact is a new one.
  if (memory_ != nullptr) memory_->undecided = !out_.colliding && out_.leaf_pairs > 0;
  return out_;
}

DetectResult random_detect(const Model& a, const Transform& pose_a, const Model& b,
                           const Transform& pose_b, const DetectRequest& request,
                           ColonyMemory* memory) {
  PairDetection detection(a, pose_a, b, pose_b, request, memory);
  if (detection.pending()) detection.step(true);
  return detection.finish();
}

}  // namespace antcd
