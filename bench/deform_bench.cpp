// Deforming-mesh CCD (antcd::deform_sweep) on a 100k-triangle cloth step against discrete exact
// queries on the same mesh at t = 1 (Model built beforehand): antcd::self_intersections (with and
// without its normal-cone cull; its cone data are built on the first call and kept), collide() of
// the mesh against a second Model of it, all contacts (every triangle touches itself and its
// neighbours there: an all-pairs discrete cost), and the boolean collide() of the two layers.
//
// Cloths (x, y in [0, 1]): "wave": one sheet of 224 x 224 quads (100 352 triangles) waving, every
// vertex moving by under half a cell (no contact: toi = 1, the whole traversal runs). "stack": two
// sheets of 224 x 112 quads (100 352 triangles together) half a cell apart, the upper one falling
// by one cell with a wave (contacts from t ~ 0.5; first-hit mode prunes by the earliest toi).
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/self.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "ccd/deform_support.hpp"

namespace {

using antcd::Mesh;
using antcd::Scalar;
using antcd::Vec3;

// A flat grid at height z: the tests' grid (tests/ccd/deform_support.hpp), lifted.
Mesh grid(int nx, int ny, Scalar sx, Scalar sy, Scalar z) {
  Mesh m = antcd::test::make_grid(nx, ny, sx, sy);
  for (Vec3& v : m.vertices) v.z() += z;
  return m;
}

struct Step {
  Mesh mesh;  ///< at t = 0
  std::vector<Vec3> v0, v1;
  Mesh lower, upper;  ///< stack only: the layers at t = 1
};

constexpr int kCells = 224;
constexpr Scalar kCell = 1.0 / kCells;

Step wave() {
  Step s;
  s.mesh = grid(kCells, kCells, 1, 1, 0);
  for (Vec3& p : s.mesh.vertices) p.z() = 0.02 * std::sin(6 * p.x()) * std::cos(5 * p.y());
  s.v0 = s.mesh.vertices;
  for (const Vec3& p : s.v0) {
    s.v1.push_back(p + 0.4 * kCell * Vec3(0.3 * std::sin(5 * p.y()), 0, std::cos(7 * p.x())));
  }
  return s;
}

Step stack() {
  Step s;
  const Mesh lower = grid(kCells, kCells / 2, 1, 1, 0);
  const Mesh upper = grid(kCells, kCells / 2, 1, 1, 0.5 * kCell);
  s.mesh = antcd::merge({lower, upper});
  s.v0 = s.mesh.vertices;
  s.v1 = s.v0;
  for (std::size_t i = lower.vertices.size(); i < s.v1.size(); ++i) {
    const Vec3& p = s.v0[i];
    s.v1[i] = p - Vec3(0, 0, kCell * (1 + 0.3 * std::sin(9 * p.x()) * std::sin(8 * p.y())));
  }
  s.lower = lower;
  s.upper = upper;
  s.upper.vertices.assign(s.v1.begin() + static_cast<std::ptrdiff_t>(lower.vertices.size()),
                          s.v1.end());
  return s;
}

const Step& wave_step() {
  static const Step s = wave();
  return s;
}
const Step& stack_step() {
  static const Step s = stack();
  return s;
}

void run_ccd(benchmark::State& state, const Step& s, bool all_pairs) {
  const antcd::Model model(s.mesh, {}, "cloth");
  antcd::DeformSweepRequest req;
  req.all_pairs = all_pairs;
  // The model's cached cull data (its subtree boundaries, built on first use and kept, as
  // self_intersections' below) are built before timing.
  antcd::DeformSweepResult r = antcd::deform_sweep(model, s.v0, s.v1, req);
  for (auto _ : state) {
    r = antcd::deform_sweep(model, s.v0, s.v1, req);
    benchmark::DoNotOptimize(r.toi);
  }
  state.counters["triangles"] = static_cast<double>(s.mesh.triangles.size());
  state.counters["hit"] = r.hit;
  state.counters["toi"] = r.toi;
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
  state.counters["primitive_queries"] = static_cast<double>(r.primitive_queries);
  state.counters["scratch_bytes"] = static_cast<double>(r.scratch_bytes);
  state.counters["scratch_bytes_per_triangle"] =
      static_cast<double>(r.scratch_bytes) / static_cast<double>(s.mesh.triangles.size());
}

/// collide() of the mesh at t = 1 against a second Model of it, every contact.
void run_discrete_all(benchmark::State& state, const Step& s) {
  Mesh at1 = s.mesh;
  at1.vertices = s.v1;
  const antcd::Model a(at1, {}, "cloth");
  const antcd::Model b(at1, {}, "cloth copy");
  antcd::CollisionRequest req;
  req.all_contacts = true;
  antcd::CollisionResult r;
  for (auto _ : state) {
    antcd::collide(a, {}, b, {}, req, r);
    benchmark::DoNotOptimize(r.colliding);
  }
  state.counters["contacts"] = static_cast<double>(r.contacts.size());
}

/// self_intersections of the mesh at t = 1.
void run_self(benchmark::State& state, const Step& s, bool cones) {
  Mesh at1 = s.mesh;
  at1.vertices = s.v1;
  const antcd::Model model(at1, {}, "cloth");
  antcd::SelfIntersectionRequest req;
  req.normal_cones = cones;
  antcd::SelfIntersectionResult r = antcd::self_intersections(model, req);  // cone data built
  for (auto _ : state) {
    r = antcd::self_intersections(model, req);
    benchmark::DoNotOptimize(r.intersecting);
  }
  state.counters["pairs"] = static_cast<double>(r.pairs.size());
}

void BM_SelfIntersections_Wave(benchmark::State& state) { run_self(state, wave_step(), true); }
void BM_SelfIntersectionsNoCones_Wave(benchmark::State& state) {
  run_self(state, wave_step(), false);
}
void BM_SelfIntersections_Stack(benchmark::State& state) { run_self(state, stack_step(), true); }
void BM_SelfIntersectionsNoCones_Stack(benchmark::State& state) {
  run_self(state, stack_step(), false);
}

void BM_DeformSweep_Wave(benchmark::State& state) { run_ccd(state, wave_step(), false); }
void BM_DiscreteAllContacts_Wave(benchmark::State& state) { run_discrete_all(state, wave_step()); }
void BM_DeformSweep_Stack(benchmark::State& state) { run_ccd(state, stack_step(), false); }
void BM_DeformSweepAllPairs_Wave(benchmark::State& state) { run_ccd(state, wave_step(), true); }
void BM_DiscreteAllContacts_Stack(benchmark::State& state) {
  run_discrete_all(state, stack_step());
}
/// The stack's two layers at t = 1, boolean collide().
void BM_DiscreteLayers_Stack(benchmark::State& state) {
  const Step& s = stack_step();
  const antcd::Model a(s.lower, {}, "lower");
  const antcd::Model b(s.upper, {}, "upper");
  for (auto _ : state) benchmark::DoNotOptimize(antcd::collide(a, {}, b, {}).colliding);
}

BENCHMARK(BM_DeformSweep_Wave)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SelfIntersections_Wave)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SelfIntersectionsNoCones_Wave)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DiscreteAllContacts_Wave)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DeformSweep_Stack)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SelfIntersections_Stack)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SelfIntersectionsNoCones_Stack)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DeformSweepAllPairs_Wave)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DiscreteAllContacts_Stack)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DiscreteLayers_Stack)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
