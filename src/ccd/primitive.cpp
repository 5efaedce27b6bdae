// Primitive CCD (vertex–face, edge–edge): inclusion-based root finding on the multilinear
// function F(t, u, v), see antcd/ccd.hpp for the definitions and guarantees.
//
// Rounding bound. Let M be the largest absolute coordinate of the 8 input points and u = 2^-53.
// Parameters t, u, v are dyadic fractions from bisecting [0, 1], hence exact doubles in [0, 1].
// One corner value is computed as (per axis, vertex–face; edge–edge has fewer operations):
//   d = x1 - x0 (once)          error <= 2uM
//   P = x0 + t * d              error <= 2uM + u|t d| + u|P|            <= 5.1 uM, |P| <= 1.01M
//   D = P1 - P0, s * D (s <= 1) error <= 2 * 5.1uM + u 2M + u 2M        <= 14.2 uM
//   S1 = P0 + s D1              error <= 5.1uM + 14.2uM + u 3M          <= 22.3 uM
//   S2 = S1 + w D2              error <= 22.3uM + 14.2uM + u 5M         <= 41.5 uM
//   F = Pv - S2                 error <= 5.1uM + 41.5uM + u 6M          <= 52.6 uM
// (first order; the second-order terms are below 1e-14 of these). kErrorFactor = 96 covers that
// with room; DBL_MIN covers gradual underflow in the products (each at most 2^-1075 off).
// The true F over a parameter box lies within [min corner - eps, max corner + eps] per axis
// because F is multilinear (affine in each parameter separately), so its extremes over the box
// are at corners.
#include <antcd/ccd.hpp>
#include <antcd/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "util/check.hpp"

namespace antcd::ccd {
namespace {

constexpr Scalar kUnitRoundoff = std::numeric_limits<Scalar>::epsilon() / 2;
constexpr Scalar kErrorFactor = 96;
/// Parameter boxes are not bisected below this width in u or v, nor in t (so the depth, and the
/// stack below, stay bounded); a box that cannot be split further is accepted (tolerance).
constexpr Scalar kMinWidth = 0x1p-50;

enum class Kind { VertexFace, EdgeEdge };

struct Box {
  Scalar t0, t1, u0, u1, v0, v1;
};

/// The moving primitives: corner k at time t is x0[k] + t * d[k].
struct Motion {
  std::array<Vec3, 4> x0;
  std::array<Vec3, 4> d;
};

void check_input(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                 Scalar min_separation, Scalar time_tolerance, const char* function) {
  for (int k = 0; k < 4; ++k) {
    if (!at_t0[static_cast<std::size_t>(k)].allFinite()) {
      throw ArgumentError(std::string(function) + ": at_t0[" + std::to_string(k) +
                          "] is not finite");
    }
    if (!at_t1[static_cast<std::size_t>(k)].allFinite()) {
      throw ArgumentError(std::string(function) + ": at_t1[" + std::to_string(k) +
                          "] is not finite");
    }
  }
  detail::require_non_negative(function, "min_separation", min_separation);
  detail::require_positive(function, "time_tolerance", time_tolerance);
}

/// F at parameters (u, v) from the corner positions p at one time.
template <Kind kKind>
inline Vec3 evaluate(const std::array<Vec3, 4>& p, Scalar u, Scalar v) {
  if constexpr (kKind == Kind::VertexFace) {
    const Vec3 s1 = p[1] + u * (p[2] - p[1]);
    const Vec3 s2 = s1 + v * (p[3] - p[1]);
    return p[0] - s2;
  } else {
    const Vec3 a = p[0] + u * (p[1] - p[0]);
    const Vec3 b = p[2] + v * (p[3] - p[2]);
    return a - b;
  }
}

inline std::array<Vec3, 4> positions(const Motion& m, Scalar t) {
  return {m.x0[0] + t * m.d[0], m.x0[1] + t * m.d[1], m.x0[2] + t * m.d[2], m.x0[3] + t * m.d[3]};
}

template <Kind kKind>
PrimitiveResult solve(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                      Scalar min_separation, Scalar time_tolerance) {
  Motion m;
  Scalar max_coord = 0;
  Scalar max_move = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    m.x0[k] = at_t0[k];
    m.d[k] = at_t1[k] - at_t0[k];
    max_coord =
        std::max({max_coord, at_t0[k].cwiseAbs().maxCoeff(), at_t1[k].cwiseAbs().maxCoeff()});
    max_move = std::max(max_move, m.d[k].cwiseAbs().maxCoeff());
  }
  const Scalar eps = kErrorFactor * kUnitRoundoff * max_coord + std::numeric_limits<Scalar>::min();
  // Inclusion test bound per axis, rounded up.
  const Scalar bound = (min_separation + eps) * (1 + 4 * kUnitRoundoff);
  // Spatial acceptance width: the tolerance's motion (two primitives moving against each other),
  // never below the rounding (else a resting contact would be bisected until the budget ends).
  const Scalar accept_width = std::max(time_tolerance * 2 * max_move, 4 * eps);
  const Scalar min_t_width = std::max(time_tolerance, kMinWidth);
  // |dF/du| and |dF/dv| (infinity norm) over the whole domain: the edges F is affine along, at
  // their longest over t (they change linearly in t, so at t = 0 or 1). u or v narrower than
  // tol_u / tol_v moves F by at most accept_width.
  const std::size_t iu0 = kKind == Kind::VertexFace ? 1 : 0;
  const std::size_t iu1 = kKind == Kind::VertexFace ? 2 : 1;
  const std::size_t iv0 = kKind == Kind::VertexFace ? 1 : 2;
  const std::size_t iv1 = 3;
  const Scalar lu = std::max((at_t0[iu1] - at_t0[iu0]).cwiseAbs().maxCoeff(),
                             (at_t1[iu1] - at_t1[iu0]).cwiseAbs().maxCoeff());
  const Scalar lv = std::max((at_t0[iv1] - at_t0[iv0]).cwiseAbs().maxCoeff(),
                             (at_t1[iv1] - at_t1[iv0]).cwiseAbs().maxCoeff());
  constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
  const Scalar tol_u = lu > 0 ? std::max(accept_width / lu, kMinWidth) : kInf;
  const Scalar tol_v = lv > 0 ? std::max(accept_width / lv, kMinWidth) : kInf;

  PrimitiveResult result;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  bool best_proven = false;

  std::array<Box, 256> stack;  // depth <= log2(1/kMinWidth) per parameter: 150 < 256
  std::size_t top = 0;
  stack[top++] = {0, 1, 0, 1, 0, 1};
  while (top > 0) {
    Box box = stack[--top];
    if (box.t0 >= best) continue;
    // Only times before the best hit so far matter: clip the window (children still cover it,
    // whatever the rounding of their midpoints, and F is evaluated at the very doubles used).
    box.t1 = std::min(box.t1, best);
    if (result.boxes >= kMaxBoxes) {
      Scalar earliest = box.t0;
      for (std::size_t i = 0; i < top; ++i) earliest = std::min(earliest, stack[i].t0);
      best = std::min(best, earliest);
      best_proven = false;
      result.budget_exhausted = true;
      break;
    }
    ++result.boxes;
    if constexpr (kKind == Kind::VertexFace) {
      if (box.u0 + box.v0 > 1) continue;  // outside the triangle (rounding only lowers the sum)
    }
    const std::array<Vec3, 4> p0 = positions(m, box.t0);
    const std::array<Vec3, 4> p1 = positions(m, box.t1);
    // Corners indexed by bits (t, u, v).
    std::array<Vec3, 8> f;
    for (int c = 0; c < 8; ++c) {
      const auto& p = (c & 4) ? p1 : p0;
      f[static_cast<std::size_t>(c)] =
          evaluate<kKind>(p, (c & 2) ? box.u1 : box.u0, (c & 1) ? box.v1 : box.v0);
    }
    Vec3 lo = f[0];
    Vec3 hi = f[0];
    for (std::size_t c = 1; c < 8; ++c) {
      lo = lo.cwiseMin(f[c]);
      hi = hi.cwiseMax(f[c]);
    }
    if ((lo.array() > bound).any() || (hi.array() < -bound).any()) continue;  // excluded

    // Per axis: settled when the inclusion lies within the separation (every point of the box is
    // that close on this axis) or is at most accept_width wide.
    const Vec3 inner = Vec3::Constant(min_separation) - Vec3::Constant(eps);
    const Eigen::Array<bool, 3, 1> contained =
        (lo.array() >= -inner.array()) && (hi.array() <= inner.array());
    const Eigen::Array<bool, 3, 1> unsettled = !contained && ((hi - lo).array() > accept_width);
    const bool t_small = box.t1 - box.t0 <= min_t_width;
    if ((t_small && !unsettled.any()) || contained.all()) {
      // Accepted at its earliest time. Proven when a corner at t0 inside the parameter domain is
      // within min_separation even after its rounding (Euclidean norm, rounded up generously).
      bool proven = false;
      for (std::size_t c = 0; c < 4; ++c) {
        const Scalar u = (c & 2) ? box.u1 : box.u0;
        const Scalar v = (c & 1) ? box.v1 : box.v0;
        if (kKind == Kind::VertexFace && u + v > 1) continue;
        if (f[c].norm() * (1 + 8 * kUnitRoundoff) + 2 * eps <= min_separation) proven = true;
      }
      best = box.t0;
      best_proven = proven;
      continue;
    }
    // Split the parameter widest relative to its tolerance: t while the window is longer than
    // the time tolerance, u and v while they can still move F by more than accept_width.
    Scalar st = t_small ? -1 : (box.t1 - box.t0) / min_t_width;
    const Scalar su = box.u1 - box.u0 > tol_u ? (box.u1 - box.u0) / tol_u : -1;
    const Scalar sv = box.v1 - box.v0 > tol_v ? (box.v1 - box.v0) / tol_v : -1;
    if (!unsettled.any()) st = 1;      // F is settled on this box but the window is too long
    if (st < 0 && su < 0 && sv < 0) {  // every parameter at its tolerance: accept
      best = box.t0;
      best_proven = false;
      continue;
    }
    const Scalar ct = unsettled.any() ? st : 1;
    const Scalar cu = unsettled.any() ? su : -1;
    const Scalar cv = unsettled.any() ? sv : -1;
    Box first = box;
    Box second = box;  // the child explored first (earlier time when splitting t)
    if (ct >= cu && ct >= cv) {
      const Scalar mid = box.t0 + (box.t1 - box.t0) / 2;
      second.t1 = mid;
      first.t0 = mid;
    } else if (cu >= cv) {
      const Scalar mid = box.u0 + (box.u1 - box.u0) / 2;
      second.u1 = mid;
      first.u0 = mid;
    } else {
      const Scalar mid = box.v0 + (box.v1 - box.v0) / 2;
      second.v1 = mid;
      first.v0 = mid;
    }
    stack[top++] = first;
    stack[top++] = second;
  }
  if (best <= 1) {
    result.hit = true;
    result.toi = best;
    result.tolerance_decided = !best_proven;
  }
  return result;
}

}  // namespace

PrimitiveResult vertex_face(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                            Scalar min_separation, Scalar time_tolerance) {
  check_input(at_t0, at_t1, min_separation, time_tolerance, "ccd::vertex_face");
  return solve<Kind::VertexFace>(at_t0, at_t1, min_separation, time_tolerance);
}

PrimitiveResult edge_edge(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                          Scalar min_separation, Scalar time_tolerance) {
  check_input(at_t0, at_t1, min_separation, time_tolerance, "ccd::edge_edge");
  return solve<Kind::EdgeEdge>(at_t0, at_t1, min_separation, time_tolerance);
}

Transform interpolate_pose(const Transform& p0, const Transform& p1, Scalar t) {
  if (t == 0) return p0;  // the frame poses themselves, bit for bit
  if (t == 1) return p1;
  const Quat q0(p0.rotation);
  const Quat q1(p1.rotation);
  Transform out;
  out.rotation = q0.slerp(t, q1).toRotationMatrix();
  out.translation = (1 - t) * p0.translation + t * p1.translation;
  return out;
}

}  // namespace antcd::ccd
