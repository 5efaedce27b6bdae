// bench/ccd_bench.cpp — continuous collision detection: primitive queries, mesh sweeps against the
// discrete boolean collide() at the end pose, and FCL's continuousCollide on the same motions.
//
// Primitives (ccd_primitive/<set>): the degenerate corpus and 2000 random near misses per kind of
// tests/ccd (exact_truth.cpp, linked here for its query generators), and 4000 generic queries
// (random corners and motions, mostly apart). Each query is timed alone
// (200 repetitions, mean); the counters give the median and 90th percentile over the queries, in
// microseconds, and (corpus and near misses) the false negatives / positives against the exact
// truth; the benchmark loop runs the whole set.
//
// Wang et al.'s Erleben queries (ccd_erleben/<set>, the part stored in tests/ccd/data/erleben):
// ns_per_query the mean over the benchmark loop, median_ns the median over the queries of each
// query's median time (see ccd_erleben below), and the false positives / negatives against the
// files' truth.
//
// Mesh sweeps (sweep/<pair>, collide_end/<pair>, fcl_ca/<pair>): 16 seeded motions per pair, A
// passing by or through B (which turns a little) while turning up to 2.5 rad, half of them
// touching. sweep runs antcd::sweep on every motion, sweep_touching on the touching ones;
// collide_end the boolean collide() of the same pair at the end poses (here the end poses are
// apart, so it is a root-level rejection); collide_at_contact the boolean collide() at each
// touching motion's first sub-stepped contact (a discrete check where it works: it stops at the
// first overlapping triangle pair); collide_near_contact the boolean collide() just before that
// contact, the surfaces 1e-3 of A's radius apart (a discrete check that must prove them apart, as
// a sweep must before its toi); frame_sweep / frame_collide the sweep of a frame-sized piece (a
// twentieth) of each touching motion ending just before its contact (/0) or at it (/1), and the
// boolean collide() at that frame's end pose (the per-frame discrete check of the same frame);
// fcl_ca FCL's continuousCollide (conservative advancement, RSS, CCDM_LINEAR interpolation = the
// same motion: linear translation, constant angular velocity about the model origin, toc_err
// 1e-6, 1000 iterations). Before timing every motion's first contact is found by 1000-step dense
// sub-stepping with exact collide(); the counters of fcl_ca count FCL's misses (no contact
// reported where sub-stepping finds one) and late answers (time of contact after the sub-stepped
// one), those of sweep the same for antcd (both must be 0); sweep's iterations counts its interval
// tests, distance queries and traversals (SweepResult::iterations) per motion.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "ccd/erleben_queries.hpp"
#include "ccd/exact_truth.hpp"

#ifdef ANTCD_BENCH_FCL
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "peers/adapters/fcl.hpp"
#include "peers/adapters/peer_mesh.hpp"
#endif

namespace {

using antcd::Scalar;
using antcd::Transform;
using antcd::Vec3;
using antcd::test::CcdKind;
using antcd::test::CcdQuery;

// ---- primitives ---------------------------------------------------------------------------

/// Generic queries: corners uniform in [-1, 1]^3, each moving by up to 0.25 per axis, half vf,
/// half ee (most are far apart: the easy bulk of a simulation's queries).
std::vector<CcdQuery> generic_queries(std::size_t count) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::vector<CcdQuery> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    out[i].kind = i % 2 == 0 ? CcdKind::VertexFace : CcdKind::EdgeEdge;
    for (std::size_t k = 0; k < 4; ++k) {
      out[i].at_t0[k] = Vec3(unit(rng), unit(rng), unit(rng));
      out[i].at_t1[k] = out[i].at_t0[k] + 0.25 * Vec3(unit(rng), unit(rng), unit(rng));
    }
  }
  return out;
}

std::vector<CcdQuery> primitive_set(int which) {
  if (which == 0) return antcd::test::degenerate_corpus();
  if (which == 3) return generic_queries(4000);
  return antcd::test::near_miss_queries(which == 1 ? CcdKind::VertexFace : CcdKind::EdgeEdge, 2000,
                                        which);
}

bool run_query(const CcdQuery& q) {
  return q.kind == CcdKind::VertexFace ? antcd::ccd::vertex_face(q.at_t0, q.at_t1).hit
                                       : antcd::ccd::edge_edge(q.at_t0, q.at_t1).hit;
}

void ccd_primitive(benchmark::State& state) {
  const auto queries = primitive_set(static_cast<int>(state.range(0)));
  std::vector<double> per_query;
  per_query.reserve(queries.size());
  for (const CcdQuery& q : queries) {
    constexpr int kReps = 200;
    const auto start = std::chrono::steady_clock::now();
    int hits = 0;
    for (int r = 0; r < kReps; ++r) hits += run_query(q) ? 1 : 0;
    benchmark::DoNotOptimize(hits);
    per_query.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count() /
        kReps);
  }
  std::sort(per_query.begin(), per_query.end());
  for (auto _ : state) {
    int hits = 0;
    for (const CcdQuery& q : queries) hits += run_query(q) ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  state.counters["queries"] = static_cast<double>(queries.size());
  state.counters["median_us"] = per_query[per_query.size() / 2];
  state.counters["p90_us"] = per_query[per_query.size() * 9 / 10];
  state.counters["max_us"] = per_query.back();
  const char* labels[] = {"degenerate corpus", "vf near misses", "ee near misses", "generic"};
  state.SetLabel(labels[state.range(0)]);
  int hits = 0;
  int false_negatives = 0;
  int false_positives = 0;
  for (const CcdQuery& q : queries) {
    const bool hit = run_query(q);
    hits += hit ? 1 : 0;
    if (const auto truth = antcd::test::ccd_truth(q); truth && *truth != hit) {
      (*truth ? false_negatives : false_positives) += 1;
    }
  }
  state.counters["hits"] = hits;
  if (state.range(0) != 3) {  // the generic queries' motions have no exact truth here
    state.counters["false_neg"] = false_negatives;
    state.counters["false_pos"] = false_positives;
  }
}
BENCHMARK(ccd_primitive)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

/// Wang et al.'s Erleben queries as stored in tests/ccd/data/erleben (its README: which part of
/// the set): /0 all of them, /1 the vertex–face ones, /2 the edge–edge ones.
std::vector<antcd::test::RationalQuery> erleben_set(int which) {
  std::vector<antcd::test::RationalQuery> out;
  for (const auto& f : antcd::test::load_erleben(ANTCD_ERLEBEN_DATA)) {
    if (which == 0 || (which == 1) == (f.kind == CcdKind::VertexFace)) {
      out.insert(out.end(), f.queries.begin(), f.queries.end());
    }
  }
  return out;
}

// The benchmark loop runs every query once per iteration: ns_per_query is the mean over the set.
// median_ns: each query alone, 7 rounds of 50 back-to-back calls; a query's time is the median
// of its 7 round means, and median_ns the median of those over the queries (p90_ns, max_ns
// likewise). false_pos / false_neg against the files' truth (the same counts as
// tests/ccd/erleben_test.cpp).
void ccd_erleben(benchmark::State& state) {
  const auto set = erleben_set(static_cast<int>(state.range(0)));
  std::vector<double> per_query;
  per_query.reserve(set.size());
  for (const auto& rq : set) {
    constexpr int kRounds = 7, kReps = 50;
    std::array<double, kRounds> rounds{};
    for (double& round : rounds) {
      const auto start = std::chrono::steady_clock::now();
      int hits = 0;
      for (int r = 0; r < kReps; ++r) hits += run_query(rq.query) ? 1 : 0;
      benchmark::DoNotOptimize(hits);
      round = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start)
                  .count() /
              kReps;
    }
    std::nth_element(rounds.begin(), rounds.begin() + kRounds / 2, rounds.end());
    per_query.push_back(rounds[kRounds / 2]);
  }
  std::sort(per_query.begin(), per_query.end());
  for (auto _ : state) {
    int hits = 0;
    for (const auto& rq : set) hits += run_query(rq.query) ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  int false_negatives = 0, false_positives = 0, negatives = 0;
  for (const auto& rq : set) {
    const bool hit = run_query(rq.query);
    negatives += rq.truth ? 0 : 1;
    false_negatives += rq.truth && !hit ? 1 : 0;
    false_positives += !rq.truth && hit ? 1 : 0;
  }
  state.counters["queries"] = static_cast<double>(set.size());
  state.counters["ns_per_query"] = benchmark::Counter(
      static_cast<double>(set.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["median_ns"] = per_query[per_query.size() / 2];
  state.counters["p90_ns"] = per_query[per_query.size() * 9 / 10];
  state.counters["max_ns"] = per_query.back();
  state.counters["negatives"] = negatives;
  state.counters["false_pos"] = false_positives;
  state.counters["false_neg"] = false_negatives;
  const char* labels[] = {"erleben all", "erleben vf", "erleben ee"};
  state.SetLabel(labels[state.range(0)]);
}
BENCHMARK(ccd_erleben)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// ---- mesh sweeps --------------------------------------------------------------------------

struct Motion {
  Transform a0, a1, b0, b1;
  std::optional<Scalar> first;  // dense sub-stepping's first contact
  /// When touching: the latest time on a 1e-4 grid before `first` at which distance() finds the
  /// surfaces more than 1e-3 of A's root radius apart.
  std::optional<Scalar> near;
};

struct Pair {
  std::string name;
  std::unique_ptr<antcd::Model> a, b;
  std::vector<Motion> motions;
};

std::optional<Scalar> dense_first(const Pair& p, const Motion& m) {
  antcd::CollisionResult res;
  for (int k = 0; k <= 1000; ++k) {
    const Scalar t = k / 1000.0;
    if (antcd::collide(*p.a, antcd::ccd::interpolate_pose(m.a0, m.a1, t), *p.b,
                       antcd::ccd::interpolate_pose(m.b0, m.b1, t), {}, res)) {
      return t;
    }
  }
  return std::nullopt;
}

Pair make_pair(int which) {
  Pair p;
  if (which == 0) {
    p.name = "torus10k_sphere5k";
    p.a = std::make_unique<antcd::Model>(antcd::make_torus(1.0, 0.3, 100, 50),
                                         antcd::BuildOptions{}, "torus");
    p.b = std::make_unique<antcd::Model>(antcd::make_sphere(0.8, 72, 36), antcd::BuildOptions{},
                                         "sphere");
  } else {
    p.name = "sheet_sheet_thin";
    p.a = std::make_unique<antcd::Model>(antcd::make_box({1, 1, 0.005}, 8), antcd::BuildOptions{},
                                         "sheet_a");
    p.b = std::make_unique<antcd::Model>(antcd::make_box({1, 1, 0.005}, 8), antcd::BuildOptions{},
                                         "sheet_b");
  }
  std::mt19937_64 rng(100 + static_cast<std::uint64_t>(which));
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const Scalar reach = p.a->root().radius + p.b->root().radius + 0.5;
  for (int i = 0; i < 16; ++i) {
    Motion m;
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    // Half the motions pass through B's middle, half well off to one side.
    const Vec3 side = Vec3(unit(rng), unit(rng), unit(rng)).cross(dir).normalized() *
                      (i % 2 == 0 ? 0.2 : 0.8) * reach;
    const Transform turn0 =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 3 * unit(rng));
    m.a0 = turn0;
    m.a0.translation = -reach * dir + side;
    m.a1 =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 2.5 * unit(rng)) * turn0;
    m.a1.translation = reach * dir + side;
    m.b0 = Transform::identity();
    m.b1 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 0.3);
    m.first = dense_first(p, m);
    const Scalar gap = 1e-3 * p.a->root().radius;
    for (Scalar t = m.first.value_or(-1); t >= 0; t -= 1e-4) {
      if (antcd::distance(*p.a, antcd::ccd::interpolate_pose(m.a0, m.a1, t), *p.b,
                          antcd::ccd::interpolate_pose(m.b0, m.b1, t))
              .distance > gap) {
        m.near = t;
        break;
      }
    }
    p.motions.push_back(m);
  }
  return p;
}

const Pair& pair(int which) {
  static std::vector<std::unique_ptr<Pair>> pairs(2);
  auto& slot = pairs[static_cast<std::size_t>(which)];
  if (!slot) slot = std::make_unique<Pair>(make_pair(which));
  return *slot;
}

void sweep(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  int misses = 0, late = 0, hits = 0, touching = 0, decided = 0;
  double iterations = 0;
  for (const Motion& m : p.motions) {
    const auto r = antcd::sweep(*p.a, m.a0, m.a1, *p.b, m.b0, m.b1);
    hits += r.hit ? 1 : 0;
    touching += m.first ? 1 : 0;
    misses += m.first && !r.hit ? 1 : 0;
    late += m.first && r.hit && r.toi > *m.first ? 1 : 0;
    decided += r.tolerance_decided ? 1 : 0;
    iterations += r.iterations;
  }
  for (auto _ : state) {
    for (const Motion& m : p.motions) {
      benchmark::DoNotOptimize(antcd::sweep(*p.a, m.a0, m.a1, *p.b, m.b0, m.b1).toi);
    }
  }
  state.counters["per_motion"] = benchmark::Counter(
      static_cast<double>(p.motions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["touching"] = touching;
  state.counters["hits"] = hits;
  state.counters["misses"] = misses;
  state.counters["late"] = late;
  state.counters["tolerance_decided"] = decided;
  state.counters["iterations"] = iterations / static_cast<double>(p.motions.size());
  state.SetLabel(p.name);
}
BENCHMARK(sweep)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// sweep on the touching motions alone: the same set as collide_at_contact and
/// collide_near_contact, for their ratios.
void sweep_touching(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  std::vector<const Motion*> touching;
  for (const Motion& m : p.motions) {
    if (m.first) touching.push_back(&m);
  }
  for (auto _ : state) {
    for (const Motion* m : touching) {
      benchmark::DoNotOptimize(antcd::sweep(*p.a, m->a0, m->a1, *p.b, m->b0, m->b1).toi);
    }
  }
  state.counters["per_motion"] = benchmark::Counter(
      static_cast<double>(touching.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(p.name);
}
BENCHMARK(sweep_touching)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void collide_end(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  antcd::CollisionResult res;
  for (auto _ : state) {
    for (const Motion& m : p.motions) {
      benchmark::DoNotOptimize(antcd::collide(*p.a, m.a1, *p.b, m.b1, {}, res));
    }
  }
  state.counters["per_motion"] = benchmark::Counter(
      static_cast<double>(p.motions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(p.name);
}
BENCHMARK(collide_end)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// Times the boolean collide() of the pair at each of `poses`; `per` names the counter of the
/// time per pose.
void time_collides(benchmark::State& state, const Pair& p,
                   const std::vector<std::pair<Transform, Transform>>& poses, const char* per) {
  antcd::CollisionResult res;
  for (auto _ : state) {
    for (const auto& [pa, pb] : poses) {
      benchmark::DoNotOptimize(antcd::collide(*p.a, pa, *p.b, pb, {}, res));
    }
  }
  state.counters[per] = benchmark::Counter(
      static_cast<double>(poses.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(p.name);
}

/// The boolean collide() at each touching motion's first sub-stepped contact: a discrete check
/// of the same pair where it does its work (the end poses of these motions are far apart).
void collide_at_contact(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  std::vector<std::pair<Transform, Transform>> poses;
  for (const Motion& m : p.motions) {
    if (!m.first) continue;
    poses.emplace_back(antcd::ccd::interpolate_pose(m.a0, m.a1, *m.first),
                       antcd::ccd::interpolate_pose(m.b0, m.b1, *m.first));
  }
  time_collides(state, p, poses, "per_motion");
}
BENCHMARK(collide_at_contact)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// The boolean collide() of each touching motion just before its first contact, where the
/// surfaces are apart by 1e-3 of A's root radius (Motion::near): a discrete check that must prove
/// the pair apart near contact, as a sweep must at every time before its toi, against
/// collide_at_contact's early exit on the first overlapping triangle pair.
void collide_near_contact(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  std::vector<std::pair<Transform, Transform>> poses;
  for (const Motion& m : p.motions) {
    if (!m.near) continue;
    poses.emplace_back(antcd::ccd::interpolate_pose(m.a0, m.a1, *m.near),
                       antcd::ccd::interpolate_pose(m.b0, m.b1, *m.near));
  }
  time_collides(state, p, poses, "per_motion");
}
BENCHMARK(collide_near_contact)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// Frame-sized pieces of the touching motions, a twentieth of the motion each (A moves about a
/// fifth of its size): kind 0 the frame ending just before contact (Motion::near; the sweep
/// proves it free), 1 the frame ending at the sub-stepped contact (the sweep finds the toi). A
/// piece of a slerp is the slerp between its end poses, so the sweep sees the same motion.
std::vector<Motion> frames(const Pair& p, int kind) {
  std::vector<Motion> out;
  for (const Motion& m : p.motions) {
    if (!m.near) continue;
    const Scalar end = kind == 0 ? *m.near : *m.first;
    const Scalar start = std::max<Scalar>(0, end - 0.05);
    Motion f;
    f.a0 = antcd::ccd::interpolate_pose(m.a0, m.a1, start);
    f.a1 = antcd::ccd::interpolate_pose(m.a0, m.a1, end);
    f.b0 = antcd::ccd::interpolate_pose(m.b0, m.b1, start);
    f.b1 = antcd::ccd::interpolate_pose(m.b0, m.b1, end);
    out.push_back(f);
  }
  return out;
}

/// antcd::sweep over each frame (see frames()).
void frame_sweep(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  const std::vector<Motion> fs = frames(p, static_cast<int>(state.range(1)));
  int hits = 0;
  for (const Motion& f : fs) hits += antcd::sweep(*p.a, f.a0, f.a1, *p.b, f.b0, f.b1).hit ? 1 : 0;
  for (auto _ : state) {
    for (const Motion& f : fs) {
      benchmark::DoNotOptimize(antcd::sweep(*p.a, f.a0, f.a1, *p.b, f.b0, f.b1).toi);
    }
  }
  state.counters["per_frame"] = benchmark::Counter(
      static_cast<double>(fs.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["hits"] = hits;
  state.SetLabel(p.name);
}
BENCHMARK(frame_sweep)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

/// The boolean collide() at each frame's end pose: the discrete check of the same frame.
void frame_collide(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  std::vector<std::pair<Transform, Transform>> poses;
  for (const Motion& f : frames(p, static_cast<int>(state.range(1))))
    poses.emplace_back(f.a1, f.b1);
  time_collides(state, p, poses, "per_frame");
}
BENCHMARK(frame_collide)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

#ifdef ANTCD_BENCH_FCL
void fcl_ca(benchmark::State& state) {
  const Pair& p = pair(static_cast<int>(state.range(0)));
  using antcd::peers::to_fcl;
  const auto a = antcd::peers::build_fcl<fcl::RSSd>(antcd::peers::peer_mesh(p.a->mesh()));
  const auto b = antcd::peers::build_fcl<fcl::RSSd>(antcd::peers::peer_mesh(p.b->mesh()));
  const fcl::ContinuousCollisionRequestd request(1000, 1e-6, fcl::CCDM_LINEAR, fcl::GST_LIBCCD,
                                                 fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
  auto query = [&](const Motion& m) {
    fcl::ContinuousCollisionResultd result;
    fcl::continuousCollide(a.get(), to_fcl(m.a0), to_fcl(m.a1), b.get(), to_fcl(m.b0), to_fcl(m.b1),
                           request, result);
    return result;
  };
  int misses = 0, late = 0, hits = 0;
  for (const Motion& m : p.motions) {
    const auto r = query(m);
    hits += r.is_collide ? 1 : 0;
    misses += m.first && !r.is_collide ? 1 : 0;
    late += m.first && r.is_collide && r.time_of_contact > *m.first ? 1 : 0;
  }
  for (auto _ : state) {
    for (const Motion& m : p.motions) benchmark::DoNotOptimize(query(m).time_of_contact);
  }
  state.counters["per_motion"] = benchmark::Counter(
      static_cast<double>(p.motions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["hits"] = hits;
  state.counters["misses"] = misses;
  state.counters["late"] = late;
  state.SetLabel(p.name);
}
BENCHMARK(fcl_ca)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
#endif

}  // namespace

BENCHMARK_MAIN();
