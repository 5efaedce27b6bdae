// bench/penetration_bench.cpp — antcd::penetration, convex and general.
//
// Convex: pairs of UV spheres (convex polytopes) of 24, 120, 528 and 2208 triangles at 32
// seeded overlapping poses; antcd's exact path against FCL's signed distance on fcl::Convex (GJK
// then EPA, libccd). Before timing, both depths are compared on every pose (FCL's tolerance,
// 1e-4 of the radius); a mismatch skips the benchmark with an error.
//
// General (non-convex): a torus sunk into a post and two boxes overlapping by 0.3 with the
// general path forced, meshes of about 1k, 10k and 100k triangles, refined to 1 %; against an
// all-contacts collide() of the same pair (the goal is <= 20x). The counter `ratio` of the
// penetration benchmarks is filled by running the collide once per iteration beside it.
//
// Benchmarks: convex_antcd, convex_fcl_epa (name/size), general_penetration,
// general_collide_all (name/shape/size); `per_query` is the mean time of one query.
#include <antcd/collide.hpp>
#include <antcd/mesh.hpp>
#include <antcd/penetration.hpp>

#include <benchmark/benchmark.h>

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

namespace {

using antcd::Scalar;
using antcd::Transform;
using antcd::Vec3;

struct ConvexCase {
  antcd::Model a, b;
  std::shared_ptr<fcl::Convexd> fa, fb;
  std::vector<std::pair<Transform, Transform>> poses;
};

std::shared_ptr<fcl::Convexd> fcl_convex(const antcd::Mesh& m) {
  auto v = std::make_shared<std::vector<fcl::Vector3d>>();
  for (const Vec3& p : m.vertices) v->emplace_back(p);
  auto f = std::make_shared<std::vector<int>>();
  int faces = 0;
  for (const auto& t : m.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    f->push_back(3);
    for (std::uint32_t i : t) f->push_back(static_cast<int>(i));
    ++faces;
  }
  return std::make_shared<fcl::Convexd>(v, faces, f);
}

fcl::Transform3d fcl_pose(const Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

Transform random_rotation(std::mt19937_64& rng, const Vec3& t) {
  std::normal_distribution<Scalar> g(0, 1);
  Transform out = Transform::from_quaternion(t, g(rng), g(rng), g(rng), g(rng));
  return out;
}

const ConvexCase& convex_case(int k) {
  static std::map<int, std::unique_ptr<ConvexCase>> cache;
  auto& slot = cache[k];
  if (!slot) {
    antcd::Mesh ma = antcd::make_sphere(1.0, 2 * k, k);
    antcd::Mesh mb = antcd::make_sphere(0.8, 2 * k, k);
    slot = std::make_unique<ConvexCase>(
        ConvexCase{antcd::Model(ma), antcd::Model(mb), fcl_convex(ma), fcl_convex(mb), {}});
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<Scalar> gap(0.2, 1.6);
    std::normal_distribution<Scalar> g(0, 1);
    for (int i = 0; i < 32; ++i) {
      const Vec3 dir = Vec3(g(rng), g(rng), g(rng)).normalized();
      slot->poses.emplace_back(random_rotation(rng, Vec3::Zero()),
                               random_rotation(rng, gap(rng) * dir));
    }
  }
  return *slot;
}

double fcl_depth(const ConvexCase& c, const Transform& pa, const Transform& pb) {
  fcl::DistanceRequestd req(true, true);
  fcl::DistanceResultd res;
  fcl::distance(c.fa.get(), fcl_pose(pa), c.fb.get(), fcl_pose(pb), req, res);
  return -res.min_distance;
}

void convex_antcd(benchmark::State& state) {
  const ConvexCase& c = convex_case(static_cast<int>(state.range(0)));
  for (const auto& [pa, pb] : c.poses) {
    const Scalar ours = antcd::penetration(c.a, pa, c.b, pb).upper;
    const Scalar theirs = std::max(0.0, fcl_depth(c, pa, pb));
    if (std::abs(ours - theirs) > 1e-4) {
      state.SkipWithError("antcd and FCL disagree on a pose");
      return;
    }
  }
  for (auto _ : state) {
    for (const auto& [pa, pb] : c.poses) {
      benchmark::DoNotOptimize(antcd::penetration(c.a, pa, c.b, pb).upper);
    }
  }
  state.counters["triangles"] = static_cast<double>(c.a.stats().triangles);
  state.counters["per_query"] =
      benchmark::Counter(static_cast<double>(state.iterations() * c.poses.size()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void convex_fcl_epa(benchmark::State& state) {
  const ConvexCase& c = convex_case(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    for (const auto& [pa, pb] : c.poses) benchmark::DoNotOptimize(fcl_depth(c, pa, pb));
  }
  state.counters["triangles"] = static_cast<double>(c.a.stats().triangles);
  state.counters["per_query"] =
      benchmark::Counter(static_cast<double>(state.iterations() * c.poses.size()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// k: 2k x k UV spheres: 4k(k-1) triangles.
BENCHMARK(convex_antcd)->Arg(3)->Arg(6)->Arg(12)->Arg(24)->Unit(benchmark::kMicrosecond);
BENCHMARK(convex_fcl_epa)->Arg(3)->Arg(6)->Arg(12)->Arg(24)->Unit(benchmark::kMicrosecond);

struct GeneralCase {
  antcd::Model a, b;
  Transform pa, pb;
  antcd::PenetrationRequest request;
};

// shape 0: torus (2k x k segments, 2k² triangles) sunk 0.15 into a post; 1: two boxes (12 s²
// triangles) overlapping by 0.3, general path forced.
const GeneralCase& general_case(int shape, int size) {
  static std::map<std::pair<int, int>, std::unique_ptr<GeneralCase>> cache;
  auto& slot = cache[{shape, size}];
  if (!slot) {
    antcd::PenetrationRequest general;
    general.shape = antcd::PenetrationRequest::Shape::General;
    if (shape == 0) {
      const int k = static_cast<int>(std::lround(std::sqrt(size / 2.0)));
      slot = std::make_unique<GeneralCase>(GeneralCase{
          antcd::Model(antcd::make_torus(2, 0.5, 2 * k, k)),
          antcd::Model(antcd::make_box(Vec3(2.6, 2.6, 1),
                                       static_cast<int>(std::lround(std::sqrt(size / 12.0))))),
          Transform::from_axis_angle(Vec3::UnitZ(), 0.1, Vec3(0, 0, 0.35)),
          Transform(antcd::Mat3::Identity(), Vec3(0, 0, -1)),
          {}});
    } else {
      const int s = static_cast<int>(std::lround(std::sqrt(size / 12.0)));
      const Transform tilt = Transform::from_axis_angle(Vec3(1, 2, 3), 0.7);
      Transform pb = tilt;
      pb.translation = tilt.rotation * Vec3(1.7, 0.3, 0.2);
      slot = std::make_unique<GeneralCase>(
          GeneralCase{antcd::Model(antcd::make_box(Vec3(1, 1, 1), s)),
                      antcd::Model(antcd::make_box(Vec3(1, 1, 1), s)), tilt, pb, general});
    }
  }
  return *slot;
}

void general_penetration(benchmark::State& state) {
  const GeneralCase& c =
      general_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  antcd::CollisionRequest all;
  all.all_contacts = true;
  (void)antcd::penetration(c.a, c.pa, c.b, c.pb, c.request);  // point-query caches built once
  double pd_s = 0, collide_s = 0;
  bool converged = true;
  std::uint32_t evaluations = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const antcd::PenetrationResult r = antcd::penetration(c.a, c.pa, c.b, c.pb, c.request);
    const auto t1 = std::chrono::steady_clock::now();
    state.PauseTiming();
    benchmark::DoNotOptimize(antcd::collide(c.a, c.pa, c.b, c.pb, all).contacts.size());
    const auto t2 = std::chrono::steady_clock::now();
    state.ResumeTiming();
    pd_s += std::chrono::duration<double>(t1 - t0).count();
    collide_s += std::chrono::duration<double>(t2 - t1).count();
    converged = converged && r.converged;
    evaluations = r.evaluations;
  }
  state.counters["triangles"] = static_cast<double>(c.a.stats().triangles + c.b.stats().triangles);
  state.counters["ratio_to_collide_all"] = pd_s / collide_s;
  state.counters["converged"] = converged ? 1 : 0;
  state.counters["collide_calls"] = evaluations;
}

BENCHMARK(general_penetration)
    ->ArgsProduct({{0, 1}, {1000, 10000, 100000}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
