// The frame-to-frame boolean query (collide() with a PairWitness, antcd/collide.hpp) against
// collide().
#include <antcd/collide.hpp>
#include <antcd/geometry.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/test_support.hpp"

namespace antcd {
namespace {

// The reported contact is a triangle pair within delta at these poses.
void expect_real_contact(const Model& a, const Transform& pa, const Model& b, const Transform& pb,
                         const CollisionResult& r, Scalar delta, const std::string& what) {
  ASSERT_EQ(r.contacts.size(), 1u) << what;
  const auto& ta = a.mesh().triangles[r.contacts[0].triangle_a];
  const auto& tb = b.mesh().triangles[r.contacts[0].triangle_b];
  const auto& va = a.mesh().vertices;
  const auto& vb = b.mesh().vertices;
  EXPECT_TRUE(geometry::triangles_within(pa.apply(va[ta[0]]), pa.apply(va[ta[1]]),
                                         pa.apply(va[ta[2]]), pb.apply(vb[tb[0]]),
                                         pb.apply(vb[tb[1]]), pb.apply(vb[tb[2]]), delta))
      << what;
}

// B sweeps through A in small steps, turning as it goes: each step's verdict equals collide()'s
// whatever the witness kept from the step before, and the witness decides some steps alone.
TEST(CoherentCollide, SweepMatchesCollideStepByStep) {
  const Model spider(test::unit_size(load_mesh(test::assimp_model("OBJ/spider.obj"))), {},
                     "spider");
  const Model wuson(test::unit_size(load_mesh(test::assimp_model("OFF/Wuson.off"))), {}, "wuson");
  for (const Scalar delta : {0.0, 0.02}) {
    PairWitness witness;
    CollisionResult coherent;
    CollisionResult plain;
    int colliding = 0;
    int by_witness = 0;
    const int steps = 160;
    for (int s = 0; s <= steps; ++s) {
      const Scalar u = static_cast<Scalar>(s) / steps;
      const Transform pa = Transform::from_axis_angle(Vec3(0, 0, 1), 0.3);
      const Transform pb =
          Transform::from_axis_angle(Vec3(1, 2, 3), 2.0 * u, Vec3(-1.6 + 3.2 * u, 0.1, 0.05));
      const CollisionRequest request{delta, false, 0};
      const std::string what = "delta " + std::to_string(delta) + " step " + std::to_string(s);
      const bool hit = collide(spider, pa, wuson, pb, request, coherent, witness);
      ASSERT_EQ(hit, collide(spider, pa, wuson, pb, request, plain)) << what;
      ASSERT_EQ(coherent.colliding, hit) << what;
      if (!hit) continue;
      ++colliding;
      if (coherent.traversal.node_pairs == 0) ++by_witness;
      expect_real_contact(spider, pa, wuson, pb, coherent, delta, what);
    }
    EXPECT_GT(colliding, 20) << "the sweep should pass through the spider";
    EXPECT_GT(by_witness, 0) << "no step was decided by the last step's contact";
    EXPECT_LT(by_witness, colliding) << "every step decided by the witness: walks untested";
  }
}

// A witness is only a hint: one left by other models, or by a far pose, changes no verdict; and
// the solid test (request.volume) still runs when the surfaces are apart.
TEST(CoherentCollide, StaleWitnessesAndVolumes) {
  const Model big(make_sphere(1.0, 24, 12), {}, "big");
  const Model small(make_sphere(0.2, 12, 6), {}, "small");
  const Model box(make_box(Vec3(0.5, 0.5, 0.5), 2), {}, "box");
  PairWitness witness;
  CollisionResult r;
  CollisionRequest request;
  // Touching surfaces leave a witness of (big, small).
  const Transform at_rim{Mat3::Identity(), Vec3(1.1, 0, 0)};
  ASSERT_TRUE(collide(big, Transform{}, small, at_rim, request, r, witness));
  ASSERT_TRUE(witness.valid);
  // Then other models, with the stale witness: the same verdicts as collide().
  for (const Scalar x : {0.0, 0.5, 0.9, 1.7}) {
    const Transform pb{Mat3::Identity(), Vec3(x, 0.1, 0)};
    CollisionResult plain;
    EXPECT_EQ(collide(box, Transform{}, small, pb, request, r, witness),
              collide(box, Transform{}, small, pb, request, plain))
        << x;
  }
  // Small wholly inside big: no surface contact, a solid one with volume.
  request.volume = true;
  witness = {};
  ASSERT_TRUE(collide(big, Transform{}, small, at_rim, request, r, witness));
  const Transform inside{Mat3::Identity(), Vec3(0.3, 0, 0)};
  EXPECT_TRUE(collide(big, Transform{}, small, inside, request, r, witness));
  EXPECT_TRUE(r.contained);
  request.volume = false;
  EXPECT_FALSE(collide(big, Transform{}, small, inside, request, r, witness));
}

}  // namespace
}  // namespace antcd
