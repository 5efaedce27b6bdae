// Tests of the triangle predicates and distances in antcd/geometry.hpp (src/geometry/triangle.cpp).
//
// Expected answers of the hand-built cases are derived by hand in the comments. The randomized
// tests use independent references: an exact integer separating-axis test for lattice triangles,
// dense sampling for distances, and duality certificates (a separating slab for the distance of
// two disjoint triangles, the projection inequalities for a closest point).
#include <antcd/geometry.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace antcd::geometry {
namespace {

using Tri = std::array<Vec3, 3>;

Vec3 V(double x, double y, double z) { return Vec3(x, y, z); }

std::string str(const Tri& t) {
  std::ostringstream os;
  os.precision(17);
  for (const Vec3& v : t) os << "(" << v.x() << ", " << v.y() << ", " << v.z() << ") ";
  return os.str();
}

bool intersect(const Tri& a, const Tri& b, Vec3* p = nullptr) {
  return triangles_intersect(a[0], a[1], a[2], b[0], b[1], b[2], p);
}

TriangleDistance distance(const Tri& a, const Tri& b) {
  return triangle_distance(a[0], a[1], a[2], b[0], b[1], b[2]);
}

bool within(const Tri& a, const Tri& b, double delta, Vec3* p = nullptr, double* d = nullptr) {
  return triangles_within(a[0], a[1], a[2], b[0], b[1], b[2], delta, p, d);
}

double point_tri_dist(const Vec3& p, const Tri& t) {
  return std::sqrt(point_triangle_distance_squared(p, t[0], t[1], t[2]));
}

Tri translated(const Tri& t, const Vec3& d) { return {t[0] + d, t[1] + d, t[2] + d}; }

double longest_edge(const Tri& t) {
  return std::sqrt(std::max(
      {(t[1] - t[0]).squaredNorm(), (t[2] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm()}));
}

double max_abs_coord(const Tri& t) {
  return std::max(
      {t[0].cwiseAbs().maxCoeff(), t[1].cwiseAbs().maxCoeff(), t[2].cwiseAbs().maxCoeff()});
}

// "Within 1e-9 relative tolerance": relative to the size of the configuration and to the size of
// its coordinates (a computed point cannot be more accurate than its coordinates).
double point_tolerance(const Tri& a, const Tri& b) {
  return 1e-9 * std::max({longest_edge(a), longest_edge(b), max_abs_coord(a), max_abs_coord(b)});
}

// The six vertex orders of a triangle: three rotations of each orientation.
std::array<Tri, 6> orderings(const Tri& t) {
  return {{{t[0], t[1], t[2]},
           {t[1], t[2], t[0]},
           {t[2], t[0], t[1]},
           {t[0], t[2], t[1]},
           {t[2], t[1], t[0]},
           {t[1], t[0], t[2]}}};
}

// Checks triangles_intersect, triangles_within(delta = 0) and triangle_distance against the
// expected answer for every vertex order and orientation of both triangles and both argument
// orders (72 variants), and that every reported common point lies on both triangles.
void check_all_variants(const Tri& a, const Tri& b, bool expected, const std::string& label) {
  SCOPED_TRACE(label + ": A = " + str(a) + " B = " + str(b));
  const double tol = point_tolerance(a, b);
  int failures = 0;
  for (const Tri& oa : orderings(a)) {
    for (const Tri& ob : orderings(b)) {
      for (int swap = 0; swap < 2; ++swap) {
        const Tri& x = swap != 0 ? ob : oa;
        const Tri& y = swap != 0 ? oa : ob;
        const Vec3 nan = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
        Vec3 p = nan;
        const bool r = intersect(x, y, &p);
        EXPECT_EQ(r, expected) << "variant X = " << str(x) << " Y = " << str(y);
        EXPECT_EQ(intersect(x, y), r);  // the answer must not depend on the point request
        if (r) {
          EXPECT_LE(point_tri_dist(p, x), tol) << "point " << p.transpose();
          EXPECT_LE(point_tri_dist(p, y), tol) << "point " << p.transpose();
        }
        Vec3 q = nan;
        double dw = -1;
        EXPECT_EQ(within(x, y, 0.0, &q, &dw), expected);
        if (expected) {
          EXPECT_EQ(dw, 0.0);
          EXPECT_LE(point_tri_dist(q, x), tol);
          EXPECT_LE(point_tri_dist(q, y), tol);
        }
        const TriangleDistance td = distance(x, y);
        if (expected) {
          EXPECT_EQ(td.distance, 0.0);
          EXPECT_EQ(td.pa, td.pb);
          EXPECT_LE(point_tri_dist(td.pa, x), tol);
          EXPECT_LE(point_tri_dist(td.pa, y), tol);
        } else {
          EXPECT_GT(td.distance, 0.0);
        }
        if (::testing::Test::HasFailure() && ++failures > 3) return;
      }
    }
  }
}

// The reference triangle most hand-built cases use: in the plane z = 0, x, y >= 0, x + y <= 4.
const Tri kA = {V(0, 0, 0), V(4, 0, 0), V(0, 4, 0)};

// ---- orient3d and is_degenerate_triangle
// ----------------------------------------------------------

TEST(TriangleOrient3d, SignConvention) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);           // counter-clockwise seen from +z
  EXPECT_GT(orient3d(a, b, c, V(0.2, 0.3, -1)), 0);        // below
  EXPECT_LT(orient3d(a, b, c, V(0.2, 0.3, 1)), 0);         // above
  EXPECT_EQ(orient3d(a, b, c, V(5, -7, 0)), 0);            // coplanar
  EXPECT_DOUBLE_EQ(orient3d(a, b, c, V(0, 0, -1)), 1.0);   // det of the unit tetrahedron
  EXPECT_DOUBLE_EQ(orient3d(b, a, c, V(0, 0, -1)), -1.0);  // swapping two rows flips the sign
  EXPECT_DOUBLE_EQ(orient3d(a, b, c, V(0, 0, -3)), 3.0);
}

// Points of the plane z = x + y whose coordinates are short dyadic numbers (so that x + y is an
// exact double) are exactly coplanar, but with coordinates of very different magnitudes their
// differences and products round, and naive floating-point determinants are usually not zero.
// orient3d must return exactly zero, and the exact sign of a one-ulp displacement off the plane.
Vec3 point_on_plane_x_plus_y(std::mt19937_64& rng, int min_exp, int max_exp) {
  std::uniform_int_distribution<int> mant(-(1 << 20), 1 << 20), ex(min_exp, max_exp), gap(-25, 25);
  const int e = ex(rng);
  const double x = std::ldexp(double(mant(rng)), e);
  const double y = std::ldexp(double(mant(rng)), e + gap(rng));
  const double z = x + y;
  EXPECT_EQ(z - x, y);  // the sum is exact
  return V(x, y, z);
}

TEST(TriangleOrient3d, ExactOnRoundingSensitiveInput) {
  std::mt19937_64 rng(12345);
  int naive_nonzero = 0;
  for (int i = 0; i < 4000; ++i) {
    // Half of the cases with wildly mixed magnitudes (inexact differences), half with moderately
    // mixed ones (exact differences, inexact products).
    const int lo = i % 2 == 0 ? -40 : -24, hi = i % 2 == 0 ? 20 : -20;
    Vec3 p[4];
    for (Vec3& v : p) v = point_on_plane_x_plus_y(rng, lo, hi);
    EXPECT_EQ(orient3d(p[0], p[1], p[2], p[3]), 0) << i;
    EXPECT_EQ(orient3d(p[3], p[1], p[0], p[2]), 0) << i;
    const Vec3 ad = p[0] - p[3], bd = p[1] - p[3], cd = p[2] - p[3];
    if (ad.dot(bd.cross(cd)) != 0) ++naive_nonzero;
    // Move p[3] one ulp up: orient3d = -n·(d - a) with n = (b-a)x(c-a) = n_z (-1, -1, 1), so the
    // sign is -sign(n_z). Only checked when n_z is clearly nonzero.
    const Vec3 nrm = (p[1] - p[0]).cross(p[2] - p[0]);
    const Vec3 up = V(p[3].x(), p[3].y(), std::nextafter(p[3].z(), 1e300));
    const Vec3 down = V(p[3].x(), p[3].y(), std::nextafter(p[3].z(), -1e300));
    const double scale = (p[1] - p[0]).norm() * (p[2] - p[0]).norm();
    if (std::abs(nrm.z()) > 1e-6 * scale) {
      const double s = nrm.z() > 0 ? 1 : -1;
      EXPECT_LT(s * orient3d(p[0], p[1], p[2], up), 0) << i;
      EXPECT_GT(s * orient3d(p[0], p[1], p[2], down), 0) << i;
      EXPECT_GT(s * orient3d(p[1], p[0], p[2], up), 0) << i;
    }
    if (HasFailure()) break;
  }
  // The test is only meaningful if the naive evaluation really fails on this input.
  EXPECT_GT(naive_nonzero, 400);
}

TEST(TriangleDegenerate, Cases) {
  EXPECT_TRUE(is_degenerate_triangle(V(1, 2, 3), V(1, 2, 3), V(1, 2, 3)));  // all coincide
  EXPECT_TRUE(is_degenerate_triangle(V(0, 0, 0), V(0, 0, 0), V(1, 1, 1)));  // two coincide
  EXPECT_TRUE(is_degenerate_triangle(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)));  // collinear
  EXPECT_TRUE(is_degenerate_triangle(V(0, 0, 0), V(2, 0, 0), V(1, 0, 0)));  // cap-shaped
  EXPECT_FALSE(is_degenerate_triangle(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)));
  // Needle with apex height h over a unit base: |cross| = h, longest edge 1: degenerate iff
  // h <= 1e-12; the verdict is scale invariant.
  for (const double s : {1.0, 1e-3, 1e4}) {
    EXPECT_TRUE(is_degenerate_triangle(V(0, 0, 0), s * V(1, 0, 0), s * V(0.5, 0.9e-12, 0))) << s;
    EXPECT_FALSE(is_degenerate_triangle(V(0, 0, 0), s * V(1, 0, 0), s * V(0.5, 1.1e-12, 0))) << s;
    EXPECT_FALSE(is_degenerate_triangle(V(0, 0, 0), s * V(1, 0, 0), s * V(0.5, 1e-6, 0))) << s;
  }
  // Thin but legitimate slivers used below are not degenerate.
  EXPECT_FALSE(is_degenerate_triangle(V(0, 0, 0), V(10, 0, 0), V(0, 1e-6, 0)));
}

// ---- triangles_intersect: hand-built configurations ---------------------------------------------

TEST(TriangleIntersect, SeparatedByPlane) {
  check_all_variants(kA, translated(kA, V(0, 0, 1)), false, "parallel copy above");
  check_all_variants(kA, {V(1, 1, 1), V(1, 1, 3), V(2, 1, 3)}, false, "above, vertical");
}

TEST(TriangleIntersect, GeneralCrossing) {
  // B lies in the plane x = y; B ∩ {z = 0} is (1,1,0)-(5,5,0), A ∩ {x = y} is (0,0,0)-(2,2,0):
  // they share (1,1,0)-(2,2,0), and A's edge x + y = 4 crosses B's interior at (2,2,0).
  check_all_variants(kA, {V(1, 1, -2), V(1, 1, 2), V(5, 5, 0)}, true, "chain-link crossing");
  // Same configuration under a generic rigid motion (non-integer coordinates).
  const Transform tr = Transform::from_axis_angle(V(0.3, -0.7, 0.4), 0.9, V(0.25, -3.5, 7.0));
  const Tri b = {V(1, 1, -2), V(1, 1, 2), V(5, 5, 0)};
  check_all_variants({tr.apply(kA[0]), tr.apply(kA[1]), tr.apply(kA[2])},
                     {tr.apply(b[0]), tr.apply(b[1]), tr.apply(b[2])}, true, "moved crossing");
}

TEST(TriangleIntersect, Piercing) {
  // B in the plane y = 1 meets z = 0 along (1,1,0)-(1.5,1,0), inside A; A's edges miss B.
  check_all_variants(kA, {V(1, 1, -1), V(1, 1, 1), V(2, 1, 1)}, true, "B pierces A");
}

TEST(TriangleIntersect, PlanesCrossButTrianglesDisjoint) {
  // B ∩ {z = 0} is (3,3,0)-(5,5,0), where x + y >= 6 > 4.
  check_all_variants(kA, {V(3, 3, -1), V(3, 3, 1), V(5, 5, 0)}, false, "beside");
}

TEST(TriangleIntersect, Coplanar) {
  check_all_variants(kA, {V(1, 1, 0), V(5, 1, 0), V(1, 5, 0)}, true, "overlapping");
  check_all_variants(kA, {V(1, 1, 0), V(2, 1, 0), V(1, 2, 0)}, true, "B inside A (and A around B)");
  // Hexagram: no vertex of one lies in the other, only edges cross.
  check_all_variants({V(0, 0, 0), V(6, 0, 0), V(3, 6, 0)}, {V(0, 4, 0), V(6, 4, 0), V(3, -2, 0)},
                     true, "hexagram");
  check_all_variants(kA, {V(3, 3, 0), V(6, 3, 0), V(3, 6, 0)}, false, "disjoint");
  // Bounding boxes overlap, but x + y >= 5 on B.
  check_all_variants(kA, {V(3, 2, 0), V(4, 4, 0), V(2, 3, 0)}, false, "disjoint, boxes overlap");
  check_all_variants(kA, {V(2, 2, 0), V(5, 2, 0), V(2, 5, 0)}, true, "vertex on edge");
  check_all_variants(kA, {V(1, 0, 0), V(3, 0, 0), V(2, -3, 0)}, true, "edge overlap");
  check_all_variants(kA, {V(0, 0, 0), V(4, 0, 0), V(2, -3, 0)}, true, "shared edge");
  check_all_variants(kA, {V(0, 0, 0), V(-3, 0, 0), V(0, -3, 0)}, true, "shared vertex");
  check_all_variants(kA, {V(5, 0, 0), V(7, 0, 0), V(6, -3, 0)}, false, "collinear edges apart");
}

TEST(TriangleIntersect, EdgeOnEdgeTouching) {
  // B lies in x + y + z = 2; B ∩ {z = 0} is (2,0,0)-(2.5,-0.5,0), which meets A only at (2,0,0),
  // an interior point of A's edge (0,0,0)-(4,0,0) and of B's edge (2,-1,1)-(2,1,-1).
  check_all_variants(kA, {V(2, -1, 1), V(2, 1, -1), V(3, -2, 1)}, true, "crossing edges");
}

TEST(TriangleIntersect, VertexTouching) {
  // z >= 0 on B with equality only at the vertex on A.
  check_all_variants(kA, {V(1, 1, 0), V(0, 0, 3), V(3, 0, 3)}, true, "vertex on face");
  check_all_variants(kA, {V(0, 0, 0), V(-2, 0, 1), V(0, -2, 1)}, true, "vertex on vertex");
  check_all_variants(kA, {V(2, 0, 0), V(2, -2, 2), V(3, -2, 1)}, true, "vertex on edge");
  check_all_variants(kA, {V(0, 0, 0), V(4, 0, 0), V(2, -3, 2)}, true, "shared edge, folded");
}

TEST(TriangleIntersect, EdgeInPlaneOfOther) {
  check_all_variants(kA, {V(1, 1, 0), V(2, 1, 0), V(1, 1, 3)}, true, "edge inside A");
  check_all_variants(kA, {V(5, 5, 0), V(6, 5, 0), V(5, 5, 3)}, false, "edge in plane, outside");
  check_all_variants(kA, {V(4, 0, 0), V(6, 0, 0), V(5, 0, 3)}, true, "collinear, touching");
  check_all_variants(kA, {V(5, 0, 0), V(6, 0, 0), V(5, 0, 3)}, false, "collinear, apart");
  // The edge (5,1,0)-(3,-1,0) passes through A's vertex (4,0,0) and nowhere else in A.
  check_all_variants(kA, {V(5, 1, 0), V(3, -1, 0), V(4, 0, 5)}, true, "edge through vertex");
  // The edge (1,-1,0)-(-1,1,0) lies on x + y = 0, which meets A only at its vertex (0,0,0);
  // shifted to x + y = -0.5 it misses A.
  check_all_variants(kA, {V(1, -1, 0), V(-1, 1, 0), V(0, 0, -2)}, true, "edge across corner");
  check_all_variants(kA, {V(1, -1.5, 0), V(-1, 0.5, 0), V(0, 0, -2)}, false, "edge near corner");
}

TEST(TriangleIntersect, NearlyParallel) {
  // B crosses z = 0 along (1.5,1,0)-(1.5,1.5,0), inside A.
  check_all_variants(kA, {V(1, 1, 1e-6), V(2, 1, -1e-6), V(1, 2, 1e-6)}, true, "crossing");
  check_all_variants(kA, {V(1, 1, 1e-6), V(2, 1, 1e-7), V(1, 2, 1e-6)}, false, "hovering");
  // B crosses z = 0 along x = 4, y in [3, 4]: outside A.
  check_all_variants(kA, {V(3, 3, 1e-6), V(5, 3, -1e-6), V(3, 5, 1e-6)}, false, "crossing beside");
  // Large, almost parallel triangles crossing in a long line.
  check_all_variants({V(-10, -10, 0), V(30, -10, 0), V(-10, 30, 0)},
                     {V(-10, -10, 1e-9), V(30, -10, -1e-9), V(-10, 30, 1e-9)}, true, "large");
}

TEST(TriangleIntersect, VeryThin) {
  // Sliver A: x in [0, 10], 0 <= y <= 1e-6 (1 - x / 10). At y = 2e-7 it reaches x = 8.
  const Tri sliver = {V(0, 0, 0), V(10, 0, 0), V(0, 1e-6, 0)};
  // B in the plane y = 2e-7 crosses z = 0 along x in [5, 5 + 5e-7].
  check_all_variants(sliver, {V(5, 2e-7, -1), V(5, 2e-7, 1), V(5 + 1e-6, 2e-7, 1)}, true,
                     "needle through sliver");
  // At y = 6e-7 the sliver only reaches x = 4.
  check_all_variants(sliver, {V(5, 6e-7, -1), V(5, 6e-7, 1), V(5 + 1e-6, 6e-7, 1)}, false,
                     "needle beside sliver");
  check_all_variants(sliver, {V(5, -1, 0), V(5 + 1e-6, -1, 0), V(5, 1, 0)}, true,
                     "coplanar slivers crossing");
  check_all_variants(sliver, {V(10.5, -1, 0), V(10.5 + 1e-6, -1, 0), V(10.5, 1, 0)}, false,
                     "coplanar slivers apart");
}

// Touching configurations moved by 1e-9 away from each other separate (and then lie between
// 0.3e-9 and 3e-9 apart), moved into each other they intersect.
TEST(TriangleIntersect, TouchingFlipsUnderTinyTranslation) {
  struct Case {
    const char* name;
    Tri b;
    Vec3 away;
    Vec3 into;
  };
  const Case cases[] = {
      {"vertex on face", {V(1, 1, 0), V(0, 0, 3), V(3, 0, 3)}, V(0, 0, 1), V(0, 0, -1)},
      // into: the apex moves to (2e-9, 2e-9, -1e-9) and B then crosses A near its corner.
      {"vertex on vertex", {V(0, 0, 0), V(-2, 0, 1), V(0, -2, 1)}, V(0, 0, 1), V(2, 2, -1)},
      {"edge on edge", {V(2, -1, 1), V(2, 1, -1), V(3, -2, 1)}, V(0, -1, 0), V(0, 1, 0)},
      {"coplanar vertex on edge", {V(2, 2, 0), V(5, 2, 0), V(2, 5, 0)}, V(1, 1, 0), V(-1, -1, 0)},
      {"folded shared edge", {V(0, 0, 0), V(4, 0, 0), V(2, -3, 2)}, V(0, -1, 0), V(0, 1, 0)},
      {"edge in plane", {V(1, 1, 0), V(2, 1, 0), V(1, 1, 3)}, V(0, 0, 1), V(0, 0, -1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    check_all_variants(kA, c.b, true, "touching");
    const Tri away = translated(c.b, 1e-9 * c.away);
    const Tri into = translated(c.b, 1e-9 * c.into);
    check_all_variants(kA, away, false, "moved apart");
    check_all_variants(kA, into, true, "moved into");
    const double d = distance(kA, away).distance;
    EXPECT_GT(d, 0.3e-9);
    EXPECT_LT(d, 3e-9);
    EXPECT_FALSE(within(kA, away, 0.0));
    EXPECT_FALSE(within(kA, away, 0.25e-9));
    EXPECT_FALSE(within(away, kA, 0.99 * d));
    EXPECT_TRUE(within(kA, away, 1.01 * d));
    EXPECT_TRUE(within(away, kA, 3e-9));
    double dw = -1;
    Vec3 p;
    ASSERT_TRUE(within(kA, away, 3e-9, &p, &dw));
    EXPECT_NEAR(dw, d, 1e-15);
    EXPECT_LE(point_tri_dist(p, kA), d);  // the midpoint of the closest points
    EXPECT_LE(point_tri_dist(p, away), d);
  }
}

// ---- exact lattice cross-check against an integer separating-axis test
// ---------------------------

using I3 = std::array<std::int64_t, 3>;
I3 isub(const I3& a, const I3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
I3 icross(const I3& a, const I3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::int64_t idot(const I3& a, const I3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Exact intersection test of closed non-degenerate lattice triangles: they are disjoint iff some
// axis strictly separates them, and the candidate axes are the facet normals of the Minkowski
// difference A - B: the two normals and the nine edge-edge cross products, plus the in-plane edge
// normals n x e when A - B is flat (parallel or coplanar triangles).
bool sat_intersect(const std::array<I3, 3>& a, const std::array<I3, 3>& b) {
  I3 ea[3], eb[3];
  for (int i = 0; i < 3; ++i) {
    ea[i] = isub(a[(i + 1) % 3], a[i]);
    eb[i] = isub(b[(i + 1) % 3], b[i]);
  }
  const I3 na = icross(ea[0], ea[1]);
  const I3 nb = icross(eb[0], eb[1]);
  std::vector<I3> axes = {na, nb};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) axes.push_back(icross(ea[i], eb[j]));
    axes.push_back(icross(na, ea[i]));
    axes.push_back(icross(nb, eb[i]));
  }
  for (const I3& ax : axes) {
    if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0) continue;
    std::int64_t amin = idot(ax, a[0]), amax = amin, bmin = idot(ax, b[0]), bmax = bmin;
    for (int i = 1; i < 3; ++i) {
      amin = std::min(amin, idot(ax, a[i]));
      amax = std::max(amax, idot(ax, a[i]));
      bmin = std::min(bmin, idot(ax, b[i]));
      bmax = std::max(bmax, idot(ax, b[i]));
    }
    if (amax < bmin || bmax < amin) return false;
  }
  return true;
}

// Small lattices are full of coplanar, collinear and touching configurations, exactly the cases
// where a tolerance-based test goes wrong. Also run on an exactly scaled and shifted copy (the
// coordinates 1024 + k * 2^-20 are still exact doubles).
TEST(TriangleIntersect, LatticeAgreesWithExactSeparatingAxisTest) {
  std::mt19937_64 rng(2024);
  int counts[2] = {0, 0};
  int coplanar = 0;
  for (const int range : {1, 2, 3}) {
    std::uniform_int_distribution<int> coord(-range, range);
    auto random_lattice_triangle = [&] {
      for (;;) {
        std::array<I3, 3> t;
        for (I3& v : t) v = {coord(rng), coord(rng), coord(rng)};
        const I3 n = icross(isub(t[1], t[0]), isub(t[2], t[0]));
        if (n[0] != 0 || n[1] != 0 || n[2] != 0) return t;
      }
    };
    auto to_tri = [](const std::array<I3, 3>& t, double s, double o) {
      Tri r;
      for (int i = 0; i < 3; ++i) {
        r[i] = V(o + s * double(t[i][0]), o + s * double(t[i][1]), o + s * double(t[i][2]));
      }
      return r;
    };
    for (int iter = 0; iter < 15000; ++iter) {
      const auto la = random_lattice_triangle();
      const auto lb = random_lattice_triangle();
      const bool expected = sat_intersect(la, lb);
      ++counts[expected ? 1 : 0];
      const I3 na = icross(isub(la[1], la[0]), isub(la[2], la[0]));
      if (idot(na, isub(lb[0], la[0])) == 0 && idot(na, isub(lb[1], la[0])) == 0 &&
          idot(na, isub(lb[2], la[0])) == 0) {
        ++coplanar;
      }
      for (const auto& [s, o] : {std::pair{1.0, 0.0}, std::pair{0x1p-20, 1024.0}}) {
        const Tri a = to_tri(la, s, o);
        const Tri b = to_tri(lb, s, o);
        const double tol = point_tolerance(a, b);
        // A random vertex order / orientation / argument order each time.
        const Tri oa = orderings(a)[iter % 6];
        const Tri ob = orderings(b)[(iter / 6) % 6];
        const bool swap = (iter / 36) % 2 != 0;
        const Tri& x = swap ? ob : oa;
        const Tri& y = swap ? oa : ob;
        Vec3 p;
        const bool r = intersect(x, y, &p);
        EXPECT_EQ(r, expected) << "A = " << str(x) << " B = " << str(y);
        if (r) {
          EXPECT_LE(point_tri_dist(p, x), tol) << "A = " << str(x) << " B = " << str(y);
          EXPECT_LE(point_tri_dist(p, y), tol) << "A = " << str(x) << " B = " << str(y);
        }
        EXPECT_EQ(within(x, y, 0.0), expected);
        EXPECT_EQ(distance(x, y).distance == 0, expected);
      }
      if (HasFailure()) return;
    }
  }
  // The sample must exercise both answers and many coplanar pairs.
  EXPECT_GT(counts[0], 5000);
  EXPECT_GT(counts[1], 5000);
  EXPECT_GT(coplanar, 200);
}

// Coplanar triangles with coordinates of no convenient form: both lie exactly in the plane
// z = x + y (x and y are rounded to a common dyadic grid so that x + y is exact; the products in
// the determinants still round). The reference is a 2-D separating-axis test in the (x, y)
// projection, used only when its verdict holds with a clear margin. A one-ulp lift of B off the
// plane must separate them (B then lies strictly above the plane of A) even if they share a vertex.
TEST(TriangleIntersect, CoplanarInexactCoordinates) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(-1, 1);
  double quantum = 1;
  auto on_plane = [&](double cx, double cy, double r) {
    Tri t;
    for (Vec3& v : t) {
      const double x = std::round((cx + r * u(rng)) / quantum) * quantum;
      const double y = std::round((cy + r * u(rng)) / quantum) * quantum;
      v = V(x, y, x + y);
      EXPECT_EQ(v.z() - x, y);
    }
    return t;
  };
  auto lift = [](const Tri& t) {
    Tri r = t;
    for (Vec3& v : r) v.z() = std::nextafter(v.z(), 1e300);
    return r;
  };
  // Margin of the 2-D separating-axis test over the six edge normals: positive = separated by
  // that much, negative = overlapping along every axis by at least that much.
  auto sat2d_margin = [](const Tri& a, const Tri& b) {
    double best = -std::numeric_limits<double>::infinity();
    for (const Tri* t : {&a, &b}) {
      for (int i = 0; i < 3; ++i) {
        const Vec3 e = (*t)[(i + 1) % 3] - (*t)[i];
        const double nx = -e.y(), ny = e.x(), len = std::hypot(nx, ny);
        double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
        for (const Vec3& v : a) {
          amin = std::min(amin, (nx * v.x() + ny * v.y()) / len);
          amax = std::max(amax, (nx * v.x() + ny * v.y()) / len);
        }
        for (const Vec3& v : b) {
          bmin = std::min(bmin, (nx * v.x() + ny * v.y()) / len);
          bmax = std::max(bmax, (nx * v.x() + ny * v.y()) / len);
        }
        best = std::max(best, std::max(bmin - amax, amin - bmax));
      }
    }
    return best;
  };
  int checked[2] = {0, 0};
  for (int iter = 0; iter < 3000; ++iter) {
    const double scale = std::pow(10.0, 4 * u(rng));
    quantum = std::ldexp(1.0, std::ilogb(scale) - 30);
    const Tri a = on_plane(3 * scale * u(rng), 3 * scale * u(rng), scale);
    Tri b = on_plane(a[0].x() + 1.5 * scale * u(rng), a[0].y() + 1.5 * scale * u(rng), scale);
    if (is_degenerate_triangle(a[0], a[1], a[2]) || is_degenerate_triangle(b[0], b[1], b[2]) ||
        (a[1] - a[0]).cross(a[2] - a[0]).norm() < 1e-3 * scale * scale ||
        (b[1] - b[0]).cross(b[2] - b[0]).norm() < 1e-3 * scale * scale) {
      continue;
    }
    const double m = sat2d_margin(a, b);
    if (std::abs(m) > 1e-6 * scale) {
      const bool expected = m < 0;
      ++checked[expected ? 1 : 0];
      Vec3 p;
      EXPECT_EQ(intersect(a, b, &p), expected) << str(a) << " | " << str(b);
      EXPECT_EQ(intersect(b, a), expected);
      if (expected) {
        EXPECT_LE(point_tri_dist(p, a), point_tolerance(a, b));
        EXPECT_LE(point_tri_dist(p, b), point_tolerance(a, b));
      }
    }
    // Share a vertex: touching, unless B is lifted off the plane by one ulp.
    b[0] = a[iter % 3];
    if (!is_degenerate_triangle(b[0], b[1], b[2])) {
      EXPECT_TRUE(intersect(a, b)) << str(a) << " | " << str(b);
      EXPECT_FALSE(intersect(a, lift(b))) << str(a) << " | " << str(lift(b));
      EXPECT_FALSE(intersect(lift(b), a));
      EXPECT_FALSE(within(a, lift(b), 0.0));
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(checked[0], 200);
  EXPECT_GT(checked[1], 200);
}

// Coplanar (z = 0) triangles touching at a vertex r of B that lies exactly on the line of A's
// edge pq (all three on the line y = 3x + 3/4, with x of mixed magnitudes and short mantissas so
// that y is exact while the 2-D orientation determinant rounds). A lies on one side of the line, B
// on the other: they touch iff r lies on the closed segment [p, q], which is decided by comparing
// x.
TEST(TriangleIntersect, CoplanarVertexExactlyOnEdgeLine) {
  std::mt19937_64 rng(606);
  std::uniform_int_distribution<int> mant(1, 1 << 20), ex(-30, 20);
  auto mixed = [&] { return std::ldexp(double(mant(rng)), ex(rng)); };
  auto on_line = [](double x) {
    const double y = 3 * x + 0.75;
    EXPECT_EQ(y - 3 * x, 0.75);
    return V(x, y, 0);
  };
  int naive_nonzero = 0;
  int counts[2] = {0, 0};
  for (int iter = 0; iter < 4000; ++iter) {
    double xs[3] = {-mixed(), mixed(), mixed() * (iter % 2 == 0 ? 1 : -1)};
    const Vec3 p = on_line(std::min(xs[0], xs[1])), q = on_line(std::max(xs[0], xs[1]));
    const Vec3 r = on_line(iter % 3 == 0 ? q.x() + mixed() : xs[2]);  // sometimes beyond q
    const double len = q.x() - p.x();
    const Tri a = {p, q, V(p.x() + 0.75 * len, p.y() + 0.25 * len, 0)};  // below the line
    const Tri b = {r, V(r.x() - 0.25 * len, r.y() + 0.25 * len, 0),
                   V(r.x() + 0.25 * len, r.y() + 1.5 * len, 0)};  // above the line
    if (r.x() == p.x() || r.x() == q.x()) continue;
    const bool expected = p.x() <= r.x() && r.x() <= q.x();
    ++counts[expected ? 1 : 0];
    const double naive = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    if (naive != 0) ++naive_nonzero;
    Vec3 pt;
    EXPECT_EQ(intersect(a, b, &pt), expected) << str(a) << " | " << str(b);
    EXPECT_EQ(intersect(b, a), expected) << str(a) << " | " << str(b);
    EXPECT_EQ(intersect(orderings(a)[4], orderings(b)[3]), expected);
    if (expected) {
      EXPECT_LE((pt - r).norm(), point_tolerance(a, b));
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(counts[0], 500);
  EXPECT_GT(counts[1], 500);
  EXPECT_GT(naive_nonzero, 100);  // the naive determinant really misjudges some of these
}

// ---- point / segment distances ------------------------------------------------------------------

TEST(TrianglePointDistance, AllSevenRegions) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  struct Case {
    const char* region;
    Vec3 p;
    Vec3 closest;
  };
  const Case cases[] = {
      {"face", V(0.25, 0.25, 2), V(0.25, 0.25, 0)},
      {"face (below)", V(0.1, 0.7, -3), V(0.1, 0.7, 0)},
      {"vertex a", V(-1, -1, 1), a},
      {"vertex b", V(2, -1, 0), b},
      {"vertex c", V(-1, 2, 0), c},
      {"edge ab", V(0.5, -1, 1), V(0.5, 0, 0)},
      {"edge ac", V(-1, 0.5, 0), V(0, 0.5, 0)},
      {"edge bc", V(1, 1, 0), V(0.5, 0.5, 0)},
      {"edge bc (above)", V(1, 1, 5), V(0.5, 0.5, 0)},
      {"on the face", V(0.2, 0.3, 0), V(0.2, 0.3, 0)},
      {"on edge bc", V(0.5, 0.5, 0), V(0.5, 0.5, 0)},
      {"on vertex b", b, b},
  };
  for (const Case& cs : cases) {
    SCOPED_TRACE(cs.region);
    const double expected = (cs.p - cs.closest).squaredNorm();
    for (const Tri& t : orderings({a, b, c})) {
      Vec3 cl;
      EXPECT_NEAR(point_triangle_distance_squared(cs.p, t[0], t[1], t[2], &cl), expected, 1e-14);
      EXPECT_NEAR((cl - cs.closest).norm(), 0.0, 1e-14);
      EXPECT_NEAR(point_triangle_distance_squared(cs.p, t[0], t[1], t[2]), expected, 1e-14);
    }
  }
}

// Needles: two far vertices and a third 2^-k off their edge, at scales 1e-6 .. 1e6. Points that
// lie on the triangle (its vertices, points of its edges) are at distance ~0, and a point lifted
// off the long edge's midpoint perpendicular to the triangle's plane is at its lift height, in
// every vertex order. The normal used to be taken at the needle's sharp tip, where the cross
// product's rounding error is largest (3.5e-8 for a vertex at scale 10, 0.37 at 1e6); slivers now
// also compare with their edges.
TEST(TrianglePointDistance, NeedlesAreAccurate) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const double scale : {1e-6, 1e-3, 1.0, 10.0, 1e3, 1e6}) {
    for (int k = 10; k <= 40; k += 6) {
      for (int trial = 0; trial < 20; ++trial) {
        const Vec3 a = scale * V(unit(rng), unit(rng), unit(rng));
        const Vec3 axis = V(unit(rng), unit(rng), unit(rng)).normalized();
        const Vec3 b = a + scale * axis;
        Vec3 side = axis.cross(V(unit(rng), unit(rng), unit(rng))).normalized();
        const Vec3 c = a + (0.5 + 0.4 * unit(rng)) * scale * axis + std::ldexp(scale, -k) * side;
        const Vec3 normal = (b - a).cross(c - a).normalized();
        const double tol = 1e-13 * scale;  // distances are compared, not squared distances
        // Off the plane the answer depends on the plane's tilt, whose rounding error grows as
        // the sliver thins (2^-k): 5e-10 relative at k = 28, 1e-7 at k = 40.
        const double lift_tol = (k <= 28 ? 1e-9 : 1e-6) * scale;
        const Vec3 mid = 0.5 * (a + b);
        const double lift = 0.25 * scale;
        for (const Tri& t : orderings({a, b, c})) {
          for (const Vec3& p : {a, b, c, Vec3(0.5 * (a + c)), Vec3(0.5 * (b + c)), mid}) {
            EXPECT_LE(std::sqrt(point_triangle_distance_squared(p, t[0], t[1], t[2])), tol)
                << "scale " << scale << " k " << k;
          }
          const Vec3 p = mid + lift * normal;
          EXPECT_NEAR(std::sqrt(point_triangle_distance_squared(p, t[0], t[1], t[2])), lift,
                      lift_tol)
              << "scale " << scale << " k " << k;
        }
      }
    }
  }
}

// Certificate: c is the closest point of the triangle to p iff c lies in the triangle and
// (p - c)·(v - c) <= 0 for the three vertices v. Also compared with dense sampling.
TEST(TrianglePointDistance, RandomAgainstCertificateAndSampling) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int iter = 0; iter < 400; ++iter) {
    const Tri t = {V(u(rng), u(rng), u(rng)), V(u(rng), u(rng), u(rng)), V(u(rng), u(rng), u(rng))};
    if ((t[1] - t[0]).cross(t[2] - t[0]).norm() < 1e-3) continue;
    const Vec3 p = 2 * V(u(rng), u(rng), u(rng));
    Vec3 c;
    const double d2 = point_triangle_distance_squared(p, t[0], t[1], t[2], &c);
    EXPECT_NEAR(d2, (p - c).squaredNorm(), 1e-14);
    // Barycentric coordinates of c.
    Eigen::Matrix<double, 3, 2> m;
    m << t[1] - t[0], t[2] - t[0];
    const Eigen::Vector2d bc = m.colPivHouseholderQr().solve(c - t[0]);
    EXPECT_LT((m * bc + t[0] - c).norm(), 1e-12);  // in the plane
    EXPECT_GE(bc[0], -1e-12);
    EXPECT_GE(bc[1], -1e-12);
    EXPECT_LE(bc[0] + bc[1], 1 + 1e-12);
    for (const Vec3& v : t) EXPECT_LE((p - c).dot(v - c), 1e-12);
    // Dense sampling: the sampled minimum is not below the exact one, and not above it by more
    // than the grid spacing.
    const int n = 100;
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 x = t[0] + (double(i) / n) * (t[1] - t[0]) + (double(j) / n) * (t[2] - t[0]);
        sampled = std::min(sampled, (p - x).norm());
      }
    }
    EXPECT_LE(std::sqrt(d2), sampled + 1e-12);
    EXPECT_GE(std::sqrt(d2), sampled - longest_edge(t) / n - 1e-12);
    if (HasFailure()) return;
  }
}

TEST(TriangleSegmentDistance, HandBuilt) {
  struct Case {
    const char* name;
    Vec3 p0, p1, q0, q1;
    double d2;
  };
  const Case cases[] = {
      {"crossing", V(-1, 0, 0), V(1, 0, 0), V(0, -1, 0), V(0, 1, 0), 0},
      {"skew", V(-1, 0, 0), V(1, 0, 0), V(0, -1, 2), V(0, 1, 2), 4},
      {"parallel, overlapping", V(0, 0, 0), V(2, 0, 0), V(1, 1, 0), V(3, 1, 0), 1},
      {"parallel, opposite directions", V(0, 0, 0), V(2, 0, 0), V(3, 1, 0), V(1, 1, 0), 1},
      {"collinear, apart", V(0, 0, 0), V(1, 0, 0), V(3, 0, 0), V(5, 0, 0), 4},
      {"collinear, overlapping", V(0, 0, 0), V(2, 0, 0), V(1, 0, 0), V(5, 0, 0), 0},
      {"parallel, offset", V(0, 0, 0), V(1, 0, 0), V(2, 1, 0), V(3, 1, 0), 2},
      {"T, clamped on one", V(0, 0, 0), V(1, 0, 0), V(2, -1, 0), V(2, 1, 0), 1},
      {"clamped on both", V(0, 0, 0), V(1, 0, 0), V(2, 1, 1), V(3, 2, 1), 3},
      {"point to point", V(1, 2, 3), V(1, 2, 3), V(4, 6, 3), V(4, 6, 3), 25},
      {"point to segment", V(0, 5, 0), V(0, 5, 0), V(-1, 0, 0), V(1, 0, 0), 25},
      {"point beyond segment end", V(3, 4, 0), V(3, 4, 0), V(-1, 0, 0), V(0, 0, 0), 25},
      {"touching at end points", V(0, 0, 0), V(1, 1, 1), V(1, 1, 1), V(2, 0, 5), 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    // All four end point orders and both argument orders.
    for (int k = 0; k < 8; ++k) {
      Vec3 p0 = c.p0, p1 = c.p1, q0 = c.q0, q1 = c.q1;
      if ((k & 1) != 0) std::swap(p0, p1);
      if ((k & 2) != 0) std::swap(q0, q1);
      if ((k & 4) != 0) {
        std::swap(p0, q0);
        std::swap(p1, q1);
      }
      Vec3 cp, cq;
      const double d2 = segment_segment_distance_squared(p0, p1, q0, q1, &cp, &cq);
      EXPECT_NEAR(d2, c.d2, 1e-14) << k;
      EXPECT_NEAR((cp - cq).squaredNorm(), c.d2, 1e-14) << k;
      // cp on [p0, p1], cq on [q0, q1].
      EXPECT_NEAR((cp - p0).norm() + (cp - p1).norm(), (p1 - p0).norm(), 1e-12) << k;
      EXPECT_NEAR((cq - q0).norm() + (cq - q1).norm(), (q1 - q0).norm(), 1e-12) << k;
      EXPECT_NEAR(segment_segment_distance_squared(p0, p1, q0, q1), c.d2, 1e-14) << k;
    }
  }
  Vec3 cp, cq;
  segment_segment_distance_squared(V(0, 0, 0), V(1, 0, 0), V(2, -1, 0), V(2, 1, 0), &cp, &cq);
  EXPECT_NEAR((cp - V(1, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((cq - V(2, 0, 0)).norm(), 0, 1e-15);
  segment_segment_distance_squared(V(0, 5, 0), V(0, 5, 0), V(-1, 0, 0), V(1, 0, 0), &cp, &cq);
  EXPECT_NEAR((cq - V(0, 0, 0)).norm(), 0, 1e-15);
  EXPECT_EQ(cp, V(0, 5, 0));
}

TEST(TriangleSegmentDistance, RandomAgainstSampling) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int iter = 0; iter < 300; ++iter) {
    const Vec3 p0 = V(u(rng), u(rng), u(rng));
    const Vec3 p1 = V(u(rng), u(rng), u(rng));
    Vec3 q0 = V(u(rng), u(rng), u(rng));
    Vec3 q1 = V(u(rng), u(rng), u(rng));
    if (iter % 3 == 1) q1 = q0 + (p1 - p0) * (0.5 + u(rng)) + 1e-9 * V(u(rng), u(rng), u(rng));
    if (iter % 3 == 2) q1 = q0 + (p1 - p0) * u(rng);  // exactly parallel (up to rounding)
    Vec3 cp, cq;
    const double d = std::sqrt(segment_segment_distance_squared(p0, p1, q0, q1, &cp, &cq));
    EXPECT_NEAR((cp - cq).norm(), d, 1e-12);
    const int n = 300;
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      const Vec3 x = p0 + (double(i) / n) * (p1 - p0);
      for (int j = 0; j <= n; ++j) {
        sampled = std::min(sampled, (x - (q0 + (double(j) / n) * (q1 - q0))).norm());
      }
    }
    const double grid = ((p1 - p0).norm() + (q1 - q0).norm()) / (2 * n);
    EXPECT_LE(d, sampled + 1e-12) << iter;
    EXPECT_GE(d, sampled - grid - 1e-12) << iter;
    if (HasFailure()) return;
  }
}

// ---- triangle distance and triangles_within ----------------------------------------------------

// A random triangle of about the given size around a random center in [-spread, spread]^3.
Tri random_triangle(std::mt19937_64& rng, double size, double spread = 1) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (;;) {
    const Vec3 c = spread * V(u(rng), u(rng), u(rng));
    Tri t = {c + size * V(u(rng), u(rng), u(rng)), c + size * V(u(rng), u(rng), u(rng)),
             c + size * V(u(rng), u(rng), u(rng))};
    if ((t[1] - t[0]).cross(t[2] - t[0]).norm() > 1e-2 * size * size) return t;
  }
}

// For disjoint A and B with closest points pa, pb at distance d, the slab between the planes
// through pa and pb orthogonal to u = (pb - pa) / d separates them: u·a <= u·pa for A's vertices
// and u·b >= u·pb for B's. With pa in A and pb in B this certifies that d is the exact distance.
//
// The slab test needs slack: the closest points are only determined to about eps * size /
// sin^2(angle between the edges) along the edges (an inherent conditioning of the problem), which
// turns the direction u by that over the distance; `slack` covers angles down to ~0.01 rad.
double certificate_slack(double size, double distance) {
  return 1e-12 * size + 1e-11 * size * size / distance;
}

void expect_distance_certificate(const Tri& a, const Tri& b, const TriangleDistance& td) {
  const double size =
      std::max({longest_edge(a), longest_edge(b), max_abs_coord(a), max_abs_coord(b)});
  const double tol = 1e-12 * size;
  EXPECT_LE(point_tri_dist(td.pa, a), tol);
  EXPECT_LE(point_tri_dist(td.pb, b), tol);
  EXPECT_NEAR((td.pb - td.pa).norm(), td.distance, tol);
  ASSERT_GT(td.distance, 0);
  const double slack = certificate_slack(size, td.distance);
  const Vec3 u = (td.pb - td.pa) / td.distance;
  for (const Vec3& v : a) EXPECT_LE(u.dot(v - td.pa), slack);
  for (const Vec3& v : b) EXPECT_GE(u.dot(v - td.pb), -slack);
}

TEST(TriangleDistanceTest, RandomAgainstDenseSamplingAndCertificate) {
  std::mt19937_64 rng(31337);
  const int n = 24;
  int intersecting = 0, disjoint = 0;
  for (int iter = 0; iter < 250; ++iter) {
    const Tri a = random_triangle(rng, 0.7, 0.5);
    const Tri b = random_triangle(rng, iter % 2 == 0 ? 0.7 : 0.2, 0.5);
    SCOPED_TRACE("A = " + str(a) + " B = " + str(b));
    const TriangleDistance td = distance(a, b);
    if (td.distance == 0) {
      ++intersecting;
      EXPECT_TRUE(intersect(a, b));
      EXPECT_EQ(td.pa, td.pb);
      EXPECT_LE(point_tri_dist(td.pa, a), 1e-12);
      EXPECT_LE(point_tri_dist(td.pa, b), 1e-12);
    } else {
      ++disjoint;
      EXPECT_FALSE(intersect(a, b));
      expect_distance_certificate(a, b, td);
    }
    // Dense barycentric sampling of both triangles.
    std::vector<Vec3> sa, sb;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        sa.push_back(a[0] + s * (a[1] - a[0]) + t * (a[2] - a[0]));
        sb.push_back(b[0] + s * (b[1] - b[0]) + t * (b[2] - b[0]));
      }
    }
    double sampled2 = std::numeric_limits<double>::infinity();
    for (const Vec3& x : sa) {
      for (const Vec3& y : sb) sampled2 = std::min(sampled2, (x - y).squaredNorm());
    }
    const double sampled = std::sqrt(sampled2);
    // Every point of a triangle is within (longest edge / n) of a grid point.
    const double grid = (longest_edge(a) + longest_edge(b)) / n;
    EXPECT_LE(td.distance, sampled + 1e-12);
    EXPECT_GE(td.distance, sampled - grid - 1e-12);
    // Symmetry.
    const TriangleDistance ts = distance(b, a);
    EXPECT_NEAR(ts.distance, td.distance, 1e-12);
    const TriangleDistance tp = distance(orderings(a)[4], orderings(b)[2]);
    EXPECT_NEAR(tp.distance, td.distance, 1e-12);
    if (HasFailure()) return;
  }
  EXPECT_GT(intersecting, 20);
  EXPECT_GT(disjoint, 20);
}

// Random near-contact configurations: the intersection verdict is checked through its
// certificates (a common point when true, a separating slab when false).
TEST(TriangleDistanceTest, IntersectVerdictCertifiedOnRandomPairs) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(-1, 1);
  int verdicts[2] = {0, 0};
  for (int iter = 0; iter < 20000; ++iter) {
    const double size = std::pow(10.0, 3 * u(rng));
    Tri a = random_triangle(rng, 1.0);
    Tri b = random_triangle(rng, 1.0);
    if (iter % 4 == 1) b[0] = a[0] + 1e-7 * V(u(rng), u(rng), u(rng));  // near vertex contact
    if (iter % 4 == 2) b[0] = a[1] + 0.5 * (a[2] - a[1]) + 1e-9 * V(u(rng), u(rng), u(rng));
    for (Vec3& v : a) v *= size;
    for (Vec3& v : b) v *= size;
    if (is_degenerate_triangle(b[0], b[1], b[2])) continue;
    Vec3 p;
    const bool r = intersect(a, b, &p);
    ++verdicts[r ? 1 : 0];
    const double tol = point_tolerance(a, b);
    if (r) {
      EXPECT_LE(point_tri_dist(p, a), tol) << str(a) << " | " << str(b);
      EXPECT_LE(point_tri_dist(p, b), tol) << str(a) << " | " << str(b);
    } else {
      SCOPED_TRACE(str(a) + " | " + str(b));
      expect_distance_certificate(a, b, distance(a, b));
    }
    EXPECT_EQ(within(a, b, 0.0), r);
    if (HasFailure()) return;
  }
  EXPECT_GT(verdicts[0], 2000);
  EXPECT_GT(verdicts[1], 2000);
}

TEST(TriangleWithin, MonotoneAndAgreesWithDistance) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0, 1);
  const double deltas[] = {0.0, 1e-9, 1e-4, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2, 2.0, 5.0};
  int true_count = 0, false_count = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    const Tri a = random_triangle(rng, 0.4);
    const Tri b = random_triangle(rng, iter % 3 == 0 ? 0.05 : 0.4);
    const TriangleDistance td = distance(a, b);
    const bool inter = intersect(a, b);
    bool previous = false;
    for (const double delta : deltas) {
      Vec3 p;
      double d = -1;
      const bool r = within(a, b, delta, &p, &d);
      EXPECT_EQ(r, inter || td.distance <= delta) << "delta " << delta << " dist " << td.distance;
      EXPECT_EQ(within(b, a, delta), r);
      EXPECT_EQ(within(orderings(a)[3], orderings(b)[1], delta), r);
      EXPECT_TRUE(r || !previous) << "not monotone at delta " << delta;
      previous = r;
      (r ? true_count : false_count)++;
      if (r) {
        EXPECT_NEAR(d, td.distance, 1e-12);
        if (inter) {
          EXPECT_LE(point_tri_dist(p, a), 1e-12);
          EXPECT_LE(point_tri_dist(p, b), 1e-12);
        } else {
          EXPECT_LE((p - (td.pa + td.pb) / 2).norm(), 1e-12);
        }
      }
    }
    // Just around the distance itself.
    if (td.distance > 1e-6) {
      EXPECT_TRUE(within(a, b, td.distance * (1 + 1e-9)));
      EXPECT_FALSE(within(a, b, td.distance * (1 - 1e-9)));
    }
    if (HasFailure()) return;
  }
  EXPECT_GT(true_count, 5000);
  EXPECT_GT(false_count, 5000);
}

// The plane rejection of triangles_within must stay conservative: parallel triangles exactly h
// apart are within any delta >= h, and triangles only slightly farther are not.
TEST(TriangleWithin, ParallelPlanesAtThreshold) {
  for (const double h : {1e-6, 0.1, 1.0, 3.0}) {
    const Tri b = translated(kA, V(1, 1, h));
    EXPECT_TRUE(within(kA, b, h));  // h is exact here: distance computed as h exactly
    EXPECT_TRUE(within(b, kA, h * (1 + 1e-12)));
    EXPECT_FALSE(within(kA, b, h * (1 - 1e-9)));
    EXPECT_FALSE(within(b, kA, h * (1 - 1e-9)));
    double d = -1;
    ASSERT_TRUE(within(kA, b, 2 * h, nullptr, &d));
    EXPECT_DOUBLE_EQ(d, h);
  }
  // Tilted: B's nearest vertex (1,1,1) is at distance 1 from A; the plane test sees the far
  // vertices at larger heights.
  const Tri b = {V(1, 1, 1), V(2, 1, 3), V(1, 2, 2)};
  EXPECT_TRUE(within(kA, b, 1.0));
  EXPECT_FALSE(within(kA, b, 0.999999));
  EXPECT_TRUE(within(b, kA, 1.0));
  EXPECT_FALSE(within(b, kA, 0.999999));
}

}  // namespace
}  // namespace antcd::geometry
