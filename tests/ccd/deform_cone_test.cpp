// The deforming sweep's continuous normal-cone cull (antcd/deform_ccd.hpp, "Normal cones";
// src/ccd/normal_cone.cpp): each motion below is one surface patch that self-collides while some
// part of the cull's condition holds, so that a cull which checked less ((i) at t = 0 only, (i)
// without the cross term, (ii) at the step's ends only) would miss a contact whose time is known
// exactly; and random cloth steps, where every proven contact without the cull is found with it.
#include <antcd/bvh.hpp>
#include <antcd/deform_ccd.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "ccd/deform_support.hpp"

namespace antcd {
namespace {

constexpr Scalar kPi = std::numbers::pi;

DeformSweepResult sweep(const Mesh& m, const std::vector<Vec3>& v0, const std::vector<Vec3>& v1,
                        bool cones, bool all_pairs = false) {
  const Model model(m, {}, "patch");
  DeformSweepRequest req;
  req.normal_cones = cones;
  req.all_pairs = all_pairs;
  return deform_sweep(model, v0, v1, req);
}

TEST(DeformCone, CalmClothIsCulledWhole) {
  // A gently waving sheet, no contact: its root is one patch whose normals stay near +z.
  Mesh m = test::make_grid(32, 32, 1, 1);
  for (Vec3& p : m.vertices) p.z() = 0.02 * std::sin(6 * p.x()) * std::cos(5 * p.y());
  std::vector<Vec3> v1 = m.vertices;
  for (Vec3& p : v1) p += 0.4 / 32 * Vec3(0.3 * std::sin(5 * p.y()), 0, std::cos(7 * p.x()));
  const DeformSweepResult on = sweep(m, m.vertices, v1, true);
  const DeformSweepResult off = sweep(m, m.vertices, v1, false);
  EXPECT_FALSE(on.hit);
  EXPECT_FALSE(off.hit);
  EXPECT_GE(on.cone_culled, 1u);
  EXPECT_EQ(on.primitive_queries, 0u);
  EXPECT_GT(off.primitive_queries, 1000u);
  EXPECT_EQ(off.cone_tests, 0u);
}

TEST(DeformCone, TentVertexPassesThroughItsSheet) {
  // An interior vertex of a flat sheet starts above it (a tent, every normal +z at t = 0) and
  // ends three cells over and below it: at t = 1/2 it is on the sheet inside a triangle not its
  // own (contact), and its triangles have turned over by t = 1.
  const int n = 16;
  const Scalar cell = 1.0 / n;
  const Mesh m = test::make_grid(n, n, 1, 1);
  std::vector<Vec3> v0 = m.vertices, v1 = m.vertices;
  const std::size_t v = 8 * (n + 1) + 8;
  v0[v].z() = 0.02;
  v1[v] = m.vertices[v] + Vec3(3 * cell, 0.3 * cell, -0.02);
  const DeformSweepResult r = sweep(m, v0, v1, true);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
  EXPECT_GE(r.cone_tests, 1u);
}

/// A disc of `rings` rings of `spokes` vertices around a centre (ring j at radius 0.1 1.15^j),
/// heights z = 0.05 r sin(theta); triangles counter-clockwise seen from +z.
Mesh polar_disc(int rings, int spokes) {
  Mesh m;
  m.vertices.emplace_back(0, 0, 0);
  for (int j = 0; j < rings; ++j) {
    const Scalar r = 0.1 * std::pow(1.15, j);
    for (int i = 0; i < spokes; ++i) {
      const Scalar a = 2 * kPi * i / spokes;
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.05 * r * std::sin(a));
    }
  }
  auto id = [&](int j, int i) { return static_cast<std::uint32_t>(1 + j * spokes + i % spokes); };
  for (int i = 0; i < spokes; ++i) m.triangles.push_back({0, id(0, i), id(0, i + 1)});
  for (int j = 0; j + 1 < rings; ++j) {
    for (int i = 0; i < spokes; ++i) {
      m.triangles.push_back({id(j, i), id(j + 1, i), id(j + 1, i + 1)});
      m.triangles.push_back({id(j, i), id(j + 1, i + 1), id(j, i + 1)});
    }
  }
  return m;
}

TEST(DeformCone, InnerDiscTurnsHalfAround) {
  // The inner rings turn by pi (x, y -> -x, -y exactly), the next ones by less and less, the
  // outer ones not at all. Every triangle faces +z at t = 0 and at t = 1 (a half turn keeps
  // orientation), but the inner disc shrinks through its centre: at t = 1/2 its vertices are all
  // at x = y = 0 and the centre vertex lies on triangles it is no corner of. The normals of the
  // inner triangles are n0 (1 - 2t)^2: the cross term is -n0, which is what excludes the cull.
  const int rings = 16, spokes = 24;
  const Mesh m = polar_disc(rings, spokes);
  std::vector<Vec3> v1 = m.vertices;
  for (std::size_t k = 1; k < v1.size(); ++k) {
    const int j = static_cast<int>((k - 1) / spokes);
    const Vec3& p = m.vertices[k];
    if (j < 3) {
      v1[k] = Vec3(-p.x(), -p.y(), p.z());
      continue;
    }
    const Scalar phi = kPi * std::max(0.0, 1.0 - (j - 2) / 8.0);  // pi / 8 less per ring
    v1[k] = Vec3(std::cos(phi) * p.x() - std::sin(phi) * p.y(),
                 std::sin(phi) * p.x() + std::cos(phi) * p.y(), p.z());
  }
  v1[0] = m.vertices[0];
  const DeformSweepResult r = sweep(m, m.vertices, v1, true);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
  EXPECT_GE(r.cone_tests, 1u);
}

TEST(DeformCone, SpiralEndSweepsOverItsStart) {
  // A strip wound once and a bit around the z axis, radius r0 + k alpha + w (alpha the angle, w
  // across the strip): its last turn lies outside its first at t = 0 and inside it at t = 1 (the
  // radius r0 - k alpha + w), the boundary simple in projection at both ends. In between the
  // last part passes over the first, coming down from above: at t = 1/2 the strip is a flat
  // band and its ends overlap (contact). Normals stay +z all along; only the boundary excludes
  // the cull.
  const int na = 120, nw = 3;
  const Scalar delta = 0.6, width = 0.1, r0 = 1, k = 0.03, h = 0.05;
  Mesh m = test::make_grid(na, nw, 2 * kPi + delta, width);
  std::vector<Vec3> v0, v1;
  for (const Vec3& p : m.vertices) {
    const Scalar a = p.x(), w = p.y();
    const Scalar s = std::max(0.0, (a - kPi) / kPi);  // height ramp of the last part
    const Vec3 dir(std::cos(a), std::sin(a), 0);
    v0.push_back((r0 + k * a + w) * dir + Vec3(0, 0, h * s));
    v1.push_back((r0 - k * a + w) * dir + Vec3(0, 0, -h * s));
  }
  m.vertices = v0;
  const DeformSweepResult r = sweep(m, v0, v1, true);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.5);
  EXPECT_GE(r.cone_tests, 1u);
}

using Key = std::tuple<int, std::array<std::uint32_t, 4>>;

TEST(DeformCone, RandomClothStepsLoseNoContact) {
  // Random steps of a 14 x 14 sheet, a third folding through themselves. The cull only drops
  // pairs: with it, the pairs (all_pairs) are a subset of those without it. And against 1000
  // sub-steps with the exact discrete self test (deform_substep_test.cpp's reference): when a
  // sub-step t_k intersects, the sweep with the cull hits with toi <= t_k.
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<Scalar> amp(-1, 1);
  int culled = 0, intersecting = 0;
  for (int trial = 0; trial < 24; ++trial) {
    Mesh m = test::make_grid(14, 14, 1, 1);
    const Scalar a0 = 0.05 * amp(rng), fx = 3 + 4 * amp(rng), fy = 3 + 4 * amp(rng);
    for (Vec3& p : m.vertices) p.z() = a0 * std::sin(fx * p.x()) * std::cos(fy * p.y());
    std::vector<Vec3> v1 = m.vertices;
    // A third of the steps fold the sheet over a random line through itself, the others wave it.
    const Scalar line = 0.3 + 0.4 * std::abs(amp(rng)), lift = 0.05 * amp(rng);
    const Scalar wave = 0.03 * amp(rng), g = 3 + 5 * std::abs(amp(rng));
    for (Vec3& p : v1) {
      if (trial % 3 == 0 && p.x() > line) {
        p = Vec3(2 * line - p.x() + 0.1 * amp(rng) * 0.1, p.y(), lift + 0.02 * std::sin(g * p.y()));
      } else {
        p.z() += wave * std::sin(g * p.x() + 2 * p.y());
      }
    }
    const std::vector<Vec3>& v0 = m.vertices;
    const DeformSweepResult all_off = sweep(m, v0, v1, false, true);
    const DeformSweepResult all_on = sweep(m, v0, v1, true, true);
    const DeformSweepResult first_on = sweep(m, v0, v1, true);
    culled += static_cast<int>(all_on.cone_culled);
    std::set<Key> on, off;
    for (const DeformPair& p : all_on.pairs) on.insert({static_cast<int>(p.kind), p.indices});
    for (const DeformPair& p : all_off.pairs) off.insert({static_cast<int>(p.kind), p.indices});
    for (const Key& k : on) EXPECT_TRUE(off.count(k)) << "trial " << trial;
    std::optional<int> first_step;
    for (int k = 0; k <= 1000 && !first_step; ++k) {
      if (test::self_intersects_disjoint(m, test::lerp(v0, v1, k / 1000.0))) first_step = k;
    }
    if (first_step) {
      ++intersecting;
      EXPECT_TRUE(first_on.hit) << "trial " << trial;
      EXPECT_LE(first_on.toi, *first_step / 1000.0) << "trial " << trial;
    }
    EXPECT_EQ(first_on.hit, all_on.hit);
  }
  std::cout << culled << " subtrees culled, " << intersecting << " of 24 steps intersect\n";
  EXPECT_GT(culled, 10);
  EXPECT_GE(intersecting, 5);
}

}  // namespace
}  // namespace antcd
