// Point queries: contains() and signed_distance() against brute force over all triangles (distance)
// and the brute-force winding number (inside/outside), on generated solids at random poses.
#include <antcd/points.hpp>

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

/// Closest distance over every non-degenerate triangle of the posed mesh (world frame).
Scalar brute_distance(const Mesh& mesh, const Transform& pose, const Vec3& p) {
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (const auto& t : mesh.triangles) {
    const Vec3 a = pose.apply(mesh.vertices[t[0]]);
    const Vec3 b = pose.apply(mesh.vertices[t[1]]);
    const Vec3 c = pose.apply(mesh.vertices[t[2]]);
    if (geometry::is_degenerate_triangle(a, b, c)) continue;
    best = std::min(best, std::sqrt(geometry::point_triangle_distance_squared(p, a, b, c)));
  }
  return best;
}

/// Winding number over every triangle of the posed mesh, no hierarchy (world frame).
bool brute_inside(const Mesh& mesh, const Transform& pose, const Vec3& p) {
  Scalar total = 0;
  for (const auto& t : mesh.triangles) {
    total +=
        geometry::solid_angle(p, pose.apply(mesh.vertices[t[0]]), pose.apply(mesh.vertices[t[1]]),
                              pose.apply(mesh.vertices[t[2]]));
  }
  return std::abs(total) > 2 * std::numbers::pi;
}

std::vector<Vec3> random_points(std::mt19937_64& rng, const Aabb& box, Scalar margin, int n) {
  std::vector<Vec3> points;
  std::uniform_real_distribution<Scalar> u(0, 1);
  const Vec3 lo = box.min - Vec3::Constant(margin);
  const Vec3 size = box.max - box.min + Vec3::Constant(2 * margin);
  for (int i = 0; i < n; ++i) {
    points.push_back(lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(size));
  }
  return points;
}

std::vector<Mesh> solids() {
  return {
      make_torus(1.0, 0.35, 40, 20), make_box(Vec3(0.8, 0.5, 0.3), 3), make_sphere(0.7, 24, 12),
      merge({make_cylinder(0.3, 1.0, 16),
             transformed(make_sphere(0.4, 12, 6),
                         Transform::from_axis_angle(Vec3::UnitY(), 0, Vec3(1.5, 0, 0)))}),
      // Overlapping pieces (winding number 2 where they overlap): signs from the winding number.
      merge({make_box(Vec3(0.5, 0.5, 0.5), 2),
             transformed(make_sphere(0.6, 20, 10),
                         Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(0.6, 0.2, 0)))})};
}

TEST(Points, MatchBruteForceDistanceAndWindingNumberAtRandomPoses) {
  std::mt19937_64 rng(11);
  for (const Mesh& mesh : solids()) {
    const Model model(mesh, {}, "solid");
    ASSERT_TRUE(model.is_closed());
    const Transform pose = test::random_pose(rng, 2.0);
    const Mesh posed = transformed(mesh, pose);
    Aabb box = posed.bounds();
    const std::vector<Vec3> points = random_points(rng, box, 0.3, 400);
    const std::vector<std::uint8_t> in = contains(model, pose, points);
    const SignedDistanceResult sd = signed_distance(model, pose, points);
    ASSERT_TRUE(sd.is_signed);
    ASSERT_EQ(in.size(), points.size());
    ASSERT_EQ(sd.points.size(), points.size());
    int inside = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const bool truth = brute_inside(mesh, pose, points[i]);
      EXPECT_EQ(in[i] != 0, truth) << "point " << i;
      const PointDistance& d = sd.points[i];
      const Scalar brute = brute_distance(mesh, pose, points[i]);
      EXPECT_NEAR(std::abs(d.distance), brute, 1e-12) << "point " << i;
      EXPECT_EQ(d.distance < 0, truth) << "point " << i;
      // The closest point lies on the reported triangle and at the reported distance.
      const auto& t = mesh.triangles[d.triangle];
      const Vec3 a = pose.apply(mesh.vertices[t[0]]), b = pose.apply(mesh.vertices[t[1]]),
                 c = pose.apply(mesh.vertices[t[2]]);
      EXPECT_LT(std::sqrt(geometry::point_triangle_distance_squared(d.closest, a, b, c)), 1e-12);
      EXPECT_NEAR((points[i] - d.closest).norm(), std::abs(d.distance), 1e-12);
      inside += truth ? 1 : 0;
    }
    EXPECT_GT(inside, 5);
    EXPECT_LT(inside, 395);
  }
}

TEST(Points, VerticesEdgesAndNearSurfacePointsGetTheRightSign) {
  // Points just off vertices and edge midpoints, along and against the outward direction: the
  // pseudo-normal cases (closest feature an edge or a vertex).
  const Mesh mesh = make_box(Vec3(1, 1, 1), 1);
  const Model model(mesh, {}, "box");
  std::vector<Vec3> points;
  std::vector<bool> expect_inside;
  for (const Vec3& v : mesh.vertices) {
    points.push_back(v * 1.01);
    expect_inside.push_back(false);
    points.push_back(v * 0.99);
    expect_inside.push_back(true);
  }
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const Vec3 mid = 0.5 * (mesh.vertices[t[i]] + mesh.vertices[t[(i + 1) % 3]]);
      points.push_back(mid * 1.001);
      expect_inside.push_back(false);
      points.push_back(mid * 0.999);
      expect_inside.push_back(true);
    }
  }
  const std::vector<std::uint8_t> in = contains(model, Transform::identity(), points);
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(in[i] != 0, expect_inside[i]) << "point " << i;
    EXPECT_EQ(sd.points[i].distance < 0, expect_inside[i]) << "point " << i;
  }
  // On the surface: distance 0.
  const SignedDistanceResult on =
      signed_distance(model, Transform::identity(), std::vector<Vec3>{Vec3(1, 0.2, 0.3)});
  EXPECT_EQ(on.points[0].distance, 0);
}

TEST(Points, ModelFrameDistanceIsExactlyTheBruteForceMinimum) {
  // Identity pose: the query point is the model-frame point, so the tree's answer must equal the
  // minimum of the same point-triangle distance over every triangle bit for bit (the descent's
  // single bounds never prune the nearest triangle). Points on, near and far from the surface.
  const Mesh mesh = make_torus(1.0, 0.35, 40, 20);
  const Model model(mesh, {}, "torus");
  std::mt19937_64 rng(5);
  std::vector<Vec3> points = random_points(rng, mesh.bounds(), 0.5, 300);
  std::normal_distribution<Scalar> g(0, 1e-6);
  for (std::size_t v = 0; v < mesh.vertices.size(); v += 7) {
    points.push_back(mesh.vertices[v]);
    points.push_back(mesh.vertices[v] + Vec3(g(rng), g(rng), g(rng)));
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 11) {
    const auto& tri = mesh.triangles[t];
    points.push_back(0.5 * (mesh.vertices[tri[0]] + mesh.vertices[tri[1]]));
    points.push_back((mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / 3);
  }
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Scalar best = std::numeric_limits<Scalar>::infinity();
    for (const auto& t : mesh.triangles) {
      best = std::min(
          best, geometry::point_triangle_distance_squared(
                    points[i], mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
    }
    ASSERT_EQ(std::abs(sd.points[i].distance), std::sqrt(best)) << "point " << i;
  }
}

TEST(Points, AnswersDoNotDependOnBatchOrderOrCompany) {
  // Batches are searched in a spatial order, each point seeded with its predecessor's triangle:
  // the answers must not depend on that (shuffled batch, one point at a time).
  const Model model(make_sphere(1.0, 32, 16), {}, "sphere");
  std::mt19937_64 rng(9);
  std::vector<Vec3> points = random_points(rng, model.mesh().bounds(), 0.4, 500);
  const SignedDistanceResult all = signed_distance(model, Transform::identity(), points);
  const std::vector<std::uint8_t> in = contains(model, Transform::identity(), points);
  std::vector<std::size_t> perm(points.size());
  for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<Vec3> shuffled;
  for (const std::size_t i : perm) shuffled.push_back(points[i]);
  const SignedDistanceResult again = signed_distance(model, Transform::identity(), shuffled);
  const std::vector<std::uint8_t> in_again = contains(model, Transform::identity(), shuffled);
  for (std::size_t j = 0; j < perm.size(); ++j) {
    const std::size_t i = perm[j];
    ASSERT_EQ(again.points[j].distance, all.points[i].distance) << "point " << i;
    ASSERT_EQ(again.points[j].triangle, all.points[i].triangle) << "point " << i;
    ASSERT_EQ(in_again[j], in[i]) << "point " << i;
  }
  for (std::size_t i = 0; i < points.size(); i += 50) {
    const SignedDistanceResult one =
        signed_distance(model, Transform::identity(), std::vector<Vec3>{points[i]});
    ASSERT_EQ(one.points[0].distance, all.points[i].distance) << "point " << i;
    ASSERT_EQ(one.points[0].triangle, all.points[i].triangle) << "point " << i;
  }
}

TEST(Points, PointsJustOffFacesEdgesAndCornersGetTheRightSign) {
  // 1e-7 off a box of side 2 (far below a grid cell, far above rounding), along the outward
  // direction and against it, at random spots of its faces, on its edges and at its corners.
  const Mesh mesh = make_box(Vec3(1, 1, 1), 3);
  const Model model(mesh, {}, "box");
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  std::vector<Vec3> points;
  std::vector<std::uint8_t> expect;
  std::vector<Scalar> expect_distance;  // inside an edge or corner: to the nearest face
  for (int i = 0; i < 600; ++i) {
    Vec3 on(u(rng), u(rng), u(rng));
    const int pinned = 1 + i % 3;  // 1: a face, 2: an edge, 3: a corner
    for (int a = 0; a < pinned; ++a) on[(i + a) % 3] = on[(i + a) % 3] < 0 ? -1 : 1;
    Vec3 out = Vec3::Zero();
    for (int a = 0; a < 3; ++a) out[a] = std::abs(on[a]) == 1 ? on[a] : 0;
    out.normalize();
    points.push_back(on + 1e-7 * out);
    expect.push_back(0);
    expect_distance.push_back(1e-7);
    points.push_back(on - 1e-7 * out);
    expect.push_back(1);
    expect_distance.push_back(1e-7 / std::sqrt(static_cast<Scalar>(pinned)));
  }
  const std::vector<std::uint8_t> in = contains(model, Transform::identity(), points);
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(in[i], expect[i]) << "point " << i;
    ASSERT_EQ(sd.points[i].distance < 0, expect[i] != 0) << "point " << i;
    ASSERT_NEAR(std::abs(sd.points[i].distance), expect_distance[i], 1e-12) << "point " << i;
  }
}

TEST(Points, ThinSolidMatchesTheWindingNumber) {
  // A plate 1e-3 thick: the inside/outside grid gets flat cells along the thin axis.
  const Mesh mesh = make_box(Vec3(1, 0.7, 5e-4), 2);
  const Model model(mesh, {}, "plate");
  std::mt19937_64 rng(4);
  const std::vector<Vec3> points = random_points(rng, mesh.bounds(), 2e-3, 400);
  const std::vector<std::uint8_t> in = contains(model, Transform::identity(), points);
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  int inside = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool truth = brute_inside(mesh, Transform::identity(), points[i]);
    ASSERT_EQ(in[i] != 0, truth) << "point " << i;
    ASSERT_EQ(sd.points[i].distance < 0, truth) << "point " << i;
    inside += truth ? 1 : 0;
  }
  EXPECT_GT(inside, 20);
}

TEST(Points, InwardFacingSolidCountsAsInsideToo) {
  Mesh flipped = make_sphere(1.0, 16, 8);
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  const Model model(flipped, {}, "flipped");
  ASSERT_TRUE(model.is_closed());
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(0.5, 0.1, 0), Vec3(2, 0, 0), Vec3(0, 1.5, 0)};
  EXPECT_EQ(contains(model, Transform::identity(), points),
            (std::vector<std::uint8_t>{1, 1, 0, 0}));
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  EXPECT_LT(sd.points[0].distance, 0);
  EXPECT_LT(sd.points[1].distance, 0);
  EXPECT_GT(sd.points[2].distance, 0);
  EXPECT_GT(sd.points[3].distance, 0);
}

TEST(Points, OpenModelGivesUnsignedDistancesAndNoContainment) {
  Mesh open = make_box(Vec3(1, 1, 1), 1);
  open.triangles.pop_back();
  const Model model(open, {}, "open box");
  ASSERT_FALSE(model.is_closed());
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(3, 0, 0)};
  const SignedDistanceResult sd = signed_distance(model, Transform::identity(), points);
  EXPECT_FALSE(sd.is_signed);
  EXPECT_NEAR(sd.points[0].distance, 1.0, 1e-15);
  EXPECT_NEAR(sd.points[1].distance, 2.0, 1e-15);
  try {
    (void)contains(model, Transform::identity(), points);
    FAIL() << "contains on an open model must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("open box"), std::string::npos) << e.what();
  }
}

TEST(Points, NonFinitePointIsAnArgumentErrorNamingIt) {
  const Model model(make_sphere(1.0, 8, 4), {}, "sphere");
  const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(std::nan(""), 0, 0)};
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0)
        (void)contains(model, Transform::identity(), points);
      else
        (void)signed_distance(model, Transform::identity(), points);
      FAIL() << "must throw";
    } catch (const ArgumentError& e) {
      EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(contains(model, Transform::identity(), std::vector<Vec3>{}).empty());
}

// A batch is ordered along a curve through its points' box; one point, coincident points and a
// box wider than the double range overflow that arithmetic (a NaN cell under the sanitizers'
// float-cast check before it was clamped). Each answer is the same as the point's alone.
TEST(Points, BatchesWhoseBoxOverflowsAnswerEachPointAsAlone) {
  const Model model(make_sphere(1.0, 16, 8), {}, "sphere");
  const Scalar huge = std::numeric_limits<Scalar>::max() / 2;
  const std::vector<std::vector<Vec3>> batches = {
      {Vec3(0.2, 0.1, 0)},
      {Vec3(3, 0, 0), Vec3(3, 0, 0), Vec3(3, 0, 0)},
      {Vec3(-huge, 0, 0), Vec3(huge, 0, 0), Vec3(0, 0.5, 0)},
      {Vec3(0, -huge, huge), Vec3(2, 0, 0), Vec3(0, huge, -huge)}};
  for (const std::vector<Vec3>& batch : batches) {
    const SignedDistanceResult sd = signed_distance(model, Transform::identity(), batch);
    const std::vector<std::uint8_t> in = contains(model, Transform::identity(), batch);
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const std::vector<Vec3> alone{batch[i]};
      const SignedDistanceResult one = signed_distance(model, Transform::identity(), alone);
      EXPECT_EQ(sd.points[i].distance, one.points[0].distance) << i;
      EXPECT_EQ(sd.points[i].triangle, one.points[0].triangle) << i;
      EXPECT_EQ(in[i], contains(model, Transform::identity(), alone)[0]) << i;
      EXPECT_EQ(in[i] != 0, brute_inside(model.mesh(), Transform::identity(), batch[i])) << i;
    }
  }
}

// Named Concurrency.* so that scripts/sanitize.sh runs it under ThreadSanitizer.
TEST(Concurrency, PointQueriesMatchOneThreadAndBuildFirstUseDataOnce) {
  const Model model(make_torus(1.0, 0.35, 40, 20), {}, "torus");
  std::mt19937_64 rng(3);
  const std::vector<Vec3> points = random_points(rng, model.mesh().bounds(), 0.2, 3000);
  SignedDistanceResult one;
  std::vector<std::uint8_t> in_one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = signed_distance(model, Transform::identity(), points);
    in_one = contains(model, Transform::identity(), points);
  }
  const Model fresh(make_torus(1.0, 0.35, 40, 20), {}, "torus");  // first use from many threads
  const SignedDistanceResult many = signed_distance(fresh, Transform::identity(), points);
  EXPECT_EQ(contains(fresh, Transform::identity(), points), in_one);
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(one.points[i].distance, many.points[i].distance);
    ASSERT_EQ(one.points[i].triangle, many.points[i].triangle);
    ASSERT_EQ(one.points[i].closest, many.points[i].closest);
  }
}

}  // namespace
}  // namespace antcd
