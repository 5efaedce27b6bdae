// The convex path of antcd::penetration against two independent references on 1000 random convex
// polytope pairs: CGAL (the convex hull of the Minkowski difference A - B in exact arithmetic; the
// depth is the distance from the origin to its nearest facet) and FCL (fcl::Convex, signed
// distance by GJK/EPA). Test-only dependencies: built when CMake finds both.
#include <antcd/collide.hpp>
#include <antcd/penetration.hpp>
#include <antcd/points.hpp>

#include <gtest/gtest.h>

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

// Convex hull of n random points in an ellipsoid, as a closed outward mesh, in world coordinates.
Mesh random_polytope(std::mt19937_64& rng, int n) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  const Vec3 axes(u(rng), u(rng), u(rng));
  std::vector<Epick::Point_3> pts;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = Vec3(g(rng), g(rng), g(rng)).normalized().cwiseProduct(axes);
    pts.emplace_back(d.x(), d.y(), d.z());
  }
  CGAL::Surface_mesh<Epick::Point_3> hull;
  CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
  Mesh m;
  std::vector<std::uint32_t> index(hull.number_of_vertices());
  for (auto v : hull.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(m.vertices.size());
    const auto& p = hull.point(v);
    m.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  for (auto f : hull.faces()) {
    TriangleIndices t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) t[k++] = index[v.idx()];
    m.triangles.push_back(t);
  }
  return m;
}

// The facets' distance from the origin, exactly, for a hull of exact points (0 when the origin is
// not strictly inside).
template <class Hull>
double nearest_facet(const Hull& hull) {
  const Epeck::Point_3 origin(0, 0, 0);
  const CGAL::Cartesian_converter<typename CGAL::Kernel_traits<typename Hull::Point>::Kernel, Epeck>
      to_exact;
  Epeck::FT best = -1;
  for (auto f : hull.faces()) {
    std::vector<Epeck::Point_3> p;
    for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      p.push_back(to_exact(hull.point(v)));
    }
    const Epeck::Plane_3 plane(p[0], p[1], p[2]);
    if (plane.oriented_side(origin) != CGAL::ON_NEGATIVE_SIDE) return 0;  // outward faces
    const Epeck::FT d2 = CGAL::squared_distance(origin, plane);
    if (best < 0 || d2 < best) best = d2;
  }
  return std::sqrt(CGAL::to_double(best));
}

// Exact reference: the distance from the origin to the boundary of conv{a - b}. `snapped`: every
// coordinate is a multiple of 2^-20 below 4 in magnitude, so the differences are exact doubles
// and the hull is built with exact predicates on them (fast); otherwise in exact arithmetic.
double cgal_depth(const Mesh& a, const Mesh& b, bool snapped) {
  if (snapped) {
    std::vector<Epick::Point_3> diff;
    for (const Vec3& p : a.vertices) {
      for (const Vec3& q : b.vertices)
        diff.emplace_back(p.x() - q.x(), p.y() - q.y(), p.z() - q.z());
    }
    CGAL::Surface_mesh<Epick::Point_3> hull;
    CGAL::convex_hull_3(diff.begin(), diff.end(), hull);
    return nearest_facet(hull);
  }
  std::vector<Epeck::Point_3> diff;
  for (const Vec3& p : a.vertices) {
    for (const Vec3& q : b.vertices) {
      diff.emplace_back(Epeck::FT(p.x()) - q.x(), Epeck::FT(p.y()) - q.y(),
                        Epeck::FT(p.z()) - q.z());
    }
  }
  CGAL::Surface_mesh<Epeck::Point_3> hull;
  CGAL::convex_hull_3(diff.begin(), diff.end(), hull);
  return nearest_facet(hull);
}

// Coordinates rounded to multiples of 2^-20 (see cgal_depth).
Mesh snapped(Mesh m) {
  for (Vec3& v : m.vertices) {
    for (int k = 0; k < 3; ++k) v[k] = std::ldexp(std::round(std::ldexp(v[k], 20)), -20);
  }
  return m;
}

std::shared_ptr<fcl::Convexd> fcl_convex(const Mesh& m) {
  auto v = std::make_shared<std::vector<fcl::Vector3d>>();
  for (const Vec3& p : m.vertices) v->emplace_back(p);
  auto f = std::make_shared<std::vector<int>>();
  for (const auto& t : m.triangles) {
    f->push_back(3);
    for (std::uint32_t i : t) f->push_back(static_cast<int>(i));
  }
  return std::make_shared<fcl::Convexd>(v, static_cast<int>(m.triangles.size()), f);
}

TEST(PenetrationReference, ConvexPairsMatchCgalAndFcl) {
  std::mt19937_64 rng(20261126);
  std::uniform_int_distribution<int> count(5, 16);
  std::uniform_real_distribution<double> offset(-1.6, 1.6);
  int overlapping = 0;
  double worst_cgal = 0, worst_fcl = 0, general_width = 0;
  int general_converged = 0;
  for (int pair = 0; pair < 1000; ++pair) {
    // Snapping keeps them convex: the hull's vertices move by 2^-21 at most, far less than the
    // random points' spacing (checked by is_convex below).
    const Mesh ma = snapped(random_polytope(rng, count(rng)));
    const Mesh mb = snapped(
        transformed(random_polytope(rng, count(rng)),
                    test::random_pose(rng, 0) *
                        Transform(Mat3::Identity(), Vec3(offset(rng), offset(rng), offset(rng)))));
    const Model a(ma), b(mb);
    ASSERT_TRUE(is_convex(a) && is_convex(b)) << pair;
    const PenetrationResult r = penetration(a, Transform::identity(), b, Transform::identity());
    ASSERT_TRUE(r.exact);
    const double ref = cgal_depth(ma, mb, true);
    SCOPED_TRACE("pair " + std::to_string(pair));
    EXPECT_EQ(r.overlapping, ref > 0);
    EXPECT_LE(std::abs(r.upper - ref), 1e-9 * std::max(ref, 1e-3));
    worst_cgal = std::max(worst_cgal, std::abs(r.upper - ref) / std::max(ref, 1e-3));
    if (ref <= 0) continue;
    ++overlapping;
    // A moved by the depth touches B at point_b; the witness is inside both (winding numbers).
    EXPECT_LT((r.point_a + r.upper * r.direction - r.point_b).norm(), 1e-12);
    const Vec3 w[1] = {r.witness};
    EXPECT_TRUE(contains(a, Transform::identity(), w)[0] &&
                contains(b, Transform::identity(), w)[0])
        << "depth " << ref << " in a " << int(contains(a, Transform::identity(), w)[0]) << " in b "
        << int(contains(b, Transform::identity(), w)[0]);
    if (overlapping <= 200) {
      // The general bounds on the same pair: certified, whatever their width.
      PenetrationRequest general;
      general.shape = PenetrationRequest::Shape::General;
      const PenetrationResult g =
          penetration(a, Transform::identity(), b, Transform::identity(), general);
      EXPECT_LE(g.lower, ref * (1 + 1e-12) + 1e-12) << "general lower";
      EXPECT_GE(g.upper, ref * (1 - 1e-12) - 1e-12) << "general upper";
      Transform moved = Transform::identity();
      moved.translation = (g.upper + 1e-9) * g.direction;
      CollisionRequest vol;
      vol.volume = true;
      EXPECT_FALSE(collide(a, moved, b, Transform::identity(), vol).colliding);
      if (g.overlapping) {
        const Vec3 gw[1] = {g.witness};
        EXPECT_TRUE(contains(a, Transform::identity(), gw)[0] &&
                    contains(b, Transform::identity(), gw)[0]);
      }
      general_width = std::max(general_width, (g.upper - g.lower) / ref);
      general_converged += g.converged;
    }
    fcl::DistanceRequestd req(true, true);
    fcl::DistanceResultd res;
    fcl::distance(fcl_convex(ma).get(), fcl::Transform3d::Identity(), fcl_convex(mb).get(),
                  fcl::Transform3d::Identity(), req, res);
    // libccd's EPA stops at a tolerance of 1e-6 (plus its polytope's own rounding).
    EXPECT_NEAR(-res.min_distance, ref, 1e-4) << "FCL";
    worst_fcl = std::max(worst_fcl, std::abs(-res.min_distance - ref));
  }
  EXPECT_GT(overlapping, 300);
  RecordProperty("overlapping_pairs", overlapping);
  std::printf(
      "overlapping %d, worst relative vs CGAL %.3g, worst |FCL - CGAL| %.3g; general "
      "bounds on 200: %d converged to 1 %%, widest %.3g of the depth\n",
      overlapping, worst_cgal, worst_fcl, general_converged, general_width);
}

TEST(PenetrationReference, PosesGiveTheSameDepthAsBakedCoordinates) {
  std::mt19937_64 rng(7);
  for (int pair = 0; pair < 50; ++pair) {
    const Mesh ma = random_polytope(rng, 10), mb = random_polytope(rng, 12);
    const Transform pa = test::random_pose(rng, 0.5), pb = test::random_pose(rng, 0.5);
    const PenetrationResult posed = penetration(Model(ma), pa, Model(mb), pb);
    const double ref = cgal_depth(transformed(ma, pa), transformed(mb, pb), false);
    EXPECT_NEAR(posed.upper, ref, 1e-12 * (1 + ref));
  }
}

}  // namespace
}  // namespace antcd
