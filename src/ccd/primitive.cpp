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
//
// Order of work:
// 1. The inclusion of the whole domain [0, 1]^3: far-apart queries end here.
// min_separation == 0:
// 2. The coplanarity cubic (ccd/primitive_cubic.hpp, certified Bernstein signs): the times where
//    it is certifiably nonzero hold no contact; it is split down to windows of min_t_width.
// 3. Per window, earliest first: accept_at checks F at the guessed nearest parameters at the
//    window's start (a contact within the window leaves the primitives within W there); if that
//    does not decide, the window search below runs on the window alone (and on the rest of
//    [0, 1] where the cubic may vanish all along: motion in one plane, or after 8 windows).
// The window search (search_separated; alone when min_separation > 0): time windows, earliest
// first, are certified apart by a separating direction over the whole window, or accepted at
// their start (a contact proven there; or, once the time tolerance wide, Euclidean distance
// within min_separation + 2W there), or halved; a window of min_t_width that is none of these
// gets the inclusion search.
// Conservative throughout: every time before the answer is excluded by a certified sign, an
// excluded box or a certified separating direction, and an accepted time has the primitives within
// 2W (+ rounding) per axis.
#include <antcd/ccd.hpp>
#include <antcd/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "ccd/primitive_cubic.hpp"
#include "ccd/primitive_unchecked.hpp"
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

/// Per-query constants of the inclusion search.
struct Setup {
  Motion m;
  Scalar min_separation = 0;
  Scalar eps = 0;           ///< rounding bound of one evaluation of F (per axis)
  Scalar bound = 0;         ///< inclusion test bound per axis, rounded up
  Scalar accept_width = 0;  ///< W: the tolerance's motion, never below the rounding
  Scalar min_t_width = 0;
  Scalar tol_u = 0, tol_v = 0;
  std::uint32_t max_boxes = kMaxBoxes;  ///< the box budget (>= 1)
};

/// The earliest accepted time so far (infinity: none) and whether it is proven.
struct Best {
  Scalar t = std::numeric_limits<Scalar>::infinity();
  bool proven = false;
};

template <Kind kKind>
Setup make_setup(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                 Scalar min_separation, Scalar time_tolerance, std::uint32_t max_boxes) {
  Setup s;
  s.max_boxes = max_boxes;
  Scalar max_coord = 0;
  Scalar max_move = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    s.m.x0[k] = at_t0[k];
    s.m.d[k] = at_t1[k] - at_t0[k];
    max_coord =
        std::max({max_coord, at_t0[k].cwiseAbs().maxCoeff(), at_t1[k].cwiseAbs().maxCoeff()});
    max_move = std::max(max_move, s.m.d[k].cwiseAbs().maxCoeff());
  }
  s.min_separation = min_separation;
  s.eps = kErrorFactor * kUnitRoundoff * max_coord + std::numeric_limits<Scalar>::min();
  s.bound = (min_separation + s.eps) * (1 + 4 * kUnitRoundoff);
  // Spatial acceptance width: the tolerance's motion (two primitives moving against each other),
  // never below the rounding (else a resting contact would be bisected until the budget ends).
  s.accept_width = std::max(time_tolerance * 2 * max_move, 4 * s.eps);
  s.min_t_width = std::max(time_tolerance, kMinWidth);
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
  s.tol_u = lu > 0 ? std::max(s.accept_width / lu, kMinWidth) : kInf;
  s.tol_v = lv > 0 ? std::max(s.accept_width / lv, kMinWidth) : kInf;
  return s;
}

/// Whether the corner value f (computed at parameters inside the domain) proves the contact:
/// within min_separation even after its rounding (Euclidean norm, rounded up generously).
inline bool proves_contact(const Setup& s, const Vec3& f) {
  return f.norm() * (1 + 8 * kUnitRoundoff) + 2 * s.eps <= s.min_separation;
}

inline Scalar clamp01(Scalar x) { return std::clamp(x, Scalar(0), Scalar(1)); }

/// Parameter along segment [a, b] of the point nearest to p (0 for a point segment).
inline Scalar nearest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Scalar len2 = ab.squaredNorm();
  return len2 > 0 ? clamp01((p - a).dot(ab) / len2) : 0;
}

/// Face parameters (u, v) of the point of the closed triangle nearest to the vertex, from the
/// positions p at one time: a guess (floating point), but always inside the domain: u, v in
/// [0, 1] and u + v <= 1 exactly.
inline std::array<Scalar, 2> guess_vertex_face(const std::array<Vec3, 4>& p) {
  const Vec3 e1 = p[2] - p[1];
  const Vec3 e2 = p[3] - p[1];
  const Vec3 w = p[0] - p[1];
  const Scalar a = e1.squaredNorm(), b = e1.dot(e2), c = e2.squaredNorm();
  const Scalar det = a * c - b * b;
  if (det > 0) {
    const Scalar u = (c * e1.dot(w) - b * e2.dot(w)) / det;
    const Scalar v = (a * e2.dot(w) - b * e1.dot(w)) / det;
    if (u >= 0 && v >= 0 && u + v < 1) return {u, v};  // < 1 in floating point: <= 1 exactly
  }
  // Outside (or degenerate): the nearest of the three edges' nearest points.
  const Scalar s01 = nearest_on_segment(p[0], p[1], p[2]);
  const Scalar s02 = nearest_on_segment(p[0], p[1], p[3]);
  const Scalar s12 = nearest_on_segment(p[0], p[2], p[3]);
  std::array<Scalar, 2> best = {s01, 0};
  Scalar best_d2 = (w - s01 * e1).squaredNorm();
  if (const Scalar d2 = (w - s02 * e2).squaredNorm(); d2 < best_d2) {
    best = {0, s02};
    best_d2 = d2;
  }
  if (const Scalar d2 = (p[0] - (p[2] + s12 * (p[3] - p[2]))).squaredNorm(); d2 < best_d2) {
    // u = 1 - s, v = s with u + v == 1 exactly: 1 - x is exact for x in [1/2, 1] (Sterbenz).
    if (s12 >= 0.5) {
      best = {1 - s12, s12};
    } else {
      const Scalar u = 1 - s12;
      best = {u, 1 - u};
    }
  }
  return best;
}

/// Edge parameters (u on edge a, v on edge b) of a nearest pair of the closed segments, from the
/// positions p at one time: a guess (floating point), clamped to [0, 1]^2.
inline std::array<Scalar, 2> guess_edge_edge(const std::array<Vec3, 4>& p) {
  const Vec3 da = p[1] - p[0];
  const Vec3 db = p[3] - p[2];
  const Vec3 r = p[0] - p[2];
  const Scalar a = da.squaredNorm(), b = da.dot(db), c = db.squaredNorm();
  const Scalar d = da.dot(r), e = db.dot(r);
  const Scalar det = a * c - b * b;
  // Parallel or degenerate (det 0): b0's nearest point on edge a.
  Scalar u = det > 0 ? clamp01((b * e - c * d) / det) : (a > 0 ? clamp01(-d / a) : 0);
  Scalar v = c > 0 ? (b * u + e) / c : 0;
  if (v < 0 || v > 1) {  // clamp v, then the best u for it
    v = clamp01(v);
    u = a > 0 ? clamp01((b * v - d) / a) : 0;
  }
  return {u, clamp01(v)};
}

/// Direct check at the start of a coplanarity window: F at the guessed nearest parameters. When
/// |F| <= 2W per axis (after its rounding), the primitives are that close at time t, which the
/// tolerance-decided guarantee allows (<= 3W): accept t (proven when F proves it). Otherwise
/// nothing is decided.
template <Kind kKind>
bool accept_at(const Setup& s, Scalar t, Best& best) {
  const std::array<Vec3, 4> p = positions(s.m, t);
  const std::array<Scalar, 2> uv =
      kKind == Kind::VertexFace ? guess_vertex_face(p) : guess_edge_edge(p);
  const Vec3 f = evaluate<kKind>(p, uv[0], uv[1]);
  const Scalar reach = (f.cwiseAbs().maxCoeff() + s.eps) * (1 + 4 * kUnitRoundoff);
  if (!(reach <= s.min_separation + 2 * s.accept_width)) return false;
  best = {t, proves_contact(s, f)};
  return true;
}

/// F at the box's 8 corners, indexed by bits (t, u, v), and their per-axis range.
template <Kind kKind>
inline void corner_values(const Setup& s, const Box& box, std::array<Vec3, 8>& f, Vec3& lo,
                          Vec3& hi) {
  const std::array<Vec3, 4> p0 = positions(s.m, box.t0);
  const std::array<Vec3, 4> p1 = positions(s.m, box.t1);
  for (int c = 0; c < 8; ++c) {
    const auto& p = (c & 4) ? p1 : p0;
    f[static_cast<std::size_t>(c)] =
        evaluate<kKind>(p, (c & 2) ? box.u1 : box.u0, (c & 1) ? box.v1 : box.v0);
  }
  lo = f[0];
  hi = f[0];
  for (std::size_t c = 1; c < 8; ++c) {
    lo = lo.cwiseMin(f[c]);
    hi = hi.cwiseMax(f[c]);
  }
}

/// The inclusion [lo - bound, hi + bound] misses the origin on some axis: no contact in the box.
inline bool excludes(const Setup& s, const Vec3& lo, const Vec3& hi) {
  return (lo.array() > s.bound).any() || (hi.array() < -s.bound).any();
}

/// Inclusion search over the parameter box `initial` (depth first, earlier times first, windows
/// clipped to the earliest accepted time); updates `best` and the result's box count / budget.
template <Kind kKind>
void search(const Setup& s, const Box& initial, PrimitiveResult& result, Best& best) {
  std::array<Box, 256> stack;  // depth <= log2(1/kMinWidth) per parameter: 150 < 256
  std::size_t top = 0;
  stack[top++] = initial;
  while (top > 0) {
    Box box = stack[--top];
    if (box.t0 >= best.t) continue;
    // Only times before the best hit so far matter: clip the window (children still cover it,
    // whatever the rounding of their midpoints, and F is evaluated at the very doubles used).
    box.t1 = std::min(box.t1, best.t);
    if (result.boxes >= s.max_boxes) {
      Scalar earliest = box.t0;
      for (std::size_t i = 0; i < top; ++i) earliest = std::min(earliest, stack[i].t0);
      best = {std::min(best.t, earliest), false};
      result.budget_exhausted = true;
      return;
    }
    ++result.boxes;
    if constexpr (kKind == Kind::VertexFace) {
      if (box.u0 + box.v0 > 1) continue;  // outside the triangle (rounding only lowers the sum)
    }
    std::array<Vec3, 8> f;
    Vec3 lo;
    Vec3 hi;
    corner_values<kKind>(s, box, f, lo, hi);
    if (excludes(s, lo, hi)) continue;

    // Per axis: settled when the inclusion lies within the separation (every point of the box is
    // that close on this axis) or is at most accept_width wide.
    const Vec3 inner = Vec3::Constant(s.min_separation) - Vec3::Constant(s.eps);
    const Eigen::Array<bool, 3, 1> contained =
        (lo.array() >= -inner.array()) && (hi.array() <= inner.array());
    const Eigen::Array<bool, 3, 1> unsettled = !contained && ((hi - lo).array() > s.accept_width);
    const bool t_small = box.t1 - box.t0 <= s.min_t_width;
    if ((t_small && !unsettled.any()) || contained.all()) {
      // Accepted at its earliest time; proven when a corner at t0 inside the domain proves it.
      bool proven = false;
      for (std::size_t c = 0; c < 4; ++c) {
        const Scalar u = (c & 2) ? box.u1 : box.u0;
        const Scalar v = (c & 1) ? box.v1 : box.v0;
        if (kKind == Kind::VertexFace && u + v > 1) continue;
        if (proves_contact(s, f[c])) proven = true;
      }
      best = {box.t0, proven};
      continue;
    }
    // Split the parameter widest relative to its tolerance: t while the window is longer than
    // the time tolerance, u and v while they can still move F by more than accept_width.
    Scalar st = t_small ? -1 : (box.t1 - box.t0) / s.min_t_width;
    const Scalar su = box.u1 - box.u0 > s.tol_u ? (box.u1 - box.u0) / s.tol_u : -1;
    const Scalar sv = box.v1 - box.v0 > s.tol_v ? (box.v1 - box.v0) / s.tol_v : -1;
    if (!unsettled.any()) st = 1;      // F is settled on this box but the window is too long
    if (st < 0 && su < 0 && sv < 0) {  // every parameter at its tolerance: accept
      best = {box.t0, false};
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
}

/// Whether the primitives are certainly farther apart than min_separation (>= 0) over
/// the whole window [t0, t1], using the direction f (F at guessed nearest parameters). For any
/// direction n, dist(A, B) >= (min over A's corners of n.a - max over B's corners of n.b) / |n|
/// (support functions of the two convex primitives; vertex-face: A is the vertex). The corners
/// move linearly, so that bound (a minimum of affine functions of t) is concave in t and its least
/// value over [t0, t1] is at t0 or t1: two evaluations certify the window. Rounding: n is any
/// vector (scaled so its largest component is about 1: no overflow or underflow in its norm); a
/// corner position is within 5.1uM of its true value (the header's bound), so each n.x is within
/// |n|_1 (5.1uM + 3.01u 1.01M) <= 8.2uM |n|_1 and their difference within 16.4uM |n|_1 + u|g|,
/// covered by |n|_1 eps (eps >= 96uM) and 4u|g|; the norm and the product with min_separation
/// are rounded up by 16u. Non-finite values (overflow) never separate.
template <Kind kKind>
bool separated_over(const Setup& s, Scalar t0, Scalar t1, const Vec3& f) {
  const Scalar m = f.cwiseAbs().maxCoeff();
  if (!(m > 0) || !std::isfinite(m)) return false;
  int e = 0;
  static_cast<void>(std::frexp(m, &e));
  const Vec3 n(std::ldexp(f.x(), -e), std::ldexp(f.y(), -e), std::ldexp(f.z(), -e));
  const Scalar l1 = n.cwiseAbs().sum();
  const Scalar need = s.min_separation * n.norm() * (1 + 16 * kUnitRoundoff);
  for (const Scalar t : {t0, t1}) {
    const std::array<Vec3, 4> p = positions(s.m, t);
    Scalar low_a = n.dot(p[0]);
    Scalar high_b = n.dot(p[2]);
    if constexpr (kKind == Kind::VertexFace) {
      high_b = std::max({n.dot(p[1]), high_b, n.dot(p[3])});
    } else {
      low_a = std::min(low_a, n.dot(p[1]));
      high_b = std::max(high_b, n.dot(p[3]));
    }
    const Scalar g = low_a - high_b;
    if (!std::isfinite(g)) return false;
    if (!(g - 4 * kUnitRoundoff * std::abs(g) - l1 * s.eps > need)) return false;
  }
  return true;
}

/// The time-window search over [t_begin, t_end]. With min_separation > 0 the inclusion search
/// alone would have to bisect the shell between the separation's sphere and its cube (F's
/// inclusion is per axis, the separation Euclidean) down to the tolerance, which a grazing
/// approach turns into the whole box budget; with 0, edges moving in one plane 1e-5 apart (the
/// coplanarity cubic vanishes all along) did the same. Instead, time windows
/// (earliest first) are either certified apart by a separating direction (separated_over), or
/// end the search at their start (every earlier time is excluded, so toi <= t*) when a contact is
/// proven there, or, for a window of at most min_t_width, when the primitives are within
/// min_separation + 2W there (Euclidean, after rounding; tolerance-decided), or are halved; a
/// window of min_t_width that is none of these goes to the inclusion search.
template <Kind kKind>
void search_separated(const Setup& s, Scalar t_begin, Scalar t_end, PrimitiveResult& result,
                      Best& best) {
  struct Window {
    Scalar t0, t1;
    bool start_checked;  ///< its start was already checked (a left half shares its parent's)
  };
  std::array<Window, 64> stack;  // windows halve down to min_t_width >= 2^-50
  std::size_t top = 0;
  stack[top++] = {t_begin, t_end, false};
  while (top > 0) {
    const Window w = stack[--top];
    if (result.boxes >= s.max_boxes) {  // the earliest unresolved window is the one popped
      best = {w.t0, false};
      result.budget_exhausted = true;
      return;
    }
    ++result.boxes;
    // Every earlier time is excluded: a contact proven at the window's start is the first.
    if (!w.start_checked) {
      const std::array<Vec3, 4> p = positions(s.m, w.t0);
      const std::array<Scalar, 2> uv =
          kKind == Kind::VertexFace ? guess_vertex_face(p) : guess_edge_edge(p);
      if (proves_contact(s, evaluate<kKind>(p, uv[0], uv[1]))) {
        best = {w.t0, true};
        return;
      }
    }
    const Scalar tm = w.t0 + (w.t1 - w.t0) / 2;
    {
      const std::array<Vec3, 4> p = positions(s.m, tm);
      const std::array<Scalar, 2> uv =
          kKind == Kind::VertexFace ? guess_vertex_face(p) : guess_edge_edge(p);
      if (separated_over<kKind>(s, w.t0, w.t1, evaluate<kKind>(p, uv[0], uv[1]))) continue;
    }
    if (w.t1 - w.t0 <= s.min_t_width) {
      // Not separated in a window of the time tolerance: a hit at its start when the primitives
      // are within min_separation + 2W there (Euclidean, after rounding), else the inclusion
      // search decides the window.
      const std::array<Vec3, 4> p = positions(s.m, w.t0);
      const std::array<Scalar, 2> uv =
          kKind == Kind::VertexFace ? guess_vertex_face(p) : guess_edge_edge(p);
      const Vec3 f = evaluate<kKind>(p, uv[0], uv[1]);
      if (f.norm() * (1 + 8 * kUnitRoundoff) + 2 * s.eps <= s.min_separation + 2 * s.accept_width) {
        best = {w.t0, false};
        return;
      }
      search<kKind>(s, {w.t0, w.t1, 0, 1, 0, 1}, result, best);
      if (best.t <= 1) return;  // every later window starts later
      continue;
    }
    stack[top++] = {tm, w.t1, false};
    stack[top++] = {w.t0, tm, true};
  }
}

/// At most this many coplanarity windows get a search of their own; then one window search covers
/// the rest of [0, 1] (motions coplanar, or nearly, over a long time).
constexpr int kMaxWindows = 8;

/// min_separation == 0: the coplanarity cubic (ccd/primitive_cubic.hpp) excludes every time where
/// it is certifiably nonzero; the windows (<= min_t_width long) where it may vanish are taken in
/// time order: first a direct check at the window's start (accept_at), then the window search
/// (search_separated) on that window alone. Where the cubic may vanish all along (Flat), or after
/// kMaxWindows windows, the window search takes the rest of [0, 1].
template <Kind kKind>
void search_coplanarity_windows(const Setup& s, const coplanar::CubicPiece& whole,
                                PrimitiveResult& result, Best& best) {
  std::array<coplanar::CubicPiece, 64> stack;  // depth <= log2(1 / kMinWidth) = 50
  std::size_t top = 0;
  stack[top++] = whole;
  int windows = 0;
  while (top > 0) {
    const coplanar::CubicPiece piece = stack[--top];
    const coplanar::CubicSign sign = coplanar::classify(piece);
    if (sign == coplanar::CubicSign::Positive || sign == coplanar::CubicSign::Negative) continue;
    const bool window = piece.t1 - piece.t0 <= s.min_t_width;
    if (sign == coplanar::CubicSign::Flat || (window && ++windows > kMaxWindows)) {
      if (accept_at<kKind>(s, piece.t0, best)) return;
      search_separated<kKind>(s, piece.t0, 1, result, best);
      return;
    }
    if (window) {
      if (accept_at<kKind>(s, piece.t0, best)) return;
      search_separated<kKind>(s, piece.t0, piece.t1, result, best);
      if (best.t <= 1) return;  // every later window starts later
      continue;
    }
    coplanar::split(piece, stack[top + 1], stack[top]);  // the earlier half on top
    top += 2;
  }
}

template <Kind kKind>
PrimitiveResult solve(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                      Scalar min_separation, Scalar time_tolerance,
                      std::uint32_t max_boxes = kMaxBoxes) {
  const Setup s = make_setup<kKind>(at_t0, at_t1, min_separation, time_tolerance, max_boxes);
  PrimitiveResult result;
  Best best;
  coplanar::CubicPiece cubic;
  constexpr bool kVf = kKind == Kind::VertexFace;
  constexpr auto kHi = kVf ? coplanar::kVertexFaceHi : coplanar::kEdgeEdgeHi;
  constexpr auto kLo = kVf ? coplanar::kVertexFaceLo : coplanar::kEdgeEdgeLo;
  // The whole domain's inclusion first: it dismisses most far-apart queries at once, before the
  // cubic's 8 determinants.
  const Box whole = {0, 1, 0, 1, 0, 1};
  std::array<Vec3, 8> f;
  Vec3 lo;
  Vec3 hi;
  corner_values<kKind>(s, whole, f, lo, hi);
  if (excludes(s, lo, hi)) {
    result.boxes = 1;
    return result;
  }
  if (min_separation == 0 && coplanar::coplanarity_cubic(at_t0, at_t1, kHi, kLo, cubic)) {
    result.boxes = 1;
    search_coplanarity_windows<kKind>(s, cubic, result, best);
  } else if (min_separation > 0) {
    search_separated<kKind>(s, 0, 1, result, best);
  } else {
    search<kKind>(s, {0, 1, 0, 1, 0, 1}, result, best);
  }
  if (best.t <= 1) {
    result.hit = true;
    result.toi = best.t;
    result.tolerance_decided = !best.proven;
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

PrimitiveResult unchecked::vertex_face(const std::array<Vec3, 4>& at_t0,
                                       const std::array<Vec3, 4>& at_t1, Scalar min_separation,
                                       Scalar time_tolerance, std::uint32_t max_boxes) {
  return solve<Kind::VertexFace>(at_t0, at_t1, min_separation, time_tolerance, max_boxes);
}

PrimitiveResult unchecked::edge_edge(const std::array<Vec3, 4>& at_t0,
                                     const std::array<Vec3, 4>& at_t1, Scalar min_separation,
                                     Scalar time_tolerance, std::uint32_t max_boxes) {
  return solve<Kind::EdgeEdge>(at_t0, at_t1, min_separation, time_tolerance, max_boxes);
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
