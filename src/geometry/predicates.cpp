// src/geometry/predicates.cpp — exact-sign orientation predicates (see antcd/geometry.hpp).
//
// Robustness
// - Every topological decision (which side of a plane, which side of a line, whether a line
//   passes through a triangle) is taken from the SIGN of an orientation determinant, and those
//   signs are exact: a floating-point evaluation is used when a forward error bound proves its
//   sign, otherwise the determinant is re-evaluated exactly with floating-point expansions
//   (error-free sums and products). The answer of triangles_intersect is therefore the exact
//   answer for the given double coordinates (barring overflow/underflow of intermediate
//   products), not only for integer input.
// - Coordinates of reported points (intersection points, closest points) are ordinary
//   floating-point approximations.
#include <antcd/geometry.hpp>

#include "geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#if defined(__FAST_MATH__)
#error "antcd's exact geometric predicates need IEEE arithmetic: do not build with -ffast-math"
#endif

namespace antcd::geometry {
namespace detail {
namespace {

// ---- error-free transformations and expansions -----------------------------------------------

// s + e == a + b exactly, with s = fl(a + b) (Knuth's branch-free TwoSum).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

// p + e == a * b exactly, with p = fl(a * b). std::fma is exact by definition, so this stays
// correct whatever the compiler does about floating-point contraction.
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
#if defined(__FMA__)
  e = std::fma(a, b, -p);
#else
  // No FMA instruction in this build, where std::fma would be a libm call on the predicates' slow
  // path: Dekker/Veltkamp splitting instead (exact barring overflow; without FMA instructions the
  // compiler cannot contract it). a = ah + al, b = bh + bl with 26-bit halves.
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  const double ca = kSplit * a;
  const double ah = ca - (ca - a);
  const double al = a - ah;
  const double cb = kSplit * b;
  const double bh = cb - (cb - b);
  const double bl = b - bh;
  e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
#endif
}

// A sum of doubles held exactly as a nonoverlapping expansion, components in increasing order of
// magnitude, zero components removed. Only used on the rare slow path of the predicates.
class Expansion {
 public:
  void add(double b) {
    double q = b;
    int m = 0;
    for (int i = 0; i < n_; ++i) {
      double h;
      two_sum(q, c_[i], q, h);
      if (h != 0) c_[m++] = h;
    }
    if (q != 0 && m < kCapacity) c_[m++] = q;
    n_ = m;
  }
  void add_product(double x, double y) {
    double p, e;
    two_product(x, y, p, e);
    add(e);
    add(p);
  }
  void add_triple_product(double x, double y, double z) {
    double p, e;
    two_product(x, y, p, e);  // x*y == p + e
    double p1, e1, p2, e2;
    two_product(p, z, p1, e1);
    two_product(e, z, p2, e2);
    add(e2);
    add(p2);
    add(e1);
    add(p1);
  }
  // An approximation of the value with exactly the sign of the value.
  [[nodiscard]] double estimate() const {
    if (n_ == 0) return 0;
    double s = 0;
    for (int i = 0; i < n_; ++i) s += c_[i];
    // The top component dominates the rest, so its sign is the sign of the exact sum.
    return sign_of(s) == sign_of(c_[n_ - 1]) ? s : c_[n_ - 1];
  }

 private:
  static constexpr int kCapacity = 128;  // callers add at most 96 terms; each add grows n_ by <= 1
  std::array<double, kCapacity> c_;      // only c_[0 .. n_) is ever read
  int n_ = 0;
};

// Adds sign * det[r0; r1; r2] (rows) to e.
void add_det3(Expansion& e, const double* r0, const double* r1, const double* r2, double sign) {
  e.add_triple_product(sign * r0[0], r1[1], r2[2]);
  e.add_triple_product(-sign * r0[0], r1[2], r2[1]);
  e.add_triple_product(-sign * r0[1], r1[0], r2[2]);
  e.add_triple_product(sign * r0[1], r1[2], r2[0]);
  e.add_triple_product(sign * r0[2], r1[0], r2[1]);
  e.add_triple_product(-sign * r0[2], r1[1], r2[0]);
}

}  // namespace

// det[a-d; b-d; c-d] evaluated exactly (returned as a sign-exact approximation).
double orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  std::array<double, 9> diff{};
  bool exact_differences = true;
  const Vec3* rows[3] = {&a, &b, &c};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) {
      double err;
      two_sum((*rows[r])[k], -d[k], diff[3 * r + k], err);
      exact_differences = exact_differences && err == 0;
    }
  }
  Expansion e;
  if (exact_differences) {
    add_det3(e, &diff[0], &diff[3], &diff[6], 1.0);
  } else {
    // Multilinearity: det(a-d, b-d, c-d) = det(a,b,c) - det(d,b,c) - det(a,d,c) - det(a,b,d).
    add_det3(e, a.data(), b.data(), c.data(), 1.0);
    add_det3(e, d.data(), b.data(), c.data(), -1.0);
    add_det3(e, a.data(), d.data(), c.data(), -1.0);
    add_det3(e, a.data(), b.data(), d.data(), -1.0);
  }
  return e.estimate();
}

// Exact-sign orient2d of the projections of p, q, r: (q-p) x (r-p). The floating-point value is
// returned when it is larger than `margin` times its error bound, else the exact value's estimate.
double orient2d(const Vec3& p, const Vec3& q, const Vec3& r, const Projection& pr, double margin) {
  const Filtered f = orient2d_float(p, q, r, pr);
  const double bound = margin * kOrient2dBound * f.perm;
  if (f.value > bound || -f.value > bound) return f.value;
  if (f.perm == 0) return 0;  // both products exactly zero
  const double px = p[pr.u], py = p[pr.v];
  const double qx = q[pr.u], qy = q[pr.v];
  const double rx = r[pr.u], ry = r[pr.v];
  // (qx-px)(ry-py) - (qy-py)(rx-px) expanded (the px*py terms cancel).
  Expansion e;
  e.add_product(qx, ry);
  e.add_product(-qx, py);
  e.add_product(-px, ry);
  e.add_product(-qy, rx);
  e.add_product(qy, px);
  e.add_product(py, rx);
  return e.estimate();
}

}  // namespace detail

using namespace detail;

bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Scalar cross2 = (b - a).cross(c - a).squaredNorm();
  const Scalar longest2 =
      std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  // |cross| <= 1e-12 * longest^2, squared. All three points equal: 0 <= 0.
  return cross2 <= 1e-24 * longest2 * longest2;
}

Scalar orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return orient3d_with_differences(a, b, c, d, a - d, b - d, c - d);
}

}  // namespace antcd::geometry
