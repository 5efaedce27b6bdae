// Continuous motion with deforming objects (World::sweep_motion / set_motion_continuous): against
// dense sub-stepping with exact discrete tests on Models rebuilt from the interpolated world
// vertices (never a missed pair, toi <= the first sub-step in contact), a sheet resting into a
// block at t = 0, the same answer at 1 and 3 threads, rigid pairs equal to sweep_poses, and bad
// input (a clear error naming the object, nothing changed).
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/self.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "self/self_meshes.hpp"

namespace antcd {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

Transform at(const Vec3& t, const Vec3& axis = Vec3::UnitZ(), Scalar angle = 0) {
  return Transform::from_axis_angle(axis, angle, t);
}

// A 2 x 2 sheet of n x n quads about the origin, waving with amplitude `amp` and phase `phase`.
std::vector<Vec3> wave(int n, Scalar amp, Scalar phase) {
  return test::grid_sheet(n, n,
                          [=](int i, int j) {
                            const Scalar x = 2.0 * i / n - 1;
                            const Scalar y = 2.0 * j / n - 1;
                            return Vec3(x, y, amp * std::sin(3 * x + 2 * y + phase));
                          })
      .vertices;
}

// A strip blended from flat (s = 0) to test::looped_sheet (s = 1), which passes through itself.
std::vector<Vec3> looping(int nx, int ny, Scalar s) {
  const Mesh flat = test::grid_sheet(
      nx, ny, [=](int i, int j) { return Vec3(-1.5 + 3.0 * i / nx, Scalar(j) / ny, 0); });
  Mesh loop = test::looped_sheet(nx, ny);
  for (std::size_t v = 0; v < loop.vertices.size(); ++v) {
    loop.vertices[v] = (1 - s) * flat.vertices[v] + s * loop.vertices[v];
  }
  return loop.vertices;
}

// One object of a motion: its Model as added, its state at t = 0 (pose, and for a deforming one
// the model-frame vertices it is set to first) and at t = 1.
struct Body {
  ModelPtr model;
  Transform pose0;
  Transform pose1;
  std::vector<Vec3> v0;  ///< deforming: model-frame vertices at t = 0 and t = 1; rigid: empty
  std::vector<Vec3> v1;
  bool self = false;
  std::string name;
};

struct Scenario {
  World world;
  std::vector<ObjectId> ids;
  std::vector<Body> bodies;
  std::vector<ObjectId> moved;
  std::vector<Transform> poses;
  std::vector<VertexMotion> deforming;
};

// Adds the bodies at their t = 0 state and fills the motion's arguments.
void build(Scenario& s) {
  for (const Body& b : s.bodies) {
    ObjectOptions o;
    o.name = b.name;
    o.self_collision = b.self;
    s.ids.push_back(s.world.add(b.model, b.pose0, o));
    if (!b.v0.empty()) s.world.set_vertices(s.ids.back(), b.v0);
  }
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const Body& b = s.bodies[k];
    s.moved.push_back(s.ids[k]);
    s.poses.push_back(b.pose1);
    if (!b.v1.empty()) s.deforming.push_back({s.ids[k], b.v1});
  }
}

// Object k's world mesh at time t of the motion (the definitions of world.hpp).
Mesh world_mesh(const Body& b, Scalar t) {
  Mesh m = b.model->mesh();
  if (!b.v0.empty()) {
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      m.vertices[i] = (1 - t) * b.pose0.apply(b.v0[i]) + t * b.pose1.apply(b.v1[i]);
    }
  } else {
    const Transform p = ccd::interpolate_pose(b.pose0, b.pose1, t);
    for (Vec3& v : m.vertices) v = p.apply(v);
  }
  return m;
}

// Per pair (k, l), k <= l (k == l: self, self objects only), the first of `steps` + 1 sub-steps
// at which the rebuilt world meshes are within min_separation (collide(), exact) or intersect
// themselves (self_intersections).
std::map<std::pair<std::size_t, std::size_t>, Scalar> substeps(const Scenario& s, int steps,
                                                               Scalar min_separation) {
  std::map<std::pair<std::size_t, std::size_t>, Scalar> first;
  const std::size_t n = s.bodies.size();
  for (int step = 0; step <= steps; ++step) {
    const Scalar t = Scalar(step) / steps;
    std::vector<Model> models;
    for (const Body& b : s.bodies) models.emplace_back(world_mesh(b, t));
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t l = k; l < n; ++l) {
        if (first.contains({k, l})) continue;
        bool hit = false;
        if (k == l) {
          hit = s.bodies[k].self && self_intersections(models[k]).intersecting;
        } else {
          hit = collide(models[k], Transform{}, models[l], Transform{},
                        CollisionRequest{min_separation})
                    .colliding;
        }
        if (hit) first[{k, l}] = t;
      }
    }
  }
  return first;
}

// Checks the motion's answer against sub-stepping: every pair found in contact at a sub-step is
// reported, with toi <= that sub-step. Returns the number of such pairs.
int expect_conservative(const Scenario& s, const std::vector<MotionToi>& got, int steps,
                        Scalar min_separation) {
  std::map<std::pair<std::size_t, std::size_t>, Scalar> reported;
  for (const MotionToi& p : got) {
    EXPECT_LE(p.a, p.b);
    EXPECT_GE(p.toi, 0);
    EXPECT_LE(p.toi, 1);
    reported[{p.a.slot, p.b.slot}] = p.toi;
  }
  const auto truth = substeps(s, steps, min_separation);
  for (const auto& [pair, t] : truth) {
    const auto it = reported.find(pair);
    EXPECT_NE(it, reported.end()) << "missed " << s.bodies[pair.first].name << " / "
                                  << s.bodies[pair.second].name << " (in contact at t = " << t
                                  << ")";
    if (it != reported.end()) {
      EXPECT_LE(it->second, t) << s.bodies[pair.first].name << " / " << s.bodies[pair.second].name;
    }
  }
  return static_cast<int>(truth.size());
}

constexpr int kSheet = 6;

// Two waving sheets (one folding through itself, with self_collision), a spinning roller and a
// box, at random poses that bring them together during the step.
Scenario random_scenario(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  const auto jitter = [&](Scalar r) { return Vec3(r * u(rng), r * u(rng), r * u(rng)); };
  Scenario s;
  const ModelPtr sheet = std::make_shared<const Model>(
      Mesh{wave(kSheet, 0, 0),
           test::grid_sheet(kSheet, kSheet, [](int i, int j) { return Vec3(i, j, 0); }).triangles});
  const ModelPtr strip =
      std::make_shared<const Model>(Mesh{looping(12, 3, 0), test::looped_sheet(12, 3).triangles});
  const ModelPtr roller =
      std::make_shared<const Model>(make_cylinder(0.3, 2.2, 16), BuildOptions{}, "roller");
  const ModelPtr box =
      std::make_shared<const Model>(make_box({0.3, 0.4, 0.2}), BuildOptions{}, "box");
  Body a{sheet,
         at(Vec3(0, 0, 0.6) + jitter(0.2)),
         at(Vec3(0, 0, -0.5) + jitter(0.2)),
         wave(kSheet, 0.1 * u(rng), u(rng)),
         wave(kSheet, 0.3 * u(rng), u(rng)),
         false,
         "sheet"};
  Body b{strip,
         at(Vec3(0.3, -0.5, -0.9) + jitter(0.3)),
         at(Vec3(0.2, -0.5, -0.6) + jitter(0.3)),
         looping(12, 3, 0.2 + 0.2 * u(rng)),
         looping(12, 3, 0.9 + 0.1 * u(rng)),
         true,
         "strip"};
  Body c{roller,
         at(jitter(0.2), Vec3::UnitX(), std::numbers::pi / 2),
         at(jitter(0.3), Vec3(1, 0.2 * u(rng), 0).normalized(), std::numbers::pi / 2 + 2 * u(rng)),
         {},
         {},
         false,
         "roller"};
  Body d{box,
         at(Vec3(1.4, 0, 0) + jitter(0.2), Vec3(u(rng), u(rng), 1).normalized(), u(rng)),
         at(Vec3(0.3, 0, 0.1) + jitter(0.4), Vec3(u(rng), 1, u(rng)).normalized(), 2 * u(rng)),
         {},
         {},
         false,
         "box"};
  s.bodies = {a, b, c, d};
  build(s);
  return s;
}

TEST(DeformMotion, NeverMissesAPairAgainstSubstepping) {
  int pairs = 0;
  int deform_pairs = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    for (const Scalar ms : {0.0, 0.02}) {
      Scenario s = random_scenario(seed);
      SweepRequest request;
      request.min_separation = ms;
      const std::vector<MotionToi> got =
          s.world.sweep_motion(s.moved, s.poses, s.deforming, request);
      pairs += expect_conservative(s, got, 200, ms);
      for (const MotionToi& p : got) deform_pairs += p.kind == MotionToiKind::Deform ? 1 : 0;
    }
  }
  // The corpus must exercise the motion: pairs in contact, and some found by deform_sweep.
  EXPECT_GT(pairs, 20);
  EXPECT_GT(deform_pairs, 5);
}

TEST(DeformMotion, SelfPairOfAFoldingStripAgainstSubstepping) {
  Scenario s;
  const ModelPtr strip =
      std::make_shared<const Model>(Mesh{looping(16, 4, 0), test::looped_sheet(16, 4).triangles});
  s.bodies = {Body{strip, at(Vec3::Zero()), at(Vec3(0.1, 0, 0.2), Vec3::UnitY(), 0.3),
                   looping(16, 4, 0.1), looping(16, 4, 1), true, "strip"}};
  build(s);
  const std::vector<MotionToi> got = s.world.sweep_motion(s.moved, s.poses, s.deforming);
  ASSERT_EQ(expect_conservative(s, got, 1000, 0), 1);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].a, got[0].b);
  EXPECT_EQ(got[0].kind, MotionToiKind::Deform);
  EXPECT_GT(got[0].toi, 0);
}

// A flat sheet of two large triangles resting 2 mm into the top of a block: its triangles cross
// the block's sides with no sheet vertex inside and no edge-edge or vertex-face contact, and it
// slides 5 cm without one appearing. Only the exact test at t = 0 sees it (deform_sweep alone
// answers a miss).
TEST(DeformMotion, SheetRestingIntoABlockAtTimeZero) {
  Scenario s;
  const Mesh quad =
      test::grid_sheet(1, 1, [](int i, int j) { return Vec3(2 * i - 1, 2 * j - 1, 0); });
  const ModelPtr sheet = std::make_shared<const Model>(quad);
  const ModelPtr block =
      std::make_shared<const Model>(make_box({0.3, 0.5, 0.3}), BuildOptions{}, "block");
  std::vector<Vec3> v0 = quad.vertices;
  std::vector<Vec3> v1 = quad.vertices;
  for (Vec3& p : v1) p.x() += 0.05;
  s.bodies = {Body{sheet, at(Vec3(0, 0, 0.298)), at(Vec3(0, 0, 0.298)), v0, v1, true, "sheet"},
              Body{block, at(Vec3::Zero()), at(Vec3::Zero()), {}, {}, false, "block"}};
  build(s);
  const std::vector<MotionToi> got = s.world.sweep_motion(s.moved, s.poses, s.deforming);
  EXPECT_EQ(expect_conservative(s, got, 200, 0), 1);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].a, s.ids[0]);
  EXPECT_EQ(got[0].b, s.ids[1]);
  EXPECT_EQ(got[0].kind, MotionToiKind::StartContact);
  EXPECT_EQ(got[0].toi, 0);
  EXPECT_FALSE(got[0].tolerance_decided);
  // deform_sweep alone misses it: the test at t = 0 is what finds it.
  std::vector<Vec3> w0;
  std::vector<Vec3> w1;
  for (std::size_t i = 0; i < v0.size(); ++i) {
    w0.push_back(s.bodies[0].pose0.apply(v0[i]));
    w1.push_back(s.bodies[0].pose1.apply(v1[i]));
  }
  EXPECT_FALSE(deform_sweep(*sheet, w0, w1, *block, Transform{}, Transform{}).hit);
}

bool same(const MotionToi& x, const MotionToi& y) {
  return x.a == y.a && x.b == y.b && x.kind == y.kind && x.toi == y.toi &&
         x.tolerance_decided == y.tolerance_decided && x.point == y.point &&
         x.triangles == y.triangles && x.primitive.kind == y.primitive.kind &&
         x.primitive.vertex_in_first == y.primitive.vertex_in_first &&
         x.primitive.indices == y.primitive.indices && x.primitive.toi == y.primitive.toi &&
         x.sweep.toi == y.sweep.toi && x.sweep.contact.triangle_a == y.sweep.contact.triangle_a &&
         x.sweep.contact.triangle_b == y.sweep.contact.triangle_b;
}

TEST(DeformMotion, SameAnswerAtOneAndThreeThreads) {
  int compared = 0;
  int exhausted = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Scenario s = random_scenario(seed);
    SweepRequest request;
    request.min_separation = 0.01;
    std::vector<MotionToi> one;
    std::vector<MotionToi> three;
    tbb::task_arena(1).execute(
        [&] { one = s.world.sweep_motion(s.moved, s.poses, s.deforming, request); });
    tbb::task_arena(3).execute(
        [&] { three = s.world.sweep_motion(s.moved, s.poses, s.deforming, request); });
    ASSERT_EQ(one.size(), three.size());
    ASSERT_FALSE(one.empty());
    for (std::size_t k = 0; k < one.size(); ++k) {
      // Pairs whose primitive ran out of its box budget included (deform_ccd.hpp, "Determinism").
      if (one[k].primitive.budget_exhausted) ++exhausted;
      EXPECT_TRUE(same(one[k], three[k])) << k << ": " << one[k].a.slot << "/" << one[k].b.slot;
      ++compared;
    }
  }
  // Budget stops, which made the answer depend on the task order before their toi was lifted,
  // no longer occur here since the primitives search separations by time windows; their
  // determinism is tested with a tiny budget in DeformCcd.BudgetStopsAreConservativeAndSame....
  std::cout << compared << " pairs compared, " << exhausted << " budget-exhausted\n";
  EXPECT_GT(compared, 20);
}

TEST(DeformMotion, BudgetStopsAgainstATurningObjectAreSameAtAnyThreadCount) {
  // A tiny primitive budget makes queries stop early (deform_ccd.hpp, "Determinism"): the answer
  // stays conservative and the same at any thread count. The sheet against the turning roller and
  // box of the random scenarios, in world coordinates as sweep_motion does. (Found: with the toi
  // lift of budget stops disabled these answers do not differ either; the order dependence it
  // removed was seen at the full budget, whose stops the separation search no longer meets.)
  int exhausted = 0;
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Scenario s = random_scenario(seed);
    const Body& sheet = s.bodies[0];
    std::vector<Vec3> w0, w1;
    for (std::size_t i = 0; i < sheet.v0.size(); ++i) {
      w0.push_back(sheet.pose0.apply(sheet.v0[i]));
      w1.push_back(sheet.pose1.apply(sheet.v1[i]));
    }
    for (const std::size_t other : {2, 3}) {
      const Body& rigid = s.bodies[other];
      for (const std::uint32_t budget : {4u, 64u}) {
        DeformSweepRequest req;
        req.min_separation = 0.01;
        req.primitive_max_boxes = budget;
        const auto run = [&](int threads, bool all) {
          req.all_pairs = all;
          return tbb::task_arena(threads).execute([&] {
            return deform_sweep(*sheet.model, w0, w1, *rigid.model, rigid.pose0, rigid.pose1, req);
          });
        };
        const DeformSweepResult all = run(1, true);
        for (const DeformPair& p : all.pairs) exhausted += p.budget_exhausted ? 1 : 0;
        // Conservative: every pair the full budget finds is still found, no later than it allows.
        DeformSweepRequest full = req;
        full.primitive_max_boxes = DeformSweepRequest{}.primitive_max_boxes;
        const DeformSweepResult reference =
            deform_sweep(*sheet.model, w0, w1, *rigid.model, rigid.pose0, rigid.pose1, full);
        for (const DeformPair& want : reference.pairs) {
          const auto found = std::find_if(all.pairs.begin(), all.pairs.end(), [&](const auto& p) {
            return p.kind == want.kind && p.indices == want.indices &&
                   p.vertex_in_first == want.vertex_in_first;
          });
          ASSERT_NE(found, all.pairs.end()) << seed << " " << rigid.name << ": a pair lost";
          EXPECT_LE(found->toi, want.toi + req.time_tolerance) << seed << " " << rigid.name;
        }
        const DeformSweepResult one = run(1, false);
        for (const int threads : {2, 3, 8}) {
          const DeformSweepResult r = run(threads, false);
          ++compared;
          EXPECT_EQ(one.hit, r.hit) << seed << " " << rigid.name << " " << threads;
          EXPECT_EQ(one.toi, r.toi) << seed << " " << rigid.name << " " << threads;
          EXPECT_EQ(one.pair.indices, r.pair.indices)
              << seed << " " << rigid.name << " " << threads;
          EXPECT_EQ(one.pair.kind, r.pair.kind) << seed << " " << rigid.name << " " << threads;
        }
      }
    }
  }
  EXPECT_GT(exhausted, 20) << compared << " answers compared";
}

TEST(DeformMotion, RigidPairsAreSweepPosesAnswers) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Scenario s = random_scenario(seed);
    const std::vector<MotionToi> got = s.world.sweep_motion(s.moved, s.poses, s.deforming);
    const std::vector<PairToi> rigid = s.world.sweep_poses(s.moved, s.poses);
    // roller (slot 2) and box (slot 3) are the rigid ones.
    std::vector<MotionToi> rigid_got;
    for (const MotionToi& p : got) {
      if (p.kind == MotionToiKind::RigidSweep) rigid_got.push_back(p);
    }
    std::vector<PairToi> want;
    for (const PairToi& p : rigid) {
      if (p.a.slot >= 2 && p.b.slot >= 2) want.push_back(p);
    }
    ASSERT_EQ(rigid_got.size(), want.size());
    for (std::size_t k = 0; k < want.size(); ++k) {
      EXPECT_EQ(rigid_got[k].a, want[k].a);
      EXPECT_EQ(rigid_got[k].b, want[k].b);
      EXPECT_EQ(rigid_got[k].toi, want[k].sweep.toi);
      EXPECT_EQ(rigid_got[k].point, want[k].sweep.contact.point);
    }
  }
}

TEST(DeformMotion, SetMotionContinuousAppliesTheMotion) {
  Scenario s = random_scenario(3);
  const std::vector<MotionToi> want = s.world.sweep_motion(s.moved, s.poses, s.deforming);
  const std::vector<MotionToi> got = s.world.set_motion_continuous(s.moved, s.poses, s.deforming);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_TRUE(same(got[k], want[k]));
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    EXPECT_EQ(s.world.pose(s.ids[k]).translation, s.bodies[k].pose1.translation);
    if (!s.bodies[k].v1.empty()) {
      EXPECT_EQ(s.world.model(s.ids[k]).mesh().vertices, s.bodies[k].v1);
    }
  }
}

// Bad input: a clear error naming the function, the argument and the object; nothing changed.
TEST(DeformMotion, BadInputNamesTheObjectAndChangesNothing) {
  Scenario s = random_scenario(2);
  const std::vector<Vec3> sheet0 = s.world.model(s.ids[0]).mesh().vertices;
  const std::vector<Vec3> strip0 = s.world.model(s.ids[1]).mesh().vertices;
  const Vec3 t0 = s.world.pose(s.ids[0]).translation;
  const auto expect_error = [&](std::vector<VertexMotion> deforming, const std::string& part) {
    try {
      (void)s.world.set_motion_continuous(s.moved, s.poses, deforming);
      ADD_FAILURE() << "no error for " << part;
    } catch (const ArgumentError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("World::sweep_motion"), std::string::npos) << what;
      EXPECT_NE(what.find(part), std::string::npos) << what;
    }
    EXPECT_EQ(s.world.model(s.ids[0]).mesh().vertices, sheet0);
    EXPECT_EQ(s.world.model(s.ids[1]).mesh().vertices, strip0);
    EXPECT_EQ(s.world.pose(s.ids[0]).translation, t0);
  };
  const std::vector<Vec3> few(3, Vec3::Zero());
  std::vector<Vec3> nan = s.bodies[1].v1;
  nan[5].y() = std::numeric_limits<Scalar>::quiet_NaN();
  std::vector<Vec3> huge = s.bodies[1].v1;
  huge[2].x() = 1e200;
  // The sheet's entry is fine, the strip's is not: the sheet must not change either.
  expect_error({s.deforming[0], {s.ids[1], few}}, "deforming[1].vertices of object 'strip'");
  expect_error({s.deforming[0], {s.ids[1], few}}, "got 3 vertices");
  expect_error({s.deforming[0], {s.ids[1], nan}}, "vertex 5 is not finite");
  expect_error({s.deforming[0], {s.ids[1], huge}}, "vertex 2's world position at t = 1");
  expect_error({s.deforming[0], s.deforming[0]}, "deforming[1].id repeats deforming[0].id");
  const ObjectId gone = s.world.add(s.bodies[3].model, Transform{}, {"gone"});
  s.world.remove(gone);
  expect_error({{gone, few}}, "deforming[0].id");
  // A NaN pose is named as in sweep_poses.
  std::vector<Transform> poses = s.poses;
  poses[2].translation.z() = std::numeric_limits<Scalar>::quiet_NaN();
  EXPECT_THROW((void)s.world.set_motion_continuous(s.moved, poses, s.deforming), ArgumentError);
  EXPECT_EQ(s.world.model(s.ids[0]).mesh().vertices, sheet0);
}

}  // namespace
}  // namespace antcd
