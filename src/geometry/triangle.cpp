// src/geometry/triangle.cpp — triangle predicates and distances (see antcd/geometry.hpp).
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
//
// Intersection algorithm (closed triangles A and B)
// 1. Classify B's vertices against A's plane; all strictly on one side -> disjoint (the cheap
//    common path: one cross product, three dot products, no exact arithmetic unless a vertex is
//    within rounding distance of the plane). Same for A's vertices against B's plane.
// 2. Both triangles in one plane -> 2-D test after dropping the dominant axis of the normal:
//    they meet iff a vertex of one lies in the other or two edges meet.
// 3. Otherwise A∩B lies on the line where the planes meet, and it is empty or a segment whose
//    end points lie on the boundary of A or of B. So they meet iff an edge of one meets the
//    other (closed) triangle. An edge pq meets triangle abc iff p and q are not strictly on one
//    side of the plane and either (both on the plane) the segment meets the triangle in 2-D, or
//    orient3d(p,q,a,b), orient3d(p,q,b,c), orient3d(p,q,c,a) are all >= 0 or all <= 0.
#include <antcd/geometry.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#if defined(__FAST_MATH__)
#error "antcd's exact geometric predicates need IEEE arithmetic: do not build with -ffast-math"
#endif

namespace antcd::geometry {
namespace {

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

int sign_of(double x) { return (x > 0) - (x < 0); }

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

// ---- 2-D orientation in a coordinate plane ------------------------------------------------------

// The plane obtained by dropping coordinate `drop`; (u, v) is a cyclic order of the other two.
struct Projection {
  int u;
  int v;
  explicit Projection(int drop) : u((drop + 1) % 3), v((drop + 2) % 3) {}
};

// Exact-sign orient2d of the projections of p, q, r: (q-p) x (r-p). The floating-point value is
// returned when it is larger than `margin` times its error bound, else the exact value's estimate.
double orient2d(const Vec3& p, const Vec3& q, const Vec3& r, const Projection& pr,
                double margin = 1) {
  const double px = p[pr.u], py = p[pr.v];
  const double qx = q[pr.u], qy = q[pr.v];
  const double rx = r[pr.u], ry = r[pr.v];
  const double left = (qx - px) * (ry - py);
  const double right = (qy - py) * (rx - px);
  const double det = left - right;
  const double bound = margin * kOrient2dBound * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return det;
  if (left == 0 && right == 0) return 0;  // both products exactly zero
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

int dominant_axis(const Vec3& n) {
  const Vec3 m = n.cwiseAbs();
  if (m.x() >= m.y() && m.x() >= m.z()) return 0;
  return m.y() >= m.z() ? 1 : 2;
}

// Collinear p, a, b: is p inside the closed box of a and b (hence on the segment)?
bool within_box(const Vec3& p, const Vec3& a, const Vec3& b, const Projection& pr) {
  for (const int k : {pr.u, pr.v}) {
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  }
  return true;
}

// Closed segments [a,b] and [c,d] with all four points in one plane, tested in projection.
bool segments_meet_2d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                      const Projection& pr, Vec3* point) {
  const double o1 = orient2d(a, b, c, pr);
  const double o2 = orient2d(a, b, d, pr);
  if ((o1 > 0 && o2 > 0) || (o1 < 0 && o2 < 0)) return false;
  const double o3 = orient2d(c, d, a, pr);
  const double o4 = orient2d(c, d, b, pr);
  if ((o3 > 0 && o4 > 0) || (o3 < 0 && o4 < 0)) return false;
  if (o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0) {  // all on one line (or point segments)
    const Vec3* candidates[4][3] = {{&c, &a, &b}, {&d, &a, &b}, {&a, &c, &d}, {&b, &c, &d}};
    for (const auto& cand : candidates) {
      if (within_box(*cand[0], *cand[1], *cand[2], pr)) {
        if (point != nullptr) *point = *cand[0];
        return true;
      }
    }
    return false;
  }
  // The lines are distinct and the segments meet in one point.
  if (point != nullptr) {
    if (o1 == 0) {
      *point = c;
    } else if (o2 == 0) {
      *point = d;
    } else if (o3 == 0) {
      *point = a;
    } else if (o4 == 0) {
      *point = b;
    } else {
      // o3, o4 nonzero with opposite signs; their floating-point values may be off by up to their
      // error bound, so re-evaluate them accurately for the crossing point.
      const double a3 = orient2d(c, d, a, pr, kInterpolationMargin);
      const double a4 = orient2d(c, d, b, pr, kInterpolationMargin);
      const double t = std::clamp(a3 / (a3 - a4), 0.0, 1.0);
      *point = a + t * (b - a);
    }
  }
  return true;
}

// Closed triangle abc (in projection) contains p; `o` = orient2d(a, b, c) must be nonzero.
bool contains_2d(const Vec3& a, const Vec3& b, const Vec3& c, double o, const Vec3& p,
                 const Projection& pr) {
  const int s = sign_of(o);
  return sign_of(orient2d(a, b, p, pr)) * s >= 0 && sign_of(orient2d(b, c, p, pr)) * s >= 0 &&
         sign_of(orient2d(c, a, p, pr)) * s >= 0;
}

// Closed segment pq against closed triangle T, all five points in one plane.
bool segment_meets_triangle_2d(const Vec3& p, const Vec3& q, const Vec3* const t[3],
                               const Projection& pr, Vec3* point) {
  const double o = orient2d(*t[0], *t[1], *t[2], pr);
  if (o != 0) {  // a zero-area T is the union of its edges: the edge tests below suffice
    for (const Vec3* e : {&p, &q}) {
      if (contains_2d(*t[0], *t[1], *t[2], o, *e, pr)) {
        if (point != nullptr) *point = *e;
        return true;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (segments_meet_2d(p, q, *t[i], *t[(i + 1) % 3], pr, point)) return true;
  }
  return false;
}

// Closed triangles A and B in one plane.
bool triangles_meet_2d(const Vec3* const A[3], const Vec3* const B[3], const Projection& pr,
                       Vec3* point) {
  const double oa = orient2d(*A[0], *A[1], *A[2], pr);
  const double ob = orient2d(*B[0], *B[1], *B[2], pr);
  if (ob != 0) {
    for (int i = 0; i < 3; ++i) {
      if (contains_2d(*B[0], *B[1], *B[2], ob, *A[i], pr)) {
        if (point != nullptr) *point = *A[i];
        return true;
      }
    }
  }
  if (oa != 0) {
    for (int i = 0; i < 3; ++i) {
      if (contains_2d(*A[0], *A[1], *A[2], oa, *B[i], pr)) {
        if (point != nullptr) *point = *B[i];
        return true;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segments_meet_2d(*A[i], *A[(i + 1) % 3], *B[j], *B[(j + 1) % 3], pr, point)) return true;
    }
  }
  return false;
}

// ---- plane classification -----------------------------------------------------------------------

// The plane of (t0, t1, t2) with normal n = (t1-t0) x (t2-t0), plus what the error bound needs.
struct Plane {
  const Vec3* t[3];
  Vec3 n;
  Vec3 nperm;  // |u_y v_z| + |u_z v_y|, ... : the permanent of each normal component
};

Plane make_plane(const Vec3& t0, const Vec3& t1, const Vec3& t2) {
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

SideValue side_value(const Plane& pl, const Vec3& p) {
  const Vec3& o = *pl.t[0];
  const double wx = p.x() - o.x(), wy = p.y() - o.y(), wz = p.z() - o.z();
  return {wx * pl.n.x() + wy * pl.n.y() + wz * pl.n.z(),
          std::abs(wx) * pl.nperm.x() + std::abs(wy) * pl.nperm.y() + std::abs(wz) * pl.nperm.z()};
}

// Exact sign of n·(p - t0) (= -orient3d(t0, t1, t2, p)); `sv.value` is replaced by a sign-exact
// approximation when the floating-point value was not certain.
int side_sign(const Plane& pl, const Vec3& p, SideValue& sv) {
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
double accurate_side(const Plane& pl, const Vec3& p, const SideValue& sv) {
  if (std::abs(sv.value) > kInterpolationMargin * kOrient3dBound * sv.perm) return sv.value;
  return -orient3d_exact(*pl.t[0], *pl.t[1], *pl.t[2], p);
}

bool certainly_one_side(const SideValue (&sv)[3]) {
  bool pos = true, neg = true;
  for (const SideValue& s : sv) {
    const double bound = kOrient3dBound * s.perm;
    pos = pos && s.value > bound;
    neg = neg && s.value < -bound;
  }
  return pos || neg;
}

bool strictly_one_side(const int (&s)[3]) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

bool all_zero(const int (&s)[3]) { return s[0] == 0 && s[1] == 0 && s[2] == 0; }

// Closed segment pq against the closed triangle of plane `pl` (non-degenerate), given the exact
// sides sp, sq of p, q and their plane values dp, dq (sign-exact).
bool edge_meets_triangle(const Vec3& p, const Vec3& q, int sp, int sq, const SideValue& dp,
                         const SideValue& dq, const Plane& pl, Vec3* point) {
  if (sp * sq > 0) return false;
  const Vec3& a = *pl.t[0];
  const Vec3& b = *pl.t[1];
  const Vec3& c = *pl.t[2];
  if (sp == 0 && sq == 0) {
    return segment_meets_triangle_2d(p, q, pl.t, Projection(dominant_axis(pl.n)), point);
  }
  // The line pq crosses the plane in one point, which lies on the segment.
  const int s1 = sign_of(orient3d(p, q, a, b));
  const int s2 = sign_of(orient3d(p, q, b, c));
  const int s3 = sign_of(orient3d(p, q, c, a));
  const bool hit = (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
  if (hit && point != nullptr) {
    if (sp == 0) {
      *point = p;
    } else if (sq == 0) {
      *point = q;
    } else {
      // dp, dq nonzero with opposite signs.
      const double vp = accurate_side(pl, p, dp);
      const double vq = accurate_side(pl, q, dq);
      const double t = std::clamp(vp / (vp - vq), 0.0, 1.0);
      *point = p + t * (q - p);
    }
  }
  return hit;
}

// Everything after the cheap plane rejection: `va`/`vb` are the plane values of A's vertices
// against B's plane and of B's vertices against A's plane.
bool intersect_core(const Plane& pa, const Plane& pb, SideValue (&va)[3], SideValue (&vb)[3],
                    Vec3* point) {
  int sb[3];
  for (int i = 0; i < 3; ++i) sb[i] = side_sign(pa, *pb.t[i], vb[i]);
  if (strictly_one_side(sb)) return false;
  int sa[3];
  for (int i = 0; i < 3; ++i) sa[i] = side_sign(pb, *pa.t[i], va[i]);
  if (strictly_one_side(sa)) return false;

  const bool a_in_b_plane = all_zero(sa);
  const bool b_in_a_plane = all_zero(sb);
  if (a_in_b_plane && b_in_a_plane) {
    // Coplanar (for non-degenerate input both hold together). Project along the better normal.
    const Vec3& n = pa.n.cwiseAbs().maxCoeff() >= pb.n.cwiseAbs().maxCoeff() ? pa.n : pb.n;
    if (n.cwiseAbs().maxCoeff() == 0) {
      // Both triangles degenerate (unsupported input): compare their edges.
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          Vec3 cp, cq;
          if (segment_segment_distance_squared(*pa.t[i], *pa.t[(i + 1) % 3], *pb.t[j],
                                               *pb.t[(j + 1) % 3], &cp, &cq) == 0) {
            if (point != nullptr) *point = cp;
            return true;
          }
        }
      }
      return false;
    }
    return triangles_meet_2d(pa.t, pb.t, Projection(dominant_axis(n)), point);
  }
  // Not coplanar. An all-zero side pattern only happens when the OTHER triangle is degenerate;
  // a degenerate triangle is the union of its edges, so testing its edges alone is exact.
  if (!a_in_b_plane) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (edge_meets_triangle(*pa.t[i], *pa.t[j], sa[i], sa[j], va[i], va[j], pb, point)) {
        return true;
      }
    }
  }
  if (!b_in_a_plane) {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (edge_meets_triangle(*pb.t[i], *pb.t[j], sb[i], sb[j], vb[i], vb[j], pa, point)) {
        return true;
      }
    }
  }
  return false;
}

// ---- distances ----------------------------------------------------------------------------------

Scalar point_segment_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b, Vec3* closest) {
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  double t = 0;
  if (dd > 0) t = std::clamp((p - a).dot(d) / dd, 0.0, 1.0);
  const Vec3 c = a + t * d;
  if (closest != nullptr) *closest = c;
  return (p - c).squaredNorm();
}

// Minimum over the 6 vertex-triangle and 9 edge-edge distances: the squared distance of two
// disjoint triangles, with a closest pair.
Scalar disjoint_distance_squared(const Vec3* const A[3], const Vec3* const B[3], Vec3& pa,
                                 Vec3& pb) {
  Scalar best = std::numeric_limits<Scalar>::infinity();
  Vec3 c, cq;
  for (int i = 0; i < 3; ++i) {
    const Scalar d = point_triangle_distance_squared(*A[i], *B[0], *B[1], *B[2], &c);
    if (d < best) {
      best = d;
      pa = *A[i];
      pb = c;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const Scalar d = point_triangle_distance_squared(*B[i], *A[0], *A[1], *A[2], &c);
    if (d < best) {
      best = d;
      pa = c;
      pb = *B[i];
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Scalar d =
          segment_segment_distance_squared(*A[i], *A[(i + 1) % 3], *B[j], *B[(j + 1) % 3], &c, &cq);
      if (d < best) {
        best = d;
        pa = c;
        pb = cq;
      }
    }
  }
  return best;
}

}  // namespace

// ---- public functions ---------------------------------------------------------------------------

bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Scalar cross2 = (b - a).cross(c - a).squaredNorm();
  const Scalar longest2 =
      std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  // |cross| <= 1e-12 * longest^2, squared. All three points equal: 0 <= 0.
  return cross2 <= 1e-24 * longest2 * longest2;
}

Scalar orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double perm = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                      (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                      (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  const double bound = kOrient3dBound * perm;
  if (det > bound || -det > bound) return det;
  if (perm == 0) return 0;  // every product is exactly zero, so is the determinant
  return orient3d_exact(a, b, c, d);
}

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                         const Vec3& b1, const Vec3& b2, Vec3* point) {
  const Plane pa = make_plane(a0, a1, a2);
  SideValue vb[3] = {side_value(pa, b0), side_value(pa, b1), side_value(pa, b2)};
  if (certainly_one_side(vb)) return false;  // the common, cheap rejection
  const Plane pb = make_plane(b0, b1, b2);
  SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
  if (certainly_one_side(va)) return false;
  return intersect_core(pa, pb, va, vb, point);
}

Scalar point_triangle_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                       Vec3* closest) {
  // The normal is taken at the vertex opposite the longest edge, whose angle is the largest: the
  // rounding error of a cross product relative to its length grows as 1 / sin(angle), so the
  // sharp tip of a needle is the worst place to take it. (b, c, a) and (c, a, b) keep the
  // orientation of (a, b, c).
  const Scalar lab = (b - a).squaredNorm();
  const Scalar lbc = (c - b).squaredNorm();
  const Scalar lca = (a - c).squaredNorm();
  const Vec3* o = &a;  // pivot: opposite the longest edge
  const Vec3* o1 = &b;
  const Vec3* o2 = &c;
  if (lca >= lab && lca >= lbc) {
    o = &b, o1 = &c, o2 = &a;
  } else if (lab >= lbc && lab >= lca) {
    o = &c, o1 = &a, o2 = &b;
  }
  const Vec3 n = (*o1 - *o).cross(*o2 - *o);
  const Scalar nn = n.squaredNorm();
  auto edges_only_into = [&](Vec3& best_c) {  // distance to the union of the three edges
    best_c = a;
    Vec3 cc;
    Scalar best = std::numeric_limits<Scalar>::infinity();
    const Vec3* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const Scalar d = point_segment_distance_squared(p, *v[i], *v[(i + 1) % 3], &cc);
      if (d < best) {
        best = d;
        best_c = cc;
      }
    }
    return best;
  };
  auto edges_only = [&]() {  // a zero-area triangle is the union of its edges
    Vec3 best_c;
    const Scalar best = edges_only_into(best_c);
    if (closest != nullptr) *closest = best_c;
    return best;
  };
  if (!(nn > 0)) return edges_only();
  // The closest point of the triangle to p is the closest one to q, p's projection onto the
  // plane. Voronoi regions of the triangle within its plane, told apart by the signs of the
  // (scaled) barycentric coordinates of q: all >= 0 -> face region, closest point q itself; one
  // negative -> the region of the opposite edge or of one of its end points; two negative -> the
  // region of their common vertex or of one of the two adjacent edges. The edge and vertex
  // regions are resolved by clamping onto the candidate edges. Everything is computed from
  // cross products of short vectors and point-segment projections, which stays accurate for
  // needle- and cap-shaped triangles (unlike closed-form barycentrics from dot products).
  const Vec3 q = p - (n.dot(p - *o) / nn) * n;
  const Vec3 qa = a - q, qb = b - q, qc = c - q;
  const Scalar wa = n.dot(qb.cross(qc));  // weight of a: side of q against edge bc
  const Scalar wb = n.dot(qc.cross(qa));  // weight of b: edge ca
  const Scalar wc = n.dot(qa.cross(qb));  // weight of c: edge ab
  if (wa >= 0 && wb >= 0 && wc >= 0) {
    const Scalar face = (p - q).squaredNorm();
    // A sliver (sine of its largest angle below 1e-3) has a plane that rounding tilts by up to
    // about 1e-16 / sine: its edges, which lie within the sliver's width of every point of it,
    // may then be nearer than the tilted projection says. Cheap triangles keep the fast path.
    const Scalar lmax = std::max({lab, lbc, lca});
    const Scalar lmid = lab + lbc + lca - lmax - std::min({lab, lbc, lca});
    if (nn < 1e-6 * lmax * lmid) {
      Vec3 edge_closest;
      const Scalar on_edges = edges_only_into(edge_closest);
      if (on_edges < face) {
        if (closest != nullptr) *closest = edge_closest;
        return on_edges;
      }
    }
    if (closest != nullptr) *closest = q;
    return face;
  }
  Vec3 best_c = a, cc;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  auto edge = [&](Scalar w, const Vec3& e0, const Vec3& e1) {
    if (!(w < 0)) return;
    const Scalar d = point_segment_distance_squared(p, e0, e1, &cc);
    if (d < best) {
      best = d;
      best_c = cc;
    }
  };
  edge(wa, b, c);
  edge(wb, c, a);
  edge(wc, a, b);
  if (!(best < std::numeric_limits<Scalar>::infinity())) return edges_only();  // NaN input
  if (closest != nullptr) *closest = best_c;
  return best;
}

Scalar segment_segment_distance_squared(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                        const Vec3& q1, Vec3* cp, Vec3* cq) {
  // The minimum is attained either with both parameters interior (then at the unique critical
  // point of non-parallel segments) or with an end point of one segment; parallel segments
  // always have a minimising pair involving an end point. So the minimum over the four
  // end-point-to-segment distances and the clamped critical point is exact.
  Vec3 bp = p0, bq = q0, c;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  auto consider = [&](Scalar d, const Vec3& x, const Vec3& y) {
    if (d < best) {
      best = d;
      bp = x;
      bq = y;
    }
  };
  consider(point_segment_distance_squared(p0, q0, q1, &c), p0, c);
  consider(point_segment_distance_squared(p1, q0, q1, &c), p1, c);
  consider(point_segment_distance_squared(q0, p0, p1, &c), c, q0);
  consider(point_segment_distance_squared(q1, p0, p1, &c), c, q1);

  const Vec3 d1 = p1 - p0;
  const Vec3 d2 = q1 - q0;
  const Vec3 r = p0 - q0;
  const Scalar a = d1.squaredNorm();
  const Scalar e = d2.squaredNorm();
  const Scalar b = d1.dot(d2);
  const Scalar denom = a * e - b * b;
  if (denom > 0 && best > 0) {
    const Scalar cc = d1.dot(r);
    const Scalar f = d2.dot(r);
    // Critical point of |r + s d1 - t d2|^2; clamping keeps it a pair of points of the segments,
    // so it can only improve the minimum when it is (nearly) the true interior optimum.
    const Scalar s = std::clamp((b * f - cc * e) / denom, 0.0, 1.0);
    const Scalar t = std::clamp((a * f - b * cc) / denom, 0.0, 1.0);
    const Vec3 x = p0 + s * d1;
    const Vec3 y = q0 + t * d2;
    consider((x - y).squaredNorm(), x, y);
  }
  if (cp != nullptr) *cp = bp;
  if (cq != nullptr) *cq = bq;
  return best;
}

TriangleDistance triangle_distance(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                   const Vec3& b1, const Vec3& b2) {
  TriangleDistance out;
  Vec3 p;
  if (triangles_intersect(a0, a1, a2, b0, b1, b2, &p)) {
    out.distance = 0;
    out.pa = p;
    out.pb = p;
    return out;
  }
  const Vec3* A[3] = {&a0, &a1, &a2};
  const Vec3* B[3] = {&b0, &b1, &b2};
  out.distance = std::sqrt(disjoint_distance_squared(A, B, out.pa, out.pb));
  return out;
}

bool triangles_within(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                      const Vec3& b1, const Vec3& b2, Scalar delta, Vec3* point, Scalar* distance) {
  const Plane pa = make_plane(a0, a1, a2);
  SideValue vb[3] = {side_value(pa, b0), side_value(pa, b1), side_value(pa, b2)};

  if (!(delta > 0)) {  // delta == 0: exactly triangles_intersect
    if (certainly_one_side(vb)) return false;
    const Plane pb = make_plane(b0, b1, b2);
    SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
    if (certainly_one_side(va)) return false;
    if (!intersect_core(pa, pb, va, vb, point)) return false;
    if (distance != nullptr) *distance = 0;
    return true;
  }

  // Conservative rejection: all vertices of one triangle farther than delta from the other's
  // plane, on one side. With D, N the exact n·(v - t0) and normal, |value - D| <= E (the orient3d
  // error bound) and |N| <= |fl(n)| + F, so value - E > delta * (|fl(n)| + F) proves D/|N| > delta.
  // The extra relative and coordinate-scale slack keeps the rejection consistent with the
  // rounding of the distance computed below.
  const Scalar scale =
      std::max({a0.cwiseAbs().maxCoeff(), a1.cwiseAbs().maxCoeff(), a2.cwiseAbs().maxCoeff(),
                b0.cwiseAbs().maxCoeff(), b1.cwiseAbs().maxCoeff(), b2.cwiseAbs().maxCoeff()});
  const Scalar slack = delta * (1 + 1e-12) + 1e-13 * scale;
  auto beyond_delta = [&](const Plane& pl, const SideValue(&sv)[3]) {
    const Scalar nlen = pl.n.norm();
    const Scalar reach = (nlen * (1 + 8 * kEps) + 8 * kEps * pl.nperm.sum()) * slack;
    bool pos = true, neg = true;
    for (const SideValue& s : sv) {
      const Scalar e = kOrient3dBound * s.perm;
      pos = pos && s.value - e > reach;
      neg = neg && s.value + e < -reach;
    }
    return pos || neg;
  };
  if (beyond_delta(pa, vb)) return false;
  const Plane pb = make_plane(b0, b1, b2);
  SideValue va[3] = {side_value(pb, a0), side_value(pb, a1), side_value(pb, a2)};
  if (beyond_delta(pb, va)) return false;

  if (intersect_core(pa, pb, va, vb, point)) {
    if (distance != nullptr) *distance = 0;
    return true;
  }
  const Vec3* A[3] = {&a0, &a1, &a2};
  const Vec3* B[3] = {&b0, &b1, &b2};
  Vec3 ca, cb;
  const Scalar d = std::sqrt(disjoint_distance_squared(A, B, ca, cb));
  if (!(d <= delta)) return false;
  if (point != nullptr) *point = (ca + cb) / 2;
  if (distance != nullptr) *distance = d;
  return true;
}

}  // namespace antcd::geometry
