// Penetration depth of solids (antcd/penetration.hpp): certified intervals on shapes whose depth
// is known by hand, at several resolutions; the exact convex path; errors.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>
#include <antcd/points.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

namespace antcd {
namespace {

/// Checks everything the header promises of a general answer against the true depth `truth`:
/// lower <= truth <= upper, width <= rel_width * truth, A moved by upper (plus 1e-9 of the
/// scale) along direction is apart from B (collide with volume), the witness is inside both.
::testing::AssertionResult certified(const Model& a, const Transform& pa, const Model& b,
                                     const Transform& pb, const PenetrationResult& r, Scalar truth,
                                     Scalar rel_width = 0.01) {
  const Scalar scale = a.root().radius + b.root().radius;
  const Scalar slack = 1e-12 * (1 + truth);
  if (!(r.lower <= truth + slack)) {
    return ::testing::AssertionFailure() << "lower " << r.lower << " > depth " << truth;
  }
  if (!(r.upper >= truth - slack)) {
    return ::testing::AssertionFailure() << "upper " << r.upper << " < depth " << truth;
  }
  if (!(r.upper - r.lower <= rel_width * truth + slack)) {
    return ::testing::AssertionFailure()
           << "width " << r.upper - r.lower << " > " << rel_width << " of " << truth;
  }
  if (std::abs(r.direction.norm() - 1) > 1e-12) {
    return ::testing::AssertionFailure() << "direction not unit";
  }
  Transform moved = pa;
  moved.translation += (r.upper + 1e-9 * scale) * r.direction;
  CollisionRequest vol;
  vol.volume = true;
  if (collide(a, moved, b, pb, vol).colliding) {
    return ::testing::AssertionFailure() << "A moved by upper " << r.upper << " still collides";
  }
  if (r.overlapping) {
    const Vec3 w[1] = {r.witness};
    if (contains(a, pa, w)[0] == 0 || contains(b, pb, w)[0] == 0) {
      return ::testing::AssertionFailure() << "witness not inside both";
    }
  }
  return ::testing::AssertionSuccess();
}

PenetrationRequest general() {
  PenetrationRequest r;
  r.shape = PenetrationRequest::Shape::General;
  return r;
}

// One rotation for both models: the depth is that of the axis-aligned configuration.
const Transform kTilt = Transform::from_axis_angle(Vec3(1, 2, 3), 0.7);

Transform tilted(const Vec3& t) {
  Transform out = kTilt;
  out.translation = kTilt.rotation * t;
  return out;
}

// Two unit cubes overlapping by 0.3 along x (1.7 apart, offsets 0.3 and 0.2 across).
void check_boxes(int subdivisions) {
  const Model a(make_box(Vec3(1, 1, 1), subdivisions), {}, "box a");
  const Model b(make_box(Vec3(1, 1, 1), subdivisions), {}, "box b");
  const Transform pa = tilted(Vec3::Zero());
  const Transform pb = tilted(Vec3(1.7, 0.3, 0.2));
  const PenetrationResult r = penetration(a, pa, b, pb, general());
  SCOPED_TRACE(std::to_string(a.stats().triangles) + " triangles");
  EXPECT_TRUE(r.overlapping);
  EXPECT_FALSE(r.exact);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(certified(a, pa, b, pb, r, 0.3));
  EXPECT_GT(r.direction.dot(kTilt.rotation * -Vec3::UnitX()), 0.999);
}

TEST(PenetrationBoxes, GeneralIntervalContainsDepthAtEveryResolution) {
  for (int s : {1, 4, 12, 29}) check_boxes(s);  // 12, 192, 1728, 10092 triangles
}

// Excluded from the ASan run (scripts/sanitize.sh): two 101 568-triangle boxes.
TEST(PenetrationLarge, BoxesOfHundredThousandTriangles) { check_boxes(92); }

TEST(PenetrationBoxes, ConvexPathIsExact) {
  const Model a(make_box(Vec3(1, 1, 1), 3));
  const Model b(make_box(Vec3(1, 1, 1), 2));
  const Transform pa = tilted(Vec3::Zero());
  const Transform pb = tilted(Vec3(1.7, 0.3, 0.2));
  const PenetrationResult r = penetration(a, pa, b, pb);
  EXPECT_TRUE(r.exact);
  EXPECT_TRUE(r.overlapping);
  EXPECT_NEAR(r.lower, 0.3, 1e-12);
  EXPECT_EQ(r.lower, r.upper);
  EXPECT_TRUE(certified(a, pa, b, pb, r, 0.3, 1e-12));
  // A moved by the depth touches B at point_b.
  EXPECT_LT((r.point_a + r.upper * r.direction - r.point_b).norm(), 1e-12);
}

TEST(PenetrationSpheres, GeneralIntervalContainsExactConvexDepth) {
  // The ball bound is tight for smooth spheres; on a coarse polytope (16 x 8) the deepest pair of
  // inscribed balls falls 1.7 % short of the polytopes' depth (the depth's facet is an edge-edge
  // one), so that resolution gets a 2.5 % width and need not converge to 1 %.
  for (const auto& [slices, stacks] : {std::pair{16, 8}, {32, 16}, {64, 32}}) {
    const Scalar width = slices == 16 ? 0.025 : 0.01;
    const Model a(make_sphere(1.0, slices, stacks));
    const Model b(make_sphere(0.7, slices, stacks));
    const Transform pa = Transform::from_axis_angle(Vec3(0, 1, 1), 0.3, Vec3(0.1, 0, 0));
    const Transform pb = Transform::from_axis_angle(Vec3(1, 0, 1), 1.1, Vec3(1.3, 0.4, -0.2));
    const PenetrationResult exact = penetration(a, pa, b, pb);
    ASSERT_TRUE(exact.exact);
    ASSERT_TRUE(exact.overlapping);
    // The smooth spheres' depth, for scale: 1 + 0.7 - |c_b - c_a|.
    EXPECT_NEAR(exact.upper, 1.7 - Vec3(1.2, 0.4, -0.2).norm(), 0.05);
    const PenetrationResult r = penetration(a, pa, b, pb, general());
    SCOPED_TRACE(std::to_string(a.stats().triangles) + " triangles");
    if (slices > 16) {
      EXPECT_TRUE(r.converged);
    }
    EXPECT_TRUE(certified(a, pa, b, pb, r, exact.upper, width));
  }
}

// A plate 6 x 6 x 1 with a 2 x 2 square hole through it (one closed surface).
Mesh plate_with_hole() {
  Mesh m;
  const Scalar o = 3, i = 1, h = 0.5;
  const Scalar sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  for (Scalar z : {-h, h}) {
    for (int k = 0; k < 4; ++k) m.vertices.emplace_back(o * sx[k], o * sy[k], z);  // outer
    for (int k = 0; k < 4; ++k) m.vertices.emplace_back(i * sx[k], i * sy[k], z);  // inner
  }
  const auto ob = [](int k) { return std::uint32_t(k % 4); };
  const auto ib = [](int k) { return std::uint32_t(4 + k % 4); };
  const auto ot = [](int k) { return std::uint32_t(8 + k % 4); };
  const auto it = [](int k) { return std::uint32_t(12 + k % 4); };
  for (int k = 0; k < 4; ++k) {
    m.triangles.push_back({ot(k), ot(k + 1), it(k + 1)});  // top, counter-clockwise from +z
    m.triangles.push_back({ot(k), it(k + 1), it(k)});
    m.triangles.push_back({ob(k), ib(k + 1), ob(k + 1)});  // bottom
    m.triangles.push_back({ob(k), ib(k), ib(k + 1)});
    m.triangles.push_back({ob(k), ob(k + 1), ot(k + 1)});  // outer wall
    m.triangles.push_back({ob(k), ot(k + 1), ot(k)});
    m.triangles.push_back({ib(k), it(k + 1), ib(k + 1)});  // hole wall
    m.triangles.push_back({ib(k), it(k), it(k + 1)});
  }
  return m;
}

TEST(PenetrationPlate, BarInHoleWallLeavesIntoTheHole) {
  const Model plate(plate_with_hole(), {}, "plate");
  ASSERT_TRUE(plate.is_closed());
  EXPECT_FALSE(is_convex(plate));
  for (int s : {1, 6}) {
    // A 1 x 0.6 x 4 bar through the hole, lodged 0.2 deep into the hole's wall at x = 1. The way
    // out is -x, into the hole (depth 0.2); the plate's convex hull (the full 6 x 6 x 1 slab)
    // would need 1.8 (+x) or 2.5 (along z).
    const Model bar(make_box(Vec3(0.5, 0.3, 2), s), {}, "bar");
    const Transform pb = tilted(Vec3::Zero());
    const Transform pa = tilted(Vec3(0.7, 0.1, 0));
    const PenetrationResult r = penetration(bar, pa, plate, pb);
    SCOPED_TRACE(std::to_string(bar.stats().triangles) + " bar triangles");
    EXPECT_FALSE(r.exact);
    EXPECT_TRUE(r.converged);
    EXPECT_TRUE(certified(bar, pa, plate, pb, r, 0.2));
    EXPECT_GT(r.direction.dot(kTilt.rotation * -Vec3::UnitX()), 0.999);
  }
}

TEST(PenetrationTorus, OnAPostDepthOfTheLowestVertex) {
  for (const auto& [big, small] : {std::pair{24, 12}, {48, 24}, {192, 96}}) {
    // A torus lying flat on a post whose top (z = 0) is wider than the torus, sunk by ~0.15:
    // every translation that separates them lifts the lowest vertex v out of the post, and lifting
    // by v's depth does, so the depth is -z of the lowest vertex.
    const Model torus(make_torus(2, 0.5, big, small), {}, "torus");
    const Model post(make_box(Vec3(2.6, 2.6, 1)), {}, "post");
    const Transform pt = Transform::from_axis_angle(Vec3::UnitZ(), 0.1, Vec3(0, 0, 0.35));
    const Transform pp(Transform::identity().rotation, Vec3(0, 0, -1));
    Scalar lowest = 0;
    for (const Vec3& v : torus.mesh().vertices) lowest = std::min(lowest, pt.apply(v).z());
    const PenetrationResult r = penetration(torus, pt, post, pp);
    SCOPED_TRACE(std::to_string(torus.stats().triangles) + " torus triangles");
    EXPECT_FALSE(is_convex(torus));
    EXPECT_TRUE(r.converged);
    EXPECT_TRUE(certified(torus, pt, post, pp, r, -lowest));
  }
}

TEST(Penetration, NestedCubeLeavesThroughAFace) {
  const Model small(make_box(Vec3(0.2, 0.2, 0.2), 2));
  const Model big(make_box(Vec3(1, 1, 1), 2));
  const Transform p = tilted(Vec3(0.05, 0, 0));
  for (const PenetrationRequest& req : {PenetrationRequest{}, general()}) {
    const PenetrationResult r = penetration(small, p, big, kTilt, req);
    EXPECT_TRUE(r.overlapping);
    EXPECT_TRUE(certified(small, p, big, kTilt, r, 1.15));
  }
}

TEST(Penetration, ApartAndTouching) {
  const Model a(make_box(Vec3(1, 1, 1)));
  const Model b(make_sphere(1, 16, 8));
  for (const PenetrationRequest& req : {PenetrationRequest{}, general()}) {
    const PenetrationResult r =
        penetration(a, Transform::identity(), b, Transform(Mat3::Identity(), Vec3(2.5, 0, 0)), req);
    EXPECT_FALSE(r.overlapping);
    EXPECT_EQ(r.lower, 0);
    EXPECT_EQ(r.upper, 0);
    EXPECT_TRUE(r.converged);
  }
  // Face on face: touching, no interior overlap.
  const PenetrationResult t =
      penetration(a, Transform::identity(), a, Transform(Mat3::Identity(), Vec3(2, 0.5, 0)));
  EXPECT_FALSE(t.overlapping);
  EXPECT_EQ(t.upper, 0);
}

TEST(Penetration, MutatedUpperBoundIsCaught) {
  // The checks above can fail: an upper bound 5 % too small is rejected.
  const Model a(make_box(Vec3(1, 1, 1), 4));
  const Transform pa = tilted(Vec3::Zero());
  const Transform pb = tilted(Vec3(1.7, 0.3, 0.2));
  PenetrationResult r = penetration(a, pa, a, pb, general());
  ASSERT_TRUE(certified(a, pa, a, pb, r, 0.3));
  r.upper *= 0.95;
  EXPECT_FALSE(certified(a, pa, a, pb, r, 0.3));
  r.lower = r.upper;  // even with the truth check loosened, the move no longer separates
  EXPECT_FALSE(certified(a, pa, a, pb, r, r.upper, 1));
}

TEST(Penetration, ConvexityDetection) {
  EXPECT_TRUE(is_convex(Model(make_box(Vec3(1, 2, 3), 3))));
  EXPECT_TRUE(is_convex(Model(make_sphere(1, 12, 6))));
  EXPECT_TRUE(is_convex(Model(make_cylinder(1, 2, 12))));
  EXPECT_FALSE(is_convex(Model(make_torus(2, 0.5))));
  EXPECT_FALSE(is_convex(Model(
      merge({make_box(Vec3(1, 1, 1)),
             transformed(make_box(Vec3(1, 1, 1)), Transform(Mat3::Identity(), Vec3(5, 0, 0)))}))));
}

TEST(Penetration, OpenModelAndBadRequestThrow) {
  Mesh open = make_box(Vec3(1, 1, 1));
  open.triangles.pop_back();
  const Model o(open, {}, "lid-less box");
  const Model b(make_box(Vec3(1, 1, 1)));
  try {
    (void)penetration(b, Transform::identity(), o, Transform::identity());
    FAIL() << "no throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("lid-less box"), std::string::npos) << e.what();
  }
  PenetrationRequest bad;
  bad.rel_tolerance = 1;
  EXPECT_THROW((void)penetration(b, Transform::identity(), b, Transform::identity(), bad),
               ArgumentError);
  bad = {};
  bad.max_evaluations = 0;
  EXPECT_THROW((void)penetration(b, Transform::identity(), b, Transform::identity(), bad),
               ArgumentError);
}

}  // namespace
}  // namespace antcd

namespace antcd {
namespace {

TEST(SignedDistance, NegativePenetrationDepthWhenSolidsOverlap) {
  const Model a(make_box(Vec3(1, 1, 1), 2), {}, "a");
  DistanceRequest req;
  // Overlapping by 0.3 (convex: exact).
  DistanceResult r = signed_distance(a, Transform::identity(), a,
                                     Transform(Mat3::Identity(), Vec3(1.7, 0.3, 0.2)), req);
  EXPECT_NEAR(r.distance, -0.3, 1e-12);
  EXPECT_LE(r.lower_bound, r.distance);
  // Apart by 0.5: the surface distance.
  r = signed_distance(a, Transform::identity(), a, Transform(Mat3::Identity(), Vec3(2.5, 0, 0)),
                      req);
  EXPECT_NEAR(r.distance, 0.5, 1e-12);
  // Touching face on face: 0.
  r = signed_distance(a, Transform::identity(), a, Transform(Mat3::Identity(), Vec3(2, 0.5, 0)),
                      req);
  EXPECT_EQ(r.distance, 0);
  // Nested (surfaces 0.8 apart): -(0.2 + 1) = -1.2, general solids (a torus is not convex).
  const Model small(make_box(Vec3(0.2, 0.2, 0.2)));
  r = signed_distance(small, Transform::identity(), a, Transform::identity(), req);
  EXPECT_NEAR(r.distance, -1.2, 1e-12);
  const Model torus(make_torus(2, 0.5, 32, 16));
  r = signed_distance(torus, Transform(Mat3::Identity(), Vec3(0, 0, 0.35)), a,
                      Transform(Mat3::Identity(), Vec3(2, 0, -1)), req);
  EXPECT_LT(r.distance, 0);
  EXPECT_TRUE(r.approximate);
  // distance() is the unsigned surface distance.
  r = distance(small, Transform::identity(), a, Transform::identity());
  EXPECT_NEAR(r.distance, 0.8, 1e-12);
  Mesh open = make_box(Vec3(1, 1, 1));
  open.triangles.pop_back();
  EXPECT_THROW((void)signed_distance(Model(open, {}, "open"), Transform::identity(), a,
                                     Transform(Mat3::Identity(), Vec3(5, 0, 0)), req),
               ArgumentError);
}

}  // namespace
}  // namespace antcd

namespace antcd {
namespace {

TEST(Penetration, ConcurrentQueriesOnSharedModelsAgree) {
  // Fresh models: the first queries build their convex and point caches concurrently.
  const Model box(make_box(Vec3(1, 1, 1), 3));
  const Model torus(make_torus(2, 0.5, 24, 12));
  std::vector<Transform> poses;
  for (int k = 0; k < 8; ++k) {
    poses.push_back(Transform::from_axis_angle(Vec3(1, k, 2), 0.3 * k, Vec3(1.5 + 0.05 * k, 0, 0)));
  }
  const auto run = [&](std::size_t k) {
    const PenetrationResult c = penetration(box, Transform::identity(), box, poses[k]);
    const PenetrationResult g = penetration(torus, poses[k], box, Transform::identity());
    return std::array<Scalar, 4>{c.lower, c.upper, g.lower, g.upper};
  };
  std::vector<std::array<Scalar, 4>> parallel(poses.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    threads.emplace_back([&, k] { parallel[k] = run(k); });
  }
  for (std::thread& t : threads) t.join();
  for (std::size_t k = 0; k < poses.size(); ++k) EXPECT_EQ(parallel[k], run(k)) << k;
}

}  // namespace
}  // namespace antcd
