// Point queries: antcd::signed_distance (closest point + sign) and antcd::contains against CGAL's
// AABB tree (closest point) plus Side_of_triangle_mesh (inside/outside, ray parity), on the same
// 100k-triangle closed mesh (a torus) and the same points, one thread each (queries per second per
// core). Two point sets of 20,000 each (argument 0 / 1, named in the label):
//   0 "uniform": uniform in the mesh's bounding box grown by 10% of its extent on every side
//                (27% of them inside the solid);
//   1 "near-surface": uniform on the surface (area-weighted), then moved along the face normal by
//                a uniform offset in [-1%, +1%] of the bounding-box diagonal (half inside).
#include <antcd/mesh.hpp>
#include <antcd/points.hpp>

#include <benchmark/benchmark.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

constexpr std::size_t kPoints = 20000;

struct Fixture {
  antcd::Mesh mesh = antcd::make_torus(1.0, 0.35, 400, 125);  // 100,000 triangles
  antcd::Model model{mesh, {}, "torus"};
  std::vector<antcd::Vec3> points[2];
  SurfaceMesh sm;
  std::vector<K::Point_3> cgal_points[2];

  Fixture() {
    const antcd::Aabb box = mesh.bounds();
    const antcd::Vec3 grow = 0.1 * box.extent();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::size_t i = 0; i < kPoints; ++i) {
      const antcd::Vec3 t(u(rng), u(rng), u(rng));
      points[0].push_back(box.min - grow + t.cwiseProduct(box.extent() + 2 * grow));
    }
    std::vector<double> area_prefix;
    double total = 0;
    for (const auto& t : mesh.triangles) {
      const antcd::Vec3& a = mesh.vertices[t[0]];
      total += (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
      area_prefix.push_back(total);
    }
    const double diagonal = box.extent().norm();
    for (std::size_t i = 0; i < kPoints; ++i) {
      const auto k = static_cast<std::size_t>(
          std::lower_bound(area_prefix.begin(), area_prefix.end(), u(rng) * total) -
          area_prefix.begin());
      const auto& t = mesh.triangles[std::min(k, mesh.triangles.size() - 1)];
      const antcd::Vec3& a = mesh.vertices[t[0]];
      const antcd::Vec3& b = mesh.vertices[t[1]];
      const antcd::Vec3& c = mesh.vertices[t[2]];
      double s1 = u(rng), s2 = u(rng);
      if (s1 + s2 > 1) s1 = 1 - s1, s2 = 1 - s2;
      const antcd::Vec3 normal = (b - a).cross(c - a).normalized();
      points[1].push_back(a + s1 * (b - a) + s2 * (c - a) +
                          (2 * u(rng) - 1) * 0.01 * diagonal * normal);
    }
    for (int d = 0; d < 2; ++d) {
      for (const antcd::Vec3& p : points[d]) cgal_points[d].emplace_back(p.x(), p.y(), p.z());
    }
    std::vector<SurfaceMesh::Vertex_index> v;
    for (const antcd::Vec3& p : mesh.vertices)
      v.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
    for (const auto& t : mesh.triangles) sm.add_face(v[t[0]], v[t[1]], v[t[2]]);
  }
};

const char* const kDistribution[2] = {"uniform in box+10%", "near-surface +-1% diag"};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_AntcdSignedDistance(benchmark::State& state) {
  Fixture& f = fixture();
  const auto& points = f.points[state.range(0)];
  state.SetLabel(kDistribution[state.range(0)]);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  (void)antcd::signed_distance(f.model, antcd::Transform::identity(), points);  // first-use data
  for (auto _ : state) {
    const auto r = antcd::signed_distance(f.model, antcd::Transform::identity(), points);
    benchmark::DoNotOptimize(r.points.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

void BM_AntcdContains(benchmark::State& state) {
  Fixture& f = fixture();
  const auto& points = f.points[state.range(0)];
  state.SetLabel(kDistribution[state.range(0)]);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  (void)antcd::contains(f.model, antcd::Transform::identity(), points);
  for (auto _ : state) {
    const auto r = antcd::contains(f.model, antcd::Transform::identity(), points);
    benchmark::DoNotOptimize(r.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

void BM_CgalSignedDistance(benchmark::State& state) {
  Fixture& f = fixture();
  const auto& cgal_points = f.cgal_points[state.range(0)];
  state.SetLabel(kDistribution[state.range(0)]);
  Tree tree(faces(f.sm).first, faces(f.sm).second, f.sm);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(f.sm);
  (void)side(cgal_points.front());  // builds its tree
  (void)tree.closest_point_and_primitive(cgal_points.front());
  std::vector<double> out(kPoints);
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPoints; ++i) {
      const auto [closest, face] = tree.closest_point_and_primitive(cgal_points[i]);
      const double d = std::sqrt(CGAL::to_double(CGAL::squared_distance(closest, cgal_points[i])));
      out[i] = side(cgal_points[i]) == CGAL::ON_BOUNDED_SIDE ? -d : d;
      benchmark::DoNotOptimize(face);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

// CGAL's closest point alone (no sign): the AABB tree's share of BM_CgalSignedDistance.
void BM_CgalClosestPoint(benchmark::State& state) {
  Fixture& f = fixture();
  const auto& cgal_points = f.cgal_points[state.range(0)];
  state.SetLabel(kDistribution[state.range(0)]);
  Tree tree(faces(f.sm).first, faces(f.sm).second, f.sm);
  tree.accelerate_distance_queries();
  (void)tree.closest_point_and_primitive(cgal_points.front());
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPoints; ++i) {
      const auto [closest, face] = tree.closest_point_and_primitive(cgal_points[i]);
      benchmark::DoNotOptimize(closest);
      benchmark::DoNotOptimize(face);
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

void BM_CgalInside(benchmark::State& state) {
  Fixture& f = fixture();
  const auto& cgal_points = f.cgal_points[state.range(0)];
  state.SetLabel(kDistribution[state.range(0)]);
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(f.sm);
  (void)side(cgal_points.front());
  std::vector<char> out(kPoints);
  for (auto _ : state) {
    for (std::size_t i = 0; i < kPoints; ++i) {
      out[i] = side(cgal_points[i]) == CGAL::ON_BOUNDED_SIDE ? 1 : 0;
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kPoints));
}

// Refit against rebuild for a deforming mesh (the same 100k-triangle torus, vertices moved).
std::vector<antcd::Vec3> moved_vertices(const antcd::Mesh& mesh) {
  std::vector<antcd::Vec3> out;
  for (const antcd::Vec3& v : mesh.vertices) {
    out.emplace_back(v.x() * (1 + 0.1 * std::sin(3 * v.z())), v.y(), v.z() + 0.05 * v.x());
  }
  return out;
}

void BM_Refit(benchmark::State& state) {
  Fixture& f = fixture();
  antcd::Model model(f.mesh, {}, "torus");
  const std::vector<antcd::Vec3> moved = moved_vertices(f.mesh);
  bool flip = false;
  for (auto _ : state) {
    model.refit(flip ? f.mesh.vertices : moved);
    flip = !flip;
    benchmark::DoNotOptimize(model.root());
  }
}

void BM_Rebuild(benchmark::State& state) {
  Fixture& f = fixture();
  antcd::Mesh moved = f.mesh;
  moved.vertices = moved_vertices(f.mesh);
  for (auto _ : state) {
    const antcd::Model model(moved, {}, "torus");
    benchmark::DoNotOptimize(model.root());
  }
}

BENCHMARK(BM_Refit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Rebuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AntcdSignedDistance)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_CgalSignedDistance)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_CgalClosestPoint)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_AntcdContains)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_CgalInside)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
