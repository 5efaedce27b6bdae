// Geometric robustness: antcd's triangle–triangle intersection against an exact-arithmetic
// reference, CGAL::do_intersect on Exact_predicates_exact_constructions_kernel::Triangle_3.
//
// The configurations are the hard ones for floating point: touching faces, shared edges and
// vertices, a vertex or an edge lying exactly on the other triangle, coplanar overlaps, nearly
// parallel planes and very thin (needle) triangles. They are built from integer and dyadic
// coordinates so that the touching cases are exact in double, then moved by exact motions (signed
// axis permutations, dyadic offsets) and scaled by powers of two from 2^-20 (~1e-6) to 2^20
// (~1e6). Variants that are NOT exact (decimal scales 1e-6 and 1e6, a few ulps of perturbation,
// arbitrary rotations) are also checked: whatever the rounded doubles are, the reference decides
// on them, and antcd promises the exact answer for the given doubles (geometry.hpp).
//
// Checked per pair: triangles_intersect in both argument orders and under vertex permutations,
// triangles_within at delta 0, triangle_distance, and that the reported common point lies on both
// triangles up to rounding. Per group of pairs: the Model-level collide() at delta 0 (boolean and
// all contacts, also under exact poses) against the reference's pair set.
#include <antcd/collide.hpp>
#include <antcd/geometry.hpp>

#include <CGAL/Distance_3/Point_3_Triangle_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Intersections_3/Triangle_3_Triangle_3.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace antcd {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Tri = std::array<Vec3, 3>;

K::Point_3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
K::Triangle_3 to_cgal(const Tri& t) { return {to_cgal(t[0]), to_cgal(t[1]), to_cgal(t[2])}; }

bool exactly_degenerate(const Tri& t) {
  return CGAL::collinear(to_cgal(t[0]), to_cgal(t[1]), to_cgal(t[2]));
}

bool reference_intersect(const Tri& a, const Tri& b) {
  return CGAL::do_intersect(to_cgal(a), to_cgal(b));
}

std::string describe(const Tri& t) {
  std::ostringstream out;
  out << std::hexfloat;
  for (const Vec3& v : t) out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ") ";
  return out.str();
}

struct Config {
  Tri a;
  Tri b;
  const char* kind;
};

// ---- generators of exactly representable configurations ---------------------------------------

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  std::mt19937_64& rng() { return rng_; }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool coin() { return integer(0, 1) == 1; }
  // Integer coordinates in [lo, hi] (drawn in x, y, z order, so the cases do not depend on the
  // compiler's order of evaluation of arguments).
  Vec3 lattice(int lo, int hi) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = integer(lo, hi);
    return v;
  }

  // A non-degenerate lattice triangle with coordinates in [lo, hi].
  Tri lattice_triangle(int lo, int hi) {
    for (;;) {
      const Tri t{lattice(lo, hi), lattice(lo, hi), lattice(lo, hi)};
      if (!exactly_degenerate(t)) return t;
    }
  }

  // (w0 t0 + w1 t1 + w2 t2) / 8 with integer weights summing to 8: a dyadic point of t's plane,
  // inside, on an edge, on a vertex or outside depending on the weights' signs.
  Vec3 plane_point(const Tri& t, int lo, int hi) {
    const int w0 = integer(lo, hi);
    const int w1 = integer(lo, hi);
    const int w2 = 8 - w0 - w1;
    return (w0 * t[0] + w1 * t[1] + w2 * t[2]) / 8.0;
  }
  // A point of t's closed boundary or interior.
  Vec3 point_on(const Tri& t) {
    switch (integer(0, 3)) {
      case 0:  // a vertex
        return t[static_cast<std::size_t>(integer(0, 2))];
      case 1: {  // on an edge
        const auto i = static_cast<std::size_t>(integer(0, 2));
        const int w = integer(0, 8);
        return (w * t[i] + (8 - w) * t[(i + 1) % 3]) / 8.0;
      }
      default:  // inside (or on the boundary when a weight is 0)
        return plane_point(t, 0, 4);
    }
  }

  Config make(int kind) {
    switch (kind) {
      case 0: {  // small lattice: many accidental touches, shared vertices, coplanar pairs
        return {lattice_triangle(0, 2), lattice_triangle(0, 2), "lattice"};
      }
      case 1: {  // shared vertex
        const Tri a = lattice_triangle(-3, 3);
        return {a,
                {a[static_cast<std::size_t>(integer(0, 2))], lattice(-3, 3), lattice(-3, 3)},
                "shared-vertex"};
      }
      case 2: {  // shared edge (folded, coplanar on either side, or crossing)
        const Tri a = lattice_triangle(-3, 3);
        const auto i = static_cast<std::size_t>(integer(0, 2));
        const std::size_t j = (i + 1) % 3;
        Vec3 third = lattice(-3, 3);
        if (integer(0, 3) == 0) third = plane_point(a, -8, 16);  // coplanar fold
        return {a, coin() ? Tri{a[i], a[j], third} : Tri{third, a[j], a[i]}, "shared-edge"};
      }
      case 3: {  // a vertex of b on a (or on a's plane), b on one side or across
        const Tri a = lattice_triangle(-3, 3);
        const Vec3 p = coin() ? point_on(a) : plane_point(a, -4, 12);
        const Vec3 n = (a[1] - a[0]).cross(a[2] - a[0]);
        Vec3 q = lattice(-3, 3);
        Vec3 r = lattice(-3, 3);
        if (coin()) {  // both other vertices strictly on one side: touching only at p
          const double sign = coin() ? 1.0 : -1.0;
          q = p + sign * (n + lattice(-2, 2) / 4.0);  // n . (n + d/4) > 0: |n| >= 1 > |d|/4
          r = p + sign * (n + lattice(-2, 2) / 4.0);
        }
        return {a, {p, q, r}, "vertex-on-face"};
      }
      case 4: {  // an edge of b in a's plane: along a face, crossing an edge, or just outside
        const Tri a = lattice_triangle(-3, 3);
        const Vec3 p = coin() ? point_on(a) : plane_point(a, -4, 12);
        const Vec3 q = coin() ? point_on(a) : plane_point(a, -4, 12);
        const Vec3 n = (a[1] - a[0]).cross(a[2] - a[0]);
        const double side = coin() ? 1.0 : -1.0;
        const Vec3 r = p + side * n + lattice(-1, 1);
        return {a, {p, q, r}, "edge-on-face"};
      }
      case 5: {  // coplanar overlap in a tilted lattice plane
        const Vec3 o = lattice(-2, 2);
        Vec3 u, v;
        do {
          u = lattice(-2, 2);
          v = lattice(-2, 2);
        } while (u.cross(v).isZero());
        auto pt = [&] {
          const int i = integer(-4, 4);
          const int j = integer(-4, 4);
          return o + i / 2.0 * u + j / 2.0 * v;
        };
        Tri a, b;
        do a = {pt(), pt(), pt()};
        while (exactly_degenerate(a));
        do b = {pt(), pt(), pt()};
        while (exactly_degenerate(b));
        return {a, b, "coplanar"};
      }
      case 6: {  // nearly parallel: a coplanar pair, then b (or one vertex of b) lifted by 2^-k n
        Config c = make(5);
        const Vec3 n = (c.a[1] - c.a[0]).cross(c.a[2] - c.a[0]);
        const double sign = coin() ? 1.0 : -1.0;
        const double lift = std::ldexp(sign, -integer(10, 40));
        if (coin()) {
          for (Vec3& v : c.b) v += lift * n;
        } else {
          c.b[static_cast<std::size_t>(integer(0, 2))] += lift * n;
        }
        c.kind = "nearly-parallel";
        return c;
      }
      default: {  // thin triangles: a needle with apex 2^-k off its long edge
        const Vec3 p = lattice(-16, 16);
        Vec3 q;
        do q = lattice(-16, 16);
        while (q == p);
        Vec3 e;
        do e = lattice(-1, 1);
        while ((q - p).cross(e).isZero());
        const Vec3 apex = (p + q) / 2.0 + std::ldexp(1.0, -integer(8, 28)) * e;
        const Tri a{p, q, apex};
        Tri b;
        switch (integer(0, 4)) {
          case 0:  // shares the long edge
            b = {q, p, lattice(-16, 16)};
            break;
          case 1: {  // a vertex on the long edge, crossing the needle or not
            const int w = integer(1, 7);
            b = {(w * p + (8 - w) * q) / 8.0, lattice(-16, 16), lattice(-16, 16)};
            break;
          }
          case 2:  // a vertex at the apex
            b = {apex, lattice(-16, 16), lattice(-16, 16)};
            break;
          case 3: {  // another needle, sharing p
            const Vec3 far = lattice(-16, 16);
            const double width = std::ldexp(1.0, -integer(8, 28));
            b = {p, far, p + width * lattice(-2, 2)};
            break;
          }
          default:  // crossing near the thin end
            b = {apex + Vec3(0, 0, 1), apex - Vec3(0, 0, 1) + std::ldexp(1.0, -20) * e,
                 lattice(-16, 16)};
            break;
        }
        if (exactly_degenerate(b)) b = {q, p, lattice(-16, 16) + Vec3(0.5, 0.25, 0.125)};
        return {a, b, "thin"};
      }
    }
  }

 private:
  std::mt19937_64 rng_;
};

constexpr int kKinds = 8;

// ---- exact motions and inexact variants ---------------------------------------------------------

// A signed permutation of the axes with determinant +1 (a rotation by multiples of 90 degrees).
Mat3 random_axis_rotation(Generator& g) {
  std::array<int, 3> perm{0, 1, 2};
  std::shuffle(perm.begin(), perm.end(), g.rng());
  Mat3 r = Mat3::Zero();
  for (int k = 0; k < 3; ++k) r(k, perm[static_cast<std::size_t>(k)]) = g.coin() ? 1 : -1;
  if (r.determinant() < 0) r.row(0) *= -1;
  return r;
}

// Exact: entries of r are 0 or +-1, the offset is a small integer, the scale a power of two.
Tri move(const Tri& t, const Mat3& r, const Vec3& offset, int exponent) {
  Tri out;
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3 p = r * t[k] + offset;
    out[k] =
        Vec3(std::ldexp(p.x(), exponent), std::ldexp(p.y(), exponent), std::ldexp(p.z(), exponent));
  }
  return out;
}

Scalar max_abs(const Tri& a, const Tri& b) {
  Scalar m = 0;
  for (const Vec3& v : a) m = std::max(m, v.cwiseAbs().maxCoeff());
  for (const Vec3& v : b) m = std::max(m, v.cwiseAbs().maxCoeff());
  return m;
}

// A few ulps on one coordinate of one vertex of one triangle. A zero (or relatively tiny)
// coordinate moves by ulps of the configuration's largest coordinate instead: ulps of 0 are
// subnormal numbers, whose products underflow, outside antcd's promise (geometry.hpp, and
// triangle.cpp: "barring overflow/underflow of intermediate products").
void perturb(Generator& g, Config& c) {
  const Scalar scale = max_abs(c.a, c.b);
  Tri& t = g.coin() ? c.a : c.b;
  const auto vertex = static_cast<std::size_t>(g.integer(0, 2));
  double& x = t[vertex][g.integer(0, 2)];
  const int steps = g.integer(1, 4) * (g.coin() ? 1 : -1);
  if (std::abs(x) < std::ldexp(scale, -30)) {
    x += steps * std::ldexp(1.0, std::ilogb(scale) - 52);
    return;
  }
  const double towards = steps > 0 ? std::numeric_limits<double>::infinity()
                                   : -std::numeric_limits<double>::infinity();
  for (int k = std::abs(steps); k > 0; --k) x = std::nextafter(x, towards);
}

// ---- the checks ---------------------------------------------------------------------------------

struct Tally {
  std::size_t cases = 0;
  std::size_t intersecting = 0;
  std::size_t failures = 0;
};

// Compares every triangle-level query with the reference on one pair; returns false on mismatch.
bool check_pair(const Tri& a, const Tri& b, const std::string& what, Tally& tally) {
  if (exactly_degenerate(a) || exactly_degenerate(b)) return true;  // outside the contract
  const bool expected = reference_intersect(a, b);
  ++tally.cases;
  tally.intersecting += expected ? 1 : 0;
  std::vector<std::string> problems;
  Vec3 point;
  if (geometry::triangles_intersect(a[0], a[1], a[2], b[0], b[1], b[2], &point) != expected) {
    problems.push_back("triangles_intersect(a, b)");
  } else if (expected) {
    // The common point lies on both triangles up to the rounding of its coordinates.
    const Scalar tol = 1e-9 * max_abs(a, b);
    const Scalar da = CGAL::to_double(CGAL::squared_distance(to_cgal(point), to_cgal(a)));
    const Scalar db = CGAL::to_double(CGAL::squared_distance(to_cgal(point), to_cgal(b)));
    if (!(std::sqrt(da) <= tol && std::sqrt(db) <= tol)) {
      std::ostringstream p;
      p << "common point off the triangles by " << std::sqrt(da) << ", " << std::sqrt(db);
      problems.push_back(p.str());
    }
  }
  if (geometry::triangles_intersect(b[0], b[1], b[2], a[0], a[1], a[2]) != expected) {
    problems.push_back("triangles_intersect(b, a)");
  }
  if (geometry::triangles_intersect(a[2], a[0], a[1], b[1], b[0], b[2]) != expected) {
    problems.push_back("triangles_intersect(a rotated, b reversed)");
  }
  if (geometry::triangles_within(a[0], a[1], a[2], b[0], b[1], b[2], 0.0) != expected) {
    problems.push_back("triangles_within(delta 0)");
  }
  if (expected && geometry::triangle_distance(a[0], a[1], a[2], b[0], b[1], b[2]).distance != 0) {
    problems.push_back("triangle_distance != 0");
  }
  if (problems.empty()) return true;
  ++tally.failures;
  if (tally.failures <= 20) {
    std::ostringstream msg;
    for (const std::string& p : problems) msg << p << "; ";
    ADD_FAILURE() << what << ": reference says " << (expected ? "intersect" : "disjoint")
                  << ", antcd disagrees in: " << msg.str() << "\n  a = " << describe(a)
                  << "\n  b = " << describe(b);
  }
  return false;
}

// Every configuration of every kind, exactly moved and scaled, plus inexact variants.
void for_each_case(std::uint64_t seed, int per_kind,
                   const std::function<void(const Config&, const std::string&)>& visit) {
  Generator g(seed);
  const int exponents[] = {-20, -10, 0, 10, 20};
  for (int kind = 0; kind < kKinds; ++kind) {
    for (int n = 0; n < per_kind; ++n) {
      const Config base = g.make(kind);
      const Mat3 r = random_axis_rotation(g);
      const Vec3 offset = g.lattice(-64, 64);
      const std::string name = std::string(base.kind) + " #" + std::to_string(n);
      for (const int e : exponents) {
        Config moved{move(base.a, r, offset, e), move(base.b, r, offset, e), base.kind};
        visit(moved, name + " scale 2^" + std::to_string(e));
        if ((n + e) % 2 == 0) {  // inexact: a few ulps off, the reference decides
          perturb(g, moved);
          visit(moved, name + " scale 2^" + std::to_string(e) + " perturbed");
        }
      }
      // Decimal scales and an arbitrary rotation: rounded coordinates, the reference decides.
      for (const double s : {1e-6, 1e6}) {
        Config scaled = base;
        for (Vec3& v : scaled.a) v *= s;
        for (Vec3& v : scaled.b) v *= s;
        visit(scaled, name + " scale " + (s < 1 ? "1e-6" : "1e6"));
      }
      std::normal_distribution<double> gauss;
      const Mat3 rotation = Quat(gauss(g.rng()), gauss(g.rng()), gauss(g.rng()), gauss(g.rng()))
                                .normalized()
                                .toRotationMatrix();
      Config rotated = base;
      for (Vec3& v : rotated.a) v = rotation * v;
      for (Vec3& v : rotated.b) v = rotation * v;
      visit(rotated, name + " rotated");
    }
  }
}

TEST(ExactReference, TriangleIntersectionMatchesCgalOnDegenerateConfigurations) {
  Tally tally;
  for_each_case(2024, 250, [&](const Config& c, const std::string& name) {
    check_pair(c.a, c.b, name, tally);
  });
  std::cout << "[ exact reference ] " << tally.cases << " triangle pairs, " << tally.intersecting
            << " intersecting, " << tally.failures << " disagreements\n";
  EXPECT_EQ(tally.failures, 0u);
  EXPECT_GT(tally.cases, 10'000u);
  // Both answers are well represented, so neither a constant true nor false could pass.
  EXPECT_GT(tally.intersecting, tally.cases / 5);
  EXPECT_LT(tally.intersecting, tally.cases * 4 / 5);
}

// ---- Model level
// ----------------------------------------------------------------------------------

using PairList = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Mesh mesh_of(const std::vector<Tri>& tris) {
  Mesh m;
  for (const Tri& t : tris) {
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), t.begin(), t.end());
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

// Exact motion of a mesh-frame point; false if the result was rounded.
bool apply_exactly(const Transform& pose, const Vec3& p, Vec3& out) {
  out = pose.apply(p);
  return pose.rotation.transpose() * (out - pose.translation) == p;
}

// The reference's pairs (triangle indices) among the triangles antcd keeps (not numerically
// degenerate, see Model), in world coordinates.
PairList reference_pairs(const std::vector<Tri>& a, const std::vector<Tri>& b) {
  PairList out;
  for (std::uint32_t i = 0; i < a.size(); ++i) {
    if (geometry::is_degenerate_triangle(a[i][0], a[i][1], a[i][2])) continue;
    for (std::uint32_t j = 0; j < b.size(); ++j) {
      if (geometry::is_degenerate_triangle(b[j][0], b[j][1], b[j][2])) continue;
      if (reference_intersect(a[i], b[j])) out.emplace_back(i, j);
    }
  }
  return out;
}

// Meshes made of the a (resp. b) triangles of a group of configurations, each configuration moved
// by its own offset, queried with collide() at delta 0 under identity and exact poses.
void check_group(const std::vector<Config>& group, const std::string& name, Tally& tally,
                 Generator& g, int exponent) {
  std::vector<Tri> ma, mb;
  const double spacing = std::ldexp(256.0, exponent);
  for (std::size_t k = 0; k < group.size(); ++k) {
    const Vec3 offset(spacing * static_cast<double>(k), 0, 0);
    Tri a = group[k].a, b = group[k].b;
    for (Vec3& v : a) v += offset;
    for (Vec3& v : b) v += offset;
    if (exactly_degenerate(a) || exactly_degenerate(b)) continue;
    ma.push_back(a);
    mb.push_back(b);
  }
  if (ma.empty()) return;
  const auto kept = [](const std::vector<Tri>& ts) {
    return std::any_of(ts.begin(), ts.end(), [](const Tri& t) {
      return !geometry::is_degenerate_triangle(t[0], t[1], t[2]);
    });
  };
  if (!kept(ma) || !kept(mb)) return;  // a Model needs a non-degenerate triangle
  const Model model_a(mesh_of(ma));
  const Model model_b(mesh_of(mb));

  // Exact poses: signed axis permutations and dyadic translations (when nothing rounds).
  std::vector<std::pair<Transform, Transform>> poses{{Transform{}, Transform{}}};
  for (int k = 0; k < 2; ++k) {
    Transform pa, pb;
    pa.rotation = random_axis_rotation(g);
    pb.rotation = random_axis_rotation(g);
    pa.translation = std::ldexp(16.0, exponent) * g.lattice(-8, 8);
    pb.translation = std::ldexp(16.0, exponent) * g.lattice(-8, 8);
    poses.emplace_back(pa, pb);
  }
  for (const auto& [pose_a, pose_b] : poses) {
    std::vector<Tri> wa = ma, wb = mb;
    bool exact = true;
    for (std::size_t i = 0; i < ma.size(); ++i) {
      for (std::size_t k = 0; k < 3; ++k) {
        exact = apply_exactly(pose_a, ma[i][k], wa[i][k]) && exact;
        exact = apply_exactly(pose_b, mb[i][k], wb[i][k]) && exact;
        // collide() maps B into A's frame: that must not round either.
        Vec3 in_a;
        exact = apply_exactly(pose_a.inverse() * pose_b, mb[i][k], in_a) && exact;
      }
    }
    if (!exact) continue;
    const PairList expected = reference_pairs(wa, wb);
    ++tally.cases;
    tally.intersecting += expected.empty() ? 0 : 1;

    CollisionResult all;
    collide(model_a, pose_a, model_b, pose_b, CollisionRequest{0.0, true, 0}, all);
    PairList got;
    for (const Contact& c : all.contacts) got.emplace_back(c.triangle_a, c.triangle_b);
    std::sort(got.begin(), got.end());
    const bool boolean =
        collide(model_a, pose_a, model_b, pose_b, CollisionRequest{0.0, false, 0}).colliding;
    const bool volumes = any_leaf_pair_overlaps(model_a, pose_a, model_b, pose_b, 0.0);
    if (got == expected && boolean == !expected.empty() && all.colliding == boolean &&
        (volumes || expected.empty())) {
      continue;
    }
    ++tally.failures;
    if (tally.failures <= 10) {
      std::ostringstream msg;
      msg << name << ": collide() at delta 0 differs from the reference: boolean " << boolean
          << ", any_leaf_pair_overlaps " << volumes << ", pairs";
      for (const auto& [i, j] : got) msg << " (" << i << "," << j << ")";
      msg << "; reference";
      for (const auto& [i, j] : expected) msg << " (" << i << "," << j << ")";
      for (std::size_t i = 0; i < wa.size(); ++i) {
        msg << "\n  a" << i << " = " << describe(wa[i]) << "\n  b" << i << " = " << describe(wb[i]);
      }
      ADD_FAILURE() << msg.str();
    }
  }
}

TEST(ExactReference, ModelCollideAtDeltaZeroMatchesCgal) {
  Tally tally;
  Generator g(77);
  const int exponents[] = {-20, 0, 20};
  std::size_t group_index = 0;
  for (const int e : exponents) {
    for (const bool perturbed : {false, true}) {
      std::vector<Config> group;
      for (int n = 0; n < 40 * kKinds; ++n) {
        const Config base = g.make(n % kKinds);
        const Mat3 r = random_axis_rotation(g);
        const Vec3 offset = g.lattice(-64, 64);
        Config c{move(base.a, r, offset, e), move(base.b, r, offset, e), base.kind};
        if (perturbed) perturb(g, c);
        group.push_back(c);
        if (group.size() == 6) {
          check_group(group,
                      "group " + std::to_string(group_index++) + " scale 2^" + std::to_string(e) +
                          (perturbed ? " perturbed" : ""),
                      tally, g, e);
          group.clear();
        }
      }
    }
  }
  std::cout << "[ exact reference ] " << tally.cases << " model queries, " << tally.intersecting
            << " colliding, " << tally.failures << " disagreements\n";
  EXPECT_EQ(tally.failures, 0u);
  EXPECT_GT(tally.cases, 300u);
  EXPECT_GT(tally.intersecting, tally.cases / 4);
  EXPECT_LT(tally.intersecting, tally.cases);
}

}  // namespace
}  // namespace antcd
