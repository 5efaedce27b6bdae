// bench/contact_bench.cpp — what contact normals, depths and the manifold reduction cost on top of
// plain all-contacts collide(), in one binary and one run (the ratio is the figure to quote).
//
// Benchmarks (name/shape/nominal triangle count):
//   contacts_plain      all_contacts = true
//   contacts_normals    all_contacts + contact_normals (normal and depth per contact)
//   contacts_manifold   all_contacts + manifold_points = 4 (normals, then the reduction)
//   boolean_plain       a boolean query (stops at the first contact)
//   boolean_volume      the same with request.volume = true (both models closed): what the
//                       containment test adds to a boolean query that finds a surface contact
// Shapes: "torus" (non-convex) and "sphere", both models the same mesh at two poses. Every
// benchmark runs the same 32 seeded pose pairs per iteration, all overlapping (the centres within
// a quarter of the radius, random rotations), and reports `per_query` and `contacts` (per query).
// Medians: --benchmark_repetitions=5 --benchmark_report_aggregates_only=true.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/mesh.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using antcd::Scalar;
using antcd::Vec3;

enum class Shape { Torus, Sphere };
enum class Mode { Plain, Normals, Manifold, Boolean, BooleanVolume };

// A mesh of about `triangles` triangles, its radius about 1.
const antcd::Model& model(Shape shape, int triangles) {
  static std::map<std::pair<Shape, int>, std::unique_ptr<antcd::Model>> cache;
  auto& slot = cache[{shape, triangles}];
  if (!slot) {
    const int k = static_cast<int>(std::lround(std::sqrt(triangles / 4.0)));
    antcd::Mesh mesh = shape == Shape::Torus ? antcd::make_torus(0.7, 0.3, 2 * k, k)
                                             : antcd::make_sphere(1.0, 2 * k, k);
    slot = std::make_unique<antcd::Model>(std::move(mesh));
  }
  return *slot;
}

std::vector<std::pair<antcd::Transform, antcd::Transform>> poses() {
  std::mt19937_64 rng(2026);
  std::normal_distribution<Scalar> g;
  std::uniform_real_distribution<Scalar> u(-0.25, 0.25);
  std::vector<std::pair<antcd::Transform, antcd::Transform>> out;
  for (int i = 0; i < 32; ++i) {
    const auto pose = [&] {
      const Vec3 axis(g(rng), g(rng), g(rng));
      return antcd::Transform::from_axis_angle(axis, std::acos(-1.0) * u(rng) * 4,
                                               Vec3(u(rng), u(rng), u(rng)));
    };
    const antcd::Transform a = pose();
    out.emplace_back(a, pose());
  }
  return out;
}

void run(benchmark::State& state, Shape shape, Mode mode) {
  const antcd::Model& m = model(shape, static_cast<int>(state.range(0)));
  const auto pairs = poses();
  antcd::CollisionRequest request;
  const bool boolean = mode == Mode::Boolean || mode == Mode::BooleanVolume;
  request.all_contacts = !boolean;
  request.volume = mode == Mode::BooleanVolume;
  if (request.volume && !m.is_closed()) {
    state.SkipWithError("the volume test needs a closed model");
    return;
  }
  request.contact_normals = mode == Mode::Normals;
  request.manifold_points = mode == Mode::Manifold ? 4 : 0;
  antcd::CollisionResult result;
  std::uint64_t contacts = 0;
  for (auto _ : state) {
    contacts = 0;
    for (const auto& [pa, pb] : pairs) {
      antcd::collide(m, pa, m, pb, request, result);
      contacts += result.contacts.size();
      benchmark::DoNotOptimize(result.contacts.data());
    }
  }
  state.counters["per_query"] = benchmark::Counter(
      static_cast<double>(pairs.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["contacts"] = static_cast<double>(contacts) / static_cast<double>(pairs.size());
}

void args(benchmark::internal::Benchmark* b) {
  b->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
}

BENCHMARK_CAPTURE(run, contacts_plain / torus, Shape::Torus, Mode::Plain)->Apply(args);
BENCHMARK_CAPTURE(run, contacts_normals / torus, Shape::Torus, Mode::Normals)->Apply(args);
BENCHMARK_CAPTURE(run, contacts_manifold / torus, Shape::Torus, Mode::Manifold)->Apply(args);
BENCHMARK_CAPTURE(run, contacts_plain / sphere, Shape::Sphere, Mode::Plain)->Apply(args);
BENCHMARK_CAPTURE(run, contacts_normals / sphere, Shape::Sphere, Mode::Normals)->Apply(args);
BENCHMARK_CAPTURE(run, contacts_manifold / sphere, Shape::Sphere, Mode::Manifold)->Apply(args);
BENCHMARK_CAPTURE(run, boolean_plain / torus, Shape::Torus, Mode::Boolean)->Apply(args);
BENCHMARK_CAPTURE(run, boolean_volume / torus, Shape::Torus, Mode::BooleanVolume)->Apply(args);
BENCHMARK_CAPTURE(run, boolean_plain / sphere, Shape::Sphere, Mode::Boolean)->Apply(args);
BENCHMARK_CAPTURE(run, boolean_volume / sphere, Shape::Sphere, Mode::BooleanVolume)->Apply(args);

}  // namespace

BENCHMARK_MAIN();
