// Contact normals, depths and the contact manifold of collide(): every contact's normal and depth
// is the triangle pair's separating push (B moved against the normal by the depth is free of A, by
// less it is not), no pair twice, and the manifold keeps 1..K contacts per region.
#include <antcd/collide.hpp>
#include <antcd/geometry.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <string>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using Tri = std::array<Vec3, 3>;

Tri world_triangle(const Model& m, const Transform& pose, std::uint32_t t) {
  const auto& idx = m.mesh().triangles[t];
  return {pose.apply(m.mesh().vertices[idx[0]]), pose.apply(m.mesh().vertices[idx[1]]),
          pose.apply(m.mesh().vertices[idx[2]])};
}

bool intersect_shifted(const Tri& a, const Tri& b, const Vec3& shift_b) {
  return geometry::triangles_intersect(a[0], a[1], a[2], b[0] + shift_b, b[1] + shift_b,
                                       b[2] + shift_b);
}

std::set<std::pair<std::uint32_t, std::uint32_t>> pair_set(const CollisionResult& r) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const Contact& c : r.contacts) out.emplace(c.triangle_a, c.triangle_b);
  return out;
}

// Each contact's normal and depth, checked on the world-frame triangles.
void expect_contacts_separate(const Model& a, const Transform& pa, const Model& b,
                              const Transform& pb, const CollisionResult& r, Scalar size,
                              const std::string& what) {
  const Scalar eps = 1e-9 * size;
  for (const Contact& c : r.contacts) {
    ASSERT_NEAR(c.normal.norm(), 1, 1e-12) << what;
    const Tri ta = world_triangle(a, pa, c.triangle_a);
    const Tri tb = world_triangle(b, pb, c.triangle_b);
    if (c.distance > 0) {  // apart, within delta
      EXPECT_DOUBLE_EQ(c.depth, -c.distance) << what;
      // The normal runs from B's closest point to A's: B pushed along it by the distance touches.
      const auto td =
          geometry::triangle_distance(ta[0], ta[1], ta[2], tb[0] + c.distance * c.normal,
                                      tb[1] + c.distance * c.normal, tb[2] + c.distance * c.normal);
      EXPECT_LE(td.distance, eps) << what;
      continue;
    }
    ASSERT_GE(c.depth, 0) << what;
    EXPECT_FALSE(intersect_shifted(ta, tb, -(c.depth + eps) * c.normal))
        << what << ": pair " << c.triangle_a << "," << c.triangle_b << " depth " << c.depth;
    if (c.depth > 2 * eps) {
      EXPECT_TRUE(intersect_shifted(ta, tb, -(c.depth - eps) * c.normal))
          << what << ": pair " << c.triangle_a << "," << c.triangle_b << " depth " << c.depth;
    }
  }
}

TEST(ContactNormals, RealMeshesEveryContactIsItsPairsSeparatingPush) {
  // Both scaled to a largest extent of 1, so two files of different units meet near the origin.
  const Model spider(test::unit_size(load_mesh(test::assimp_model("OBJ/spider.obj"))), {},
                     "spider");
  const Model wuson(test::unit_size(load_mesh(test::assimp_model("OFF/Wuson.off"))), {}, "wuson");
  std::mt19937_64 rng(15);
  const Scalar size = 2;
  int colliding = 0;
  std::size_t contacts = 0;
  for (int pose = 0; pose < 12; ++pose) {
    const Transform pa = test::random_pose(rng, 0.15);
    const Transform pb = test::random_pose(rng, 0.15);
    const Scalar delta = pose % 3 == 0 ? 0.01 : 0;
    CollisionRequest plain;
    plain.delta = delta;
    plain.all_contacts = true;
    CollisionRequest with_normals = plain;
    with_normals.contact_normals = true;
    const CollisionResult p = collide(spider, pa, wuson, pb, plain);
    const CollisionResult n = collide(spider, pa, wuson, pb, with_normals);
    const std::string what = "pose " + std::to_string(pose);
    // Same pairs with or without normals, each once; plain contacts carry no normal.
    ASSERT_EQ(n.contacts.size(), p.contacts.size()) << what;
    EXPECT_EQ(pair_set(n).size(), n.contacts.size()) << what << ": a triangle pair twice";
    EXPECT_EQ(pair_set(n), pair_set(p)) << what;
    for (const Contact& c : p.contacts) EXPECT_EQ(c.normal, Vec3::Zero()) << what;
    expect_contacts_separate(spider, pa, wuson, pb, n, size, what);
    colliding += n.colliding ? 1 : 0;
    contacts += n.contacts.size();
  }
  // The poses overlap often enough to test something.
  EXPECT_GE(colliding, 6);
  EXPECT_GE(contacts, 200u);
}

TEST(ContactNormals, SwappingTheModelsFlipsTheNormals) {
  const Model box(make_box(Vec3(0.5, 0.5, 0.5), 2), {}, "box");
  const Transform below = Transform::identity();
  const Transform above = Transform::from_axis_angle(Vec3(1, 2, 3), 0.3, Vec3(0.1, -0.2, 0.9));
  CollisionRequest req;
  req.all_contacts = true;
  req.contact_normals = true;
  const CollisionResult ab = collide(box, above, box, below, req);
  const CollisionResult ba = collide(box, below, box, above, req);
  ASSERT_TRUE(ab.colliding);
  ASSERT_EQ(ab.contacts.size(), ba.contacts.size());
  for (const Contact& c : ab.contacts) {
    const auto it = std::find_if(ba.contacts.begin(), ba.contacts.end(), [&](const Contact& d) {
      return d.triangle_a == c.triangle_b && d.triangle_b == c.triangle_a;
    });
    ASSERT_NE(it, ba.contacts.end());
    EXPECT_NEAR(it->depth, c.depth, 1e-12);
    if (c.depth > 1e-9) {
      EXPECT_NEAR((it->normal + c.normal).norm(), 0, 1e-9);
    }
  }
}

// A box pushed 0.05 into a floor (z = 0, facing up) and a wall (x = 0, facing -x) of model B.
struct Corner {
  Model box{make_box(Vec3(0.5, 0.5, 0.5), 4), {}, "box"};
  Model walls{merge({Mesh{{Vec3(0, -20, 0), Vec3(0, 20, 0), Vec3(-40, 0, 0)}, {{0, 1, 2}}},
                     Mesh{{Vec3(0, -20, 0), Vec3(0, 0, 40), Vec3(0, 20, 0)}, {{0, 1, 2}}}}),
              {},
              "corner"};
  Transform box_pose = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(-0.45, 0, 0.45));
};

TEST(ContactManifold, BoxInACornerGivesTwoRegionsOfAtMostKContacts) {
  const Corner s;
  CollisionRequest all;
  all.all_contacts = true;
  all.contact_normals = true;
  const CollisionResult full = collide(s.box, s.box_pose, s.walls, Transform::identity(), all);
  ASSERT_GT(full.contacts.size(), 20u);
  for (const Contact& c : full.contacts) {
    EXPECT_NEAR(c.depth, 0.05, 1e-12);
    const bool floor = c.triangle_b == 0;
    EXPECT_NEAR((c.normal - (floor ? Vec3::UnitZ() : Vec3(-Vec3::UnitX()))).norm(), 0, 1e-12);
  }
  for (std::uint32_t k : {1u, 2u, 4u, 6u}) {
    CollisionRequest req = all;
    req.manifold_points = k;
    const CollisionResult m = collide(s.box, s.box_pose, s.walls, Transform::identity(), req);
    ASSERT_TRUE(m.colliding);
    ASSERT_EQ(m.regions, 2u) << k;
    std::vector<std::size_t> per_region(m.regions, 0);
    for (const Contact& c : m.contacts) {
      ASSERT_LT(c.region, m.regions);
      ++per_region[c.region];
      EXPECT_TRUE(pair_set(full).count({c.triangle_a, c.triangle_b})) << "not a contact";
    }
    for (std::size_t n : per_region) {
      EXPECT_GE(n, 1u) << k;
      EXPECT_LE(n, k) << k;
    }
    // The kept points reach across each region: their spread is at least half the region's.
    for (std::uint32_t r = 0; r < m.regions; ++r) {
      const Vec3 normal =
          m.contacts[0].region == r ? m.contacts[0].normal : m.contacts.back().normal;
      Scalar full_span = 0, kept_span = 0;
      for (const Contact& x : full.contacts) {
        for (const Contact& y : full.contacts) {
          if (x.normal.dot(normal) > 0.9 && y.normal.dot(normal) > 0.9) {
            full_span = std::max(full_span, (x.point - y.point).norm());
          }
        }
      }
      for (const Contact& x : m.contacts) {
        for (const Contact& y : m.contacts) {
          if (x.region == r && y.region == r)
            kept_span = std::max(kept_span, (x.point - y.point).norm());
        }
      }
      if (k >= 2) {
        EXPECT_GE(kept_span, 0.5 * full_span) << "region " << r << " k " << k;
      }
    }
  }
}

TEST(ContactManifold, RealMeshesKeepBetweenOneAndKPerRegionCoveringEveryNormal) {
  const Model spider(load_mesh(test::assimp_model("OBJ/spider.obj")), {}, "spider");
  std::mt19937_64 rng(7);
  int checked = 0;
  for (int pose = 0; pose < 10; ++pose) {
    const Transform pa = test::random_pose(rng, 0.3 * spider.root().radius);
    const Transform pb = test::random_pose(rng, 0.3 * spider.root().radius);
    CollisionRequest req;
    req.all_contacts = true;
    req.contact_normals = true;
    const CollisionResult full = collide(spider, pa, spider, pb, req);
    req.manifold_points = 4;
    const CollisionResult m = collide(spider, pa, spider, pb, req);
    ASSERT_EQ(m.colliding, full.colliding);
    if (!full.colliding) continue;
    ++checked;
    std::vector<std::size_t> per_region(m.regions, 0);
    std::vector<const Contact*> seed(m.regions, nullptr);
    for (const Contact& c : m.contacts) {
      ASSERT_LT(c.region, m.regions);
      if (per_region[c.region]++ == 0) seed[c.region] = &c;
    }
    for (std::size_t n : per_region) {
      EXPECT_GE(n, 1u);
      EXPECT_LE(n, 4u);
    }
    EXPECT_LE(m.contacts.size(), full.contacts.size());
    // Every contact found has a region whose deepest contact's normal is within the angle.
    const Scalar min_cos = std::cos(req.manifold_angle);
    for (const Contact& c : full.contacts) {
      EXPECT_TRUE(std::any_of(seed.begin(), seed.end(), [&](const Contact* s) {
        return s->normal.dot(c.normal) >= min_cos;
      }));
    }
  }
  EXPECT_GE(checked, 5);
}

TEST(ContactManifold, RefusesAnAngleOutsideZeroToPi) {
  const Model box(make_box(Vec3(1, 1, 1)), {}, "box");
  CollisionRequest req;
  req.manifold_points = 4;
  req.manifold_angle = -0.1;
  EXPECT_THROW(collide(box, Transform::identity(), box, Transform::identity(), req), ArgumentError);
  req.manifold_angle = 4;
  EXPECT_THROW(collide(box, Transform::identity(), box, Transform::identity(), req), ArgumentError);
}

}  // namespace
}  // namespace antcd
