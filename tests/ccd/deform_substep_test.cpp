// Deforming-mesh CCD (antcd/deform_ccd.hpp) against dense sub-stepping: 1000 steps of the motion,
// each checked with exact discrete tests (antcd::triangles_intersect on the triangle pairs that
// share no vertex, or antcd::collide between two meshes). Whenever a step at t_k intersects, the
// CCD must report a hit with toi <= t_k (0 false negatives). Real meshes (Debian's assimp models)
// bent and twisted, a folding strip, a twisting strip, a cloth falling onto a sphere and a cloth
// hit by a turning box.
#include <antcd/bvh.hpp>
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/load.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <numbers>
#include <optional>

#include "ccd/deform_support.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

constexpr int kSteps = 1000;

struct Tally {
  int cases = 0, intersecting = 0, false_negatives = 0, ccd_only = 0;
};

/// First step k (t = k / kSteps) at which `intersects(t)` holds, if any.
std::optional<int> first_step(const std::function<bool(Scalar)>& intersects) {
  for (int k = 0; k <= kSteps; ++k) {
    if (intersects(static_cast<Scalar>(k) / kSteps)) return k;
  }
  return std::nullopt;
}

void compare(const char* name, const DeformSweepResult& r, std::optional<int> k, Tally& t) {
  ++t.cases;
  if (k) {
    ++t.intersecting;
    const Scalar tk = static_cast<Scalar>(*k) / kSteps;
    if (!r.hit || r.toi > tk) {
      ++t.false_negatives;
      ADD_FAILURE() << name << ": sub-step " << *k << " intersects, CCD hit " << r.hit << " toi "
                    << r.toi;
    }
  } else if (r.hit) {
    ++t.ccd_only;  // a contact between steps (or a graze) that no step shows
  }
}

void report(const char* what, const Tally& t) {
  std::cout << what << ": " << t.cases << " motions, " << t.intersecting
            << " intersect at a sub-step, " << t.false_negatives << " false negatives, "
            << t.ccd_only << " CCD hits no sub-step shows\n";
}

/// Self case: CCD vs the sub-steps' exact self test (pairs sharing no vertex).
void self_case(const char* name, const Mesh& mesh, const std::vector<Vec3>& v0,
               const std::vector<Vec3>& v1, Tally& t) {
  const Model model(mesh, {}, name);
  const DeformSweepResult r = deform_sweep(model, v0, v1);
  const auto k = first_step(
      [&](Scalar s) { return test::self_intersects_disjoint(mesh, test::lerp(v0, v1, s)); });
  compare(name, r, k, t);
}

/// Bend: the part above height c folds over (rotates by `angle` about the x axis through c),
/// twist: rotation about y by `twist` times the height fraction.
std::vector<Vec3> bend_and_twist(const std::vector<Vec3>& v, Scalar angle, Scalar twist) {
  Aabb box;
  for (const Vec3& p : v) box.extend(p);
  const Scalar c = (box.min.y() + box.max.y()) / 2;
  const Scalar h = box.max.y() - box.min.y();
  const Vec3 centre = (box.min + box.max) / 2;
  std::vector<Vec3> out;
  for (const Vec3& p : v) {
    Vec3 q = p - centre;
    const Scalar frac = (p.y() - box.min.y()) / h;
    q = Eigen::AngleAxis<Scalar>(twist * frac, Vec3::UnitY()) * q;
    if (p.y() > c) {
      const Vec3 pivot(0, c - centre.y(), 0);
      q = pivot + Eigen::AngleAxis<Scalar>(angle, Vec3::UnitX()) * (q - pivot);
    }
    out.push_back(q + centre);
  }
  return out;
}

TEST(DeformCcdSubstep, AssimpModelsBentAndTwisted) {
  Tally t;
  for (const char* file : {"OBJ/WusonOBJ.obj", "OBJ/box.obj", "PLY/cube.ply"}) {
    const Mesh mesh = load_mesh(test::assimp_model(file));
    const std::vector<Vec3> v0 = mesh.vertices;
    for (Scalar angle : {0.3, 1.5, 2.8}) {
      for (Scalar twist : {0.0, 1.0, 3.0}) {
        self_case(file, mesh, v0, bend_and_twist(v0, angle, twist), t);
      }
    }
  }
  report("assimp models bent and twisted", t);
  EXPECT_EQ(t.false_negatives, 0);
  EXPECT_GT(t.intersecting, 5);
}

TEST(DeformCcdSubstep, FoldingStrip) {
  Tally t;
  for (int n : {20, 60}) {
    const Mesh strip = test::make_grid(n, 4, 2, 0.2);
    const std::vector<Vec3> v0 = [&] {
      std::vector<Vec3> v = strip.vertices;
      for (Vec3& p : v) {
        if (p.x() > 1) p.z() = 0.3 * (p.x() - 1);  // the second half lifted in a V
      }
      return v;
    }();
    for (Scalar depth : {-0.5, -0.05, 0.2}) {  // the far half swung below (through) or above
      std::vector<Vec3> v1 = v0;
      for (Vec3& p : v1) {
        if (p.x() > 1) p = Vec3(2 - p.x(), p.y(), depth * (p.x() - 1) + 0.01);
      }
      self_case("folding strip", strip, v0, v1, t);
    }
  }
  report("folding strip", t);
  EXPECT_EQ(t.false_negatives, 0);
  EXPECT_GE(t.intersecting, 2);
}

TEST(DeformCcdSubstep, TwistingStrip) {
  Tally t;
  for (Scalar turns : {0.25, 0.75, 1.5}) {
    const Mesh strip = test::make_grid(80, 3, 4, 0.6);
    std::vector<Vec3> v0 = strip.vertices, v1 = strip.vertices;
    for (std::size_t i = 0; i < v1.size(); ++i) {
      const Vec3& p = v0[i];
      const Scalar a = 2 * std::numbers::pi * turns * p.x() / 4;
      const Scalar y = p.y() - 0.3;
      // Twisted about the strip's axis and pulled into a loop so that its ends cross.
      const Scalar phi = std::numbers::pi * 1.2 * p.x() / 4;
      v1[i] =
          Vec3(std::sin(phi) * 1.2, y * std::cos(a) + 0.5 * (1 - std::cos(phi)), y * std::sin(a));
    }
    self_case("twisting strip", strip, v0, v1, t);
  }
  report("twisting strip", t);
  EXPECT_EQ(t.false_negatives, 0);
}

TEST(DeformCcdSubstep, ClothFallingOntoSphere) {
  Tally t;
  const Mesh sphere = make_sphere(1, 24, 12);
  const Model ball(sphere, {}, "sphere");
  for (Scalar drop : {0.2, 0.35, 0.6, 1.2}) {
    Mesh cloth = test::make_grid(24, 24, 3, 3);
    for (Vec3& p : cloth.vertices) p += Vec3(-1.5, -1.5, 1.3);
    const std::vector<Vec3> v0 = cloth.vertices;
    std::vector<Vec3> v1 = v0;
    for (Vec3& p : v1) {
      const Scalar r2 = p.x() * p.x() + p.y() * p.y();
      p.z() -= drop * (1 + 0.3 * r2);  // drapes: the rim falls further
    }
    const Model cloth_model(cloth, {}, "cloth");
    const std::vector<Vec3>& s = sphere.vertices;
    const DeformSweepResult deforming = deform_sweep(cloth_model, v0, v1, ball, s, s);
    const DeformSweepResult rigid =
        deform_sweep(cloth_model, v0, v1, ball, Transform{}, Transform{});
    const auto k = first_step([&](Scalar u) {
      Mesh at = cloth;
      at.vertices = test::lerp(v0, v1, u);
      return collide(Model(at, {}, "cloth"), Transform{}, ball, Transform{}).colliding;
    });
    compare("cloth on sphere (deforming other)", deforming, k, t);
    compare("cloth on sphere (rigid other)", rigid, k, t);
    EXPECT_EQ(deforming.hit, rigid.hit);
  }
  report("cloth falling onto a sphere", t);
  EXPECT_EQ(t.false_negatives, 0);
  EXPECT_GE(t.intersecting, 4);
}

TEST(DeformCcdSubstep, ClothHitByTurningBox) {
  Tally t;
  const Mesh box = make_box({0.6, 0.1, 0.1}, 2);
  const Model bar(box, {}, "bar");
  for (Scalar lift : {0.05, 0.3, 0.6}) {
    Mesh cloth = test::make_grid(20, 20, 2, 2);
    for (Vec3& p : cloth.vertices) p += Vec3(-1, -1, 0);
    const std::vector<Vec3> v0 = cloth.vertices;
    std::vector<Vec3> v1 = v0;
    for (Vec3& p : v1) p.z() += lift * (1 - p.squaredNorm() / 2);  // bulges up
    Transform p0, p1;
    p0.translation = Vec3(0, 0, 0.5);
    p1.translation = Vec3(0.2, 0, 0.25);
    p1.rotation = Eigen::AngleAxis<Scalar>(2.0, Vec3(0.3, 1, 0.2).normalized()).toRotationMatrix();
    const Model cloth_model(cloth, {}, "cloth");
    const DeformSweepResult r = deform_sweep(cloth_model, v0, v1, bar, p0, p1);
    const auto k = first_step([&](Scalar u) {
      Mesh at = cloth;
      at.vertices = test::lerp(v0, v1, u);
      return collide(Model(at, {}, "cloth"), Transform{}, bar, ccd::interpolate_pose(p0, p1, u))
          .colliding;
    });
    compare("cloth and turning bar", r, k, t);
  }
  report("cloth hit by a turning box", t);
  EXPECT_EQ(t.false_negatives, 0);
  EXPECT_GE(t.intersecting, 1);
}

}  // namespace
}  // namespace antcd
