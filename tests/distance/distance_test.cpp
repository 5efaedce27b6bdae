// Minimum distance against brute force over all triangle pairs, on real meshes (assimp test
// models) at random, touching and nearly touching poses; request semantics (upper bound,
// tolerance, argument errors).
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

struct BruteDistance {
  Scalar distance = std::numeric_limits<Scalar>::infinity();
};

// Minimum over every pair of non-degenerate triangles, each placed in the world by its pose.
BruteDistance brute_force_distance(const Mesh& a, const Transform& pa, const Mesh& b,
                                   const Transform& pb) {
  BruteDistance out;
  std::vector<Vec3> va, vb;
  for (const Vec3& v : a.vertices) va.push_back(pa.apply(v));
  for (const Vec3& v : b.vertices) vb.push_back(pb.apply(v));
  for (const auto& ta : a.triangles) {
    if (geometry::is_degenerate_triangle(a.vertices[ta[0]], a.vertices[ta[1]], a.vertices[ta[2]]))
      continue;
    for (const auto& tb : b.triangles) {
      if (geometry::is_degenerate_triangle(b.vertices[tb[0]], b.vertices[tb[1]], b.vertices[tb[2]]))
        continue;
      const Scalar d = geometry::triangle_distance(va[ta[0]], va[ta[1]], va[ta[2]], vb[tb[0]],
                                                   vb[tb[1]], vb[tb[2]])
                           .distance;
      out.distance = std::min(out.distance, d);
    }
  }
  return out;
}

// A real mesh cut down to its first `limit` triangles (brute force stays affordable).
Mesh first_triangles(Mesh mesh, std::size_t limit) {
  if (mesh.triangles.size() > limit) mesh.triangles.resize(limit);
  return mesh;
}

Vec3 world_vertex(const Model& m, const Transform& pose, std::uint32_t tri, int k) {
  return pose.apply(m.mesh().vertices[m.mesh().triangles[tri][k]]);
}

// Checks the result's internal consistency: witness points on the named triangles, their distance
// equal to the reported one, intersecting iff distance 0 iff collide says so.
void expect_consistent(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                       const DistanceResult& r, Scalar scale, const std::string& what) {
  ASSERT_TRUE(std::isfinite(r.distance)) << what;
  EXPECT_FALSE(r.approximate) << what;
  EXPECT_FALSE(r.beyond_upper_bound) << what;
  EXPECT_EQ(r.lower_bound, r.distance) << what;
  EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12 * scale) << what;
  EXPECT_LE(std::sqrt(geometry::point_triangle_distance_squared(
                r.point_a, world_vertex(a, pa, r.triangle_a, 0),
                world_vertex(a, pa, r.triangle_a, 1), world_vertex(a, pa, r.triangle_a, 2))),
            1e-12 * scale)
      << what << ": point_a is not on triangle_a";
  EXPECT_LE(std::sqrt(geometry::point_triangle_distance_squared(
                r.point_b, world_vertex(b, pb, r.triangle_b, 0),
                world_vertex(b, pb, r.triangle_b, 1), world_vertex(b, pb, r.triangle_b, 2))),
            1e-12 * scale)
      << what << ": point_b is not on triangle_b";
  if (r.intersecting) {
    EXPECT_EQ(r.distance, 0) << what;
  }
  EXPECT_EQ(r.intersecting,
            r.intersecting &&
                geometry::triangles_intersect(
                    world_vertex(a, pa, r.triangle_a, 0), world_vertex(a, pa, r.triangle_a, 1),
                    world_vertex(a, pa, r.triangle_a, 2), world_vertex(b, pb, r.triangle_b, 0),
                    world_vertex(b, pb, r.triangle_b, 1), world_vertex(b, pb, r.triangle_b, 2)))
      << what << ": the witness triangles do not intersect";
  EXPECT_EQ(r.intersecting, collide(a, pa, b, pb).colliding) << what;
}

// B rotated by `rot` with its vertex `vb` on A's vertex `va`, then moved by s * dir (dir unit):
// at s = 0 the surfaces share a point.
struct Placement {
  Mat3 rot;
  Vec3 va, vb, dir;
  [[nodiscard]] Transform at(Scalar s) const {
    Transform pb;
    pb.rotation = rot;
    pb.translation = va - rot * vb + s * dir;
    return pb;
  }
};

Placement random_placement(const Model& a, const Model& b, std::mt19937_64& rng) {
  std::normal_distribution<Scalar> gauss;
  const auto& ma = a.mesh();
  const auto& mb = b.mesh();
  const auto pick = [&](const Mesh& m) {
    const auto& t =
        m.triangles[std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng)];
    return m.vertices[t[std::uniform_int_distribution<int>(0, 2)(rng)]];
  };
  return {test::random_pose(rng, 0).rotation, pick(ma), pick(mb),
          Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized()};
}

// An offset s at which B (placement) goes from touching A (at the identity) to apart: bisection on
// the exact collision verdict between `near` (colliding) and `far` (separate).
Scalar touching_offset(const Model& a, const Model& b, const Placement& p, Scalar near,
                       Scalar far) {
  for (int i = 0; i < 80; ++i) {
    const Scalar mid = (near + far) / 2;
    (collide(a, Transform::identity(), b, p.at(mid)).colliding ? near : far) = mid;
  }
  return far;
}

struct MeshPair {
  std::string a, b;
  std::size_t limit;  // triangles kept of each, for the brute force
};

class DistanceBruteForce : public ::testing::TestWithParam<MeshPair> {};

TEST_P(DistanceBruteForce, MatchesAllPairsAtRandomTouchingAndNearPoses) {
  const MeshPair& p = GetParam();
  const Model a(first_triangles(load_mesh(test::assimp_model(p.a)), p.limit), {}, p.a);
  const Model b(first_triangles(load_mesh(test::assimp_model(p.b)), p.limit), {}, p.b);
  const Scalar ra = a.root().radius + a.root().center.norm();
  const Scalar rb = b.root().radius + b.root().center.norm();
  const Scalar scale = ra + rb;
  std::mt19937_64 rng(15);
  int poses = 0, near = 0, zero = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const Placement place = random_placement(a, b, rng);
    const Scalar contact = touching_offset(a, b, place, 0, 2 * scale);
    // Random gaps, the touching pose, and gaps a hair either side of it.
    for (const Scalar offset :
         {contact * 0.5, contact, contact * (1 + 1e-9), contact * (1 - 1e-9),
          contact + 1e-6 * scale, contact + 0.05 * scale, contact + 0.3 * scale}) {
      const Transform pb = place.at(offset);
      const Transform pa = Transform::identity();
      const std::string what = p.a + " / " + p.b + " trial " + std::to_string(trial) + " offset " +
                               std::to_string(offset);
      const DistanceResult r = distance(a, pa, b, pb);
      const BruteDistance truth = brute_force_distance(a.mesh(), pa, b.mesh(), pb);
      ASSERT_NEAR(r.distance, truth.distance, 1e-12 * scale) << what;
      expect_consistent(a, pa, b, pb, r, scale, what);
      ++poses;
      near += r.distance > 0 && r.distance < 1e-5 * scale;
      zero += r.intersecting;
    }
  }
  EXPECT_EQ(poses, 112);
  EXPECT_GT(near, 16) << "nearly touching poses were not generated";
  EXPECT_GT(zero, 16) << "intersecting poses were not generated";
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, DistanceBruteForce,
                         ::testing::Values(MeshPair{"OBJ/spider.obj", "OFF/Wuson.off", 150},
                                           MeshPair{"PLY/cube.ply", "OBJ/spider.obj", 400},
                                           MeshPair{"STL/sphereWithHole.stl", "PLY/Wuson.ply",
                                                    150}));

TEST(Distance, RandomPosesOfFullMeshesAgreeWithBruteForce) {
  const Model a(load_mesh(test::assimp_model("OBJ/spider.obj")), {}, "spider");
  const Model b(load_mesh(test::assimp_model("STL/sphereWithHole.stl")), {}, "sphereWithHole");
  std::mt19937_64 rng(7);
  const Scalar scale = a.root().radius + b.root().radius;
  for (int trial = 0; trial < 3; ++trial) {
    const Transform pa = test::random_pose(rng, 0.3 * scale);
    const Transform pb = test::random_pose(rng, 0.8 * scale);
    const DistanceResult r = distance(a, pa, b, pb);
    const Scalar truth = brute_force_distance(a.mesh(), pa, b.mesh(), pb).distance;
    const std::string what = "trial " + std::to_string(trial);
    ASSERT_NEAR(r.distance, truth, 1e-12 * scale) << what;
    expect_consistent(a, pa, b, pb, r, scale + pa.translation.norm() + pb.translation.norm(), what);
  }
}

TEST(Distance, SeparatedBoxesHaveTheirGapAndFaceWitnesses) {
  const Model a(make_box(Vec3(1, 1, 1)), {}, "a");
  const Model b(make_box(Vec3(0.5, 0.5, 0.5)), {}, "b");
  Transform pb;
  pb.translation = Vec3(3, 0.2, -0.1);  // faces x = 1 and x = 2.5
  const DistanceResult r = distance(a, Transform::identity(), b, pb);
  EXPECT_NEAR(r.distance, 1.5, 1e-14);
  EXPECT_NEAR(r.point_a.x(), 1, 1e-14);
  EXPECT_NEAR(r.point_b.x(), 2.5, 1e-14);
  EXPECT_NEAR((r.point_b - r.point_a).normalized().dot(Vec3::UnitX()), 1, 1e-12);
  EXPECT_FALSE(r.intersecting);
  EXPECT_GT(r.triangle_tests, 0u);
}

TEST(Distance, NestedClosedMeshesAreAtPositiveSurfaceDistance) {
  const Model outer(make_sphere(2.0, 32, 16), {}, "outer");
  const Model inner(make_box(Vec3(0.5, 0.5, 0.5)), {}, "inner");
  const DistanceResult r = distance(outer, Transform::identity(), inner, Transform::identity());
  EXPECT_FALSE(r.intersecting);
  EXPECT_GT(r.distance, 1.0);
  EXPECT_LT(r.distance, 2.0 - std::sqrt(0.75) + 1e-9);
}

TEST(Distance, UpperBoundStopsAndSaysSo) {
  const Model a(make_sphere(1.0, 24, 12), {}, "a");
  const Model b(make_torus(1.0, 0.3, 24, 12), {}, "b");
  Transform pb;
  pb.translation = Vec3(5, 0, 0);
  const DistanceResult exact = distance(a, Transform::identity(), b, pb);
  ASSERT_GT(exact.distance, 2.5);

  DistanceRequest below;
  below.upper_bound = 1.0;
  const DistanceResult r = distance(a, Transform::identity(), b, pb, below);
  EXPECT_TRUE(r.beyond_upper_bound);
  EXPECT_GT(r.lower_bound, 1.0);
  EXPECT_LE(r.lower_bound, exact.distance);
  EXPECT_LT(r.node_pairs, exact.node_pairs);

  DistanceRequest above;
  above.upper_bound = exact.distance * 1.01;
  const DistanceResult r2 = distance(a, Transform::identity(), b, pb, above);
  EXPECT_FALSE(r2.beyond_upper_bound);
  EXPECT_EQ(r2.distance, exact.distance);
}

TEST(Distance, ToleranceGivesAFlaggedBoundedAnswer) {
  const Model a(make_sphere(1.0, 64, 32), {}, "a");
  const Model b(make_torus(1.0, 0.3, 64, 32), {}, "b");
  std::mt19937_64 rng(3);
  int approximate = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Transform pb = test::random_pose(rng, 3.0);
    const DistanceResult exact = distance(a, Transform::identity(), b, pb);
    DistanceRequest request;
    request.rel_tolerance = 0.2;
    request.abs_tolerance = 0.01;
    const DistanceResult r = distance(a, Transform::identity(), b, pb, request);
    const Scalar tol = std::max(0.01, 0.2 * r.distance);
    EXPECT_GE(exact.distance, r.distance - tol - 1e-12) << trial;
    EXPECT_GE(r.distance, exact.distance - 1e-12) << trial;
    EXPECT_LE(r.lower_bound, exact.distance + 1e-12) << trial;
    EXPECT_LE(r.node_pairs, exact.node_pairs) << trial;
    if (r.approximate) {
      ++approximate;
      EXPECT_LT(r.lower_bound, r.distance);
    } else {
      EXPECT_EQ(r.lower_bound, r.distance);
    }
  }
  EXPECT_GT(approximate, 0) << "the tolerance never let the search skip anything";
}

TEST(Distance, RejectsInvalidRequests) {
  const Model a(make_box(Vec3(1, 1, 1)), {}, "a");
  const Transform id = Transform::identity();
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  for (const auto& [ub, at, rt] :
       {std::tuple{-1.0, 0.0, 0.0}, std::tuple{nan, 0.0, 0.0}, std::tuple{1.0, -1.0, 0.0},
        std::tuple{1.0, nan, 0.0}, std::tuple{1.0, 0.0, 1.0}, std::tuple{1.0, 0.0, -0.1}}) {
    DistanceRequest request;
    request.upper_bound = ub;
    request.abs_tolerance = at;
    request.rel_tolerance = rt;
    EXPECT_THROW(distance(a, id, a, id, request), ArgumentError);
  }
}

}  // namespace
}  // namespace antcd
