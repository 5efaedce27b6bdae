#include "scene/pair_query.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>
#include <antcd/rng.hpp>

#include <algorithm>
#include <limits>

namespace antcd::detail {

PairOutcome query_pair(const PairSide& a, const PairSide& b, const SceneQuery& query,
                       std::size_t frame) {
  PairOutcome out;
  switch (query.method) {
    case Method::Exact: {
      CollisionResult result;
      out.colliding = collide(*a.model, a.pose, *b.model, b.pose,
                              CollisionRequest{query.delta, false, 0}, result);
      return out;
    }
    case Method::SphereObb:
      out.colliding = any_leaf_pair_overlaps(*a.model, a.pose, *b.model, b.pose, query.delta);
      return out;
    case Method::Aco:
    case Method::Maco:
    case Method::Pso:
    case Method::Ga:
    case Method::Exhaustive:
      break;
  }
  SearchRequest request;
  request.method = query.method;
  // The radii are the ones the scene cached per model, so this is default_delta(a, b).
  request.delta = query.feature_delta > 0 ? query.feature_delta
                                          : default_delta(a.feature_radius, b.feature_radius);
  request.iterations = query.iterations;
  request.ant.ants = query.agents;
  request.pso.particles = query.agents;
  request.ga.population = query.agents;
  request.seed =
      mix_seed(mix_seed(mix_seed(query.seed) ^ frame) ^ (std::uint64_t{a.index} << 32 | b.index));
  request.stop.first_hit = !(query.search_all || query.count_feature_truth);
  SamplingOptions sampling;
  sampling.samples_per_side = static_cast<std::uint32_t>(query.samples_per_side);
  sampling.delta = request.delta;
  const FeatureSpace space =
      build_feature_space(*a.model, a.pose, *b.model, b.pose, sampling, request.seed);
  if (query.count_feature_truth) {
    out.feature_truth = count_colliding(space, request.delta);
  }
  const SearchResult found = search(space, request);
  out.colliding = found.found;
  out.feature_hits = found.hits.size();
  return out;
}

}  // namespace antcd::detail
