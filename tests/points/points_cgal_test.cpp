// Point queries against CGAL (tests only): inside/outside against Side_of_triangle_mesh (exact
// predicates), distances against CGAL's AABB tree closest point, on closed third-party meshes
// (Debian assimp-testmodels) at random poses.
#include <antcd/load.hpp>
#include <antcd/points.hpp>

#include <gtest/gtest.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <random>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

SurfaceMesh to_cgal(const Mesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const Vec3& p : mesh.vertices) v.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    sm.add_face(v[t[0]], v[t[1]], v[t[2]]);
  }
  return sm;
}

void check_against_cgal(const Mesh& mesh, const std::string& name, std::uint64_t seed) {
  const Model model(mesh, {}, name);
  ASSERT_TRUE(model.is_closed()) << name;
  std::mt19937_64 rng(seed);
  const Transform pose = test::random_pose(rng, 10.0);
  const Mesh posed = transformed(mesh, pose);
  const SurfaceMesh sm = to_cgal(posed);
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(sm);
  Tree tree(faces(sm).first, faces(sm).second, sm);
  tree.accelerate_distance_queries();

  const Aabb box = posed.bounds();
  const Vec3 size = box.extent();
  std::uniform_real_distribution<Scalar> u(0, 1);
  std::vector<Vec3> points;
  for (int i = 0; i < 600; ++i) {
    points.push_back(box.min - 0.1 * size + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(1.2 * size));
  }
  // Points near the surface: vertices pushed a little along random directions.
  std::uniform_int_distribution<std::size_t> pick(0, posed.vertices.size() - 1);
  std::normal_distribution<Scalar> g(0, 1e-3 * size.norm());
  for (int i = 0; i < 200; ++i)
    points.push_back(posed.vertices[pick(rng)] + Vec3(g(rng), g(rng), g(rng)));

  const std::vector<std::uint8_t> in = contains(model, pose, points);
  const SignedDistanceResult sd = signed_distance(model, pose, points);
  ASSERT_TRUE(sd.is_signed);
  const Scalar tiny = 1e-9 * size.norm();
  int inside = 0, checked = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const K::Point_3 q(points[i].x(), points[i].y(), points[i].z());
    const Scalar cgal_d = std::sqrt(CGAL::to_double(tree.squared_distance(q)));
    ASSERT_NEAR(std::abs(sd.points[i].distance), cgal_d, 1e-12 * (1 + size.norm()))
        << name << " point " << i;
    if (cgal_d < tiny) continue;  // within rounding of the surface: either answer is right
    const bool cgal_inside = side(q) == CGAL::ON_BOUNDED_SIDE;
    ASSERT_EQ(in[i] != 0, cgal_inside) << name << " point " << i;
    ASSERT_EQ(sd.points[i].distance < 0, cgal_inside) << name << " point " << i;
    inside += cgal_inside ? 1 : 0;
    ++checked;
  }
  EXPECT_GT(inside, 10) << name;
  EXPECT_LT(inside, checked - 10) << name;
}

// Side_of_triangle_mesh counts ray crossings (odd: inside), which agrees with the winding number
// only for surfaces that do not overlap themselves: models with overlapping pieces are tested
// against the brute-force winding number in points_test.cpp instead.
TEST(PointsAgainstCgal, ClosedThirdPartyMeshes) {
  for (const std::string file : {"Collada/duck.dae", "3DS/fels.3ds", "OBJ/empty_mat.obj",
                                 "glTF/TwoBoxes/TwoBoxes.gltf", "OFF/Cube.off"}) {
    const Mesh mesh = load_mesh(test::assimp_model(file));
    check_against_cgal(mesh, file, std::hash<std::string>{}(file) % 1000);
  }
}

TEST(PointsAgainstCgal, GeneratedSolids) {
  check_against_cgal(make_torus(1.0, 0.35, 48, 24), "torus", 1);
  check_against_cgal(
      merge({make_box(Vec3(1, 0.5, 0.3), 4),
             transformed(make_cylinder(0.2, 3.0, 20),
                         Transform::from_axis_angle(Vec3::UnitX(), 0.3, Vec3(2.5, 0, 0)))}),
      "box and cylinder", 2);
}

}  // namespace
}  // namespace antcd
