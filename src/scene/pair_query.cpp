#include "scene/pair_query.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>

#include <algorithm>
#include <limits>

namespace antcd::detail {

namespace {

// SplitMix64 finaliser: spreads (seed, frame, i, j) into independent-looking stream seeds.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

SearchMethod search_method(Method m) {
  switch (m) {
    case Method::Aco:
      return SearchMethod::Aco;
    case Method::Maco:
      return SearchMethod::Maco;
    case Method::Pso:
      return SearchMethod::Pso;
    default:
      return SearchMethod::Ga;
  }
}

}  // namespace

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
      out.colliding = leaves_overlap(*a.model, a.pose, *b.model, b.pose, query.delta);
      return out;
    case Method::Aco:
    case Method::Maco:
    case Method::Pso:
    case Method::Ga:
      break;
  }
  SearchRequest request;
  request.method = search_method(query.method);
  if (query.feature_delta > 0) {
    request.delta = query.feature_delta;
  } else {
    // default_delta(a, b), from the radii the scene cached (random.hpp).
    request.delta =
        std::max(a.feature_radius + b.feature_radius, std::numeric_limits<Scalar>::min());
  }
  request.iterations = query.iterations;
  request.ant.ants = query.agents;
  request.pso.particles = query.agents;
  request.ga.population = query.agents;
  request.seed = mix(mix(mix(query.seed) ^ frame) ^ (std::uint64_t{a.index} << 32 | b.index));
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
