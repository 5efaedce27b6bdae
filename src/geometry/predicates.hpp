// Private: the exact-sign orientation predicates and the plane classification the triangle
// intersection and distance tests are built on (predicates.cpp).
#pragma once

#include <antcd/math.hpp>

#include <cmath>

namespace antcd::geometry::detail {

constexpr double kEps = 0x1p-53;  // unit roundoff of double
// Forward error bounds of the plain floating-point determinants, relative to their
// "permanents" (the same expressions with absolute values). Shewchuk's analysis gives
// about 7 eps for orient3d and 3 eps for orient2d; we use comfortably larger factors.
constexpr double kOrient3dBound = 16 * kEps;
constexpr double kOrient2dBound = 8 * kEps;
// A determinant used to interpolate a crossing point (not only for its sign) is taken in floating
// point only when it exceeds its error bound this many times (relative error <= 2^-40); otherwise
// it is re-evaluated exactly. Near-parallel crossings would otherwise move the point far off.
constexpr double kInterpolationMargin = 0x1p40;

inline int sign_of(double x) { return (x > 0) - (x < 0); }

// det[a-d; b-d; c-d] evaluated exactly (returned as a sign-exact approximation).
double orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The floating-point value of det[ad; bd; cd] and the permanent bounding its rounding error: the
// error is at most kOrient3dBound * perm (barring underflow), so |det| above that proves its sign.
struct Filtered {
  double value;
  double perm;
};

inline Filtered orient3d_float(const Vec3& ad, const Vec3& bd, const Vec3& cd) {
  const double bdxcdy = bd.x() * cd.y(), cdxbdy = cd.x() * bd.y();
  const double cdxady = cd.x() * ad.y(), adxcdy = ad.x() * cd.y();
  const double adxbdy = ad.x() * bd.y(), bdxady = bd.x() * ad.y();
  return {ad.z() * (bdxcdy - cdxbdy) + bd.z() * (cdxady - adxcdy) + cd.z() * (adxbdy - bdxady),
          (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(ad.z()) +
              (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bd.z()) +
              (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cd.z())};
}

// The sign of orient3d(a, b, c, d) when the floating-point error bound proves it, else 0: a
// filter only (0 says nothing; the exact sign may be anything). No exact arithmetic.
inline int orient3d_sign_if_certain(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Filtered f = orient3d_float(a - d, b - d, c - d);
  const double bound = kOrient3dBound * f.perm;
  return (f.value > bound) - (-f.value > bound);
}

// orient3d(a, b, c, d) (antcd/geometry.hpp), exact-sign, given the differences ad = a - d,
// bd = b - d, cd = c - d rounded as orient3d rounds them: callers that share a base point d
// compute them once. The floating-point value when its error bound proves the sign, else the exact
// value's estimate.
inline double orient3d_with_differences(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                                        const Vec3& ad, const Vec3& bd, const Vec3& cd) {
  const Filtered f = orient3d_float(ad, bd, cd);
  const double bound = kOrient3dBound * f.perm;
  if (f.value > bound || -f.value > bound) return f.value;
  if (f.perm == 0) return 0;  // every product is exactly zero, so is the determinant
  return orient3d_exact(a, b, c, d);
}

// ---- 2-D orientation in a coordinate plane ------------------------------------------------------

// The plane obtained by dropping coordinate `drop`; (u, v) is a cyclic order of the other two.
struct Projection {
  int u;
  int v;
  explicit Projection(int drop) : u((drop + 1) % 3), v((drop + 2) % 3) {}
};

// The floating-point value of orient2d(p, q, r) in `pr`, (q-p) x (r-p), and the sum of the two
// products' magnitudes: the error is at most kOrient2dBound * perm (barring underflow).
inline Filtered orient2d_float(const Vec3& p, const Vec3& q, const Vec3& r, const Projection& pr) {
  const double left = (q[pr.u] - p[pr.u]) * (r[pr.v] - p[pr.v]);
  const double right = (q[pr.v] - p[pr.v]) * (r[pr.u] - p[pr.u]);
  return {left - right, std::abs(left) + std::abs(right)};
}

// The sign of orient2d(p, q, r) in `pr` when the floating-point error bound proves it, else 0: a
// filter only (0 says nothing). No exact arithmetic.
inline int orient2d_sign_if_certain(const Vec3& p, const Vec3& q, const Vec3& r,
                                    const Projection& pr) {
  const Filtered f = orient2d_float(p, q, r, pr);
  const double bound = kOrient2dBound * f.perm;
  return (f.value > bound) - (-f.value > bound);
}

// Exact-sign orient2d of the projections of p, q, r: (q-p) x (r-p). The floating-point value is
// returned when it is larger than `margin` times its error bound, else the exact value's estimate.
double orient2d(const Vec3& p, const Vec3& q, const Vec3& r, const Projection& pr,
                double margin = 1);

inline int dominant_axis(const Vec3& n) {
  const Vec3 m = n.cwiseAbs();
  if (m.x() >= m.y() && m.x() >= m.z()) return 0;
  return m.y() >= m.z() ? 1 : 2;
}

// ---- plane classification -----------------------------------------------------------------------

// The plane of (t0, t1, t2) with normal n = (t1-t0) x (t2-t0), plus what the error bound needs.
struct Plane {
  const Vec3* t[3];
  Vec3 n;
  Vec3 nperm;  // |u_y v_z| + |u_z v_y|, ... : the permanent of each normal component
};

inline Plane make_plane(const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  Plane pl{{&t0, &t1, &t2}, Vec3::Zero(), Vec3::Zero()};
  const double ux = t1.x() - t0.x(), uy = t1.y() - t0.y(), uz = t1.z() - t0.z();
  const double vx = t2.x() - t0.x(), vy = t2.y() - t0.y(), vz = t2.z() - t0.z();
  const double xa = uy * vz, xb = uz * vy;
  const double ya = uz * vx, yb = ux * vz;
  const double za = ux * vy, zb = uy * vx;
  pl.n = Vec3(xa - xb, ya - yb, za - zb);
  pl.nperm =
      Vec3(std::abs(xa) + std::abs(xb), std::abs(ya) + std::abs(yb), std::abs(za) + std::abs(zb));
  return pl;
}

// Floating-point n·(p - t0) and the permanent bounding its rounding error.
struct SideValue {
  double value;
  double perm;
};

inline SideValue side_value(const Plane& pl, const Vec3& p) {
  const Vec3& o = *pl.t[0];
  const double wx = p.x() - o.x(), wy = p.y() - o.y(), wz = p.z() - o.z();
  return {wx * pl.n.x() + wy * pl.n.y() + wz * pl.n.z(),
          std::abs(wx) * pl.nperm.x() + std::abs(wy) * pl.nperm.y() + std::abs(wz) * pl.nperm.z()};
}

// Exact sign of n·(p - t0) (= -orient3d(t0, t1, t2, p)); `sv.value` is replaced by a sign-exact
// approximation when the floating-point value was not certain.
inline int side_sign(const Plane& pl, const Vec3& p, SideValue& sv) {
  const double bound = kOrient3dBound * sv.perm;
  if (sv.value > bound) return 1;
  if (sv.value < -bound) return -1;
  if (sv.perm == 0) {  // every product is exactly zero, so is the determinant
    sv.value = 0;
    return 0;
  }
  sv.value = -orient3d_exact(*pl.t[0], *pl.t[1], *pl.t[2], p);
  sv.perm = 0;  // the value is now accurate, see accurate_side
  return sign_of(sv.value);
}

// n·(p - t0) accurate to a relative 2^-40, for interpolating a crossing point: `sv` when its error
// bound allows (or when side_sign already re-evaluated it), else re-evaluated exactly.
inline double accurate_side(const Plane& pl, const Vec3& p, const SideValue& sv) {
  if (std::abs(sv.value) > kInterpolationMargin * kOrient3dBound * sv.perm) return sv.value;
  return -orient3d_exact(*pl.t[0], *pl.t[1], *pl.t[2], p);
}

inline bool certainly_one_side(const SideValue (&sv)[3]) {
  bool pos = true, neg = true;
  for (const SideValue& s : sv) {
    const double bound = kOrient3dBound * s.perm;
    pos = pos && s.value > bound;
    neg = neg && s.value < -bound;
  }
  return pos || neg;
}

inline bool strictly_one_side(const int (&s)[3]) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

inline bool all_zero(const int (&s)[3]) { return s[0] == 0 && s[1] == 0 && s[2] == 0; }

}  // namespace antcd::geometry::detail
