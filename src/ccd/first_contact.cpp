// The earliest contact of two rigidly moving models, every pair advancing on its own; see
// first_contact.hpp.
#include "ccd/first_contact.hpp"

#include <antcd/geometry.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "ccd/motion.hpp"
#include "distance/node_bound.hpp"  // obb_gap

namespace antcd::ccd {

namespace {

/// One set of points (model frame) against a direction u (the same frame) for pair_step: the
/// largest |p . (u x k)| (k the spin's axis, allowing for its error; |p| where no axis is known)
/// and the largest reach.
struct Lever {
  Scalar lever = 0;
  Scalar reach = 0;
};
Lever lever_of(const Spin& s, const Vec3& u, std::span<const Vec3> points) {
  Lever l;
  if (!s.about_axis) {
    for (const Vec3& p : points) l.reach = std::max(l.reach, p.norm());
    l.lever = l.reach;
    return l;
  }
  const Vec3 e = u.cross(s.axis);
  for (const Vec3& p : points) {
    const Scalar off = s.axis_error * p.cwiseAbs().sum();  // |p| <= |p|_1
    l.lever = std::max(l.lever, std::abs(p.dot(e)) + off);
    l.reach = std::max(l.reach, s.axis.cross(p).norm() + off);
  }
  return l;
}

/// pair_step from the two sets' levers.
Scalar step_of(Scalar gap, const Vec3& n, Scalar n_error, const Vec3& v, const RigidPair& m,
               const Lever& la, const Lever& lb) {
  const Spin& sa = m.spin_a;
  const Spin& sb = m.spin_b;
  const Scalar turning = sa.theta * la.reach + sb.theta * lb.reach;
  const Scalar cap = tolerance::widened(m.speed + turning);
  // Nearer than a few allowances the direction is not known.
  if (!(n_error < 0.5)) return gap / cap;
  const Scalar err = n_error + tolerance::kArithmetic;
  const Scalar along = -n.dot(v) + v.norm() * err;
  const Scalar rate = std::min(cap, tolerance::widened(turning + along));
  const Scalar tangent = rate > 0 ? gap / rate : std::numeric_limits<Scalar>::infinity();
  // Without an axis the lever is the reach: the directional step is never the longer.
  if (!sa.about_axis && !sb.about_axis) return tangent;
  const Scalar r1 =
      along + sa.theta * (la.lever + la.reach * err) + sb.theta * (lb.lever + lb.reach * err);
  const Scalar r1w = r1 + std::abs(r1) * tolerance::kArithmetic;  // rounded up, either sign
  const Scalar r2 =
      tolerance::widened(sa.theta * sa.theta * la.reach + sb.theta * sb.theta * lb.reach);
  Scalar directional = std::numeric_limits<Scalar>::infinity();
  if (r2 > 0) {
    // The positive root of r2 / 2 tau^2 + r1 tau - gap, in the form without cancellation.
    const Scalar root = std::sqrt(r1w * r1w + 2 * r2 * gap);
    directional = r1w > 0 ? 2 * gap / (r1w + root) : (root - r1w) / r2;
  } else if (r1w > 0) {
    directional = gap / r1w;
  }
  return std::max(tangent, directional * (1 - tolerance::kArithmetic));
}

}  // namespace

Scalar pair_step(Scalar gap, const Vec3& n, Scalar n_error, const Vec3& v, const Mat3& b_to_a,
                 const RigidPair& m, std::span<const Vec3> a_points,
                 std::span<const Vec3> b_points) {
  return step_of(gap, n, n_error, v, m, lever_of(m.spin_a, n, a_points),
                 lever_of(m.spin_b, b_to_a.transpose() * n, b_points));
}

namespace {

/// A step of d / rate, rounded down (the allowance covers the sum's rounding).
constexpr Scalar kStepShrink = 1 - 1e-15;
/// Times are rounded down to multiples of 1 / kGrid where a step is longer than that.
constexpr Scalar kGrid = 1 << 14;

/// A rotation at constant angular velocity from q0: q(t) = q0 (cos(t w), sin(t w) u), the
/// shorter arc to q1 (the slerp of ccd::interpolate_pose, up to rounding).
struct Turn {
  Quat q0;
  Vec3 axis = Vec3::Zero();
  Scalar half_angle = 0;

  explicit Turn(const Mat3& r0, const Mat3& r1) {
    const TurnDelta d = turn_delta(r0, r1);
    q0 = d.q0;
    const Scalar s = d.delta.vec().norm();
    if (s > 0) {
      axis = d.delta.vec() / s;
      half_angle = std::atan2(s, d.delta.w());
    }
  }
  [[nodiscard]] Quat at(Scalar t) const {
    if (half_angle == 0) return q0;
    const Scalar a = t * half_angle;
    const Scalar s = std::sin(a);
    Quat d;
    d.w() = std::cos(a);
    d.vec() = s * axis;
    return q0 * d;
  }
};

enum class Kind : std::uint8_t { nodes, triangles };
/// A node pair (indices into the node arrays) or a triangle pair (leaf triangle indices) known
/// to stay apart before t.
struct Entry {
  Scalar t;
  std::uint32_t a, b;
  Kind kind;
  std::uint8_t steps = 0;  ///< advancement steps of the pair so far (capped at 255)
};

/// The pair queues of a search: kept per thread (first_contact), so that a sweep's traversals
/// allocate only when they outgrow every earlier one on that thread.
struct Queues {
  std::vector<Entry> heap;
  std::vector<Entry> local;  ///< the pairs opened at the current time
  /// Capacity kept between searches (entries); a queue that grew beyond it is freed after use.
  static constexpr std::size_t kKept = 1 << 16;
  void release_oversized() {
    if (heap.capacity() > kKept) std::vector<Entry>().swap(heap);
    if (local.capacity() > kKept) std::vector<Entry>().swap(local);
  }
};

/// Work of one search; entries are examined earliest first.
class Search {
 public:
  Search(const RigidPair& m, Scalar separation, Scalar allowance, Scalar volume, Scalar stop_gap,
         const FirstContactLimits& limits, Queues& queues)
      : m_(m),
        turn_a_(m.a0.rotation, m.a1.rotation),
        turn_b_(m.b0.rotation, m.b1.rotation),
        v_((m.a1.translation - m.a0.translation) - (m.b1.translation - m.b0.translation)),
        triangle_margin_(separation + allowance),
        node_margin_(separation + allowance + volume),
        separation_(separation),
        allowance_(allowance),
        stop_gap_(stop_gap),
        limits_(limits),
        nodes_a_(m.a.nodes()),
        nodes_b_(m.b.nodes()),
        corners_a_(m.a.leaf_corners()),
        corners_b_(m.b.leaf_corners()),
        queues_(queues) {
    // The thread's queues move in for the search and back out after it (members, not
    // references: the hot loop then reads them without an indirection).
    heap_.swap(queues.heap);
    local_.swap(queues.local);
  }
  ~Search() {
    heap_.swap(queues_.heap);
    local_.swap(queues_.local);
  }
  Search(const Search&) = delete;
  Search& operator=(const Search&) = delete;

  FirstContact run(Scalar t0) {
    heap_.clear();
    local_.clear();
    heap_.push_back({t0, 0, 0, Kind::nodes, 0});
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), Later{});
      const Entry e = heap_.back();
      heap_.pop_back();
      // Every pair still to examine stays apart until at least e.t. The pairs that e opens at
      // e.t are examined at once, with e's frame (a local depth-first walk).
      const Frame f = frame_at(e.t);
      local_.clear();
      local_.push_back(e);
      // Pairs queued at the same time (see advance) share the frame.
      while (!heap_.empty() && heap_.front().t == e.t) {
        std::pop_heap(heap_.begin(), heap_.end(), Later{});
        local_.push_back(heap_.back());
        heap_.pop_back();
      }
      while (!local_.empty()) {
        const Entry x = local_.back();
        local_.pop_back();
        if (++result_.pairs > limits_.pairs) {
          result_ = {};
          result_.outcome = FirstContact::Outcome::gave_up;
          result_.toi = e.t;  // every pair still queued stays apart until then
          return result_;
        }
        if (x.kind == Kind::nodes) {
          nodes(x, f);
        } else if (triangles(x, f)) {
          return result_;
        }
      }
    }
    return result_;  // every pair passed t = 1: a miss
  }

 private:
  struct Later {
    bool operator()(const Entry& x, const Entry& y) const { return x.t > y.t; }
  };
  /// B's model frame in A's at one time, and the relative translation velocity in A's frame.
  struct Frame {
    Mat3 rot;
    Vec3 trans;
    Vec3 v;
  };

  /// Queues e again at e.t + advance, unless that passes t = 1.
  void advance(Entry e, Scalar advance) {
    Scalar next = e.t + advance * kStepShrink;
    if (!(next < 1)) return;  // apart until the end of the motion
    // Rounded down to a multiple of kGrid when that still moves on, so that pairs share times
    // and the poses computed for them.
    if (const Scalar g = std::floor(next * kGrid) / kGrid; g > e.t) next = g;
    e.t = next;
    if (e.steps < 255) ++e.steps;
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), Later{});
  }

  [[nodiscard]] Frame frame_at(Scalar t) const {
    const Quat qa = turn_a_.at(t);
    const Quat qb = turn_b_.at(t);
    const Quat to_a = qa.conjugate();
    const Vec3 ta = (1 - t) * m_.a0.translation + t * m_.a1.translation;
    const Vec3 tb = (1 - t) * m_.b0.translation + t * m_.b1.translation;
    return {(to_a * qb).toRotationMatrix(), to_a * (tb - ta), to_a * v_};
  }

  /// How far a point of B may stray, in A's frame, from the chord between its positions at t and
  /// t + w, given y = reach_b of the point (B's model frame) and p = reach_a of its position in A's
  /// frame at t: w^2 / 8 times a bound of the second derivative of its path p(s) = R_a(s)^T q(s),
  /// q(s) = R_b(s) y + T_b(s) - T_a(s): |q'| <= theta_b y + speed, |q''| <= theta_b^2 y, and A's
  /// turn at constant angular velocity about its axis k gives |p''| <= theta_a^2 |k x p(s)| +
  /// 2 theta_a |q'| + |q''|, with |k x p(s)| <= p + w |q'| over the interval (ccd::Spin).
  [[nodiscard]] Scalar bend(Scalar w, Scalar y, Scalar p) const {
    const Scalar theta_a = m_.spin_a.theta;
    const Scalar theta_b = m_.spin_b.theta;
    const Scalar drift = theta_b * y + m_.speed;
    const Scalar q = p + w * drift;
    return tolerance::widened(
        w * w / 8 * (theta_a * theta_a * q + 2 * theta_a * drift + theta_b * theta_b * y));
  }

  /// The chord step: how far from e.t a pair may jump when the conservative step is `step`
  /// (then tried by a chord test, see nodes() and triangles()).
  [[nodiscard]] static Scalar chord_width(Scalar t, Scalar step) {
    return std::min(1 - t, kChordSteps * step);
  }

  /// A node pair at e.t: advanced while its spheres or boxes are apart, else its children (or its
  /// leaves' triangle pairs) are queued at e.t.
  void nodes(const Entry& e, const Frame& f) {
    const BvhNode& na = nodes_a_[e.a];
    const BvhNode& nb = nodes_b_[e.b];
    const Vec3 centre_b = f.rot * nb.center + f.trans;
    const Scalar centres = (centre_b - na.center).norm();
    const Scalar sphere = centres - na.radius - nb.radius - node_margin_;
    const Scalar ca = m_.spin_a.reach(na.center);
    const Scalar cb = m_.spin_b.reach(nb.center);
    Scalar step = 0;
    if (sphere > 0) {
      // A ball turns into itself about its centre: only the centres' paths count, and the
      // spheres stay apart while the centres' gap along their direction at e.t does.
      const Vec3 n = (na.center - centre_b) / centres;
      const Lever la =
          m_.spin_a.about_axis ? lever_of(m_.spin_a, n, {&na.center, 1}) : Lever{ca, ca};
      const Lever lb = m_.spin_b.about_axis
                           ? lever_of(m_.spin_b, f.rot.transpose() * n, {&nb.center, 1})
                           : Lever{cb, cb};
      step = step_of(sphere, n, 2 * allowance_ / centres, f.v, m_, la, lb);
      if (!(e.t + step * kStepShrink < 1)) return;  // apart until the end of the motion
      // The chord test: in A's frame, B's centre runs within bend() of the chord between its
      // positions at e.t and e.t + w, so the spheres stay apart over that interval when the
      // chord stays farther from A's centre than the radii, the margin and the bend.
      if (const Scalar w = chord_width(e.t, step); w > step) {
        const Frame g = frame_at(e.t + w);
        const Vec3 q0 = centre_b - na.center;
        const Vec3 dq = g.rot * nb.center + g.trans - centre_b;
        const Scalar len2 = dq.squaredNorm();
        const Scalar u = len2 > 0 ? std::clamp(-q0.dot(dq) / len2, Scalar{0}, Scalar{1}) : 0;
        if ((q0 + u * dq).norm() - na.radius - nb.radius - node_margin_ -
                bend(w, cb, m_.spin_a.reach(centre_b)) >
            0) {
          return advance(e, w);
        }
      }
    }
    // The box gap over all 15 axes (a stop of 0: the centre and edge axes only when no face axis
    // separates); face axes alone examined twice the node pairs on the bench's torus/sphere.
    const Scalar box =
        detail::obb_gap(na.obb(), f.rot * nb.axes(), centre_b, nb.half_extents(), 0) - node_margin_;
    if (box > 0) {
      const Scalar rate =
          tolerance::widened(m_.speed + m_.spin_a.theta * (ca + m_.spin_a.node_reach(na)) +
                             m_.spin_b.theta * (cb + m_.spin_b.node_reach(nb)));
      step = std::max(step, box / rate);
    }
    if (step > 0 && e.steps < kNodeSteps) return advance(e, step);
    if (na.is_leaf() && nb.is_leaf()) {
      for (std::uint32_t i = 0; i < na.count; ++i) {
        for (std::uint32_t j = 0; j < nb.count; ++j) {
          local_.push_back({e.t, na.first_or_right + i, nb.first_or_right + j, Kind::triangles, 0});
        }
      }
      return;
    }
    // Descend the larger sphere (or the only internal node).
    if (nb.is_leaf() || (!na.is_leaf() && na.radius >= nb.radius)) {
      local_.push_back({e.t, e.a + 1, e.b, Kind::nodes, 0});
      local_.push_back({e.t, na.first_or_right, e.b, Kind::nodes, 0});
    } else {
      local_.push_back({e.t, e.a, e.b + 1, Kind::nodes, 0});
      local_.push_back({e.t, e.a, nb.first_or_right, Kind::nodes, 0});
    }
  }

  /// A triangle pair at e.t: true when it is within reach there (the search's answer: every
  /// other pair stays apart until at least e.t), else advanced.
  bool triangles(const Entry& e, const Frame& f) {
    const auto x = corners_a_.triangle(e.a);
    const auto y = corners_b_.triangle(e.b);
    const std::array<Vec3, 3> yb{f.rot * y[0] + f.trans, f.rot * y[1] + f.trans,
                                 f.rot * y[2] + f.trans};
    if (e.steps < kCheapSteps) {
      // Cheap lower bounds first (the exact distance costs 15 primitive distances): the gaps
      // along the normals of both triangles and the axis through their centroids.
      const Vec3 na = (x[1] - x[0]).cross(x[2] - x[0]).normalized();
      const Vec3 nb = (yb[1] - yb[0]).cross(yb[2] - yb[0]).normalized();
      const Vec3 to_b = ((yb[0] + yb[1] + yb[2]) - (x[0] + x[1] + x[2])).normalized();
      Vec3 axis = na;
      Scalar best = -std::numeric_limits<Scalar>::infinity();
      for (const Vec3& n : {na, Vec3(-na), nb, Vec3(-nb), Vec3(-to_b)}) {
        if (const Scalar g = axis_gap(n, x, yb); g > best) {
          best = g;
          axis = n;
        }
      }
      if (best - triangle_margin_ > 0) {
        const Scalar step = pair_step(best - triangle_margin_, axis, 0, f.v, f.rot, m_, x, y);
        advance(e, e.steps > 0 ? chord_step(axis, x, y, yb, e.t, step) : step);
        return false;
      }
    }
    const geometry::TriangleDistance d =
        geometry::triangle_distance(x[0], x[1], x[2], yb[0], yb[1], yb[2]);
    const Scalar gap = d.distance - triangle_margin_;
    if (gap <= stop_gap_) {
      result_.outcome = FirstContact::Outcome::hit;
      result_.toi = e.t;
      result_.triangle_a = m_.a.leaf_triangles()[e.a];
      result_.triangle_b = m_.b.leaf_triangles()[e.b];
      result_.distance = d.distance;
      result_.proven =
          d.distance + allowance_ <= separation_ ||
          (d.distance == 0 && geometry::triangles_intersect(x[0], x[1], x[2], yb[0], yb[1], yb[2]));
      return true;
    }
    const Scalar step = pair_step(gap, (d.pa - d.pb) / d.distance, 2 * allowance_ / d.distance, f.v,
                                  f.rot, m_, x, y);
    // The chord test along the closest-point direction.
    advance(e, d.distance > 4 * allowance_
                   ? chord_step((d.pa - d.pb) / d.distance, x, y, yb, e.t, step)
                   : step);
    return false;
  }

  /// The chord test of a triangle pair over [t, t + w] along the unit axis n: A's triangle x
  /// lies above the plane n . p = min n . x_i; B's corners (y in B's frame, yb in A's at t) run
  /// within bend() of their chords in A's frame, so B's triangle stays below max(n . y_k at t,
  /// n . y_k at t + w) + bend (a point of the triangle is a fixed combination of its corners).
  /// Returns the gap that leaves between them over the whole interval, less the margin (> 0: apart
  /// throughout), and in `end_gap` the same at t + w alone.
  Scalar chord_gap(const Vec3& n, const std::array<Vec3, 3>& x, const std::array<Vec3, 3>& y,
                   const std::array<Vec3, 3>& yb, Scalar t, Scalar w, Scalar& end_gap) const {
    const Frame g = frame_at(t + w);
    const std::array<Vec3, 3> y1{g.rot * y[0] + g.trans, g.rot * y[1] + g.trans,
                                 g.rot * y[2] + g.trans};
    Scalar strayed = 0;
    for (int k = 0; k < 3; ++k) {
      strayed = std::max(strayed, bend(w, m_.spin_b.reach(y[k]), m_.spin_a.reach(yb[k])));
    }
    end_gap = axis_gap(n, x, y1) - strayed - triangle_margin_;
    return std::min(axis_gap(n, x, yb) - strayed - triangle_margin_, end_gap);
  }

  /// The step a triangle pair at t takes along the unit axis n when its conservative step is
  /// `step`: the chord test over kChordSteps such steps; where that fails because the pair's gap
  /// along n has closed at the far end (a pair approaching its contact, which conservative steps
  /// reach only in ever shorter steps: each covers a fixed fraction of the time left), once more
  /// over kSecantShare of the width at which the two ends' gaps, interpolated, close. Each test
  /// is a proof over its own interval (chord_gap), whatever width it is given.
  Scalar chord_step(const Vec3& n, const std::array<Vec3, 3>& x, const std::array<Vec3, 3>& y,
                    const std::array<Vec3, 3>& yb, Scalar t, Scalar step) const {
    const Scalar w = chord_width(t, step);
    if (!(w > step)) return step;
    Scalar end = 0;
    if (chord_gap(n, x, y, yb, t, w, end) > 0) return w;
    const Scalar start = axis_gap(n, x, yb) - triangle_margin_;
    if (!(end < 0 && start > 0)) return step;
    const Scalar w2 = kSecantShare * w * start / (start - end);
    return w2 > step && chord_gap(n, x, y, yb, t, w2, end) > 0 ? w2 : step;
  }

  /// Advancement steps of a node pair before its children are examined (from where it reached).
  static constexpr std::uint8_t kNodeSteps = 4;
  /// Steps of a triangle pair on cheap bounds before its exact distance is taken.
  static constexpr std::uint8_t kCheapSteps = 4;
  /// A chord test spans this many conservative steps (or the rest of the motion).
  static constexpr Scalar kChordSteps = 8;
  /// A failed chord test is tried once more over this share of the width at which the pair's
  /// gap would close (chord_step). Shares of 0.6 / 0.8 / 0.9 / 0.95 / 0.99 on 133 replayed
  /// sheet/roller sweeps: 2.34 / 2.21 / 2.14 / 2.09 / 2.07 G instructions (no retry: 2.37 G).
  static constexpr Scalar kSecantShare = 0.95;

  const RigidPair& m_;
  Turn turn_a_, turn_b_;
  Vec3 v_;
  Scalar triangle_margin_, node_margin_, separation_, allowance_, stop_gap_;
  FirstContactLimits limits_;
  std::span<const BvhNode> nodes_a_, nodes_b_;
  LeafCorners corners_a_, corners_b_;
  Queues& queues_;
  std::vector<Entry> heap_;
  std::vector<Entry> local_;  ///< the pairs opened at the current time
  FirstContact result_;
};

}  // namespace

FirstContact first_contact(const RigidPair& m, Scalar t0, Scalar separation, Scalar allowance,
                           Scalar volume, Scalar stop_gap, const FirstContactLimits& limits) {
  thread_local Queues queues;
  FirstContact result;
  {
    Search search(m, separation, allowance, volume, stop_gap, limits, queues);
    result = search.run(t0);
  }
  queues.release_oversized();
  return result;
}

}  // namespace antcd::ccd
