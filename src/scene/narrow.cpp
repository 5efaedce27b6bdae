#include "scene/narrow.hpp"

#include <antcd/collide.hpp>
#include <antcd/random.hpp>

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

PairOutcome narrow_phase(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                         const SceneQuery& query, std::size_t frame, std::uint32_t i,
                         std::uint32_t j) {
  PairOutcome out;
  switch (query.method) {
    case Method::Exact: {
      CollisionResult result;
      out.colliding = collide(a, pa, b, pb, CollisionRequest{query.delta, false, 0}, result);
      return out;
    }
    case Method::SphereObb:
      out.colliding = leaves_overlap(a, pa, b, pb, query.delta);
      return out;
    case Method::Aco:
    case Method::Maco:
    case Method::Pso:
    case Method::Ga:
      break;
  }
  SearchRequest request;
  request.method = search_method(query.method);
  request.delta = query.feature_delta > 0 ? query.feature_delta : default_delta(a, b);
  request.iterations = query.iterations;
  request.ant.ants = query.agents;
  request.pso.particles = query.agents;
  request.ga.population = query.agents;
  request.seed = mix(mix(mix(query.seed) ^ frame) ^ (std::uint64_t{i} << 32 | j));
  SamplingOptions sampling;
  sampling.samples_per_side = static_cast<std::uint32_t>(query.samples_per_side);
  sampling.delta = request.delta;
  const FeatureSpace space = build_feature_space(a, pa, b, pb, sampling, request.seed);
  if (query.count_feature_truth) {
    out.feature_truth = count_colliding(space, request.delta);
    request.stop.reference_count = out.feature_truth;
  }
  const SearchResult found = search(space, request);
  out.colliding = found.found;
  out.feature_hits = found.hits.size();
  return out;
}

}  // namespace antcd::detail
