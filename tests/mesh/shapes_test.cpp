// Tests of the generated shapes and of merge / transformed.
//
// Volumes: every shape here is a polyhedron whose volume has a closed form, so the signed volume
// is checked twice: exactly (to rounding) against the polyhedron, and against the smooth solid
// within the tessellation error. The sphere, cylinder and torus are solids of revolution of a
// polygonal profile P (in the half-plane rho >= 0) swept through n equal steps with straight
// chords; each step's wedge has volume sin(2π/n) · ∫_P rho dA, so the polyhedron's volume is
// n · sin(2π/n) · ∫_P rho dA. For a regular profile polygon ∫_P rho dA = area(P) · centroid_rho.
#include "support/test_support.hpp"

#include <antcd/mesh.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd {
namespace {

constexpr Scalar pi = std::numbers::pi;

Scalar signed_volume(const Mesh& m) {
  Scalar six_v = 0;
  for (const auto& t : m.triangles) {
    six_v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]]));
  }
  return six_v / 6;
}

/// Closed and consistently oriented: every directed edge occurs exactly once and its reverse
/// exactly once, so every undirected edge is shared by exactly two triangles that traverse it in
/// opposite directions.
void expect_closed_and_oriented(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0) << "edges not shared by exactly two opposite triangles";
}

/// V - E + F: 2 for a closed surface of genus 0 (box, sphere, cylinder), 0 for a torus.
int euler_characteristic(const Mesh& m) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    }
  }
  return static_cast<int>(m.vertices.size()) - static_cast<int>(edges.size()) +
         static_cast<int>(m.triangles.size());
}

void expect_no_duplicate_vertices(const Mesh& m) {
  std::set<std::array<Scalar, 3>> seen;
  for (const Vec3& v : m.vertices) seen.insert({v.x(), v.y(), v.z()});
  EXPECT_EQ(seen.size(), m.vertices.size());
}

/// No zero-area triangle, by the library's own count and by a direct check that twice the area
/// stays well above the degeneracy threshold (1e-12 · longest edge²).
void expect_no_degenerate(const Mesh& m) {
  EXPECT_EQ(m.degenerate_triangle_count(), 0u);
  Scalar worst = std::numeric_limits<Scalar>::infinity();
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Scalar longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    worst = std::min(worst, (b - a).cross(c - a).norm() / longest);
  }
  EXPECT_GT(worst, 1e-3);
}

void expect_every_index_in_range(const Mesh& m) {
  for (const auto& t : m.triangles) {
    for (const auto i : t) ASSERT_LT(i, m.vertices.size());
  }
}

void expect_valid_shape(const Mesh& m, int expected_euler) {
  expect_every_index_in_range(m);
  EXPECT_NO_THROW(validate_mesh(m, "shape"));
  expect_closed_and_oriented(m);
  EXPECT_EQ(euler_characteristic(m), expected_euler);
  expect_no_duplicate_vertices(m);
  expect_no_degenerate(m);
  EXPECT_GT(signed_volume(m), 0);
}

void expect_bounds(const Mesh& m, const Vec3& lo, const Vec3& hi, Scalar tol) {
  const Aabb b = m.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], lo[k], tol) << "axis " << k;
    EXPECT_NEAR(b.max[k], hi[k], tol) << "axis " << k;
  }
}

/// ∫_P rho dA for a polygon given counter-clockwise in the (rho, z) plane.
Scalar first_moment(const std::vector<std::pair<Scalar, Scalar>>& polygon) {
  Scalar sum = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const auto [r0, z0] = polygon[k];
    const auto [r1, z1] = polygon[(k + 1) % polygon.size()];
    sum += (r0 + r1) * (r0 * z1 - r1 * z0);
  }
  return sum / 6;
}

Scalar revolution_volume(const std::vector<std::pair<Scalar, Scalar>>& profile, int steps) {
  return steps * std::sin(2 * pi / steps) * first_moment(profile);
}

// ---- box ----

TEST(MakeBox, SingleSubdivision) {
  const Mesh m = make_box(Vec3(1, 2, 3));
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  expect_valid_shape(m, 2);
  EXPECT_NEAR(signed_volume(m), 48.0, 1e-12);
  expect_bounds(m, Vec3(-1, -2, -3), Vec3(1, 2, 3), 0);
}

TEST(MakeBox, Subdivided) {
  for (const int s : {2, 3, 7}) {
    SCOPED_TRACE(s);
    const Vec3 h(0.5, 0.25, 4);
    const Mesh m = make_box(h, s);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(6 * s * s + 2));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(12 * s * s));
    expect_valid_shape(m, 2);
    EXPECT_NEAR(signed_volume(m), 8 * h.prod(), 1e-12);
    expect_bounds(m, -h, h, 0);
    // Every vertex lies on the surface of the box.
    for (const Vec3& v : m.vertices) {
      EXPECT_TRUE(((v.cwiseAbs() - h).array().abs() == 0).any()) << v.transpose();
    }
  }
}

TEST(MakeBox, InvalidArguments) {
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  const Scalar inf = std::numeric_limits<Scalar>::infinity();
  EXPECT_THROW(make_box(Vec3(0, 1, 1)), antcd::ArgumentError);
  EXPECT_THROW(make_box(Vec3(1, -1, 1)), antcd::ArgumentError);
  EXPECT_THROW(make_box(Vec3(1, 1, nan)), antcd::ArgumentError);
  EXPECT_THROW(make_box(Vec3(inf, 1, 1)), antcd::ArgumentError);
  EXPECT_THROW(make_box(Vec3(1, 1, 1), 0), antcd::ArgumentError);
  EXPECT_THROW(make_box(Vec3(1, 1, 1), -3), antcd::ArgumentError);
  // 6 · 40000² vertices do not fit 32-bit indices: refused before anything is allocated.
  EXPECT_THROW(make_box(Vec3(1, 1, 1), 40000), antcd::ArgumentError);
  try {
    (void)make_box(Vec3(1, 1, 1), 0);
  } catch (const antcd::ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("subdivisions must be >= 1, got 0"), std::string::npos)
        << e.what();
  }
}

// ---- sphere ----

std::vector<std::pair<Scalar, Scalar>> sphere_profile(Scalar r, int stacks) {
  std::vector<std::pair<Scalar, Scalar>> p;  // from the south pole up the rho >= 0 side
  for (int i = stacks; i >= 0; --i) {
    const Scalar theta = pi * i / stacks;
    p.emplace_back(i == 0 || i == stacks ? 0.0 : r * std::sin(theta), r * std::cos(theta));
  }
  return p;
}

TEST(MakeSphere, DefaultTessellation) {
  const Scalar r = 2.5;
  const Mesh m = make_sphere(r);
  EXPECT_EQ(m.vertices.size(), 32u * 15u + 2u);
  EXPECT_EQ(m.triangles.size(), 2u * 32u * 15u);
  expect_valid_shape(m, 2);
  for (const Vec3& v : m.vertices) EXPECT_NEAR(v.norm(), r, 1e-14 * r);
  // slices divisible by 4 and stacks even: the extreme points ±r on each axis are vertices.
  expect_bounds(m, Vec3::Constant(-r), Vec3::Constant(r), 0);
  const Scalar exact = revolution_volume(sphere_profile(r, 16), 32);
  EXPECT_NEAR(signed_volume(m), exact, 1e-12 * exact);
  // Inscribed polyhedron: a little smaller than the ball; 32 x 16 loses under 2 %.
  const Scalar ball = 4.0 / 3.0 * pi * r * r * r;
  EXPECT_LT(signed_volume(m), ball);
  EXPECT_GT(signed_volume(m), 0.98 * ball);
}

TEST(MakeSphere, ConvergesToBallVolume) {
  // The inscribed polyhedron misses a relative volume of about 16.5 / n² for n slices and n / 2
  // stacks (the missing caps scale with the squared angular step): bounded here by 20 / n², and
  // each doubling of n divides the error by about 4.
  const Scalar ball = 4.0 / 3.0 * pi;
  Scalar previous_error = 1;
  for (const int n : {8, 16, 32, 64, 128}) {
    const Mesh m = make_sphere(1, n, n / 2);
    const Scalar error = (ball - signed_volume(m)) / ball;
    EXPECT_GT(error, 0) << n;
    EXPECT_LT(error, 20.0 / (n * n)) << n;
    EXPECT_LT(error, previous_error / 3.5) << n;
    previous_error = error;
  }
}

TEST(MakeSphere, MinimalAndOddTessellations) {
  const Mesh bipyramid = make_sphere(1, 3, 2);  // poles + one ring of 3
  EXPECT_EQ(bipyramid.vertices.size(), 5u);
  EXPECT_EQ(bipyramid.triangles.size(), 6u);
  expect_valid_shape(bipyramid, 2);
  for (const auto& [slices, stacks] : {std::pair{5, 3}, std::pair{7, 2}, std::pair{3, 9}}) {
    SCOPED_TRACE(slices);
    const Mesh m = make_sphere(0.1, slices, stacks);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(slices * (stacks - 1) + 2));
    expect_valid_shape(m, 2);
    const Scalar exact = revolution_volume(sphere_profile(0.1, stacks), slices);
    EXPECT_NEAR(signed_volume(m), exact, 1e-12 * exact);
    // The poles are always vertices.
    EXPECT_EQ(m.bounds().max.z(), 0.1);
    EXPECT_EQ(m.bounds().min.z(), -0.1);
  }
}

TEST(MakeSphere, InvalidArguments) {
  EXPECT_THROW(make_sphere(0), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(-1), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(std::numeric_limits<Scalar>::quiet_NaN()), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(std::numeric_limits<Scalar>::infinity()), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(1, 2, 8), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(1, 8, 1), antcd::ArgumentError);
  EXPECT_THROW(make_sphere(1, 100000, 100000), antcd::ArgumentError);
  try {
    (void)make_sphere(-1);
  } catch (const antcd::ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("make_sphere: radius must be finite and > 0, got -1"),
              std::string::npos)
        << e.what();
  }
}

// ---- cylinder ----

TEST(MakeCylinder, VolumeAndBounds) {
  const Scalar r = 1.5;
  const Scalar h = 4;
  for (const auto& [slices, stacks] : {std::pair{32, 1}, std::pair{3, 1}, std::pair{7, 5}}) {
    SCOPED_TRACE(slices);
    const Mesh m = make_cylinder(r, h, slices, stacks);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(slices * (stacks + 1) + 2));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * slices * (stacks + 1)));
    expect_valid_shape(m, 2);
    // A prism over the inscribed regular polygon: (n/2) sin(2π/n) r² h.
    const Scalar prism = slices / 2.0 * std::sin(2 * pi / slices) * r * r * h;
    EXPECT_NEAR(signed_volume(m), prism, 1e-12 * prism);
    EXPECT_LT(signed_volume(m), pi * r * r * h);
    EXPECT_EQ(m.bounds().min.z(), -h / 2);
    EXPECT_EQ(m.bounds().max.z(), h / 2);
    EXPECT_EQ(m.bounds().max.x(), r);
  }
  const Mesh m = make_cylinder(r, h);  // 32 slices: within 1 % of the smooth cylinder
  EXPECT_GT(signed_volume(m), 0.99 * pi * r * r * h);
  expect_bounds(m, Vec3(-r, -r, -h / 2), Vec3(r, r, h / 2), 0);
}

TEST(MakeCylinder, InvalidArguments) {
  EXPECT_THROW(make_cylinder(0, 1), antcd::ArgumentError);
  EXPECT_THROW(make_cylinder(1, 0), antcd::ArgumentError);
  EXPECT_THROW(make_cylinder(1, -2), antcd::ArgumentError);
  EXPECT_THROW(make_cylinder(1, std::numeric_limits<Scalar>::infinity()), antcd::ArgumentError);
  EXPECT_THROW(make_cylinder(1, 1, 2), antcd::ArgumentError);
  EXPECT_THROW(make_cylinder(1, 1, 8, 0), antcd::ArgumentError);
}

// ---- torus ----

TEST(MakeTorus, VolumeAndBounds) {
  const Scalar big = 3;
  const Scalar small = 1;
  for (const auto& [M, m_] : {std::pair{48, 24}, std::pair{3, 3}, std::pair{5, 7}}) {
    SCOPED_TRACE(M);
    const Mesh m = make_torus(big, small, M, m_);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(M * m_));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * M * m_));
    expect_valid_shape(m, 0);
    // Profile: regular m-gon of circumradius `small` centred at rho = big.
    const Scalar profile_area = m_ / 2.0 * std::sin(2 * pi / m_) * small * small;
    const Scalar exact = M * std::sin(2 * pi / M) * big * profile_area;
    EXPECT_NEAR(signed_volume(m), exact, 1e-12 * exact);
    EXPECT_EQ(m.bounds().max.x(), big + small);
  }
  const Mesh m = make_torus(big, small);
  const Scalar smooth = 2 * pi * pi * big * small * small;
  EXPECT_LT(signed_volume(m), smooth);
  EXPECT_GT(signed_volume(m), 0.98 * smooth);
  expect_bounds(m, Vec3(-4, -4, -1), Vec3(4, 4, 1), 0);
}

TEST(MakeTorus, InvalidArguments) {
  EXPECT_THROW(make_torus(0, 0.5), antcd::ArgumentError);
  EXPECT_THROW(make_torus(1, 0), antcd::ArgumentError);
  EXPECT_THROW(make_torus(1, 1), antcd::ArgumentError);  // tube reaches the axis
  EXPECT_THROW(make_torus(1, 2), antcd::ArgumentError);
  EXPECT_THROW(make_torus(2, 1, 2, 8), antcd::ArgumentError);
  EXPECT_THROW(make_torus(2, 1, 8, 2), antcd::ArgumentError);
  EXPECT_THROW(make_torus(2, std::numeric_limits<Scalar>::quiet_NaN()), antcd::ArgumentError);
}

// ---- merge and transformed ----

TEST(Merge, ConcatenatesWithOffsets) {
  const Mesh box = make_box(Vec3(1, 1, 1));
  const Mesh ball = transformed(make_sphere(0.5, 8, 4),
                                Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(5, 0, 0)));
  const Mesh both = merge({box, ball});
  EXPECT_EQ(both.vertices.size(), box.vertices.size() + ball.vertices.size());
  EXPECT_EQ(both.triangles.size(), box.triangles.size() + ball.triangles.size());
  expect_closed_and_oriented(both);
  EXPECT_NEAR(signed_volume(both), signed_volume(box) + signed_volume(ball), 1e-12);
  EXPECT_EQ(both.triangles[box.triangles.size()][0], ball.triangles[0][0] + 8);
  expect_bounds(both, Vec3(-1, -1, -1), Vec3(5.5, 1, 1), 1e-15);
  EXPECT_TRUE(merge({}).vertices.empty());
  EXPECT_TRUE(merge({}).triangles.empty());
}

TEST(Merge, RejectsPartWithBadIndex) {
  Mesh bad = make_box(Vec3(1, 1, 1));
  bad.triangles[3][2] = 8;  // one past the end: after offsetting it would hit the next part
  EXPECT_THROW(merge({bad, make_box(Vec3(1, 1, 1))}), antcd::ArgumentError);
}

TEST(Transformed, RigidMotionKeepsShape) {
  const Mesh torus = make_torus(2, 0.5, 16, 8);
  const Transform t = Transform::from_axis_angle(Vec3(1, -2, 0.5), 1.1, Vec3(3, 4, -5));
  const Mesh moved = transformed(torus, t);
  ASSERT_EQ(moved.vertices.size(), torus.vertices.size());
  EXPECT_EQ(moved.triangles, torus.triangles);
  for (std::size_t i = 0; i < torus.vertices.size(); ++i) {
    EXPECT_LT((moved.vertices[i] - t.apply(torus.vertices[i])).norm(), 1e-15);
  }
  EXPECT_NEAR(signed_volume(moved), signed_volume(torus), 1e-12);
  expect_closed_and_oriented(moved);
}

}  // namespace
}  // namespace antcd
