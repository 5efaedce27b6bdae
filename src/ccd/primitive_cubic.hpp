// Private: the coplanarity cubic of primitive CCD (src/ccd/primitive.cpp), a certified filter on
// time for min_separation == 0.
//
// A vertex–face or edge–edge contact at time t needs the four points coplanar:
//   c(t) = det[e1(t), e2(t), e3(t)] = 0,
// vertex–face {p, f0, f1, f2}: e1 = f1 - f0, e2 = f2 - f0, e3 = p - f0 (p = f0 + u e1 + v e2);
// edge–edge {a0, a1, b0, b1}:  e1 = a1 - a0, e2 = b1 - b0, e3 = b0 - a0 (e3 = u e1 - v e2).
// Degenerate primitives (zero-area face, point edge, parallel edges) make c vanish too, so
// "c(t) != 0" always excludes a contact at t.
//
// Each e_k(t) = (1 - t) e_k(0) + t e_k(1) is affine, so c is a cubic whose Bernstein coefficients
// on [0, 1] are averages of the 8 determinants with each e_k taken at t = 0 or t = 1:
//   b_j = (sum over the C(3, j) choices with j vectors at t = 1) / C(3, j).
// Rounding. e_k(0), e_k(1) are single rounded differences of input coordinates (relative error
// <= u = 2^-53 per component), and a determinant is evaluated as a . (b x c): each of its six
// monomials sees three perturbed factors and five roundings, so the computed value is within
// (3u + gamma_5) P <= 8.01 u P of the exact one, P the permanent (sum of the |monomials|). The
// averages add at most 3.01 u P. Every coefficient is therefore within E = 16 u Pmax (+ DBL_MIN
// for gradual underflow) of the exact one, Pmax the largest computed permanent (the margin
// 16 / 11.02 also covers the rounding of the permanent itself).
// Subdivision at the midpoint (de Casteljau, three levels of averages (a + b) / 2) adds at most
// 3u max|b_k| (+ underflow) per level set; the new bound is E (1 + 2^-50) + 8u max|b_k| +
// DBL_MIN, which stays above that after its own rounding.
// The exact cubic on an interval lies in the convex hull of its exact Bernstein coefficients, so:
// all computed coefficients > E  => c > 0 on the whole interval (no contact there); < -E likewise.
#pragma once

#include <antcd/math.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>

namespace antcd::ccd::coplanar {

/// e_k = x[hi[k]] - x[lo[k]] for each kind (see above).
inline constexpr std::array<std::size_t, 3> kVertexFaceHi = {2, 3, 0};
inline constexpr std::array<std::size_t, 3> kVertexFaceLo = {1, 1, 1};
inline constexpr std::array<std::size_t, 3> kEdgeEdgeHi = {1, 3, 2};
inline constexpr std::array<std::size_t, 3> kEdgeEdgeLo = {0, 2, 0};

/// Bernstein coefficients of c on [t0, t1] and a bound on their error (see above).
struct CubicPiece {
  Scalar t0 = 0, t1 = 1;
  std::array<Scalar, 4> b{};
  Scalar error = 0;
};

enum class CubicSign { Positive, Negative, Uncertain, Flat };

/// Certified sign of c on the piece: Positive / Negative (never zero there), Flat (every
/// coefficient is within its error of zero: c may vanish all along), or Uncertain.
inline CubicSign classify(const CubicPiece& piece) {
  const auto [lo, hi] = std::minmax_element(piece.b.begin(), piece.b.end());
  if (*lo > piece.error) return CubicSign::Positive;
  if (*hi < -piece.error) return CubicSign::Negative;
  if (-*lo <= piece.error && *hi <= piece.error) return CubicSign::Flat;
  return CubicSign::Uncertain;
}

/// Determinant a . (b x c) and its permanent (the sum of the absolute monomials).
inline Scalar determinant(const Vec3& a, const Vec3& b, const Vec3& c, Scalar& permanent) {
  const Scalar m0 = b.y() * c.z(), m1 = b.z() * c.y();
  const Scalar m2 = b.z() * c.x(), m3 = b.x() * c.z();
  const Scalar m4 = b.x() * c.y(), m5 = b.y() * c.x();
  permanent = std::abs(a.x()) * (std::abs(m0) + std::abs(m1)) +
              std::abs(a.y()) * (std::abs(m2) + std::abs(m3)) +
              std::abs(a.z()) * (std::abs(m4) + std::abs(m5));
  return a.x() * (m0 - m1) + a.y() * (m2 - m3) + a.z() * (m4 - m5);
}

/// The cubic on [0, 1] from e_k = x[hi[k]] - x[lo[k]] at t = 0 (x0) and t = 1 (x1). Returns false
/// when a coefficient or the bound is not finite (huge coordinates): no filter then.
inline bool coplanarity_cubic(const std::array<Vec3, 4>& x0, const std::array<Vec3, 4>& x1,
                              const std::array<std::size_t, 3>& hi,
                              const std::array<std::size_t, 3>& lo, CubicPiece& out) {
  std::array<std::array<Vec3, 3>, 2> e;  // e[time][k]
  for (std::size_t k = 0; k < 3; ++k) {
    e[0][k] = x0[hi[k]] - x0[lo[k]];
    e[1][k] = x1[hi[k]] - x1[lo[k]];
  }
  std::array<Scalar, 4> sum{};
  Scalar pmax = 0;
  for (unsigned mask = 0; mask < 8; ++mask) {  // bit k: e_k at t = 1
    Scalar p = 0;
    const Scalar d =
        determinant(e[mask & 1u][0], e[(mask >> 1) & 1u][1], e[(mask >> 2) & 1u][2], p);
    sum[static_cast<std::size_t>(std::popcount(mask))] += d;
    pmax = std::max(pmax, p);
  }
  out.t0 = 0;
  out.t1 = 1;
  out.b = {sum[0], sum[1] / 3, sum[2] / 3, sum[3]};
  out.error = 0x1p-49 * pmax + std::numeric_limits<Scalar>::min();
  return std::isfinite(out.error) &&
         std::all_of(out.b.begin(), out.b.end(), [](Scalar x) { return std::isfinite(x); });
}

/// Splits the piece at its (exact, dyadic) midpoint by de Casteljau.
inline void split(const CubicPiece& piece, CubicPiece& left, CubicPiece& right) {
  const auto& b = piece.b;
  const Scalar m01 = (b[0] + b[1]) / 2, m12 = (b[1] + b[2]) / 2, m23 = (b[2] + b[3]) / 2;
  const Scalar m012 = (m01 + m12) / 2, m123 = (m12 + m23) / 2;
  const Scalar mid = (m012 + m123) / 2;
  const Scalar magnitude =
      std::max({std::abs(b[0]), std::abs(b[1]), std::abs(b[2]), std::abs(b[3])});
  const Scalar error =
      piece.error * (1 + 0x1p-50) + 0x1p-50 * magnitude + std::numeric_limits<Scalar>::min();
  const Scalar tm = piece.t0 + (piece.t1 - piece.t0) / 2;
  left = {piece.t0, tm, {b[0], m01, m012, mid}, error};
  right = {tm, piece.t1, {mid, m123, m23, b[3]}, error};
}

}  // namespace antcd::ccd::coplanar
