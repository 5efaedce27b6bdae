// The exact verdict on one triangle pair under the sharing rule of antcd/self.hpp.
//
// Why each case is exact (A, B non-degenerate closed triangles):
// - One shared vertex v. A ∩ B is convex and holds v. If it holds another point, it holds a
//   segment from v, and the largest such segment ends on the boundary of A or of B away from v:
//   on the edge of A opposite v (a chord of A from its corner v ends there) or on the edge of B
//   opposite v. Conversely a point of A's opposite edge in B is not v (A has non-zero area), so
//   the pair meets beyond v exactly when one opposite edge meets the other triangle.
// - One shared edge uv. Not coplanar: the planes meet in the line uv, and each triangle meets
//   that line in uv exactly, so A ∩ B = uv. Coplanar: the triangles are the two sides of uv
//   (A ∩ B = uv) or overlap near uv, as their third vertices lie on opposite or the same side of
//   uv in the plane. The side test is a 2-D orientation in a coordinate plane where A's
//   projection has non-zero area (one exists, decided exactly), which keeps every side.
// - Three shared vertices: the same point set twice.
//
// Floating-point certificates in front (no exact arithmetic; each applies only when the error
// bounds of its orientations prove their signs, and then its verdict is the exact one). Let P
// drop one coordinate axis, so that P is linear and P(A), P(B) are the projected triangles.
// - Shared edge uv, free corners p of A and q of B: if orient2d(u, v, p) and orient2d(u, v, q)
//   in P are both nonzero with opposite signs, then P is one-to-one on A and on B, and P(A),
//   P(B) lie on opposite closed sides of the line through P(u), P(v), meeting in P(uv) only. A
//   point x of both has P(x) on P(uv), so x (in A, P one-to-one on A) is on uv: A ∩ B = uv. Else
//   if orient3d(u, v, p, q) is proved nonzero the pair is not coplanar: A ∩ B = uv.
// - Shared vertex w, A = (w, a1, a2), B = (w, b1, b2): A ∩ B holds a point x other than w iff
//   the wedges W_A = {s(a1 - w) + t(a2 - w) : s, t >= 0} and W_B meet beyond 0 (x - w is in
//   both; conversely e d is in A - w and B - w for a common d and small e > 0). If in P both
//   triangles have nonzero orientation and the line through P(w) along one of the four edges at
//   w has the other edge at w of its own triangle on one side and both free corners of the other
//   triangle strictly on the other side, P(W_A) and P(W_B) meet in 0 only; a common d then has
//   P(d) = 0, which for d != 0 in W_A would make P(a1 - w), P(a2 - w) dependent, that is
//   orient2d(w, a1, a2) = 0: so A ∩ B = {w}. With the four signs c_kl of orient2d(w, a_k, b_l)
//   and s_A, s_B the triangles' own: the ray w-a1 separates when c_11 = c_12 = -s_A, w-a2 when
//   c_21 = c_22 = s_A, w-b1 when c_11 = c_21 = s_B, w-b2 when c_12 = c_22 = -s_B.
// Both use the projection along the dominant axis of A's floating-point normal (any axis would be
// correct; that one keeps near-flat neighbourhoods far from the bounds).
#include "self/pair_test.hpp"

#include <antcd/geometry.hpp>

#include "geometry/intersection.hpp"
#include "geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace antcd::self_detail {

using geometry::detail::orient2d;
using geometry::detail::orient2d_sign_if_certain;
using geometry::detail::Projection;
using geometry::detail::sign_of;

std::uint8_t normal_signs(const Vec3& a, const Vec3& b, const Vec3& c, int* axis) {
  // Dropping axis k leaves the cyclic pair (k+1, k+2): the 2-D orientation is n_k. Signs the
  // floating-point filter proves first; the exact ones only when it proves none (a flat sheet's
  // tiny tangential components would otherwise run the expansions for every triangle).
  int s[3];
  double n[3];
  for (int k = 0; k < 3; ++k) {
    const geometry::detail::Filtered f = geometry::detail::orient2d_float(a, b, c, Projection(k));
    const double bound = geometry::detail::kOrient2dBound * f.perm;
    s[k] = (f.value > bound) - (-f.value > bound);  // orient2d_sign_if_certain
    n[k] = f.value;  // (b - a) x (c - a), component k, as certificate_axis computes it
  }
  if (axis != nullptr) *axis = geometry::detail::dominant_axis(Vec3(n[0], n[1], n[2]));
  if (s[0] == 0 && s[1] == 0 && s[2] == 0) {
    for (int k = 0; k < 3; ++k) s[k] = sign_of(orient2d(a, b, c, Projection(k)));
  }
  std::uint8_t bits = 0;
  for (int k = 0; k < 3; ++k) {
    if (s[k] > 0) bits = static_cast<std::uint8_t>(bits | (1u << (2 * k)));
    if (s[k] < 0) bits = static_cast<std::uint8_t>(bits | (1u << (2 * k + 1)));
  }
  return bits;
}

namespace {

/// The two coordinates a projection dropping one axis keeps (Projection's u, v), as a table.
struct Kept {
  int u;
  int v;
};
constexpr Kept kKept[3] = {{1, 2}, {2, 0}, {0, 1}};

/// x - w in the kept coordinates.
struct Offset {
  double u;
  double v;
};
Offset offset(const Vec3& x, const Vec3& w, Kept k) { return {x[k.u] - w[k.u], x[k.v] - w[k.v]}; }

/// orient2d_sign_if_certain(w, x, y) from dx = x - w and dy = y - w: the same floating-point
/// operations (so the same value and bound), the differences found once for several signs.
int certain_sign(Offset dx, Offset dy) {
  const double left = dx.u * dy.v;
  const double right = dx.v * dy.u;
  const double value = left - right;
  const double bound = geometry::detail::kOrient2dBound * (std::abs(left) + std::abs(right));
  return (value > bound) - (-value > bound);
}

/// Triangles (u, v, p) and (u, v, q) sharing the edge uv: proved to meet in uv only by the
/// floating-point certificates of the header (false: not proved).
bool edge_pair_apart_certified(const Vec3& u, const Vec3& v, const Vec3& p, const Vec3& q, Kept k) {
  const Offset e = offset(v, u, k);
  if (certain_sign(e, offset(p, u, k)) * certain_sign(e, offset(q, u, k)) < 0) return true;
  return geometry::detail::orient3d_sign_if_certain(u, v, p, q) != 0;
}

/// Triangles (w, a1, a2) and (w, b1, b2) sharing the vertex w: proved to meet in w only by the
/// wedge certificate of the header (false: not proved).
bool vertex_pair_apart_certified(const Vec3& w, const Vec3& a1, const Vec3& a2, const Vec3& b1,
                                 const Vec3& b2, Kept k) {
  const Offset da1 = offset(a1, w, k), da2 = offset(a2, w, k);
  const int sa = certain_sign(da1, da2);
  if (sa == 0) return false;
  const Offset db1 = offset(b1, w, k), db2 = offset(b2, w, k);
  const int sb = certain_sign(db1, db2);
  if (sb == 0) return false;
  const int c11 = certain_sign(da1, db1);
  const int c12 = certain_sign(da1, db2);
  if (c11 == -sa && c12 == -sa) return true;
  const int c21 = certain_sign(da2, db1);
  if (c11 == sb && c21 == sb) return true;
  const int c22 = certain_sign(da2, db2);
  return (c21 == sa && c22 == sa) || (c12 == -sb && c22 == -sb);
}

/// Triangles (u, v, p) and (u, v, q) sharing the edge uv: folded flat onto each other.
bool folded_flat(const Vec3& u, const Vec3& v, const Vec3& p, const Vec3& q) {
  if (geometry::orient3d(u, v, p, q) != 0) return false;
  for (int k = 0; k < 3; ++k) {
    const Projection pr(k);
    const int sp = sign_of(orient2d(u, v, p, pr));
    if (sp == 0) continue;  // this projection flattens the plane
    return sp == sign_of(orient2d(u, v, q, pr));
  }
  return false;  // unreachable for a triangle of non-zero area
}

/// The closed boxes of the point sets are disjoint: exact comparisons, a filter in front of the
/// exact tests (sets in disjoint boxes cannot meet).
bool boxes_apart(std::initializer_list<const Vec3*> a, std::initializer_list<const Vec3*> b) {
  for (int k = 0; k < 3; ++k) {
    double alo = (*a.begin())->coeff(k), ahi = alo, blo = (*b.begin())->coeff(k), bhi = blo;
    for (const Vec3* p : a) {
      alo = std::min(alo, p->coeff(k));
      ahi = std::max(ahi, p->coeff(k));
    }
    for (const Vec3* p : b) {
      blo = std::min(blo, p->coeff(k));
      bhi = std::max(bhi, p->coeff(k));
    }
    if (ahi < blo || bhi < alo) return true;
  }
  return false;
}

}  // namespace

int certificate_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  return geometry::detail::dominant_axis((b - a).cross(c - a));
}

bool pair_intersects(const Mesh& mesh, std::uint32_t i, std::uint32_t j, int& shared,
                     PairHint hint) {
  return pair_intersects(mesh, mesh.triangles[i], mesh.triangles[j], shared, hint);
}

bool pair_intersects(const Mesh& mesh, const TriangleIndices& ti, const TriangleIndices& tj,
                     int& shared, PairHint hint) {
  const auto& v = mesh.vertices;
  // Corners twice over, so that A[a], A[a + 1], A[a + 2] is a rotation of the triangle.
  const Vec3* A[5] = {&v[ti[0]], &v[ti[1]], &v[ti[2]], &v[ti[0]], &v[ti[1]]};
  const Vec3* B[5] = {&v[tj[0]], &v[tj[1]], &v[tj[2]], &v[tj[0]], &v[tj[1]]};
  int ai[3], bj[3];
  shared = 0;
  for (int a = 0; a < 3; ++a) {
    const std::uint32_t x = ti[static_cast<std::size_t>(a)];
    const int b = x == tj[0] ? 0 : x == tj[1] ? 1 : x == tj[2] ? 2 : -1;
    if (b >= 0) {
      ai[shared] = a;
      bj[shared] = b;
      ++shared;
    }
  }
  if (shared == 0) {
    if (!hint.boxes_tested && boxes_apart({A[0], A[1], A[2]}, {B[0], B[1], B[2]})) return false;
    return geometry::triangles_intersect(*A[0], *A[1], *A[2], *B[0], *B[1], *B[2]);
  }
  if (shared == 3) return true;
  const Kept pr = kKept[hint.axis >= 0 ? hint.axis : certificate_axis(*A[0], *A[1], *A[2])];
  if (shared == 1) {
    const int a = ai[0], b = bj[0];
    if (vertex_pair_apart_certified(*A[a], *A[a + 1], *A[a + 2], *B[b + 1], *B[b + 2], pr)) {
      return false;
    }
    const auto edge_meets = [](const Vec3& p, const Vec3& q, const Vec3& t0, const Vec3& t1,
                               const Vec3& t2) {
      return !boxes_apart({&p, &q}, {&t0, &t1, &t2}) &&
             geometry::detail::segment_meets_triangle(p, q, t0, t1, t2);
    };
    return edge_meets(*A[a + 1], *A[a + 2], *B[0], *B[1], *B[2]) ||
           edge_meets(*B[b + 1], *B[b + 2], *A[0], *A[1], *A[2]);
  }
  // The unshared corners: the one index of each triangle not matched.
  const Vec3& p = *A[3 - ai[0] - ai[1]];
  const Vec3& q = *B[3 - bj[0] - bj[1]];
  if (edge_pair_apart_certified(*A[ai[0]], *A[ai[1]], p, q, pr)) return false;
  return folded_flat(*A[ai[0]], *A[ai[1]], p, q);
}

}  // namespace antcd::self_detail
