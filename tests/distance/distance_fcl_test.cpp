// Minimum distance against FCL's distance query (fcl::BVHModel<OBBRSS>, the same triangles and
// poses) on thousands of poses of real meshes: random, touching and nearly touching ones. FCL is a
// test-only dependency; this file is built only when CMake finds it.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/distance.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

// The mesh's non-degenerate triangles (antcd ignores the others) in FCL's form.
std::shared_ptr<FclModel> fcl_model(const Mesh& mesh) {
  std::vector<fcl::Vector3d> vertices;
  for (const Vec3& v : mesh.vertices) vertices.emplace_back(v.x(), v.y(), v.z());
  std::vector<fcl::Triangle> triangles;
  for (const auto& t : mesh.triangles) {
    if (!geometry::is_degenerate_triangle(mesh.vertices[t[0]], mesh.vertices[t[1]],
                                          mesh.vertices[t[2]])) {
      triangles.emplace_back(t[0], t[1], t[2]);
    }
  }
  auto model = std::make_shared<FclModel>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d fcl_pose(const Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

struct Case {
  std::string a, b;
};

class DistanceAgainstFcl : public ::testing::TestWithParam<Case> {};

TEST_P(DistanceAgainstFcl, SameDistanceOnThousandsOfPoses) {
  const Case& c = GetParam();
  const Model a(load_mesh(test::assimp_model(c.a)), {}, c.a);
  const Model b(load_mesh(test::assimp_model(c.b)), {}, c.b);
  const auto fa = fcl_model(a.mesh());
  const auto fb = fcl_model(b.mesh());
  const Scalar scale =
      a.root().radius + b.root().radius + a.root().center.norm() + b.root().center.norm();
  std::mt19937_64 rng(2026);
  std::normal_distribution<Scalar> gauss;
  int separated = 0, near = 0, zero = 0;
  constexpr int kPoses = 1500;
  for (int i = 0; i < kPoses; ++i) {
    // A random vertex of B (rotated at random) put on a random vertex of A, then moved along a
    // random direction by up to the smaller bounding radius: from overlap through grazing to
    // apart. A third of the poses are pushed to just touching by bisection on the exact
    // collision verdict, then moved by 1e-7 relative either way.
    const Mat3 rot = test::random_pose(rng, 0).rotation;
    const Vec3 dir = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const auto vertex = [&](const Mesh& m) {
      const auto& t =
          m.triangles[std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng)];
      return m.vertices[t[std::uniform_int_distribution<int>(0, 2)(rng)]];
    };
    const Vec3 va = vertex(a.mesh());
    const Vec3 vb = vertex(b.mesh());
    const auto pose_at = [&](Scalar s) {
      Transform pb;
      pb.rotation = rot;
      pb.translation = va - rot * vb + s * dir;
      return pb;
    };
    const Scalar reach = std::min(a.root().radius, b.root().radius);
    Scalar s = std::uniform_real_distribution<Scalar>(0, 1)(rng) * reach;
    if (i % 3 == 0) {
      Scalar lo = 0, hi = 3 * scale;
      for (int k = 0; k < 36; ++k) {  // 3·scale·2^-36 is far below the 1e-7 nudge
        const Scalar mid = (lo + hi) / 2;
        (collide(a, Transform::identity(), b, pose_at(mid)).colliding ? lo : hi) = mid;
      }
      s = hi * (1 + 1e-7 * std::uniform_real_distribution<Scalar>(-1, 1)(rng));
    }
    const Transform pa = Transform::identity();
    const Transform pb = pose_at(s);
    const DistanceResult r = distance(a, pa, b, pb);

    fcl::CollisionObjectd oa(fa, fcl_pose(pa));
    fcl::CollisionObjectd ob(fb, fcl_pose(pb));
    fcl::DistanceRequestd request;
    request.enable_nearest_points = true;
    fcl::DistanceResultd expected;
    fcl::distance(&oa, &ob, request, expected);
    const std::string what = c.a + " / " + c.b + " pose " + std::to_string(i);
    if (r.intersecting) {
      // FCL reports intersecting meshes as distance 0 or a negative value, or (when its
      // triangle distance routine misses a crossing) a tiny positive one.
      EXPECT_LE(expected.min_distance, 1e-9 * scale) << what;
      ++zero;
      continue;
    }
    // FCL's triangle distance is its own floating-point computation: agree to 1e-9 relative.
    ASSERT_NEAR(r.distance, expected.min_distance, 1e-9 * scale) << what;
    ++separated;
    near += r.distance < 1e-5 * scale;
  }
  EXPECT_GT(separated, kPoses / 4);
  EXPECT_GT(zero, kPoses / 10);
  EXPECT_GT(near, kPoses / 10) << "nearly touching poses were not generated";
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, DistanceAgainstFcl,
                         ::testing::Values(Case{"OBJ/spider.obj", "OFF/Wuson.off"},
                                           Case{"STL/sphereWithHole.stl", "OBJ/spider.obj"}));

}  // namespace
}  // namespace antcd
