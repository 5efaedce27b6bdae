// Solids: Model::is_closed and CollisionRequest::volume (one model wholly inside another).
#include <antcd/collide.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "support/test_support.hpp"

namespace antcd {
namespace {

TEST(IsClosed, GeneratedSolidsAreClosedAndHolesOrFlipsAreNot) {
  for (const Mesh& m : {make_box(Vec3(1, 2, 3), 2), make_sphere(1.0, 16, 8),
                        make_cylinder(0.5, 2.0, 12), make_torus(1.0, 0.3, 16, 8)}) {
    EXPECT_TRUE(is_closed(m));
    EXPECT_TRUE(Model(m).is_closed());
    Mesh holed = m;
    holed.triangles.pop_back();
    EXPECT_FALSE(is_closed(holed));
    Mesh flipped_one = m;
    std::swap(flipped_one.triangles[0][1], flipped_one.triangles[0][2]);
    EXPECT_FALSE(is_closed(flipped_one)) << "inconsistent orientation";
    Mesh flipped_all = m;
    for (auto& t : flipped_all.triangles) std::swap(t[1], t[2]);
    EXPECT_TRUE(is_closed(flipped_all)) << "inward-facing but consistent";
    Mesh doubled = merge({m, m});
    EXPECT_TRUE(is_closed(doubled)) << "two disjoint closed copies (distinct indices)";
    doubled.triangles.push_back(m.triangles[0]);
    EXPECT_FALSE(is_closed(doubled)) << "an edge used by three triangles";
  }
}

TEST(Volume, NestedClosedModelsCollideOnlyWithVolume) {
  const Model outer(make_sphere(2.0, 32, 16), {}, "outer");
  const Model inner(make_torus(0.5, 0.2, 24, 12), {}, "inner");
  const Transform id = Transform::identity();
  EXPECT_FALSE(collide(outer, id, inner, id).colliding) << "surface semantics by default";
  CollisionRequest volume;
  volume.volume = true;
  for (const bool all : {false, true}) {
    volume.all_contacts = all;
    const CollisionResult r = collide(outer, id, inner, id, volume);
    EXPECT_TRUE(r.colliding);
    EXPECT_TRUE(r.contained);
    EXPECT_FALSE(r.surface_only);
    EXPECT_TRUE(r.contacts.empty());
    const CollisionResult swapped = collide(inner, id, outer, id, volume);
    EXPECT_TRUE(swapped.colliding && swapped.contained) << "inner as A";
  }
  // Moved out: apart; moved to cross the sphere: a surface contact, not a containment.
  const CollisionResult apart = collide(
      outer, id, inner, Transform::from_axis_angle(Vec3::UnitX(), 0, Vec3(5, 0, 0)), volume);
  EXPECT_FALSE(apart.colliding);
  const CollisionResult crossing = collide(
      outer, id, inner, Transform::from_axis_angle(Vec3::UnitX(), 0, Vec3(2, 0, 0)), volume);
  EXPECT_TRUE(crossing.colliding);
  EXPECT_FALSE(crossing.contained);
  EXPECT_FALSE(crossing.contacts.empty());
}

TEST(Volume, InsideTheHoleOfATorusIsOutside) {
  const Model torus(make_torus(1.0, 0.3, 48, 24), {}, "torus");
  const Model tet(make_sphere(0.05, 4, 2), {}, "small");  // a closed octahedron-like solid
  CollisionRequest volume;
  volume.volume = true;
  const Transform id = Transform::identity();
  EXPECT_FALSE(collide(torus, id, tet, id, volume).colliding) << "in the hole";
  const Transform in_tube = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(1, 0, 0));
  const CollisionResult r = collide(torus, id, tet, in_tube, volume);
  EXPECT_TRUE(r.colliding);
  EXPECT_TRUE(r.contained);
}

TEST(Volume, OpenModelsKeepSurfaceSemanticsAndSaySo) {
  Mesh open = make_sphere(2.0, 16, 8);
  open.triangles.pop_back();
  const Model outer(open, {}, "open");
  ASSERT_FALSE(outer.is_closed());
  const Model inner(make_box(Vec3(0.2, 0.2, 0.2)), {}, "inner");
  CollisionRequest volume;
  volume.volume = true;
  const CollisionResult r =
      collide(outer, Transform::identity(), inner, Transform::identity(), volume);
  EXPECT_FALSE(r.colliding);
  EXPECT_TRUE(r.surface_only);
  EXPECT_FALSE(r.contained);
}

}  // namespace
}  // namespace antcd
