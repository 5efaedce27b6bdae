// Exact detection against brute force over all triangle pairs.
#include <antcd/collide.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <set>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using PairSet = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

PairSet sorted_contacts(const CollisionResult& r) {
  PairSet out;
  for (const Contact& c : r.contacts) out.emplace_back(c.triangle_a, c.triangle_b);
  std::sort(out.begin(), out.end());
  return out;
}

// Distance from p to triangle t of `mesh` placed by `pose`.
Scalar distance_to_triangle(const Vec3& p, const Mesh& mesh, const Transform& pose,
                            std::uint32_t t) {
  const auto& tri = mesh.triangles[t];
  return std::sqrt(geometry::point_triangle_distance_squared(p, pose.apply(mesh.vertices[tri[0]]),
                                                             pose.apply(mesh.vertices[tri[1]]),
                                                             pose.apply(mesh.vertices[tri[2]])));
}

// Runs the boolean and all-contacts queries at one pose and checks them against brute force:
// same verdict, same set of triangle pairs, and every contact point where the contract says.
void expect_matches_brute_force(const Model& a, const Transform& pa, const Model& b,
                                const Transform& pb, Scalar delta, const std::string& what) {
  const PairSet truth = test::brute_force_pairs(a.mesh(), pa, b.mesh(), pb, delta);

  CollisionResult boolean;
  collide(a, pa, b, pb, CollisionRequest{delta, false, 0}, boolean);
  ASSERT_EQ(boolean.colliding, !truth.empty()) << what;
  if (boolean.colliding) {
    ASSERT_EQ(boolean.contacts.size(), 1u) << what;
    const Contact& c = boolean.contacts.front();
    EXPECT_TRUE(
        std::binary_search(truth.begin(), truth.end(), std::make_pair(c.triangle_a, c.triangle_b)))
        << what;
  }

  CollisionResult all;
  collide(a, pa, b, pb, CollisionRequest{delta, true, 0}, all);
  EXPECT_EQ(all.colliding, !truth.empty()) << what;
  const PairSet found = sorted_contacts(all);
  ASSERT_EQ(found, truth) << what << ": all-contacts set differs from brute force";

  const Scalar scale =
      a.root().radius + b.root().radius + pa.translation.norm() + pb.translation.norm();
  for (const Contact& c : all.contacts) {
    EXPECT_LE(c.distance, delta) << what;
    // The point is a common point (delta 0) or the closest points' midpoint: within distance/2
    // of both triangles, up to rounding.
    const Scalar tol = 1e-9 * scale + 0.5 * c.distance;
    EXPECT_LE(distance_to_triangle(c.point, a.mesh(), pa, c.triangle_a), tol) << what;
    EXPECT_LE(distance_to_triangle(c.point, b.mesh(), pb, c.triangle_b), tol) << what;
  }
}

// Random poses around a shared centre, scaled so that roughly half the poses collide.
void random_pose_sweep(const Model& a, const Model& b, int poses, std::uint64_t seed,
                       const std::vector<Scalar>& deltas, const std::string& name) {
  std::mt19937_64 rng(seed);
  const Scalar reach = 0.9 * (a.root().radius + b.root().radius);
  int colliding = 0;
  for (int i = 0; i < poses; ++i) {
    Transform pa = test::random_pose(rng, 0.0);
    Transform pb = test::random_pose(rng, reach);
    pa.translation = -a.root().center;  // centre A's bounding sphere on the origin
    pb.translation -= pb.rotation * b.root().center;
    for (const Scalar delta : deltas) {
      expect_matches_brute_force(
          a, pa, b, pb, delta,
          name + " pose " + std::to_string(i) + " delta " + std::to_string(delta));
      if (::testing::Test::HasFatalFailure()) return;
    }
    colliding += collide(a, pa, b, pb).colliding ? 1 : 0;
  }
  // The sweep must exercise both answers, or it proves little.
  EXPECT_GT(colliding, poses / 10) << name;
  EXPECT_LT(colliding, poses - poses / 10) << name;
}

TEST(ExactCollide, GeneratedShapesMatchBruteForceOnRandomPoses) {
  const Model sphere(make_sphere(1.0, 16, 8), {}, "sphere");
  const Model torus(make_torus(1.0, 0.3, 24, 12), {}, "torus");
  const Model box(make_box(Vec3(0.8, 0.5, 0.3), 3), {}, "box");
  const Model cyl(make_cylinder(0.4, 2.0, 16, 3), {}, "cylinder");
  random_pose_sweep(sphere, torus, 400, 1, {0.0, 0.05}, "sphere-torus");
  random_pose_sweep(torus, torus, 400, 2, {0.0, 0.02}, "torus-torus");
  random_pose_sweep(box, cyl, 400, 3, {0.0, 0.1}, "box-cylinder");
  random_pose_sweep(cyl, box, 400, 4, {0.0}, "cylinder-box");
}

TEST(ExactCollide, RealMeshesMatchBruteForceOnRandomPoses) {
  const Model spider(load_mesh(test::assimp_model("OBJ/spider.obj")), {}, "spider");
  const Model box(load_mesh(test::assimp_model("OBJ/box.obj")), {}, "box");
  const Model cube(load_mesh(test::assimp_model("OFF/Cube.off")), {}, "cube");
  random_pose_sweep(spider, spider, 60, 5, {0.0, 0.5}, "spider-spider");
  // box.obj is a unit cube, far smaller than the spider: scale it to a third of the spider's size.
  Mesh big_box = load_mesh(test::assimp_model("OBJ/box.obj"));
  for (Vec3& v : big_box.vertices) v *= 0.6 * spider.root().radius;
  const Model scaled_box(big_box, {}, "scaled box");
  random_pose_sweep(spider, scaled_box, 200, 6, {0.0, 0.3}, "spider-box");
  random_pose_sweep(cube, box, 600, 7, {0.0, 0.1}, "cube-box");
}

TEST(ExactCollide, LeafSizesAndCovarianceMethodsGiveTheSameAnswers) {
  const Mesh mesh = make_torus(1.0, 0.3, 20, 10);
  std::mt19937_64 rng(11);
  for (const std::uint32_t leaf : {1u, 2u, 7u, 64u}) {
    for (const auto method :
         {CovarianceMethod::VertexMean, CovarianceMethod::AreaWeightedCentroid}) {
      const Model m(mesh, {leaf, method});
      for (int i = 0; i < 40; ++i) {
        const Transform pa = test::random_pose(rng, 0.2);
        const Transform pb = test::random_pose(rng, 1.2);
        expect_matches_brute_force(m, pa, m, pb, 0.0, "leaf " + std::to_string(leaf));
        if (HasFatalFailure()) return;
      }
    }
  }
}

TEST(ExactCollide, LargeLeavesAroundASmallMeshMatchBruteForce) {
  // A coarse box (2 x 2 triangles per face, leaves of several big triangles) against a small fine
  // sphere near its surface: the traversal tests the big leaves' triangles one by one against the
  // sphere's nodes (dual_traverse's masks). Answers must equal brute force from both sides, with
  // leaves small enough to be masked and too large to be (over 32 triangles).
  const Mesh box = make_box(Vec3(1.0, 0.7, 0.5), 2);
  const Model sphere(make_sphere(0.06, 16, 8), {}, "small sphere");
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  for (const std::uint32_t leaf : {4u, 8u, 48u}) {
    const Model big(box, {leaf, CovarianceMethod::AreaWeightedCentroid}, "coarse box");
    std::uint64_t triangle_rejects = 0;
    int colliding = 0;
    const int poses = 150;
    for (int i = 0; i < poses; ++i) {
      // A point on a random face of the box, pushed in or out by up to 0.09.
      const int axis = static_cast<int>(rng() % 3);
      Vec3 c(u(rng) * 1.0, u(rng) * 0.7, u(rng) * 0.5);
      const Vec3 half(1.0, 0.7, 0.5);
      c[axis] = (u(rng) < 0 ? -1 : 1) * (half[axis] + 0.09 * u(rng));
      Transform pb = test::random_pose(rng, 0.0);
      pb.translation = c;
      const std::string what = "leaf " + std::to_string(leaf) + " pose " + std::to_string(i);
      for (const Scalar delta : {0.0, 0.02}) {
        expect_matches_brute_force(big, Transform::identity(), sphere, pb, delta, what);
        expect_matches_brute_force(sphere, pb, big, Transform::identity(), delta,
                                   what + " swapped");
        if (HasFatalFailure()) return;
      }
      const CollisionResult r = collide(big, Transform::identity(), sphere, pb);
      triangle_rejects += r.traversal.triangle_rejects;
      colliding += r.colliding ? 1 : 0;
    }
    EXPECT_GT(colliding, poses / 10) << "leaf " << leaf;
    EXPECT_LT(colliding, poses - poses / 10) << "leaf " << leaf;
    // The masks are used for leaves of 2 to 32 triangles, never above.
    if (leaf <= 32) {
      EXPECT_GT(triangle_rejects, 0u) << "leaf " << leaf;
    } else {
      EXPECT_EQ(triangle_rejects, 0u) << "leaf " << leaf;
    }
  }
}

// Two unit boxes (half extent 1) side by side along x, at exactly representable offsets.
class BoxContact : public ::testing::Test {
 protected:
  Model a{make_box(Vec3(1, 1, 1), 2), {}, "a"};
  Model b{make_box(Vec3(1, 1, 1), 2), {}, "b"};

  bool hits(const Vec3& offset, Scalar delta = 0, const Transform& rot = {}) {
    Transform pb = rot;
    pb.translation = offset;
    expect_matches_brute_force(a, Transform::identity(), b, pb, delta, "offset");
    return collide(a, Transform::identity(), b, pb, CollisionRequest{delta}).colliding;
  }
};

TEST_F(BoxContact, CoplanarFacesTouching) { EXPECT_TRUE(hits(Vec3(2, 0, 0))); }
TEST_F(BoxContact, CoplanarFacesPartlyOverlapping) { EXPECT_TRUE(hits(Vec3(2, 0.5, 0.25))); }
TEST_F(BoxContact, EdgeTouching) { EXPECT_TRUE(hits(Vec3(2, 2, 0.5))); }
TEST_F(BoxContact, VertexTouching) { EXPECT_TRUE(hits(Vec3(2, 2, 2))); }
TEST_F(BoxContact, JustSeparated) {
  EXPECT_FALSE(hits(Vec3(2 + 1e-9, 0, 0)));
  EXPECT_FALSE(hits(Vec3(2, 2 + 1e-9, 2)));
  EXPECT_FALSE(hits(Vec3(2 + 1e-12, 2, 2)));
}
TEST_F(BoxContact, DeltaClosesTheGap) {
  EXPECT_TRUE(hits(Vec3(2.25, 0, 0), 0.25));
  EXPECT_FALSE(hits(Vec3(2.25, 0, 0), 0.2499));
  // Corner to corner, gap sqrt(3) * 0.1 ≈ 0.1732.
  EXPECT_TRUE(hits(Vec3(2.1, 2.1, 2.1), 0.174));
  EXPECT_FALSE(hits(Vec3(2.1, 2.1, 2.1), 0.173));
}
TEST_F(BoxContact, EdgeOnFaceAfterRotation) {
  // B turned 45° about z: its vertical edge at x = 2 - sqrt(2) + ... touches A's face when B's
  // centre sits at x = 1 + sqrt(2).
  const Transform rot = Transform::from_axis_angle(Vec3::UnitZ(), std::numbers::pi / 4);
  EXPECT_TRUE(hits(Vec3(1 + std::sqrt(2.0) - 1e-12, 0, 0), 0, rot));
  EXPECT_FALSE(hits(Vec3(1 + std::sqrt(2.0) + 1e-9, 0, 0), 0, rot));
  EXPECT_TRUE(hits(Vec3(1 + std::sqrt(2.0) + 1e-9, 0, 0), 2e-9, rot));
}

TEST(ExactCollide, NestedSurfacesDoNotCollideUntilDeltaReachesTheGap) {
  const Model outer(make_sphere(2.0, 24, 12), {}, "outer");
  const Model inner(make_sphere(0.5, 24, 12), {}, "inner");
  const Transform id = Transform::identity();
  EXPECT_FALSE(collide(outer, id, inner, id).colliding);
  expect_matches_brute_force(outer, id, inner, id, 0.0, "nested");
  // The gap is a little under 1.5 (the outer sphere's facets lie inside radius 2).
  EXPECT_FALSE(collide(outer, id, inner, id, CollisionRequest{1.3}).colliding);
  EXPECT_TRUE(collide(outer, id, inner, id, CollisionRequest{1.5}).colliding);
  expect_matches_brute_force(outer, id, inner, id, 1.45, "nested delta");
}

TEST(ExactCollide, PosesComposeBothWays) {
  // Moving both models by the same rigid motion cannot change the answer.
  const Model torus(make_torus(1.0, 0.3, 24, 12));
  const Model box(make_box(Vec3(0.3, 0.3, 1.5), 2));
  std::mt19937_64 rng(21);
  int colliding = 0;
  for (int i = 0; i < 200; ++i) {
    const Transform pb = test::random_pose(rng, 1.5);
    const Transform world = test::random_pose(rng, 100.0);
    const bool local = collide(torus, Transform::identity(), box, pb).colliding;
    EXPECT_EQ(local, collide(torus, world, box, world * pb).colliding) << i;
    colliding += local;
  }
  EXPECT_GT(colliding, 20);
  EXPECT_LT(colliding, 180);
}

TEST(ExactCollide, MaxContactsStopsEarlyAndBooleanFindsOne) {
  const Model a(make_sphere(1.0, 32, 16));
  const Model b(make_sphere(1.0, 32, 16));
  Transform pb;
  pb.translation = Vec3(1.0, 0.1, 0.0);
  const CollisionResult all = collide(a, Transform::identity(), b, pb, CollisionRequest{0, true});
  ASSERT_GT(all.contacts.size(), 10u);
  const CollisionResult some =
      collide(a, Transform::identity(), b, pb, CollisionRequest{0, true, 5});
  EXPECT_EQ(some.contacts.size(), 5u);
  const CollisionResult one = collide(a, Transform::identity(), b, pb, CollisionRequest{0, false});
  EXPECT_EQ(one.contacts.size(), 1u);
  EXPECT_LT(one.triangle_tests, all.triangle_tests);
}

TEST(ExactCollide, RejectsBadDelta) {
  const Model a(make_box(Vec3(1, 1, 1)));
  EXPECT_THROW(collide(a, {}, a, {}, CollisionRequest{-1.0}), antcd::ArgumentError);
  EXPECT_THROW(collide(a, {}, a, {}, CollisionRequest{std::numeric_limits<Scalar>::quiet_NaN()}),
               antcd::ArgumentError);
  EXPECT_THROW(collide(a, {}, a, {}, CollisionRequest{std::numeric_limits<Scalar>::infinity()}),
               antcd::ArgumentError);
}

TEST(ExactCollide, ReusedResultDoesNotGrowAndIsCleared) {
  const Model a(make_sphere(1.0, 16, 8));
  CollisionResult result;
  Transform near;
  near.translation = Vec3(1.5, 0, 0);
  Transform far;
  far.translation = Vec3(5, 0, 0);
  collide(a, {}, a, near, CollisionRequest{0, true}, result);
  ASSERT_TRUE(result.colliding);
  const auto capacity = result.contacts.capacity();
  collide(a, {}, a, far, CollisionRequest{0, true}, result);
  EXPECT_FALSE(result.colliding);
  EXPECT_TRUE(result.contacts.empty());
  EXPECT_EQ(result.contacts.capacity(), capacity);
}

}  // namespace
}  // namespace antcd
