// Random collision detection: time for ACO, MACO, PSO and GA to reach 20/40/60/80 % of the
// colliding feature pairs (the paper's "detection rate", Table 1), for 1000² ... 5000² feature
// pairs, against exhaustive enumeration of the same space measured in the same run.
//
// Scene: two boxes with finely tessellated faces (100 x 100 quads per face, 60 000 triangles
// each), B resting on A's top face, turned 0.3 rad about the vertical and shifted: a large flat
// resting contact. The Sphere-OBB traversal keeps about 20 000 candidate triangles per side; the
// feature space samples 1000 ... 5000 of them per side (seed 1) in leaf order.
//
// Each benchmark iteration is one search with its own seed (0, 1, 2, ...), run until 80 % of the
// space's colliding pairs are found or 2 x (number of feature pairs) fitness evaluations are spent,
// restarting the N = 100 iteration run as often as needed (SearchRequest::restarts). Between
// iterations, with the timer paused, the space is enumerated exhaustively once: both are timed
// under the same machine load.
//
// Counters (medians over the seeds; a mark not reached counts as +inf, so the median is inf when
// at least half the seeds missed it):
//   tN_ms   wall time until N % of the colliding pairs were found (t1st_ms: the first one)
//   xN      tN_ms / exh_ms: time relative to a full exhaustive enumeration (< 1: faster)
//   reachN  share of the seeds that reached N %
//   eN      fitness evaluations until N % were found (machine-independent)
//   exh_ms  median time of the full exhaustive enumeration
//   evals   median evaluations per search; pairs, colliding: the space
// The Exhaustive rows' tN_ms are the times at which the row-by-row enumeration passed each mark.
// The MACO-without-k / MACO-only-k / MACO-corridor / MACO-greedy rows (2000² pairs) are the
// ablation of the MACO switches (shared/maco_ablation.hpp).
//
// Cost/... rows: the price of one evaluation, apart from how good the search is. On the 5000²
// space, under the paper-centroid verdict with a centroid threshold no pair meets (so no hit is
// recorded and no witness test runs), Cost/exhaustive scans the whole space and Cost/aco and
// Cost/maco run a fixed budget of evaluations. Counters:
//   ns_per_eval   thread CPU time / evaluations (exhaustive: per centroid distance); CPU time,
//                 not wall time, so that waiting for a core on a shared machine is not counted
//   wall_ns       the same with wall time
//   overhead_ns   ns_per_eval minus the exhaustive scan's ns per distance measured in the same
//                 benchmark (interleaved): what the colony adds per evaluated candidate
// Targets: exhaustive <= 1 ns per distance, colony overhead <= 10 ns.
#include <antcd/random.hpp>

#include "shared/maco_ablation.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace {

using namespace antcd;

struct Scene {
  Model a{make_box(Vec3(1, 1, 1), 100), BuildOptions{}, "box-a"};
  Model b{make_box(Vec3(1, 1, 1), 100), BuildOptions{}, "box-b"};
  Transform pose_a = Transform::identity();
  Transform pose_b = Transform::from_axis_angle(Vec3::UnitZ(), 0.3, Vec3(0.31, 0.17, 2.0));
};

const Scene& scene() {
  static const Scene s;
  return s;
}

struct Space {
  FeatureSpace space;
  std::uint64_t colliding = 0;
};

const Space& space_for(std::uint32_t samples) {
  static std::mutex mutex;
  static std::map<std::uint32_t, Space> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find(samples);
  if (it == cache.end()) {
    const Scene& s = scene();
    SamplingOptions options;
    options.triangle_masks = false;  // the paper's leaf pairs, as in antcd bench paper
    options.samples_per_side = samples;
    Space sp;
    sp.space = build_feature_space(s.a, s.pose_a, s.b, s.pose_b, options, 1);
    sp.colliding = count_colliding(sp.space);
    it = cache.emplace(samples, std::move(sp)).first;
  }
  return it->second;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double exhaustive_ms(const FeatureSpace& space) {
  SearchRequest r;
  r.method = Method::Exhaustive;
  const auto t0 = std::chrono::steady_clock::now();
  const SearchResult res = search(space, r);
  benchmark::DoNotOptimize(res.hits.data());
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void set_space_counters(benchmark::State& state, const Space& sp) {
  state.counters["pairs"] = static_cast<double>(sp.space.cells());
  state.counters["colliding"] = static_cast<double>(sp.colliding);
  state.counters["cand_a"] = static_cast<double>(sp.space.candidates_a);
  state.counters["cand_b"] = static_cast<double>(sp.space.candidates_b);
}

constexpr std::array<const char*, 5> kMarkNames = {"1st", "20", "40", "60", "80"};
// 1e-12 of the truth rounds up to one pair: the first hit.
const std::vector<double> kMarks = {1e-12, 0.2, 0.4, 0.6, 0.8};

// The full enumeration (the reference), and as a side result the times at which a row-by-row
// enumeration passes each mark (what an exhaustive search stopping at that rate would cost).
void bm_exhaustive(benchmark::State& state, std::uint32_t samples) {
  const Space& sp = space_for(samples);
  SearchRequest r;
  r.method = Method::Exhaustive;
  r.stop.reference_count = sp.colliding;
  r.progress_marks = kMarks;
  std::array<std::vector<double>, 5> mark_ms;
  for (auto _ : state) {
    const SearchResult res = search(sp.space, r);
    benchmark::DoNotOptimize(res.hits.data());
    for (std::size_t k = 0; k < kMarks.size(); ++k)
      mark_ms[k].push_back(res.progress[k].seconds * 1e3);
  }
  for (std::size_t k = 0; k < kMarks.size(); ++k) {
    state.counters[std::string("t") + kMarkNames[k] + "_ms"] = median(mark_ms[k]);
  }
  set_space_counters(state, sp);
}

void bm_search(benchmark::State& state, Method method, std::uint32_t samples,
               MacoSwitches switches) {
  const Space& sp = space_for(samples);
  const auto& kNames = kMarkNames;
  SearchRequest r;
  r.method = method;
  r.ant.maco = switches;
  r.restarts = std::numeric_limits<std::uint32_t>::max();
  r.stop.max_evaluations = 2 * sp.space.cells();
  r.stop.target_share = 0.8;
  r.stop.reference_count = sp.colliding;
  r.progress_marks = kMarks;

  std::array<std::vector<double>, 5> mark_ms, mark_evals;
  std::array<int, 5> reached{};
  std::vector<double> reference_ms, evaluations;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    r.seed = seed++;
    const SearchResult res = search(sp.space, r);
    state.PauseTiming();
    for (std::size_t k = 0; k < kNames.size(); ++k) {
      const ProgressMark& m = res.progress[k];
      constexpr double kInf = std::numeric_limits<double>::infinity();
      mark_ms[k].push_back(m.reached ? m.seconds * 1e3 : kInf);
      mark_evals[k].push_back(m.reached ? static_cast<double>(m.evaluations) : kInf);
      reached[k] += m.reached ? 1 : 0;
    }
    evaluations.push_back(static_cast<double>(res.evaluations));
    reference_ms.push_back(exhaustive_ms(sp.space));
    state.ResumeTiming();
  }
  const double ref = median(reference_ms);
  const double runs = static_cast<double>(seed);
  for (std::size_t k = 0; k < kNames.size(); ++k) {
    const double t = median(mark_ms[k]);
    state.counters[std::string("t") + kNames[k] + "_ms"] = t;
    state.counters[std::string("x") + kNames[k]] = t / ref;
    state.counters[std::string("reach") + kNames[k]] = reached[k] / runs;
    state.counters[std::string("e") + kNames[k]] = median(mark_evals[k]);
  }
  state.counters["exh_ms"] = ref;
  state.counters["evals"] = median(evaluations);
  set_space_counters(state, sp);
}

// The cost rows' search request: nothing collides, so every evaluation is a plain one.
SearchRequest cost_request(Method method) {
  SearchRequest r;
  r.method = method;
  r.verdict = Verdict::PaperCentroid;
  r.centroid_delta = 1e-12;
  r.restarts = std::numeric_limits<std::uint32_t>::max();
  return r;
}

double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

double exhaustive_ns_per_distance(const FeatureSpace& space) {
  const SearchRequest r = cost_request(Method::Exhaustive);
  const double t0 = thread_cpu_ns();
  const SearchResult res = search(space, r);
  const double ns = thread_cpu_ns() - t0;
  benchmark::DoNotOptimize(res.evaluations);
  return ns / static_cast<double>(res.evaluations);
}

void bm_cost(benchmark::State& state, Method method) {
  const Space& sp = space_for(5000);
  SearchRequest r = cost_request(method);
  constexpr std::uint64_t kBudget = 4'000'000;
  r.stop.max_evaluations = kBudget;
  std::vector<double> per_eval, wall, reference;
  std::uint64_t seed = 0;
  std::uint64_t total = 0;
  for (auto _ : state) {
    r.seed = seed++;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_ns();
    const SearchResult res = search(sp.space, r);
    const double ns = thread_cpu_ns() - c0;
    const double wall_ns =
        std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
    if (!res.hits.empty()) state.SkipWithError("a cost row must record no hit");
    total += res.evaluations;
    per_eval.push_back(ns / static_cast<double>(res.evaluations));
    wall.push_back(wall_ns / static_cast<double>(res.evaluations));
    state.PauseTiming();
    reference.push_back(exhaustive_ns_per_distance(sp.space));
    state.ResumeTiming();
  }
  const double mine = median(per_eval);
  state.counters["ns_per_eval"] = mine;
  state.counters["wall_ns"] = median(wall);
  if (method != Method::Exhaustive) state.counters["overhead_ns"] = mine - median(reference);
  state.counters["exh_ns"] = median(reference);
  state.SetItemsProcessed(static_cast<std::int64_t>(total));
  set_space_counters(state, sp);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  for (const Method m : {Method::Exhaustive, Method::Aco, Method::Maco}) {
    benchmark::RegisterBenchmark(("Cost/" + std::string(method_name(m))).c_str(), bm_cost, m)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(7);
  }
  const std::uint32_t sizes[] = {1000, 2000, 3000, 4000, 5000};
  for (const std::uint32_t n : sizes) {
    benchmark::RegisterBenchmark(("Exhaustive/samples:" + std::to_string(n)).c_str(), bm_exhaustive,
                                 n)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(5);
    for (const Method m : {Method::Aco, Method::Maco, Method::Pso, Method::Ga}) {
      const std::string name = std::string(method_label(m)) + "/samples:" + std::to_string(n);
      benchmark::RegisterBenchmark(name.c_str(), bm_search, m, n, MacoSwitches{})
          ->Unit(benchmark::kMillisecond)
          ->Iterations(5);
    }
  }
  // Ablation of the MACO switches (shared/maco_ablation.hpp, the list `antcd bench paper` runs
  // too), at 2000² pairs.
  for (const shared::MacoVariant& v : shared::maco_ablation()) {
    benchmark::RegisterBenchmark((std::string(v.label) + "/samples:2000").c_str(), bm_search,
                                 Method::Maco, 2000u, v.switches)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(5);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
