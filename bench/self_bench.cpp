// self_intersections (antcd/self.hpp) against CGAL::Polygon_mesh_processing::self_intersections
// with CGAL::Exact_predicates_inexact_constructions_kernel (the kernel its users run; sequential,
// its default), on meshes of 10k to 1M triangles: Debian's assimp models refined by midpoint
// subdivision (the same surface, 4x the triangles per step) and generated sheets and spheres
// made to pass through themselves. The pairs are checked equal once per mesh before timing (the
// run aborts otherwise). Each mesh runs antcd then CGAL back to back: quote ratios of one run.
// What is timed: antcd/ rows are repeat calls on a Model built before timing (prepare()'s check
// made the first call, which built the cone topology; every call builds its own boxes); cgal/
// rows are whole PMP::self_intersections calls (its face boxes included); "antcd build+self"
// rows add the Model build, the fair row for a mesh seen once.
//
// Also the deforming sheet of the issue: a 100k-triangle sheet waving without touching itself,
// each iteration one refit and one self test, both timed inside the iteration (interleaved), so
// refit_ms / self_ms / self_over_refit come from the same frames.
//
//   build/bench/antcd_bench_self --benchmark_counters_tabular=true
#include <antcd/load.hpp>
#include <antcd/self.hpp>

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "self/self_meshes.hpp"

namespace {

using namespace antcd;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;
using Pairs = std::vector<std::array<std::uint32_t, 2>>;

/// Each triangle split into four at its edge midpoints (shared edges share their midpoint).
Mesh subdivided(const Mesh& m) {
  Mesh out;
  out.vertices = m.vertices;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    const auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const auto id = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.push_back(0.5 * (m.vertices[a] + m.vertices[b]));
    mid.emplace(key, id);
    return id;
  };
  for (const auto& t : m.triangles) {
    const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                        ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

Mesh refined_to(Mesh m, std::size_t at_least) {
  while (m.triangles.size() < at_least) m = subdivided(m);
  return m;
}

/// The mesh through CGAL's soup repair into a Surface_mesh, and back (both sides read it).
struct Prepared {
  std::string name;
  Mesh mesh;
  SurfaceMesh sm;
  std::unique_ptr<Model> model;
};

Pairs cgal_pairs(const SurfaceMesh& sm, std::size_t& degenerate) {
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> found;
  PMP::self_intersections(sm, std::back_inserter(found));
  Pairs out;
  degenerate = 0;
  for (const auto& [f, g] : found) {
    const auto a = static_cast<std::uint32_t>(f.idx()), b = static_cast<std::uint32_t>(g.idx());
    if (a == b) {
      ++degenerate;
    } else {
      out.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::shared_ptr<Prepared> prepare(const std::string& name, const Mesh& in) {
  auto p = std::make_shared<Prepared>();
  p->name = name;
  std::vector<K::Point_3> points;
  for (const Vec3& v : in.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : in.triangles) polygons.push_back({t[0], t[1], t[2]});
  PMP::orient_polygon_soup(points, polygons);
  PMP::polygon_soup_to_polygon_mesh(points, polygons, p->sm);
  for (const auto v : p->sm.vertices()) {
    const auto& q = p->sm.point(v);
    p->mesh.vertices.emplace_back(q.x(), q.y(), q.z());
  }
  for (const auto f : p->sm.faces()) {
    TriangleIndices t{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(p->sm.halfedge(f), p->sm)) {
      t[static_cast<std::size_t>(k++)] = static_cast<std::uint32_t>(v.idx());
    }
    p->mesh.triangles.push_back(t);
  }
  p->model = std::make_unique<Model>(p->mesh, BuildOptions{}, name);
  std::size_t degenerate = 0;
  const Pairs cgal = cgal_pairs(p->sm, degenerate);
  const SelfIntersectionResult ours = self_intersections(*p->model);
  if (ours.pairs != cgal || ours.degenerate_triangles.size() != degenerate) {
    std::fprintf(stderr, "%s: antcd %zu pairs, CGAL %zu: not equal\n", name.c_str(),
                 ours.pairs.size(), cgal.size());
    std::abort();
  }
  std::printf("%s: %zu triangles, %zu pairs (equal to CGAL's), %zu degenerate\n", name.c_str(),
              p->mesh.triangles.size(), cgal.size(), degenerate);
  return p;
}

void antcd_self(benchmark::State& state, std::shared_ptr<Prepared> p, int threads) {
  tbb::task_arena arena(threads);
  SelfIntersectionStats stats;
  std::size_t pairs = 0;
  for (auto _ : state) {
    arena.execute([&] {
      const SelfIntersectionResult r = self_intersections(*p->model);
      pairs = r.pairs.size();
      stats = r.stats;
      benchmark::DoNotOptimize(r.pairs.data());
    });
  }
  state.counters["triangles"] = static_cast<double>(p->mesh.triangles.size());
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["node_pairs"] = static_cast<double>(stats.node_pairs);
  state.counters["tri_pairs"] = static_cast<double>(stats.triangle_pairs);
  state.counters["adjacent"] = static_cast<double>(stats.adjacent_pairs);
  state.counters["cone_culled"] = static_cast<double>(stats.cone_culled);
  state.counters["cone_bytes_per_tri"] =
      static_cast<double>(stats.cone_cache_bytes) / p->mesh.triangles.size();
}

void antcd_build_and_self(benchmark::State& state, std::shared_ptr<Prepared> p, int threads) {
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    arena.execute([&] {
      const Model model(p->mesh);
      const SelfIntersectionResult r = self_intersections(model);
      benchmark::DoNotOptimize(r.pairs.data());
    });
  }
  state.counters["triangles"] = static_cast<double>(p->mesh.triangles.size());
}

void cgal_self(benchmark::State& state, std::shared_ptr<Prepared> p) {
  std::size_t pairs = 0, degenerate = 0;
  for (auto _ : state) {
    const Pairs r = cgal_pairs(p->sm, degenerate);
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["triangles"] = static_cast<double>(p->mesh.triangles.size());
  state.counters["pairs"] = static_cast<double>(pairs);
}

/// The deforming sheet: side x side quads (2 side^2 triangles) waving gently in z, never
/// touching itself; per iteration one refit to the next frame's vertices and one self test.
void deforming_sheet(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const auto frame = [side](int f) {
    return test::grid_sheet(side, side, [=](int i, int j) {
      const Scalar x = Scalar(i) / side, y = Scalar(j) / side;
      return Vec3(x, y, 0.05 * std::sin(6.0 * x + 0.1 * f) * std::cos(4.0 * y - 0.07 * f));
    });
  };
  std::vector<std::vector<Vec3>> frames;
  for (int f = 0; f < 16; ++f) frames.push_back(frame(f).vertices);
  Model model(frame(0));
  double refit_s = 0, self_s = 0;
  std::uint64_t culled = 0, tested = 0, cone_bytes = 0;
  int f = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    model.refit(frames[static_cast<std::size_t>(++f % 16)]);
    const auto t1 = std::chrono::steady_clock::now();
    const SelfIntersectionResult r = self_intersections(model);
    const auto t2 = std::chrono::steady_clock::now();
    if (!r.pairs.empty()) state.SkipWithError("the sheet touches itself");
    refit_s += std::chrono::duration<double>(t1 - t0).count();
    self_s += std::chrono::duration<double>(t2 - t1).count();
    culled += r.stats.cone_culled;
    tested += r.stats.triangle_pairs;
    cone_bytes = r.stats.cone_cache_bytes;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(model.mesh().triangles.size());
  state.counters["refit_ms"] = 1000 * refit_s / n;
  state.counters["self_ms"] = 1000 * self_s / n;
  state.counters["self_over_refit"] = self_s / refit_s;
  state.counters["cone_culled"] = static_cast<double>(culled) / n;
  state.counters["triangle_pairs"] = static_cast<double>(tested) / n;
  state.counters["model_bytes_per_tri"] =
      static_cast<double>(model.stats().memory_bytes) / model.mesh().triangles.size();
  state.counters["cone_bytes_per_tri"] =
      static_cast<double>(cone_bytes) / model.mesh().triangles.size();
}

/// The rebuild rule's measurement: a 100k-triangle sheet built flat, then refitted to a twist of
/// state.range(0) degrees about its long axis (no contact), against a Model built for the twisted
/// sheet: refit_growth() and the self test's time on each, interleaved per iteration.
void twisted_sheet(benchmark::State& state) {
  const Scalar twist = static_cast<Scalar>(state.range(0)) * 3.14159265358979 / 180;
  const int side = 224;
  const auto sheet = [side](Scalar angle) {
    return test::grid_sheet(side, side, [=](int i, int j) {
      const Scalar x = Scalar(i) / side, y = Scalar(j) / side - 0.5;
      const Scalar a = angle * x;
      return Vec3(x, y * std::cos(a), y * std::sin(a));
    });
  };
  Model refitted(sheet(0));
  const Mesh twisted = sheet(twist);
  refitted.refit(twisted.vertices);
  const Model fresh(twisted);
  double refitted_s = 0, fresh_s = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const SelfIntersectionResult a = self_intersections(refitted);
    const auto t1 = std::chrono::steady_clock::now();
    const SelfIntersectionResult b = self_intersections(fresh);
    const auto t2 = std::chrono::steady_clock::now();
    if (a.pairs != b.pairs) state.SkipWithError("refitted and fresh models disagree");
    refitted_s += std::chrono::duration<double>(t1 - t0).count();
    fresh_s += std::chrono::duration<double>(t2 - t1).count();
  }
  state.counters["refit_growth"] = refitted.refit_growth();
  state.counters["refitted_over_fresh"] = refitted_s / fresh_s;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const std::filesystem::path models = "/usr/share/assimp/models";
  std::vector<std::shared_ptr<Prepared>> meshes;
  for (const char* file : {"OBJ/spider.obj", "PLY/Wuson.ply"}) {
    if (!std::filesystem::exists(models / file)) continue;
    const Mesh m = load_mesh(models / file);
    meshes.push_back(prepare(std::string(file) + " x" + "10k", refined_to(m, 10000)));
    meshes.push_back(prepare(std::string(file) + " x" + "100k", refined_to(m, 100000)));
  }
  meshes.push_back(prepare("looped sheet 10k", test::looped_sheet(500, 10)));
  meshes.push_back(prepare("looped sheet 100k", test::looped_sheet(1000, 50)));
  meshes.push_back(prepare("looped sheet 1M", test::looped_sheet(2000, 250)));
  meshes.push_back(
      prepare("pushed sphere 110k", refined_to(test::pushed_sphere(1, 0.7, 1.9), 100000)));
  meshes.push_back(prepare("torus 1M (no pair)", make_torus(1, 0.3, 1000, 500)));
  for (const auto& p : meshes) {
    benchmark::RegisterBenchmark(("antcd/" + p->name + "/2 threads").c_str(), antcd_self, p, 2)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("antcd/" + p->name + "/1 thread").c_str(), antcd_self, p, 1)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("antcd build+self/" + p->name + "/1 thread").c_str(),
                                 antcd_build_and_self, p, 1)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("cgal/" + p->name).c_str(), cgal_self, p)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("deforming sheet", deforming_sheet)
      ->Arg(224)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("twisted sheet (degrees)", twisted_sheet)
      ->Arg(15)
      ->Arg(45)
      ->Arg(90)
      ->Arg(180)
      ->Arg(360)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
