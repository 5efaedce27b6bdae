// search() and random_collide(): request validation, then dispatch to one engine.
#include <antcd/rng.hpp>

#include "random/engines.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace antcd {
namespace {

void require(bool ok, const char* what) {
  if (!ok) throw antcd::ArgumentError(std::string("antcd::search: ") + what);
}

void validate(const SearchRequest& r) {
  require(!std::isnan(r.delta) && !std::isinf(r.delta),
          "delta must be finite (negative = default)");
  require(r.iterations >= 1, "iterations must be >= 1");
  const StopCriteria& s = r.stop;
  require(s.target_share >= 0 && s.target_share <= 1, "stop.target_share must be in [0, 1]");
  require(s.max_seconds >= 0 && !std::isnan(s.max_seconds), "stop.max_seconds must be >= 0");
  for (const double mark : r.progress_marks) {
    require(mark > 0 && mark <= 1, "progress_marks must be in (0, 1]");
  }
  switch (r.method) {
    case Method::Aco:
    case Method::Maco: {
      const AntParams& p = r.ant;
      require(p.ants >= 1, "ant.ants must be >= 1");
      require(p.alpha >= 0 && p.beta >= 0, "ant.alpha and ant.beta must be >= 0");
      require(p.rho >= 0 && p.rho <= 1, "ant.rho must be in [0, 1]");
      require(p.q > 0 && std::isfinite(p.q), "ant.q must be > 0");
      require(p.tau0 > 0 && std::isfinite(p.tau0), "ant.tau0 must be > 0");
      require(p.n > 0 && std::isfinite(p.n), "ant.n must be > 0");
      require(std::isfinite(p.theta) && std::isfinite(p.mu), "ant.theta and ant.mu must be finite");
      require(p.pheromone_resolution >= 1, "ant.pheromone_resolution must be >= 1");
      break;
    }
    case Method::Pso: {
      const PsoParams& p = r.pso;
      require(p.particles >= 1, "pso.particles must be >= 1");
      require(std::isfinite(p.inertia) && std::isfinite(p.cognitive) && std::isfinite(p.social),
              "pso coefficients must be finite");
      require(p.max_velocity > 0 && std::isfinite(p.max_velocity), "pso.max_velocity must be > 0");
      break;
    }
    case Method::Ga: {
      const GaParams& p = r.ga;
      require(p.population >= 2, "ga.population must be >= 2");
      require(p.tournament >= 1, "ga.tournament must be >= 1");
      require(p.crossover >= 0 && p.crossover <= 1, "ga.crossover must be in [0, 1]");
      require(!std::isnan(p.mutation) && p.mutation <= 1, "ga.mutation must be <= 1");
      break;
    }
    case Method::Exhaustive:
      break;
    case Method::Exact:
    case Method::SphereObb:
      throw ArgumentError("antcd::search: method '" + std::string(method_name(r.method)) +
                          "' is not a random search (expected aco, maco, pso, ga or exhaustive)");
  }
}

}  // namespace

SearchResult search(const FeatureSpace& space, const SearchRequest& request) {
  validate(request);
  const Scalar delta = request.delta < 0 ? space.delta : request.delta;
  SearchResult result;
  result.delta = delta;
  if (space.empty()) {
    result.stop = StopReason::EmptySpace;
    return result;
  }
  const bool needs_truth = request.stop.target_share > 0 || !request.progress_marks.empty();
  const std::uint64_t truth = !needs_truth                        ? 0
                              : request.stop.reference_count != 0 ? request.stop.reference_count
                                                                  : count_colliding(space, delta);
  std::uint64_t target = 0;
  if (request.stop.target_share > 0) {
    // A target of 0 (no colliding pair exists) cannot be met by finding pairs: the search runs to
    // its other limits and reports found = false.
    target = static_cast<std::uint64_t>(
        std::ceil(request.stop.target_share * static_cast<double>(truth)));
  }
  detail::Recorder rec(space, request, delta, target, result);
  rec.set_marks(request.progress_marks, truth);
  if (request.method == Method::Exhaustive) {
    rec.begin_run();
    detail::run_exhaustive(space, rec);
  } else {
    for (std::uint64_t run = 0; run <= request.restarts && !rec.stopped(); ++run) {
      rec.begin_run();
      // Run 0 uses the request's seed as it is; restarts get derived, unrelated streams.
      const std::uint64_t seed = run == 0 ? request.seed : mix_seed(request.seed + run);
      switch (request.method) {
        case Method::Aco:
          detail::run_colony(space, request, false, seed, rec);
          break;
        case Method::Maco:
          detail::run_colony(space, request, true, seed, rec);
          break;
        case Method::Pso:
          detail::run_pso(space, request, seed, rec);
          break;
        case Method::Ga:
          detail::run_ga(space, request, seed, rec);
          break;
        case Method::Exhaustive:
        case Method::Exact:
        case Method::SphereObb:  // refused by validate()
          break;
      }
    }
  }
  rec.finish();
  return result;
}

SearchResult random_collide(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, const SearchRequest& request,
                            const SamplingOptions& sampling) {
  validate(request);
  SamplingOptions options = sampling;
  if (request.delta >= 0) options.delta = request.delta;
  const FeatureSpace space = build_feature_space(a, pose_a, b, pose_b, options, request.seed);
  return search(space, request);
}

}  // namespace antcd
