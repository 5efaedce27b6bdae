// Model::refit: after moving the vertices, every query answers as on a Model built from the moved
// mesh; the volumes still bound their triangles; bad input is rejected and leaves the Model as it
// was.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/points.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

/// A smooth non-rigid deformation: twist about z and a radial bulge.
std::vector<Vec3> deform(const std::vector<Vec3>& vertices, Scalar amount) {
  std::vector<Vec3> out;
  for (const Vec3& v : vertices) {
    const Scalar a = amount * v.z();
    const Scalar s = 1 + 0.3 * amount * std::sin(3 * v.x());
    out.emplace_back(s * (std::cos(a) * v.x() - std::sin(a) * v.y()),
                     s * (std::sin(a) * v.x() + std::cos(a) * v.y()), v.z() + 0.2 * amount * v.x());
  }
  return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_of(const CollisionResult& r) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const Contact& c : r.contacts) out.emplace_back(c.triangle_a, c.triangle_b);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Refit, QueriesMatchAFreshlyBuiltModel) {
  const Mesh original = make_torus(1.0, 0.3, 32, 16);
  const Model other(make_sphere(0.5, 16, 8), {}, "sphere");
  std::mt19937_64 rng(9);
  Model refitted(original, {}, "torus");
  for (const Scalar amount : {0.3, 0.8, -0.5}) {
    Mesh moved = original;
    moved.vertices = deform(original.vertices, amount);
    refitted.refit(moved.vertices);
    const Model fresh(moved, {}, "fresh");
    // Every node's volumes hold its triangles.
    for (const BvhNode& node : refitted.nodes()) {
      if (!node.is_leaf()) continue;
      for (std::uint32_t k = 0; k < 3 * node.count; ++k) {
        const Vec3 v =
            refitted.leaf_corners()(node.first_or_right + k / 3, static_cast<int>(k % 3));
        const Vec3 local = node.axes().transpose() * (v - node.center);
        ASSERT_TRUE(((local.cwiseAbs() - node.half_extents()).array() <= 1e-12).all());
        ASSERT_LE((v - node.center).norm(), node.radius + 1e-12);
      }
    }
    CollisionRequest all;
    all.all_contacts = true;
    all.delta = 0.01;
    int colliding = 0;
    for (int i = 0; i < 60; ++i) {
      const Transform pose = test::random_pose(rng, 1.5);
      const CollisionResult a = collide(refitted, Transform::identity(), other, pose, all);
      const CollisionResult b = collide(fresh, Transform::identity(), other, pose, all);
      ASSERT_EQ(a.colliding, b.colliding) << "pose " << i;
      ASSERT_EQ(pairs_of(a), pairs_of(b)) << "pose " << i;
      colliding += a.colliding ? 1 : 0;
      const DistanceResult da = distance(refitted, Transform::identity(), other, pose);
      const DistanceResult db = distance(fresh, Transform::identity(), other, pose);
      ASSERT_NEAR(da.distance, db.distance, 1e-12) << "pose " << i;
    }
    EXPECT_GT(colliding, 5);
    EXPECT_LT(colliding, 55);
    std::vector<Vec3> points;
    std::uniform_real_distribution<Scalar> u(-1.5, 1.5);
    for (int i = 0; i < 300; ++i) points.emplace_back(u(rng), u(rng), 0.5 * u(rng));
    EXPECT_EQ(contains(refitted, Transform::identity(), points),
              contains(fresh, Transform::identity(), points));
    const SignedDistanceResult sa = signed_distance(refitted, Transform::identity(), points);
    const SignedDistanceResult sb = signed_distance(fresh, Transform::identity(), points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_NEAR(sa.points[i].distance, sb.points[i].distance, 1e-12) << "point " << i;
    }
  }
}

TEST(Refit, BadInputIsAnArgumentErrorAndChangesNothing) {
  const Mesh mesh = make_box(Vec3(1, 1, 1), 1);
  Model model(mesh, {}, "box");
  const std::vector<BvhNode> before(model.nodes().begin(), model.nodes().end());
  std::vector<Vec3> fewer(mesh.vertices.begin(), mesh.vertices.end() - 1);
  try {
    model.refit(fewer);
    FAIL() << "wrong count must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("box"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vertices"), std::string::npos) << e.what();
  }
  std::vector<Vec3> nan = mesh.vertices;
  nan[3].y() = std::nan("");
  try {
    model.refit(nan);
    FAIL() << "NaN must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
  for (const double bad : {-1.0, std::nan("")}) {
    try {
      model.refit(mesh.vertices, bad);
      FAIL() << "rebuild_above " << bad << " must throw";
    } catch (const ArgumentError& e) {
      EXPECT_NE(
          std::string(e.what()).find("box: refit: rebuild_above must be >= 0 (or +inf), got "),
          std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(model.mesh().vertices, mesh.vertices);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(model.nodes()[i].center, before[i].center);
  }
}

}  // namespace
}  // namespace antcd
