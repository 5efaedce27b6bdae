// bench/distance_bench.cpp — antcd::distance against FCL's distance query in one binary.
//
// Meshes: generated UV spheres and tori of about 1k, 10k, 100k and 1M triangles (the sizes of
// core_bench); both models of a pair are the same mesh at two poses. FCL gets the same triangles
// in fcl::BVHModel<RSS> and fcl::BVHModel<OBBRSS> (its bounding volumes meant for distance).
//
// Poses: 32 seeded pairs per size. Pair i rotates each copy at random and places B along a random
// direction at the contact offset (found by bisection on antcd's exact collision verdict) plus a
// gap of r·10^(-6 .. -1) (r the bounding radius), so every pose is separated — from nearly
// touching to a tenth of the radius apart — which is where a distance query does its work. Before
// timing, antcd's and FCL's distances are compared on every pose (1e-9 relative); a mismatch
// skips the benchmark with an error naming the pose.
//
// Benchmarks: distance_antcd, distance_fcl_rss, distance_fcl_obbrss (name/shape/size); each
// iteration runs the 32 poses; the counter `per_query` is the mean time of one query.
// --benchmark_repetitions=5 and compare medians (docs/performance.md).
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/mesh.hpp>

#include <benchmark/benchmark.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/distance.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using antcd::Scalar;
using antcd::Vec3;

enum class Shape { Sphere, Torus };

antcd::Mesh make_mesh(Shape shape, std::int64_t nominal) {
  // A sphere with 2k slices and k stacks has 4k(k - 1) triangles, a torus with 2k by k segments
  // 4k².
  const int k = static_cast<int>(std::lround(std::sqrt(static_cast<double>(nominal) / 4.0)));
  return shape == Shape::Sphere ? antcd::make_sphere(1.0, 2 * k, k)
                                : antcd::make_torus(1.0, 0.4, 2 * k, k);
}

template <class Bv>
std::unique_ptr<fcl::BVHModel<Bv>> fcl_model(const antcd::Mesh& mesh) {
  std::vector<fcl::Vector3d> vertices(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_unique<fcl::BVHModel<Bv>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d to_fcl(const antcd::Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

constexpr int kPoses = 32;

struct Scene {
  std::unique_ptr<antcd::Model> model;
  std::unique_ptr<fcl::BVHModel<fcl::RSSd>> rss;
  std::unique_ptr<fcl::BVHModel<fcl::OBBRSSd>> obbrss;
  std::vector<antcd::Transform> pa, pb;
  std::vector<fcl::Transform3d> fa, fb;
  std::string error;
};

template <class Bv>
double fcl_distance(const fcl::BVHModel<Bv>& m, const fcl::Transform3d& a,
                    const fcl::Transform3d& b) {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;  // antcd always returns closest points
  fcl::DistanceResultd result;
  fcl::distance(&m, a, &m, b, request, result);
  return result.min_distance;
}

std::unique_ptr<Scene> make_scene(Shape shape, std::int64_t nominal) {
  auto s = std::make_unique<Scene>();
  const antcd::Mesh mesh = make_mesh(shape, nominal);
  s->model = std::make_unique<antcd::Model>(mesh);
  s->rss = fcl_model<fcl::RSSd>(mesh);
  s->obbrss = fcl_model<fcl::OBBRSSd>(mesh);
  const Scalar radius = s->model->root().radius + s->model->root().center.norm();
  std::mt19937_64 rng(0x64697374ULL + static_cast<std::uint64_t>(nominal));
  std::normal_distribution<Scalar> gauss;
  std::uniform_real_distribution<Scalar> uni(0, 1);
  const auto rotation = [&] {
    return antcd::Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
        .normalized()
        .toRotationMatrix();
  };
  for (int i = 0; i < kPoses; ++i) {
    antcd::Transform a, b;
    a.rotation = rotation();
    b.rotation = rotation();
    const Vec3 d = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    Scalar lo = 0, hi = 2.5 * radius;  // centres together: copies of a closed mesh always touch
    for (int k = 0; k < 60; ++k) {
      const Scalar mid = (lo + hi) / 2;
      b.translation = mid * d;
      (antcd::collide(*s->model, a, *s->model, b).colliding ? lo : hi) = mid;
    }
    b.translation = (hi + radius * std::pow(10.0, -6 + 5 * uni(rng))) * d;
    s->pa.push_back(a);
    s->pb.push_back(b);
    s->fa.push_back(to_fcl(a));
    s->fb.push_back(to_fcl(b));
    const Scalar mine = antcd::distance(*s->model, a, *s->model, b).distance;
    const double rss = fcl_distance(*s->rss, s->fa.back(), s->fb.back());
    const double obbrss = fcl_distance(*s->obbrss, s->fa.back(), s->fb.back());
    if (s->error.empty() &&
        (std::abs(mine - rss) > 1e-9 * radius || std::abs(mine - obbrss) > 1e-9 * radius)) {
      s->error = "pose " + std::to_string(i) + ": antcd " + std::to_string(mine) + ", FCL RSS " +
                 std::to_string(rss) + ", FCL OBBRSS " + std::to_string(obbrss);
    }
  }
  return s;
}

const Scene& scene_for(Shape shape, std::int64_t nominal) {
  static std::map<std::pair<Shape, std::int64_t>, std::unique_ptr<Scene>> cache;
  auto& slot = cache[{shape, nominal}];
  if (!slot) slot = make_scene(shape, nominal);
  return *slot;
}

enum class Peer { Antcd, FclRss, FclObbrss };

template <Peer kPeer, Shape kShape>
void distance_query(benchmark::State& state) {
  const Scene& s = scene_for(kShape, state.range(0));
  if (!s.error.empty()) {
    state.SkipWithError(("antcd and FCL disagree: " + s.error).c_str());
    return;
  }
  for (auto _ : state) {
    for (int i = 0; i < kPoses; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if constexpr (kPeer == Peer::Antcd) {
        benchmark::DoNotOptimize(antcd::distance(*s.model, s.pa[k], *s.model, s.pb[k]));
      } else if constexpr (kPeer == Peer::FclRss) {
        benchmark::DoNotOptimize(fcl_distance(*s.rss, s.fa[k], s.fb[k]));
      } else {
        benchmark::DoNotOptimize(fcl_distance(*s.obbrss, s.fa[k], s.fb[k]));
      }
    }
  }
  if constexpr (kPeer == Peer::Antcd) {  // the work of one query, for tuning
    double nodes = 0, triangles = 0;
    for (int i = 0; i < kPoses; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const auto r = antcd::distance(*s.model, s.pa[k], *s.model, s.pb[k]);
      nodes += static_cast<double>(r.node_pairs);
      triangles += static_cast<double>(r.triangle_tests);
    }
    state.counters["node_pairs"] = nodes / kPoses;
    state.counters["triangle_tests"] = triangles / kPoses;
  }
  state.counters["per_query"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kPoses,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

#define ANTCD_DISTANCE_BENCH(peer, shape, name) \
  BENCHMARK(distance_query<peer, shape>)        \
      ->Name(name)                              \
      ->Arg(1'000)                              \
      ->Arg(10'000)                             \
      ->Arg(100'000)                            \
      ->Arg(1'000'000)                          \
      ->Unit(benchmark::kMicrosecond)

ANTCD_DISTANCE_BENCH(Peer::Antcd, Shape::Sphere, "distance_antcd/sphere");
ANTCD_DISTANCE_BENCH(Peer::FclRss, Shape::Sphere, "distance_fcl_rss/sphere");
ANTCD_DISTANCE_BENCH(Peer::FclObbrss, Shape::Sphere, "distance_fcl_obbrss/sphere");
ANTCD_DISTANCE_BENCH(Peer::Antcd, Shape::Torus, "distance_antcd/torus");
ANTCD_DISTANCE_BENCH(Peer::FclRss, Shape::Torus, "distance_fcl_rss/torus");
ANTCD_DISTANCE_BENCH(Peer::FclObbrss, Shape::Torus, "distance_fcl_obbrss/torus");

}  // namespace

BENCHMARK_MAIN();
