// How long two rigidly moving models stay apart across one plane; see plane_step.hpp.
#include "ccd/plane_step.hpp"

#include <antcd/ccd.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccd/motion.hpp"

namespace antcd::ccd {

namespace {

/// The least (sign +1) or the greatest (sign -1) of n . (R p + T) over the model's vertices p at
/// pose `pose` (R, T): sign times the least of sign n . (R p + T).
Scalar extreme(const Model& model, const Transform& pose, const Vec3& n, Scalar sign) {
  const Vec3 u = sign * (pose.rotation.transpose() * n);
  Scalar least = std::numeric_limits<Scalar>::infinity();
  for (const Vec3& p : model.mesh().vertices) least = std::min(least, u.dot(p));
  return sign * (least + sign * n.dot(pose.translation));
}

/// The gap along n at time s between A's least and B's greatest vertex projections.
Scalar gap_at(const RigidPair& m, const Vec3& n, Scalar s) {
  return extreme(m.a, interpolate_pose(m.a0, m.a1, s), n, 1) -
         extreme(m.b, interpolate_pose(m.b0, m.b1, s), n, -1);
}

/// Candidate widths tried after the whole rest of the motion.
constexpr int kSecantTries = 3;
/// Each secant estimate is shortened to this share (an estimate at the crossing itself fails).
constexpr Scalar kSecantShare = 0.95;

}  // namespace

Scalar plane_step(const RigidPair& m, const Vec3& n, Scalar t, Scalar margin, Scalar limit) {
  const Scalar e0 = gap_at(m, n, t) - margin;
  if (!(e0 > 0) || !(limit > 0)) return 0;
  // The chords' stray per unit width squared: theta^2 rho / 8 for each model.
  const Scalar bend =
      tolerance::widened((m.spin_a.theta * m.spin_a.theta * model_reach(m.a, m.spin_a) +
                          m.spin_b.theta * m.spin_b.theta * model_reach(m.b, m.spin_b)) /
                         8);
  Scalar tau = limit;
  for (int k = 0; k <= kSecantTries; ++k) {
    const Scalar sag = tolerance::widened(bend * tau * tau);
    const Scalar e1 = gap_at(m, n, std::min<Scalar>(t + tau, 1)) - margin;
    if (std::min(e0, e1) - sag > 0) return tau;
    // Where the interpolated ends' gap less the stray meets the margin: the linear part's
    // crossing, and the width at which the stray alone would use up e0.
    Scalar next = tau;
    if (e1 - sag < 0) next = std::min(next, tau * e0 / (e0 - (e1 - sag)));
    if (sag > 0) next = std::min(next, tau * std::sqrt(e0 / sag));
    next *= kSecantShare;
    if (!(next > 0) || !(next < tau)) return 0;
    tau = next;
  }
  return 0;
}

}  // namespace antcd::ccd
