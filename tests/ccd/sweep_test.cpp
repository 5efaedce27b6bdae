// Mesh sweeps (antcd::sweep) against dense sub-stepping with the exact discrete query, on thin
// sheets that tunnel, rotating bars and random fast motions of real and generated meshes.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/geometry.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "ccd/continuous_support.hpp"
#include "distance/seeded.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

/// The sweep's promises on one motion, checked against dense sub-stepping and the exact distance.
void check_motion(const Model& a, const Transform& a0, const Transform& a1, const Model& b,
                  const Transform& b0, const Transform& b1, const SweepRequest& req,
                  const std::string& what, int* hits = nullptr) {
  const SweepResult r = sweep(a, a0, a1, b, b0, b1, req);
  const auto dense = test::first_substep_contact(a, a0, a1, b, b0, b1, req.min_separation);
  if (dense) {
    ASSERT_TRUE(r.hit) << what << ": dense stepping touches at " << *dense;
    EXPECT_LE(r.toi, *dense) << what;
  }
  if (!r.hit) return;
  if (hits != nullptr) ++*hits;
  EXPECT_FALSE(r.budget_exhausted) << what;
  const Transform pa = ccd::interpolate_pose(a0, a1, r.toi);
  const Transform pb = ccd::interpolate_pose(b0, b1, r.toi);
  const DistanceResult d = distance(a, pa, b, pb);
  // Within the separation plus the tolerance's motion (plus rounding) at toi.
  EXPECT_LE(d.distance, req.min_separation + r.motion_bound * req.time_tolerance + 1e-9) << what;
  if (!r.tolerance_decided) {
    CollisionRequest cr;
    cr.delta = req.min_separation + 1e-9;
    EXPECT_TRUE(collide(a, pa, b, pb, cr).colliding) << what << ": proven hit must touch";
  }
  EXPECT_GE(r.contact.distance, d.distance - 1e-9) << what;
  EXPECT_LE(r.contact.distance, d.distance + r.motion_bound * req.time_tolerance / 2 + 1e-9)
      << what;
}

/// check_motion, and 400 exact collide() steps over [0.98 toi, toi) of a hit find nothing within
/// min_separation; counts the hits in `hits`.
void check_fine_motion(const Model& a, const Transform& a0, const Transform& a1, const Model& b,
                       const Transform& b0, const Transform& b1, const SweepRequest& req,
                       const std::string& what, int& hits) {
  check_motion(a, a0, a1, b, b0, b1, req, what, &hits);
  const SweepResult r = sweep(a, a0, a1, b, b0, b1, req);
  if (!r.hit) return;
  CollisionRequest cr;
  cr.delta = req.min_separation;
  CollisionResult res;
  for (int k = 0; k < 400; ++k) {
    const Scalar t = r.toi * (1 - 0.02 * (1 - k / 400.0));
    EXPECT_FALSE(
        collide(a, ccd::interpolate_pose(a0, a1, t), b, ccd::interpolate_pose(b0, b1, t), cr, res))
        << what << ": touches at " << t << " before toi " << r.toi;
  }
}

Model box_model(const Vec3& half, const std::string& name) {
  return Model(make_box(half), {}, name);
}

TEST(Sweep, ThinSheetsTunnellingAreCaught) {
  // Sheets 0.01 thick, 1 wide; A passes through B by 1.0 per frame (100x its thickness): the
  // frame poses are apart, the motion is not.
  const Model sheet_a = box_model({0.5, 0.5, 0.005}, "sheet_a");
  const Model sheet_b = box_model({0.5, 0.5, 0.005}, "sheet_b");
  const Transform a0 = Transform::from_axis_angle(Vec3::UnitZ(), 0, {0, 0, -0.5});
  const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), 0, {0, 0, 0.5});
  const Transform b = Transform::identity();
  EXPECT_FALSE(collide(sheet_a, a0, sheet_b, b).colliding);
  EXPECT_FALSE(collide(sheet_a, a1, sheet_b, b).colliding);
  const SweepResult r = sweep(sheet_a, a0, a1, sheet_b, b, b);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.49);
  EXPECT_GE(r.toi, 0.49 - 2e-6);
  EXPECT_NEAR(r.contact.point.z(), -0.005, 1e-5);
  EXPECT_LT(r.contact.normal.z(), -0.99);  // from B towards A: A comes from below
  check_motion(sheet_a, a0, a1, sheet_b, b, b, {}, "sheets");
}

TEST(Sweep, RotationSweepsThroughBetweenFrames) {
  // A bar along x turns a quarter turn about z onto y; a small cube sits on the diagonal. Neither
  // frame touches the cube, the turn does: a motion bound without the rotation term misses it.
  const Model bar = box_model({2, 0.05, 0.05}, "bar");
  const Model cube = box_model({0.1, 0.1, 0.1}, "cube");
  const Transform a0 = Transform::identity();
  const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), M_PI / 2);
  const Transform b = Transform::from_axis_angle(Vec3::UnitZ(), 0, {1.2, 1.2, 0});
  EXPECT_FALSE(collide(bar, a0, cube, b).colliding);
  EXPECT_FALSE(collide(bar, a1, cube, b).colliding);
  const SweepResult r = sweep(bar, a0, a1, cube, b, b);
  ASSERT_TRUE(r.hit);
  EXPECT_GT(r.motion_bound, 0);
  check_motion(bar, a0, a1, cube, b, b, {}, "bar");
  // Both move: the bar turns back while the cube rotates about its own off-centre origin.
  const Transform c0 = Transform::from_axis_angle(Vec3(1, 1, 0), 0.3, {1.2, 1.2, 0});
  const Transform c1 = Transform::from_axis_angle(Vec3(0, 1, 1), 2.5, {1.0, 1.3, 0.1});
  check_motion(bar, a1, a0, cube, c0, c1, {}, "bar and cube");
}

TEST(Sweep, FineBarArcSweepsAProbeBeyondEveryChord) {
  // A finely split bar (many small nodes and triangles) turns by 120 degrees about z, from -60 to
  // +60 degrees, while sliding a little along y. A small cube sits on its arc near the tip at
  // t = 0.5, 0.45 beyond the chords between the end positions of every bar point: a swept test
  // that moves nodes or triangles along those chords without the arc's bend misses it.
  const Model bar(make_box({1, 0.05, 0.05}, 16), {}, "fine bar");
  const Model probe = box_model({0.03, 0.03, 0.03}, "probe");
  const Transform a0 = Transform::from_axis_angle(Vec3::UnitZ(), -M_PI / 3, {0, -0.02, 0});
  const Transform a1 = Transform::from_axis_angle(Vec3::UnitZ(), M_PI / 3, {0, 0.02, 0});
  const Transform b = Transform::from_axis_angle(Vec3::UnitZ(), 0, {0.9, 0, 0});
  EXPECT_FALSE(collide(bar, a0, probe, b).colliding);
  EXPECT_FALSE(collide(bar, a1, probe, b).colliding);
  ASSERT_TRUE(test::first_substep_contact(bar, a0, a1, probe, b, b, 0).has_value());
  ASSERT_TRUE(sweep(bar, a0, a1, probe, b, b).hit);
  check_motion(bar, a0, a1, probe, b, b, {}, "fine bar");
  // The same with the probe moving and the roles swapped.
  const Transform b1 = Transform::from_axis_angle(Vec3::UnitX(), 0.4, {0.85, 0.05, 0});
  check_motion(probe, b, b1, bar, a0, a1, {}, "probe and fine bar");
}

TEST(Sweep, FreeMotionsAndRestingContact) {
  const Model a = box_model({0.5, 0.5, 0.5}, "a");
  const Model b = box_model({0.5, 0.5, 0.5}, "b");
  const Transform far0 = Transform::from_axis_angle(Vec3::UnitX(), 0, {3, 0, 0});
  const Transform far1 = Transform::from_axis_angle(Vec3::UnitX(), 1.0, {3, 2, 0});
  const SweepResult free = sweep(a, Transform::identity(), Transform::identity(), b, far0, far1);
  EXPECT_FALSE(free.hit);
  // A proven lower bound: at least min_separation (0) and at most the distance at the end.
  EXPECT_GE(free.distance, 0);
  EXPECT_LE(free.distance, distance(a, Transform::identity(), b, far1).distance);
  // Touching at t = 0 (faces on x = 0.5): a proven hit at 0.
  const Transform touch = Transform::from_axis_angle(Vec3::UnitX(), 0, {1, 0, 0});
  const SweepResult rest = sweep(a, Transform::identity(), Transform::identity(), b, touch, far1);
  ASSERT_TRUE(rest.hit);
  EXPECT_EQ(rest.toi, 0);
  EXPECT_FALSE(rest.tolerance_decided);
  // Settled by the one exact test at the start, its contact an intersecting pair at t = 0.
  EXPECT_EQ(rest.iterations, 1u);
  EXPECT_EQ(rest.contact.distance, 0);
  // Overlapping at t = 0 and moving apart: still toi 0, and a pair that intersects there.
  const Transform deep = Transform::from_axis_angle(Vec3::UnitZ(), 0.3, {0.6, 0.2, 0.1});
  const SweepResult overlap = sweep(a, Transform::identity(), Transform::identity(), b, deep, far1);
  ASSERT_TRUE(overlap.hit);
  EXPECT_EQ(overlap.toi, 0);
  EXPECT_FALSE(overlap.tolerance_decided);
  {
    const auto& ta = a.mesh().triangles[overlap.contact.triangle_a];
    const auto& tb = b.mesh().triangles[overlap.contact.triangle_b];
    const auto& va = a.mesh().vertices;
    const auto& vb = b.mesh().vertices;
    EXPECT_TRUE(geometry::triangles_intersect(va[ta[0]], va[ta[1]], va[ta[2]],
                                              deep.apply(vb[tb[0]]), deep.apply(vb[tb[1]]),
                                              deep.apply(vb[tb[2]])));
  }
  // Separation: B passes 0.2 above A; a hit with min_separation 0.25, none with 0.15.
  const Transform over0 = Transform::from_axis_angle(Vec3::UnitX(), 0, {-3, 0, 1.2});
  const Transform over1 = Transform::from_axis_angle(Vec3::UnitX(), 0, {3, 0, 1.2});
  SweepRequest req;
  req.min_separation = 0.25;
  EXPECT_TRUE(sweep(a, Transform::identity(), Transform::identity(), b, over0, over1, req).hit);
  check_motion(a, Transform::identity(), Transform::identity(), b, over0, over1, req, "over");
  req.min_separation = 0.15;
  EXPECT_FALSE(sweep(a, Transform::identity(), Transform::identity(), b, over0, over1, req).hit);
}

TEST(Sweep, RandomFastMotionsNeverBeatDenseStepping) {
  const Model spider(load_mesh(test::assimp_model("OBJ/spider.obj")), {}, "spider");
  const Model torus(make_torus(1.0, 0.15, 24, 8), {}, "torus");
  const Model plate = box_model({1.5, 1.5, 0.01}, "plate");
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const Scalar size = spider.root().radius;
  int hits = 0;
  int motions = 0;
  for (int i = 0; i < 12; ++i) {
    const Model& b = i % 2 == 0 ? torus : plate;
    const Scalar reach = size + 1.5;
    // A passes from one side of B to the other, turning by up to ~2.5 rad.
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Vec3 side = Vec3(unit(rng), unit(rng), unit(rng)) * 0.5 * size;
    const Transform a0 = test::random_pose(rng, 0.1);
    Transform a1 =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 2.5 * unit(rng)) * a0;
    Transform start = a0;
    start.translation = -reach * dir + side;
    a1.translation = reach * dir + side;
    const Transform b0 = Transform::from_axis_angle(Vec3::UnitZ(), 0.1 * i);
    const Transform b1 = Transform::from_axis_angle(Vec3(1, 0, 0), 0.4, {0.1, 0, 0}) * b0;
    SweepRequest req;
    req.min_separation = i % 3 == 0 ? 0.02 * size : 0;
    check_motion(spider, start, a1, b, b0, b1, req, "motion " + std::to_string(i), &hits);
    ++motions;
  }
  // Spinning in place (no translation at all) with B inside the spider's reach: only the rotation
  // moves the surfaces.
  int spin_hits = 0;
  for (int i = 0; i < 6; ++i) {
    const Model& b = i % 2 == 0 ? torus : plate;
    const Transform a0 = test::random_pose(rng, 0);
    const Transform a1 =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 3.0) * a0;
    const Transform pb = Transform::from_axis_angle(
        Vec3::UnitZ(), 0, Vec3(unit(rng), unit(rng), unit(rng)).normalized() * 0.4 * size);
    check_motion(spider, a0, a1, b, pb, pb, {}, "spin " + std::to_string(i), &spin_hits);
    ++motions;
  }
  hits += spin_hits;
  EXPECT_GE(spin_hits, 2);
  std::cout << "random fast motions: " << motions << ", hits " << hits << '\n';
  EXPECT_GE(hits, motions / 3);
}

TEST(Sweep, FineMeshesNeverTouchBeforeTheToi) {
  // Fine meshes (a 10k-triangle torus through a 5k-triangle sphere, as in bench/ccd_bench.cpp):
  // near contact the hierarchy queries open many node pairs, so the sweep hands over to its
  // traversal, every pair advancing on its own (src/ccd/first_contact.cpp). Besides
  // dense stepping, the last stretch before each toi is stepped finely: nothing may touch there.
  const Model torus(make_torus(1.0, 0.3, 100, 50), {}, "torus");
  const Model sphere(make_sphere(0.8, 72, 36), {}, "sphere");
  std::mt19937_64 rng(124);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const Scalar reach = torus.root().radius + sphere.root().radius + 0.5;
  int hits = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Vec3 side = Vec3(unit(rng), unit(rng), unit(rng)).cross(dir).normalized() * 0.2 * reach;
    Transform a0 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 3 * unit(rng));
    Transform a1 =
        Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 2.5 * unit(rng)) * a0;
    a0.translation = -reach * dir + side;
    a1.translation = reach * dir + side;
    const Transform b0 = Transform::identity();
    const Transform b1 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 0.3);
    SweepRequest req;
    req.min_separation = i % 2 == 0 ? 0.0 : 0.01;
    check_fine_motion(torus, a0, a1, sphere, b0, b1, req, "fine motion " + std::to_string(i), hits);
  }
  EXPECT_GE(hits, 6);
}

TEST(Sweep, FineMeshesSpinningInPlaceNeverTouchBeforeTheToi) {
  // The fine torus turning about an axis in its plane, without translation, its rim sweeping into
  // a fine sphere: the traversal's per-pair steps (ccd::pair_step, src/ccd/first_contact.cpp)
  // then rest on the turning term alone.
  const Model torus(make_torus(1.0, 0.3, 100, 50), {}, "torus");
  const Model sphere(make_sphere(0.3, 72, 36), {}, "sphere");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  int hits = 0;
  for (int i = 0; i < 6; ++i) {
    // Turning by phi about x takes the rim point (0, 1, 0) to (0, cos phi, sin phi); the sphere
    // waits near where it arrives at phi ~ 0.8 (a little off the rim's circle).
    const Scalar phi = 0.8 + 0.2 * unit(rng);
    const Vec3 at = Vec3(0.3 * unit(rng), std::cos(phi), std::sin(phi)) * (1 + 0.1 * unit(rng));
    const Transform a0 = Transform::identity();
    const Transform a1 = Transform::from_axis_angle(Vec3(1, 0.1 * unit(rng), 0), 1.6);
    const Transform b = Transform::from_axis_angle(Vec3::UnitZ(), 0, at);
    SweepRequest req;
    req.min_separation = i % 2 == 0 ? 0.0 : 0.01;
    check_fine_motion(torus, a0, a1, sphere, b, b, req, "spin " + std::to_string(i), hits);
  }
  EXPECT_GE(hits, 4);
}

TEST(Sweep, FastSheetSceneContinuousFindsEveryContactDiscreteMisses) {
  // Twelve nearly horizontal sheets 0.01 thick over each other, each moving 0.1 (10x its thickness)
  // up or down per frame with a slight drift and tilt, for 20 frames. Per frame step and pair:
  // truth = 200-step sub-stepping with exact collide; discrete = collide at the frame poses;
  // continuous = sweep between the two frames.
  const Model sheet = box_model(test::fast_sheet_half(), "sheet");
  constexpr int kSheets = 12;
  constexpr int kFrames = 20;
  const auto poses = test::fast_sheet_tracks(kSheets, kFrames + 1);
  int truth = 0, discrete = 0, continuous = 0, false_alarms = 0;
  for (int f = 0; f < kFrames; ++f) {
    for (int i = 0; i < kSheets; ++i) {
      for (int j = i + 1; j < kSheets; ++j) {
        const auto& a = poses[static_cast<std::size_t>(i)];
        const auto& b = poses[static_cast<std::size_t>(j)];
        const auto fi = static_cast<std::size_t>(f);
        const auto dense =
            test::first_substep_contact(sheet, a[fi], a[fi + 1], sheet, b[fi], b[fi + 1], 0, 200);
        const bool frame_hit = collide(sheet, a[fi + 1], sheet, b[fi + 1]).colliding;
        const SweepResult r = sweep(sheet, a[fi], a[fi + 1], sheet, b[fi], b[fi + 1]);
        truth += dense ? 1 : 0;
        discrete += dense && frame_hit ? 1 : 0;
        continuous += dense && r.hit ? 1 : 0;
        false_alarms += !dense && r.hit ? 1 : 0;
        if (dense) {
          EXPECT_TRUE(r.hit) << "frame " << f << " pair " << i << "," << j;
          EXPECT_LE(r.toi, *dense) << "frame " << f << " pair " << i << "," << j;
        }
      }
    }
  }
  std::cout << "fast sheet scene: " << truth << " frame steps with contact, discrete finds "
            << discrete << ", continuous finds " << continuous
            << " (hits without a sub-stepped contact: " << false_alarms << ")\n";
  EXPECT_GT(truth, 10);
  EXPECT_EQ(continuous, truth);
  EXPECT_LT(discrete, truth / 2);  // the scene is one where per-frame checks tunnel
}

TEST(Sweep, ThreadsShareModelsAndGetTheSameAnswers) {
  const Model torus(make_torus(1.0, 0.3, 32, 16), {}, "torus");
  const Model sphere(make_sphere(0.5, 24, 12), {}, "sphere");
  std::vector<std::array<Transform, 2>> motions;
  std::mt19937_64 rng(5);
  for (int i = 0; i < 8; ++i) {
    Transform a0 = test::random_pose(rng, 0);
    Transform a1 = test::random_pose(rng, 0);
    a0.translation = Vec3(-2, 0.3 * i - 1, 3.0 * (i % 2));
    a1.translation = Vec3(2, 0.1 * i, 0.2 + 3.0 * (i % 2));
    motions.push_back({a0, a1});
  }
  auto run_all = [&] {
    std::vector<SweepResult> out;
    for (const auto& m : motions) {
      out.push_back(sweep(sphere, m[0], m[1], torus, Transform::identity(), Transform::identity()));
    }
    return out;
  };
  const auto reference = run_all();
  const auto hits =
      std::count_if(reference.begin(), reference.end(), [](const SweepResult& r) { return r.hit; });
  EXPECT_GT(hits, 0);
  EXPECT_LT(hits, static_cast<long>(reference.size()));
  std::vector<std::vector<SweepResult>> got(4);
  std::vector<std::thread> threads;
  for (auto& g : got) threads.emplace_back([&g, &run_all] { g = run_all(); });
  for (auto& t : threads) t.join();
  for (const auto& g : got) {
    for (std::size_t i = 0; i < reference.size(); ++i) {
      EXPECT_EQ(g[i].hit, reference[i].hit);
      EXPECT_EQ(g[i].toi, reference[i].toi);
      EXPECT_EQ(g[i].contact.triangle_a, reference[i].contact.triangle_a);
    }
  }
}

// The advancement's distance queries start from the last closest pair (src/distance/seeded.hpp):
// whatever the seed pair, the answer keeps distance()'s guarantees, and the closest pair as the
// seed prunes at least as much as no seed.
TEST(SeededDistance, AnySeedPairKeepsTheGuaranteesOfDistance) {
  const Model a(make_torus(1.0, 0.3, 24, 12), {}, "torus");
  const Model b(make_sphere(0.5, 16, 8), {}, "sphere");
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::uniform_int_distribution<std::uint32_t> tri_a(0, a.mesh().triangles.size() - 1);
  std::uniform_int_distribution<std::uint32_t> tri_b(0, b.mesh().triangles.size() - 1);
  const auto pair_at = [&](const Transform& pa, const Transform& pb, std::uint32_t ta,
                           std::uint32_t tb) {
    const auto& x = a.mesh().triangles[ta];
    const auto& y = b.mesh().triangles[tb];
    const auto& va = a.mesh().vertices;
    const auto& vb = b.mesh().vertices;
    return geometry::triangle_distance(pa.apply(va[x[0]]), pa.apply(va[x[1]]), pa.apply(va[x[2]]),
                                       pb.apply(vb[y[0]]), pb.apply(vb[y[1]]), pb.apply(vb[y[2]]));
  };
  std::uint64_t seeded_pairs = 0;
  std::uint64_t unseeded_pairs = 0;
  for (int i = 0; i < 60; ++i) {
    const Transform pa = test::random_pose(rng, 0.2);
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    const Transform pb = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)),
                                                    3 * unit(rng), (1.2 + unit(rng)) * dir);
    const DistanceResult exact = distance(a, pa, b, pb);
    if (exact.intersecting) continue;
    const std::string what = "pose " + std::to_string(i);
    for (int k = 0; k < 2; ++k) {
      // k 0: a random pair; k 1: the closest pair.
      const std::uint32_t ta = k == 0 ? tri_a(rng) : exact.triangle_a;
      const std::uint32_t tb = k == 0 ? tri_b(rng) : exact.triangle_b;
      const detail::DistanceSeed seed = detail::make_seed(pair_at(pa, pb, ta, tb), ta, tb);
      for (const Scalar rel : {Scalar{0}, Scalar{0.15}}) {
        DistanceRequest req;
        req.rel_tolerance = rel;
        const DistanceResult r = detail::seeded_distance(a, pa, b, pb, req, seed);
        EXPECT_LE(r.lower_bound, exact.distance + 1e-12) << what;
        EXPECT_GE(r.distance, exact.distance - 1e-12) << what;
        EXPECT_GE(exact.distance, r.distance * (1 - rel) - 1e-12) << what;
        if (rel == 0) {
          EXPECT_NEAR(r.distance, exact.distance, 1e-12) << what;
        }
        // The pair and points reported are the distance's own.
        EXPECT_NEAR(pair_at(pa, pb, r.triangle_a, r.triangle_b).distance, r.distance, 1e-12)
            << what;
        EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12) << what;
        if (k == 1 && rel > 0) {
          const DistanceResult plain = distance(a, pa, b, pb, req);
          EXPECT_LE(r.node_pairs, plain.node_pairs) << what;
          seeded_pairs += r.node_pairs;
          unseeded_pairs += plain.node_pairs;
        }
      }
    }
  }
  std::cout << "node pairs seeded with the closest pair " << seeded_pairs << ", unseeded "
            << unseeded_pairs << '\n';
  EXPECT_LT(seeded_pairs, unseeded_pairs);
}

TEST(Sweep, RejectsBadArguments) {
  const Model a = box_model({0.5, 0.5, 0.5}, "a");
  const Transform id = Transform::identity();
  SweepRequest req;
  req.min_separation = -1;
  EXPECT_THROW((void)sweep(a, id, id, a, id, id, req), ArgumentError);
  req = {};
  req.time_tolerance = 0;
  EXPECT_THROW((void)sweep(a, id, id, a, id, id, req), ArgumentError);
  Transform bad = id;
  bad.rotation(0, 0) = 2;
  try {
    (void)sweep(a, id, id, a, id, bad);
    FAIL() << "no throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("pose_b1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace antcd
