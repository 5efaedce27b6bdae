// CollisionRequest::volume against CGAL's Side_of_triangle_mesh (exact predicates): a small closed
// solid placed at random points in and around a closed model collides exactly when its surface
// meets the model's or its first vertex lies inside the model's solid.
#include <antcd/collide.hpp>

#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;

SurfaceMesh to_cgal(const Mesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const Vec3& p : mesh.vertices) v.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : mesh.triangles) sm.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return sm;
}

TEST(VolumeAgainstCgal, SmallSolidsInAndAroundClosedModels) {
  for (const Mesh& big :
       {make_torus(1.0, 0.35, 40, 20),
        merge({make_box(Vec3(0.8, 0.5, 0.3), 2),
               transformed(make_sphere(0.5, 20, 10),
                           Transform::from_axis_angle(Vec3::UnitX(), 0, Vec3(2, 0, 0)))})}) {
    const Model a(big, {}, "big");
    ASSERT_TRUE(a.is_closed());
    const SurfaceMesh sm = to_cgal(big);
    const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(sm);
    const Model small(make_sphere(0.04, 6, 3), {}, "small");
    // The vertex the volume test uses: the first one of the first leaf triangle.
    const Vec3 first = small.leaf_corners()(0, 0);
    std::mt19937_64 rng(5);
    const Aabb box = big.bounds();
    std::uniform_real_distribution<Scalar> ux(box.min.x() - 0.2, box.max.x() + 0.2);
    std::uniform_real_distribution<Scalar> uy(box.min.y() - 0.2, box.max.y() + 0.2);
    std::uniform_real_distribution<Scalar> uz(box.min.z() - 0.2, box.max.z() + 0.2);
    int inside = 0, outside = 0, touching = 0;
    CollisionRequest volume;
    volume.volume = true;
    for (int i = 0; i < 400; ++i) {
      Transform pose = test::random_pose(rng, 0);
      pose.translation = Vec3(ux(rng), uy(rng), uz(rng));
      const CollisionResult surface = collide(a, Transform::identity(), small, pose);
      const CollisionResult r = collide(a, Transform::identity(), small, pose, volume);
      const Vec3 v = pose.apply(first);
      const bool cgal_inside = side(K::Point_3(v.x(), v.y(), v.z())) == CGAL::ON_BOUNDED_SIDE;
      ASSERT_EQ(r.colliding, surface.colliding || cgal_inside) << "pose " << i;
      EXPECT_EQ(r.contained, !surface.colliding && cgal_inside) << "pose " << i;
      touching += surface.colliding;
      inside += !surface.colliding && cgal_inside;
      outside += !surface.colliding && !cgal_inside;
    }
    EXPECT_GT(inside, 20);
    EXPECT_GT(outside, 20);
    EXPECT_GT(touching, 5);
  }
}

}  // namespace
}  // namespace antcd
