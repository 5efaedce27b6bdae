// Contact normal and penetration depth of triangle pairs (geometry::triangle_penetration) against
// the motion that separates them: pushing B against the normal by the depth (and a hair more)
// separates the pair, by less does not, and no sampled direction separates with a shorter push.
#include <antcd/geometry.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace antcd {
namespace {

using Tri = std::array<Vec3, 3>;

bool intersect(const Tri& a, const Tri& b, const Vec3& shift_b) {
  return geometry::triangles_intersect(a[0], a[1], a[2], b[0] + shift_b, b[1] + shift_b,
                                       b[2] + shift_b);
}

geometry::TrianglePenetration penetration(const Tri& a, const Tri& b) {
  return geometry::triangle_penetration(a[0], a[1], a[2], b[0], b[1], b[2]);
}

// The shortest push of B along -u (u unit) that separates the pair: the set of s where
// A ∩ (B - s u) is not empty is an interval (a line through the convex set B - A) containing 0,
// whose upper end is found by bisection on the exact predicate.
Scalar push_to_separate(const Tri& a, const Tri& b, const Vec3& u, Scalar reach) {
  Scalar lo = 0, hi = reach;
  if (intersect(a, b, -hi * u)) return reach;  // not separated within reach
  for (int it = 0; it < 60; ++it) {
    const Scalar mid = 0.5 * (lo + hi);
    (intersect(a, b, -mid * u) ? lo : hi) = mid;
  }
  return hi;
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<Scalar> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v.normalized();
}

TEST(TrianglePenetration, SpikeThroughAFaceHasTheSpikesDepthAndPointsFromBToA) {
  // A: a wide horizontal triangle at z = 0. B: a vertical triangle from z = -3 whose apex pokes
  // 0.25 above A. The cheapest way out is B down by 0.25: A lies on B's +z side.
  const Tri a = {Vec3(-10, -10, 0), Vec3(10, -10, 0), Vec3(0, 10, 0)};
  const Tri b = {Vec3(-1, 0.5, -3), Vec3(1, 0.5, -3), Vec3(0.2, 0.5, 0.25)};
  const auto p = penetration(a, b);
  EXPECT_NEAR(p.depth, 0.25, 1e-14);
  EXPECT_NEAR((p.normal - Vec3::UnitZ()).norm(), 0, 1e-14);
  // Swapping the roles flips the normal and keeps the depth.
  const auto q = penetration(b, a);
  EXPECT_NEAR(q.depth, 0.25, 1e-14);
  EXPECT_NEAR((q.normal + Vec3::UnitZ()).norm(), 0, 1e-14);
  // Moving A instead: up along the normal by the depth and a little more separates.
  const Tri a_up = {a[0] + 0.2501 * p.normal, a[1] + 0.2501 * p.normal, a[2] + 0.2501 * p.normal};
  EXPECT_FALSE(intersect(a_up, b, Vec3::Zero()));
}

TEST(TrianglePenetration, TouchingHasDepthZeroAndApartHasMinusDistance) {
  // Sharing one vertex, B below A's plane.
  const Tri a = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const Tri b = {Vec3(0, 0, 0), Vec3(-1, 0, -1), Vec3(0, -1, -1)};
  const auto t = penetration(a, b);
  EXPECT_EQ(t.depth, 0);
  EXPECT_NEAR(t.normal.norm(), 1, 1e-15);
  EXPECT_FALSE(intersect(a, b, -1e-9 * t.normal));
  // Coplanar faces of two solids resting on each other (opposite orientations): B's normal.
  const Tri top_of_b = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};     // faces +z
  const Tri bottom_of_a = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0)};  // faces -z
  const auto c = penetration(bottom_of_a, top_of_b);
  EXPECT_EQ(c.depth, 0);
  EXPECT_NEAR((c.normal - Vec3::UnitZ()).norm(), 0, 1e-15);
  // Apart by 0.5 along z: depth -0.5, normal from B's closest point up to A's.
  const Tri lifted = {a[0] + Vec3(0, 0, 0.5), a[1] + Vec3(0, 0, 0.5), a[2] + Vec3(0, 0, 0.5)};
  const auto s = penetration(lifted, b);
  EXPECT_NEAR(s.depth, -0.5, 1e-15);
  EXPECT_NEAR((s.normal - Vec3::UnitZ()).norm(), 0, 1e-15);
}

TEST(TrianglePenetration, PushingBByTheDepthSeparatesAndNoDirectionDoesWithLess) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  int checked = 0;
  for (int trial = 0; checked < 200 && trial < 20000; ++trial) {
    Tri a, b;
    for (Vec3& v : a) v = Vec3(unit(rng), unit(rng), unit(rng));
    const Vec3 offset = 0.4 * Vec3(unit(rng), unit(rng), unit(rng));
    for (Vec3& v : b) v = Vec3(unit(rng), unit(rng), unit(rng)) + offset;
    if (geometry::is_degenerate_triangle(a[0], a[1], a[2]) ||
        geometry::is_degenerate_triangle(b[0], b[1], b[2]) || !intersect(a, b, Vec3::Zero())) {
      continue;
    }
    ++checked;
    const auto p = penetration(a, b);
    ASSERT_NEAR(p.normal.norm(), 1, 1e-14) << trial;
    ASSERT_GE(p.depth, 0) << trial;
    constexpr Scalar kEps = 1e-9;
    // Sign and length: B pushed against the normal by the depth (+eps) is free of A ...
    EXPECT_FALSE(intersect(a, b, -(p.depth + kEps) * p.normal)) << trial;
    // ... pushed by less, or pushed the other way, it still intersects.
    if (p.depth > 2 * kEps) {
      EXPECT_TRUE(intersect(a, b, -(p.depth - kEps) * p.normal)) << trial;
      EXPECT_TRUE(intersect(a, b, (p.depth - kEps) * p.normal)) << trial;
    }
    // Minimal: no direction separates with a shorter push (sampled directions and the normal).
    EXPECT_NEAR(push_to_separate(a, b, p.normal, 10), p.depth, 1e-9) << trial;
    for (int k = 0; k < 32; ++k) {
      const Vec3 u = random_unit(rng);
      ASSERT_GE(push_to_separate(a, b, u, 10), p.depth - 1e-9) << trial << " direction " << k;
    }
    // Roles swapped: same depth, opposite normal (B pushed away from A is A pushed away from B).
    const auto q = penetration(b, a);
    EXPECT_NEAR(q.depth, p.depth, 1e-12) << trial;
  }
  EXPECT_EQ(checked, 200);
}

}  // namespace
}  // namespace antcd
