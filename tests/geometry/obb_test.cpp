// The 15-axis separating-axis test against an independent reference.
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>

#include <random>

#include "support/test_support.hpp"

namespace antcd {
namespace {

// Corners of a box.
std::array<Vec3, 8> corners(const Obb& b) {
  std::array<Vec3, 8> out;
  for (int i = 0; i < 8; ++i) {
    const Vec3 s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    out[i] = b.center + b.axes * s.cwiseProduct(b.half_extents);
  }
  return out;
}

bool contains(const Obb& b, const Vec3& p) {
  const Vec3 local = b.axes.transpose() * (p - b.center);
  return (local.cwiseAbs().array() <= b.half_extents.array()).all();
}

// Reference: two convex solids intersect iff their surfaces intersect or one holds a vertex of the
// other. Surfaces are compared with the triangle test on the boxes' 12 triangles each.
bool boxes_intersect_reference(const Obb& a, const Obb& b) {
  const Mesh unit = make_box(Vec3(1, 1, 1));
  const auto surface = [&](const Obb& box) {
    std::vector<Vec3> v;
    for (const Vec3& p : unit.vertices)
      v.push_back(box.center + box.axes * p.cwiseProduct(box.half_extents));
    return v;
  };
  const auto va = surface(a);
  const auto vb = surface(b);
  for (const auto& ta : unit.triangles) {
    for (const auto& tb : unit.triangles) {
      if (geometry::triangles_intersect(va[ta[0]], va[ta[1]], va[ta[2]], vb[tb[0]], vb[tb[1]],
                                        vb[tb[2]])) {
        return true;
      }
    }
  }
  return contains(a, corners(b)[0]) || contains(b, corners(a)[0]);
}

Obb random_box(std::mt19937_64& rng, Scalar spread) {
  std::uniform_real_distribution<Scalar> size(0.05, 1.0);
  const Transform pose = test::random_pose(rng, spread);
  Obb b;
  b.center = pose.translation;
  b.axes = pose.rotation;
  b.half_extents = Vec3(size(rng), size(rng), size(rng));
  return b;
}

TEST(ObbOverlap, AgreesWithSurfaceReferenceOnRandomBoxes) {
  std::mt19937_64 rng(17);
  int overlapping = 0;
  for (int i = 0; i < 3000; ++i) {
    const Obb a = random_box(rng, 0.0);
    const Obb b = random_box(rng, 1.5);
    const bool expected = boxes_intersect_reference(a, b);
    EXPECT_EQ(geometry::obb_overlap(a, b), expected) << "case " << i;
    EXPECT_EQ(geometry::obb_overlap(b, a), expected) << "case " << i << " swapped";
    overlapping += expected;
  }
  EXPECT_GT(overlapping, 300);
  EXPECT_LT(overlapping, 2700);
}

TEST(ObbOverlap, RelativeTransformFormMatchesWorldForm) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Obb a = random_box(rng, 0.0);
    const Obb b_local = random_box(rng, 0.3);
    const Transform b_to_a = test::random_pose(rng, 1.5);
    Obb b_world = b_local;
    b_world.center = b_to_a.apply(b_local.center);
    b_world.axes = b_to_a.rotation * b_local.axes;
    EXPECT_EQ(geometry::obb_overlap(a, b_local, b_to_a, 0.0), geometry::obb_overlap(a, b_world));
  }
}

TEST(ObbOverlap, MarginIsConservativeForDistance) {
  // Boxes at distance d apart report overlap once the margin reaches d.
  Obb a;
  a.half_extents = Vec3(1, 1, 1);
  Obb b = a;
  b.center = Vec3(2.5, 0, 0);
  EXPECT_FALSE(geometry::obb_overlap(a, b, 0.0));
  EXPECT_FALSE(geometry::obb_overlap(a, b, 0.49));
  EXPECT_TRUE(geometry::obb_overlap(a, b, 0.5));
  // Corner to corner at distance sqrt(3) * 0.5: an axis-aligned margin of 0.5 already covers it
  // (the grown box is larger than the Minkowski sum), and 0.49 * sqrt(3) > 0.5 too.
  b.center = Vec3(2.5, 2.5, 2.5);
  EXPECT_TRUE(geometry::obb_overlap(a, b, 0.5));
  EXPECT_FALSE(geometry::obb_overlap(a, b, 0.4));
}

TEST(ObbOverlap, TouchingFacesEdgesAndCornersOverlap) {
  Obb a;
  a.half_extents = Vec3(1, 1, 1);
  Obb b = a;
  for (const Vec3& c : {Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(2, 2, 2), Vec3(0, -2, 2)}) {
    b.center = c;
    EXPECT_TRUE(geometry::obb_overlap(a, b)) << c.transpose();
  }
  b.center = Vec3(2, 2, 2.0001);
  EXPECT_FALSE(geometry::obb_overlap(a, b));
}

TEST(SphereOverlap, TouchingAndMargin) {
  const Sphere a{Vec3(0, 0, 0), 1.0};
  const Sphere b{Vec3(3, 0, 0), 1.0};
  EXPECT_FALSE(geometry::sphere_overlap(a, b));
  EXPECT_TRUE(geometry::sphere_overlap(a, b, 1.0));
  EXPECT_FALSE(geometry::sphere_overlap(a, b, 0.999));
  EXPECT_TRUE(geometry::sphere_overlap(a, Sphere{Vec3(2, 0, 0), 1.0}));
}

}  // namespace
}  // namespace antcd
