// search() and random_collide(): request validation, the memory's witnesses, then dispatch to one
// engine; confirm_witnesses() and proves_separate().
#include <antcd/error.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bvh/traverse.hpp"
#include "random/engines.hpp"
#include "util/check.hpp"

namespace antcd {
namespace {

// A condition the helpers of util/check.hpp do not cover; the same message format.
void require(bool ok, const char* caller, const char* argument, const char* requirement) {
  if (!ok) detail::argument_error(caller, argument, requirement, "another value");
}

}  // namespace

void detail::validate_search(const SearchRequest& r, const char* caller) {
  if (r.centroid_delta) detail::require_positive(caller, "centroid_delta", *r.centroid_delta);
  detail::require_at_least(caller, "iterations", r.iterations, 1);
  require(r.verdict == Verdict::Witness || r.verdict == Verdict::PaperCentroid, caller, "verdict",
          "Witness or PaperCentroid");
  const StopCriteria& s = r.stop;
  detail::require_in_range(caller, "stop.target_share", s.target_share, 0, 1, false, "[0, 1]");
  detail::require_bound(caller, "stop.max_seconds", s.max_seconds);
  for (const double mark : r.progress_marks) {
    if (!(mark > 0 && mark <= 1)) {
      detail::argument_error(caller, "progress_marks", "in (0, 1]", number_text(mark));
    }
  }
  switch (r.method) {
    case Method::Aco:
    case Method::Maco: {
      const AntParams& p = r.ant;
      detail::require_at_least(caller, "ant.ants", p.ants, 1);
      detail::require_non_negative(caller, "ant.alpha", p.alpha);
      detail::require_non_negative(caller, "ant.beta", p.beta);
      detail::require_in_range(caller, "ant.rho", p.rho, 0, 1, false, "[0, 1]");
      detail::require_positive(caller, "ant.q", p.q);
      detail::require_positive(caller, "ant.tau0", p.tau0);
      detail::require_positive(caller, "ant.n", p.n);
      detail::require_finite(caller, "ant.theta", p.theta);
      detail::require_finite(caller, "ant.mu", p.mu);
      detail::require_at_least(caller, "ant.pheromone_resolution", p.pheromone_resolution, 1);
      require(p.start == AntStart::LeafPairs || p.start == AntStart::Uniform, caller, "ant.start",
              "LeafPairs or Uniform");
      break;
    }
    case Method::Pso: {
      const PsoParams& p = r.pso;
      detail::require_at_least(caller, "pso.particles", p.particles, 1);
      detail::require_finite(caller, "pso.inertia", p.inertia);
      detail::require_finite(caller, "pso.cognitive", p.cognitive);
      detail::require_finite(caller, "pso.social", p.social);
      detail::require_positive(caller, "pso.max_velocity", p.max_velocity);
      break;
    }
    case Method::Ga: {
      const GaParams& p = r.ga;
      detail::require_at_least(caller, "ga.population", p.population, 2);
      detail::require_at_least(caller, "ga.tournament", p.tournament, 1);
      detail::require_in_range(caller, "ga.crossover", p.crossover, 0, 1, false, "[0, 1]");
      if (!(p.mutation <= 1)) {
        detail::argument_error(caller, "ga.mutation", "<= 1 (negative: automatic)",
                               number_text(p.mutation));
      }
      break;
    }
    case Method::Exhaustive:
    case Method::Grid:
      break;
    case Method::Exact:
    case Method::SphereObb:
      throw ArgumentError(std::string(caller) + ": method '" + std::string(method_name(r.method)) +
                          "' is not a random search (expected aco, maco, pso, ga, exhaustive or "
                          "grid)");
  }
}

namespace {

/// The cells of the space that hold one of the memory's witnesses.
std::vector<std::pair<std::uint32_t, std::uint32_t>> witness_cells(const FeatureSpace& space,
                                                                   const ColonyMemory& memory) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> cells;
  if (memory.witnesses.empty()) return cells;
  auto index = [](const FeatureSide& side) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> by_position(side.size());
    for (std::uint32_t k = 0; k < side.size(); ++k) by_position[k] = {side.position[k], k};
    std::sort(by_position.begin(), by_position.end());
    return by_position;
  };
  const auto ia = index(space.a);
  const auto ib = index(space.b);
  auto find = [](const auto& by_position, std::uint32_t p) -> std::int64_t {
    auto it = std::lower_bound(by_position.begin(), by_position.end(),
                               std::pair<std::uint32_t, std::uint32_t>{p, 0});
    return it != by_position.end() && it->first == p ? std::int64_t{it->second} : -1;
  };
  for (const auto& [pa, pb] : memory.witnesses) {
    const std::int64_t i = find(ia, pa);
    const std::int64_t j = find(ib, pb);
    if (i >= 0 && j >= 0) {
      cells.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    }
  }
  return cells;
}

void remember_witnesses(const FeatureSpace& space, const SearchResult& result,
                        ColonyMemory& memory) {
  memory.witnesses.clear();
  for (const FeaturePair& h : result.hits) {
    if (memory.witnesses.size() == ColonyMemory::kMaxWitnesses) break;
    memory.witnesses.emplace_back(space.a.position[h.i], space.b.position[h.j]);
  }
}

/// A leaf-order triangle of one model, in the frame of the witness test: vertices, centroid and
/// circumradius about it.
struct FrameTriangle {
  Vec3 v[3];
  Vec3 centroid;
  Scalar radius = 0;
};

FrameTriangle frame_triangle(const Model& model, const Transform& to_frame,
                             std::uint32_t position) {
  const LeafCorners verts = model.leaf_corners();
  FrameTriangle t;
  for (int k = 0; k < 3; ++k) t.v[k] = to_frame.apply(verts(std::size_t{position}, k));
  t.centroid = (t.v[0] + t.v[1] + t.v[2]) / 3;
  Scalar r2 = 0;
  for (const Vec3& v : t.v) r2 = std::max(r2, (v - t.centroid).squaredNorm());
  t.radius = std::sqrt(r2);
  return t;
}

bool within(const FrameTriangle& ta, const FrameTriangle& tb, Scalar delta) {
  return geometry::triangles_within(ta.v[0], ta.v[1], ta.v[2], tb.v[0], tb.v[1], tb.v[2], delta);
}

}  // namespace

SearchResult search(const FeatureSpace& space, const SearchRequest& request, ColonyMemory* memory) {
  detail::validate_search(request);
  SearchResult result;
  const detail::Thresholds t =
      detail::thresholds(space, request.verdict, request.centroid_delta, "antcd::search");
  result.verdict = t.verdict;
  result.centroid_delta = t.centroid;
  if (space.empty()) {
    result.stop = StopReason::EmptySpace;
    return result;
  }
  const bool needs_truth = request.stop.target_share > 0 || !request.progress_marks.empty();
  const std::uint64_t truth = !needs_truth ? 0
                              : request.stop.reference_count != 0
                                  ? request.stop.reference_count
                                  : count_colliding(space, request.verdict, request.centroid_delta);
  std::uint64_t target = 0;
  if (request.stop.target_share > 0) {
    // A target of 0 (no colliding pair exists) cannot be met by finding pairs: the search runs to
    // its other limits and reports found = false.
    target = static_cast<std::uint64_t>(
        std::ceil(request.stop.target_share * static_cast<double>(truth)));
  }
  detail::Recorder rec(space, request, t, target, result);
  rec.set_marks(request.progress_marks, truth);
  const bool colony = request.method == Method::Aco || request.method == Method::Maco;
  ColonyMemory scratch;
  ColonyMemory& mem = memory != nullptr && colony ? *memory : scratch;
  // Temporal coherence: last search's witnesses first.
  const auto remembered = witness_cells(space, mem);
  // A budget that covers the space (and the witnesses' evaluations): the complete scan is the
  // cheaper search.
  const bool covered = colony && request.ant.scan_covered_spaces && request.stop.first_hit &&
                       !needs_truth && request.stop.max_evaluations > 0 &&
                       space.leaf_pair_cells() + remembered.size() < request.stop.max_evaluations;
  result.scanned =
      covered || request.method == Method::Exhaustive || request.method == Method::Grid;
  for (const auto& [i, j] : remembered) {
    rec.evaluate(i, j);
    if (rec.stopped()) break;
  }
  if (covered) {
    rec.begin_run();
    if (!rec.stopped()) detail::run_leaf_pair_scan(space, rec);
  } else if (request.method == Method::Exhaustive) {
    rec.begin_run();
    if (!rec.stopped()) detail::run_exhaustive(space, rec);
  } else if (request.method == Method::Grid) {
    rec.begin_run();
    if (!rec.stopped()) detail::run_grid(space, rec);
  } else {
    for (std::uint64_t run = 0; run <= request.restarts && !rec.stopped(); ++run) {
      rec.begin_run();
      // Run 0 uses the request's seed as it is; restarts get derived, unrelated streams.
      const std::uint64_t seed = run == 0 ? request.seed : mix_seed(request.seed + run);
      switch (request.method) {
        case Method::Aco:
          detail::run_colony(space, request, false, seed, mem, rec);
          break;
        case Method::Maco:
          detail::run_colony(space, request, true, seed, mem, rec);
          break;
        case Method::Pso:
          detail::run_pso(space, request, seed, rec);
          break;
        case Method::Ga:
          detail::run_ga(space, request, seed, rec);
          break;
        default:
          break;
      }
    }
  }
  rec.finish();
  if (memory != nullptr && colony) remember_witnesses(space, result, *memory);
  return result;
}

WitnessCheck confirm_witnesses(const Model& a, const Transform& pose_a, const Model& b,
                               const Transform& pose_b, Scalar delta, ColonyMemory& memory,
                               bool stop_at_first, std::uint32_t neighbourhood) {
  detail::require_non_negative("confirm_witnesses", "delta", delta);
  WitnessCheck check;
  auto& w = memory.witnesses;
  const auto na = static_cast<std::uint32_t>(a.leaf_triangles().size());
  const auto nb = static_cast<std::uint32_t>(b.leaf_triangles().size());
  // In A's frame with B mapped into it, as collide() and the feature spaces test.
  const Transform b_to_a = detail::relative_pose(pose_a, pose_b);
  const Transform identity = Transform::identity();
  std::size_t valid = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto [pa, pb] = w[k];
    if (pa >= na || pb >= nb) continue;
    ++check.tests;
    if (!within(frame_triangle(a, identity, pa), frame_triangle(b, b_to_a, pb), delta)) continue;
    std::swap(w[valid], w[k]);
    ++valid;
    if (stop_at_first) {
      check.valid = valid;
      return check;  // the rest stay, untested
    }
  }
  if (valid == 0 && neighbourhood > 0 && !w.empty()) {
    // The contact may have slid to a neighbouring triangle: scan each witness's neighbourhood in
    // leaf order (what an ant's unit moves reach) with the reach filter, then the exact test.
    std::vector<FrameTriangle> side_a, side_b;
    const auto remembered = w;  // w grows as pairs are found
    for (const auto& [pa, pb] : remembered) {
      if (pa >= na || pb >= nb) continue;
      const std::uint32_t a0 = pa > neighbourhood ? pa - neighbourhood : 0;
      const std::uint32_t a1 = std::min(na - 1, pa + neighbourhood);
      const std::uint32_t b0 = pb > neighbourhood ? pb - neighbourhood : 0;
      const std::uint32_t b1 = std::min(nb - 1, pb + neighbourhood);
      side_a.clear();
      side_b.clear();
      for (std::uint32_t p = a0; p <= a1; ++p) side_a.push_back(frame_triangle(a, identity, p));
      for (std::uint32_t p = b0; p <= b1; ++p) side_b.push_back(frame_triangle(b, b_to_a, p));
      for (std::uint32_t i = 0; i < side_a.size(); ++i) {
        for (std::uint32_t j = 0; j < side_b.size(); ++j) {
          ++check.evaluations;
          const Scalar reach = side_a[i].radius + side_b[j].radius + delta;
          if ((side_a[i].centroid - side_b[j].centroid).squaredNorm() > reach * reach) continue;
          ++check.tests;
          if (!within(side_a[i], side_b[j], delta)) continue;
          w.insert(w.begin() + static_cast<std::ptrdiff_t>(valid), {a0 + i, b0 + j});
          ++valid;
          if (stop_at_first) {
            check.valid = valid;
            return check;
          }
        }
      }
    }
  }
  // Every remembered witness was tested (and their neighbourhoods scanned): keep the valid ones.
  w.resize(valid);
  check.valid = valid;
  return check;
}

bool proves_separate(const FeatureSpace& space, const SearchResult& result) {
  return !result.found && result.verdict == Verdict::Witness && result.scanned &&
         result.stop == StopReason::Iterations && space.complete &&
         space.candidates_a == space.a.size() && space.candidates_b == space.b.size();
}

SearchResult random_collide(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, const SearchRequest& request,
                            const SamplingOptions& sampling) {
  detail::validate_search(request);
  const FeatureSpace space = build_feature_space(a, pose_a, b, pose_b, sampling, request.seed);
  return search(space, request);
}

}  // namespace antcd
