// Ray casts against brute force over every triangle of every object, computed here another way
// (plane intersection, then inside tests by signed areas), on generated and real meshes.
#include <antcd/load.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

struct BruteHit {
  ObjectId object;
  std::uint32_t triangle;
  Scalar distance;
  bool ambiguous;  // grazing or within rounding of an edge: either answer is right
};

std::vector<BruteHit> brute_force(const World& world, const Ray& ray) {
  const Vec3 d = ray.direction.normalized();
  std::vector<BruteHit> out;
  for (const ObjectId id : world.objects()) {
    const Mesh& mesh = world.model(id).mesh();
    const Transform& pose = world.pose(id);
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 a = pose.apply(mesh.vertices[tri[0]]);
      const Vec3 b = pose.apply(mesh.vertices[tri[1]]);
      const Vec3 c = pose.apply(mesh.vertices[tri[2]]);
      if (geometry::is_degenerate_triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                           mesh.vertices[tri[2]])) {
        continue;
      }
      const Vec3 n = (b - a).cross(c - a);
      const Scalar denom = n.dot(d);
      const Scalar cosine = std::abs(denom) / n.norm();
      if (cosine < 1e-12) continue;
      const Scalar s = n.dot(a - ray.origin) / denom;
      const Scalar scale = (b - a).norm() + (c - a).norm() + (c - b).norm();
      const Vec3 p = ray.origin + s * d;
      // Signed distances of p from each edge within the plane, relative to the triangle's size.
      const Vec3 un = n.normalized();
      const Scalar e0 = (b - a).cross(p - a).dot(un) / scale;
      const Scalar e1 = (c - b).cross(p - b).dot(un) / scale;
      const Scalar e2 = (a - c).cross(p - c).dot(un) / scale;
      const Scalar inside = std::min({e0, e1, e2});
      const Scalar tol = 1e-7;
      const bool near_range = std::abs(s) < tol * (1 + std::abs(s)) ||
                              std::abs(s - ray.max_distance) < tol * (1 + std::abs(s));
      if (inside < -tol * scale) continue;
      if (s < -tol || s > ray.max_distance * (1 + tol) + tol) continue;
      out.push_back({id, t, s, inside < tol * scale || cosine < 1e-6 || near_range});
    }
  }
  return out;
}

void check_rays(const World& world, std::mt19937_64& rng, int rays, Scalar extent,
                std::size_t& hits_seen) {
  std::uniform_real_distribution<Scalar> u(-1, 1);
  for (int k = 0; k < rays; ++k) {
    Ray ray;
    ray.origin = extent * Vec3(u(rng), u(rng), u(rng));
    // Aim near some object so that most rays hit something.
    const std::vector<ObjectId> ids = world.objects();
    const Vec3 target =
        world.pose(ids[rng() % ids.size()]).translation + 0.3 * Vec3(u(rng), u(rng), u(rng));
    ray.direction = (target - ray.origin) * (0.5 + u(rng) * u(rng));
    if (k % 4 == 3) ray.max_distance = (target - ray.origin).norm();
    const std::vector<BruteHit> brute = brute_force(world, ray);
    const std::vector<RayHit> all = world.raycast_all(ray);
    hits_seen += all.size();
    // Every unambiguous brute-force hit is reported, at the same distance.
    for (const BruteHit& b : brute) {
      const auto it = std::find_if(all.begin(), all.end(), [&](const RayHit& h) {
        return h.object == b.object && h.triangle == b.triangle;
      });
      if (b.ambiguous && it == all.end()) continue;
      ASSERT_NE(it, all.end()) << "ray " << k << " missed triangle " << b.triangle;
      EXPECT_NEAR(it->distance, b.distance, 1e-9 * (1 + b.distance));
    }
    // Every reported hit is a brute-force hit, consistent, and the list is sorted.
    for (const RayHit& h : all) {
      const auto it = std::find_if(brute.begin(), brute.end(), [&](const BruteHit& b) {
        return h.object == b.object && h.triangle == b.triangle;
      });
      ASSERT_NE(it, brute.end()) << "ray " << k << " reported triangle " << h.triangle;
      EXPECT_NEAR((h.point - (ray.origin + h.distance * ray.direction.normalized())).norm(), 0,
                  1e-9 * (1 + h.distance));
      EXPECT_NEAR(h.normal.norm(), 1, 1e-12);
      EXPECT_LE(h.normal.dot(ray.direction), 0);
      EXPECT_TRUE(h.distance >= 0 && h.distance <= ray.max_distance);
    }
    EXPECT_TRUE(std::is_sorted(all.begin(), all.end(), [](const RayHit& a, const RayHit& b) {
      return a.distance < b.distance;
    }));
    // The first hit is the first of all hits.
    const std::optional<RayHit> first = world.raycast(ray);
    ASSERT_EQ(first.has_value(), !all.empty());
    if (first) {
      EXPECT_EQ(first->object, all.front().object);
      EXPECT_EQ(first->triangle, all.front().triangle);
      EXPECT_EQ(first->distance, all.front().distance);
      // Same answer as the single-model cast on that object.
      const auto single = raycast(world.model(first->object), world.pose(first->object), ray);
      ASSERT_TRUE(single.has_value());
      EXPECT_EQ(single->distance, first->distance);
    }
  }
}

TEST(WorldRaycast, GeneratedMeshesMatchBruteForceOverAllTriangles) {
  World world;
  std::mt19937_64 rng(5);
  const std::shared_ptr<const Model> models[] = {
      std::make_shared<const Model>(make_sphere(0.5, 12, 6)),
      std::make_shared<const Model>(make_box(Vec3(0.6, 0.2, 0.3), 2)),
      std::make_shared<const Model>(make_torus(0.5, 0.15, 16, 8))};
  for (int i = 0; i < 25; ++i) world.add(models[i % 3], test::random_pose(rng, 3));
  std::size_t hits = 0;
  check_rays(world, rng, 300, 5, hits);
  EXPECT_GT(hits, 300u);  // not vacuous
}

TEST(WorldRaycast, RealMeshesMatchBruteForceOverAllTriangles) {
  World world;
  std::mt19937_64 rng(6);
  auto spider = std::make_shared<const Model>(load_mesh(test::assimp_model("OBJ/spider.obj")));
  // The spider is about 40 units wide: poses in a box of that scale.
  for (int i = 0; i < 8; ++i) world.add(spider, test::random_pose(rng, 40));
  std::size_t hits = 0;
  check_rays(world, rng, 150, 80, hits);
  EXPECT_GT(hits, 150u);
}

TEST(WorldRaycast, FiltersAndEdgeCases) {
  World world;
  auto box = std::make_shared<const Model>(make_box(Vec3(1, 1, 1), 1));
  const ObjectId near = world.add(box, Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(0, 0, 5)),
                                  {"near", 0, 1, ~0U});
  const ObjectId far = world.add(box, Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(0, 0, 10)),
                                 {"far", 0, 2, ~0U});
  Ray ray{Vec3::Zero(), Vec3(0, 0, 2)};
  auto hit = world.raycast(ray);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->object, near);
  EXPECT_DOUBLE_EQ(hit->distance, 4);
  EXPECT_TRUE(hit->normal.isApprox(Vec3(0, 0, -1)));
  // The ray enters and leaves each box: four faces (each face hit on one triangle or on the
  // shared diagonal, where both triangles count).
  EXPECT_GE(world.raycast_all(ray).size(), 4u);
  hit = world.raycast(ray, {~0U, 2});  // only group 2
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->object, far);
  ray.max_distance = 3.5;
  EXPECT_FALSE(world.raycast(ray));
  ray.max_distance = 4;  // exactly touching the face counts
  EXPECT_TRUE(world.raycast(ray));
  // Parallel to the xy faces, inside the slab of a box: hits the side faces only.
  const Ray side{Vec3(-5, 0.25, 5.25), Vec3(1, 0, 0)};
  hit = world.raycast(side);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->distance, 4);
  EXPECT_TRUE(hit->normal.isApprox(Vec3(-1, 0, 0)));
  world.remove(near);
  EXPECT_EQ(world.raycast(Ray{Vec3::Zero(), Vec3::UnitZ()})->object, far);
}

}  // namespace
}  // namespace antcd
