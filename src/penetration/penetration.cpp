// Penetration depth of two closed models (antcd/penetration.hpp): the exact convex path, and the
// certified interval for general solids.
//
// General solids: the lower bound comes from a point inside both (inside_point.hpp). Upper
// bounds are translations t verified by collide() (volume, delta 0) at exactly A's pose moved by
// t. Directions come from the witness (towards B's nearest surface point, away from A's), then
// from small turns of the best direction. Along a direction u the length starts just above the
// lower bound and grows until the models are apart; a distance query there gives the gap g, and
// moving back by 0.99 g cannot make the surfaces meet (every point moves by less than the gap),
// so that shorter translation is the next candidate (verified again); bisection against the last
// length found overlapping finishes it.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>

#include "penetration/convex.hpp"
#include "penetration/inside_point.hpp"
#include "util/check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace antcd {

namespace {

constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
// The convex path's arc tests cost E_A * E_B; beyond this the general bounds are cheaper.
constexpr double kMaxConvexWork = 4e7;

void check_request(const Model& a, const Model& b, const PenetrationRequest& r) {
  for (const Model* m : {&a, &b}) {
    if (!m->is_closed()) {
      throw ArgumentError("penetration: model '" + m->source() +
                          "' is not closed (no solid; penetration depth needs closed models)");
    }
  }
  detail::require_non_negative("penetration", "abs_tolerance", r.abs_tolerance);
  detail::require_in_range("penetration", "rel_tolerance", r.rel_tolerance, 0, 1, true, "[0, 1)");
  if (r.abs_tolerance == 0 && r.rel_tolerance == 0) {
    throw ArgumentError(
        "penetration: abs_tolerance and rel_tolerance are both 0 (no stopping rule)");
  }
  detail::require_at_least("penetration", "max_evaluations", r.max_evaluations, 1);
  detail::require_bound("penetration", "max_seconds", r.max_seconds);
}

// Collide calls at translated poses of A, within the budget.
class UpperSearch {
 public:
  UpperSearch(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
              const PenetrationRequest& request, PenetrationResult& result)
      : a_(a),
        b_(b),
        pose_a_(pose_a),
        pose_b_(pose_b),
        request_(request),
        result_(result),
        start_(std::chrono::steady_clock::now()) {
    collide_.volume = true;
  }

  [[nodiscard]] bool budget_left() const {
    if (result_.evaluations >= request_.max_evaluations) return false;
    if (request_.max_seconds <= 0) return true;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s < request_.max_seconds;
  }
  [[nodiscard]] Transform moved(const Vec3& u, Scalar s) const {
    Transform t = pose_a_;
    t.translation = pose_a_.translation + s * u;
    return t;
  }
  /// collide() at A moved by s * u; records a verified upper bound when apart.
  bool apart(const Vec3& u, Scalar s) {
    const Transform t = moved(u, s);
    ++result_.evaluations;
    if (collide(a_, t, b_, pose_b_, collide_).colliding) return false;
    // The displacement actually applied, rounded up.
    const Vec3 d = t.translation - pose_a_.translation;
    const Scalar len =
        d.norm() * (1 + 1e-15) + 4e-16 * (t.translation.norm() + pose_a_.translation.norm());
    if (len < result_.upper) {
      result_.upper = len;
      result_.direction = d.norm() > 0 ? Vec3(d.normalized()) : u;
    }
    return true;
  }
  [[nodiscard]] bool converged() const {
    if (!(result_.upper < kInf)) return false;
    const Scalar tol = std::max(request_.abs_tolerance, request_.rel_tolerance * result_.upper);
    return result_.upper - result_.lower <= tol;
  }
  /// Gap between the surfaces with A moved by s * u (a proven lower bound of it).
  Scalar gap(const Vec3& u, Scalar s) const {
    DistanceRequest dr;
    dr.rel_tolerance = 0.05;
    return distance(a_, moved(u, s), b_, pose_b_, dr).lower_bound;
  }

  /// Searches direction u (unit) for a short separating length; lengths beyond the best upper
  /// bound are not tried.
  void along(const Vec3& u, Scalar tiny) {
    if (!budget_left() || converged()) return;
    const Scalar base = std::max(result_.lower, tiny);
    const Scalar rel = std::max(request_.rel_tolerance, 1e-6);
    Scalar lo = 0;  // longest length known to leave them overlapping (0: none tried)
    Scalar inc = 0.5 * rel * base + 0.5 * request_.abs_tolerance;
    Scalar s = base + inc;
    Scalar hi = kInf;
    while (budget_left()) {
      if (s >= result_.upper) return;  // cannot improve on the best
      if (apart(u, s)) {
        hi = s;
        break;
      }
      lo = s;
      inc *= 2;
      s = base + inc;
    }
    if (hi == kInf) return;
    // Back along u by less than the gap: the surfaces cannot meet on the way.
    if (!converged() && budget_left()) {
      const Scalar g = gap(u, hi);
      const Scalar back = hi - 0.99 * g;
      if (g > 0 && back > lo && apart(u, back)) hi = back;
    }
    while (!converged() && budget_left() && hi - lo > 0.25 * rel * base) {
      const Scalar mid = 0.5 * (lo + hi);
      if (apart(u, mid)) {
        hi = mid;
      } else {
        lo = mid;
      }
    }
  }

 private:
  const Model& a_;
  const Model& b_;
  Transform pose_a_, pose_b_;
  const PenetrationRequest& request_;
  PenetrationResult& result_;
  CollisionRequest collide_;
  std::chrono::steady_clock::time_point start_;
};

// Unit vectors orthogonal to u.
void tangents(const Vec3& u, Vec3& e1, Vec3& e2) {
  const int k = std::abs(u.x()) < 0.6 ? 0 : (std::abs(u.y()) < 0.6 ? 1 : 2);
  e1 = u.cross(Vec3::Unit(k)).normalized();
  e2 = u.cross(e1);
}

void general(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
             const PenetrationRequest& request, PenetrationResult& out) {
  out.upper = kInf;
  UpperSearch search(a, pose_a, b, pose_b, request, out);
  // Apart already: depth 0.
  if (search.apart(Vec3::UnitX(), 0)) {
    out.lower = out.upper = 0;
    out.converged = true;
    return;
  }
  const detail::DepthProbe probe(a, pose_a, b, pose_b);
  const detail::DepthPoint w = probe.best_point({});
  out.overlapping = w.inside && w.bound > 0;
  out.lower = w.bound;
  out.witness = w.p;
  out.point_a = w.closest_a;
  out.point_b = w.closest_b;
  const Scalar tiny = 1e-9 * probe.scale();

  std::vector<Vec3> dirs;
  const auto add = [&](const Vec3& v) {
    if (v.norm() > 0 && v.allFinite()) dirs.push_back(v.normalized());
  };
  if (w.inside) {
    const Vec3 to_b = w.dist_b > 0 ? Vec3((w.closest_b - w.p) / w.dist_b) : Vec3::Zero();
    const Vec3 from_a = w.dist_a > 0 ? Vec3((w.p - w.closest_a) / w.dist_a) : Vec3::Zero();
    add(to_b + from_a);
    add(to_b);
    add(from_a);
  }
  // Where the surfaces cross: the normals of the deepest triangle pairs (each pair's own
  // separating direction, from B towards A: the way to move A).
  {
    CollisionRequest cr;
    cr.all_contacts = true;
    cr.max_contacts = 512;
    cr.contact_normals = true;
    CollisionResult c = collide(a, pose_a, b, pose_b, cr);
    std::sort(c.contacts.begin(), c.contacts.end(),
              [](const Contact& x, const Contact& y) { return x.depth > y.depth; });
    for (std::size_t k = 0; k < std::min<std::size_t>(2, c.contacts.size()); ++k) {
      add(c.contacts[k].normal);
    }
  }
  if (!w.inside) {
    for (int k = 0; k < 3; ++k) {
      add(Vec3::Unit(k));
      add(-Vec3::Unit(k));
    }
  }
  for (const Vec3& u : dirs) search.along(u, tiny);
  // Turn the best direction by shrinking angles.
  for (Scalar angle = 0.2; angle > 1e-3 && !search.converged() && search.budget_left();
       angle *= 0.25) {
    if (!(out.upper < kInf)) break;
    const Vec3 u = out.direction;
    Vec3 e1, e2;
    tangents(u, e1, e2);
    for (const Vec3& e : {e1, Vec3(-e1), e2, Vec3(-e2)}) {
      search.along((u + angle * e).normalized(), tiny);
    }
  }
  if (!(out.upper < kInf)) {
    // No separating translation within the budget: the only certain upper bound is unknown.
    out.converged = false;
    return;
  }
  out.converged = search.converged();
}

void convex(const detail::ConvexPolytope& pa, const detail::ConvexPolytope& pb, const Model& a,
            const Transform& pose_a, const Model& b, const Transform& pose_b,
            PenetrationResult& out) {
  const detail::ConvexDepth d = detail::convex_depth(pa, pb);
  out.exact = true;
  out.converged = true;
  out.direction = d.direction;
  out.point_a = d.point_a;
  out.point_b = d.point_b;
  out.overlapping = d.depth > 0;
  out.lower = out.upper = std::max<Scalar>(0, d.depth);
  if (!out.overlapping) return;
  // A point inside both by the face planes, clear of them by far more than rounding; else the
  // general search for one, checked by winding numbers.
  Scalar margin = 0;
  Vec3 w = detail::convex_witness(pa, pb, d, margin);
  const detail::DepthProbe probe(a, pose_a, b, pose_b);
  const Scalar clear = -1e-9 * probe.scale();
  if (margin >= clear) {
    // A∩B is convex, so the centroid of points in it (where the surfaces cross, and the vertices
    // of each inside the other) is in it, and inside it unless they are all coplanar.
    CollisionRequest all;
    all.all_contacts = true;
    all.max_contacts = 1024;
    Vec3 sum = Vec3::Zero();
    std::size_t count = 0;
    for (const Contact& c : collide(a, pose_a, b, pose_b, all).contacts) sum += c.point, ++count;
    for (const Vec3& v : pa.vertices) {
      if (pb.plane_margin(v) <= 0) sum += v, ++count;
    }
    for (const Vec3& v : pb.vertices) {
      if (pa.plane_margin(v) <= 0) sum += v, ++count;
    }
    if (count > 0) {
      const Vec3 c = sum / static_cast<Scalar>(count);
      for (const Vec3& candidate : {c, Vec3(0.5 * (c + w))}) {
        const Scalar m = std::max(pa.plane_margin(candidate), pb.plane_margin(candidate));
        if (m < margin) {
          margin = m;
          w = candidate;
        }
      }
    }
  }
  if (margin >= clear) w = detail::push_inside(pa, pb, w, 1e-3 * d.depth, margin);
  if (margin < clear) {
    out.witness = w;
    return;
  }
  const detail::DepthPoint deep = probe.best_point(std::span<const Vec3>(&w, 1));
  out.witness = deep.inside ? deep.p : w;
}

}  // namespace

bool is_convex(const Model& model) { return detail::convex_polytope(model, {}, nullptr); }

PenetrationResult penetration(const Model& a, const Transform& pose_a, const Model& b,
                              const Transform& pose_b, const PenetrationRequest& request) {
  check_request(a, b, request);
  PenetrationResult out;
  using Shape = PenetrationRequest::Shape;
  if (request.shape != Shape::General) {
    detail::ConvexPolytope pa, pb;
    const bool declared = request.shape == Shape::Convex;
    bool convex_pair =
        detail::convex_polytope(a, pose_a, &pa) && detail::convex_polytope(b, pose_b, &pb);
    if (declared && !convex_pair) {
      throw ArgumentError("penetration: shape Convex declared, but model '" +
                          (detail::convex_polytope(a, {}, nullptr) ? b.source() : a.source()) +
                          "' is not convex");
    }
    const double work = static_cast<double>(pa.edges.size()) * static_cast<double>(pb.edges.size());
    if (convex_pair && (declared || work <= kMaxConvexWork)) {
      convex(pa, pb, a, pose_a, b, pose_b, out);
      return out;
    }
  }
  general(a, pose_a, b, pose_b, request, out);
  return out;
}

}  // namespace antcd
