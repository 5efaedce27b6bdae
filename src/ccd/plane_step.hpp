// Private: how long two rigidly moving models stay apart across one plane (the mesh sweep's step
// for convex pairs; sweep.cpp).
#pragma once

#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include "ccd/swept_proximity.hpp"

namespace antcd::ccd {

/// A step of the sweep's advancement along one direction: `n` a unit direction (world frame, from
/// B towards A, e.g. the closest points' at time t). Returns tau in [0, limit] such that over
/// [t, t + tau], min over A's vertices of n . a(s) less max over B's vertices of n . b(s) stays
/// above `margin`: the convex hulls of the two vertex sets, hence their surfaces, stay more than
/// `margin` apart over that interval (0 when the vertex sets are not that far apart at t).
///
/// Bound: for a vertex p of A and q of B, f(s) = n . a_p(s) - n . b_q(s) is the difference of two
/// linear terms (the translations) and two sinusoids in s (R_A(s)^T n turns about A's axis at
/// theta_A, ccd::Spin), of amplitudes at most the vertices' distances from the axes, reach(p) and
/// reach(q); so |f''| <= theta_A^2 reach(p) + theta_B^2 reach(q), f stays within tau^2 / 8 of that
/// of its chord over a width tau, and a chord's least value is at one of its ends. The gap is the
/// least f over all pairs (p, q) at each time, so over [t, t + tau] it is at least the lesser of
/// its two end values (each an exact minimum over the vertices) less
/// (theta_A^2 rho_A + theta_B^2 rho_B) tau^2 / 8 (rho = model_reach). Candidate widths: the rest
/// of the motion, then up to three secant estimates of where the ends' gap less that stray meets
/// the margin; the first (longest) proven one is returned. The vertex sets are scanned whole
/// (O(vertices) per width): the caller uses it where the hulls are the surfaces (convex models).
/// Rounding: the caller's margin must hold the arithmetic's allowance; the terms are rounded up.
/// Thread safety: reads its models only. Exported for the tests (tests/ccd/plane_step_test.cpp).
ANTCD_API Scalar plane_step(const RigidPair& m, const Vec3& n, Scalar t, Scalar margin,
                            Scalar limit);

}  // namespace antcd::ccd
