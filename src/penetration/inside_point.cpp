// Points inside two solids and the lower bound they prove (see inside_point.hpp).
//
// The bound f(p) = dist(p, ∂A) + dist(p, ∂B) is maximised locally from a few seeds: a vertex v of
// one model deep inside the other gives the midpoint of v and its nearest point on the other's
// surface (for two slabs overlapping by d that midpoint already has f = d); a coarse grid over
// the overlap of the bounding boxes catches overlaps without a vertex inside. The ascent steps
// along the gradient of f ((p - c_A) / d_A + (p - c_B) / d_B) and the coordinate axes, halving the
// step when none improves.
#include "penetration/inside_point.hpp"

#include "penetration/convex.hpp"

#include <antcd/collide.hpp>
#include <antcd/points.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <cmath>

namespace antcd::detail {

namespace {

constexpr std::size_t kMaxContainsPoints = 20000;  // vertices tested per model (evenly spaced)
constexpr std::size_t kMaxDistancePoints = 1024;   // inside vertices measured per model
constexpr std::size_t kVertexSeeds = 16;           // deepest vertices kept per model
constexpr int kGrid = 10;                          // grid seeds per axis
constexpr std::size_t kAscents = 4;                // best seeds refined
constexpr int kAscentSteps = 60;
constexpr std::size_t kContactSeeds = 64;  // surface crossings used as seeds

std::vector<Vec3> every_nth(std::span<const Vec3> points, std::size_t limit) {
  const std::size_t stride = std::max<std::size_t>(1, (points.size() + limit - 1) / limit);
  std::vector<Vec3> out;
  out.reserve(points.size() / stride + 1);
  for (std::size_t i = 0; i < points.size(); i += stride) out.push_back(points[i]);
  return out;
}

Aabb world_box(const Model& m, const Transform& pose) {
  const Vec3 c = pose.apply(m.root().center);
  const Scalar r = m.root().radius;
  Aabb box;
  box.extend(c - Vec3::Constant(r));
  box.extend(c + Vec3::Constant(r));
  return box;
}

}  // namespace

DepthProbe::DepthProbe(const Model& a, const Transform& pose_a, const Model& b,
                       const Transform& pose_b)
    : a_(a), b_(b), pose_a_(pose_a), pose_b_(pose_b) {
  scale_ = pose_a.translation.norm() + pose_b.translation.norm() + a.root().center.norm() +
           b.root().center.norm() + a.root().radius + b.root().radius;
  allowance_ = tolerance::kPoint * scale_;
}

std::vector<DepthPoint> DepthProbe::evaluate(std::span<const Vec3> points) const {
  const SignedDistanceResult ra = signed_distance(a_, pose_a_, points);
  const SignedDistanceResult rb = signed_distance(b_, pose_b_, points);
  std::vector<DepthPoint> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    DepthPoint& d = out[i];
    d.p = points[i];
    d.closest_a = ra.points[i].closest;
    d.closest_b = rb.points[i].closest;
    d.dist_a = std::abs(ra.points[i].distance);
    d.dist_b = std::abs(rb.points[i].distance);
    d.inside = ra.points[i].distance < 0 && rb.points[i].distance < 0;
    if (d.inside) {
      d.bound =
          std::max<Scalar>(0, d.dist_a - allowance_) + std::max<Scalar>(0, d.dist_b - allowance_);
    }
  }
  return out;
}

void DepthProbe::vertex_seeds(const Model& m, const Transform& pose, const Model& other,
                              const Transform& other_pose, std::vector<Vec3>& seeds) const {
  std::vector<Vec3> world;
  world.reserve(m.mesh().vertices.size());
  for (const Vec3& v : m.mesh().vertices) world.push_back(pose.apply(v));
  const std::vector<Vec3> tested = every_nth(world, kMaxContainsPoints);
  const std::vector<std::uint8_t> in = contains(other, other_pose, tested);
  std::vector<Vec3> inside;
  for (std::size_t i = 0; i < tested.size(); ++i) {
    if (in[i] != 0) inside.push_back(tested[i]);
  }
  if (inside.empty()) return;
  const std::vector<Vec3> measured = every_nth(inside, kMaxDistancePoints);
  const SignedDistanceResult r = signed_distance(other, other_pose, measured);
  std::vector<std::size_t> order(measured.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const std::size_t keep = std::min(kVertexSeeds, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(),
                    [&](std::size_t x, std::size_t y) {
                      return r.points[x].distance < r.points[y].distance;  // deepest first
                    });
  for (std::size_t k = 0; k < keep; ++k) {
    const std::size_t i = order[k];
    seeds.push_back(0.5 * (measured[i] + r.points[i].closest));
  }
}

void DepthProbe::contact_seeds(std::vector<Vec3>& seeds) const {
  // Where the surfaces cross, both solids lie behind both triangles: step from the crossing point
  // against the sum of the two outward normals (outward: the sign of each mesh's volume).
  CollisionRequest all;
  all.all_contacts = true;
  all.max_contacts = kContactSeeds;
  const CollisionResult r = collide(a_, pose_a_, b_, pose_b_, all);
  if (r.contacts.empty()) return;
  const auto outward = [](const Model& m, const Transform& pose, std::uint32_t t, Scalar sign) {
    const TriangleIndices& tri = m.mesh().triangles[t];
    const Vec3& p0 = m.mesh().vertices[tri[0]];
    const Vec3 n = (m.mesh().vertices[tri[1]] - p0).cross(m.mesh().vertices[tri[2]] - p0);
    return Vec3(sign * pose.apply_vector(n).normalized());
  };
  const Scalar sign_a = (signed_volume6(a_.mesh()) < 0 ? -1.0 : 1.0);
  const Scalar sign_b = (signed_volume6(b_.mesh()) < 0 ? -1.0 : 1.0);
  const Scalar size = std::min(a_.root().radius, b_.root().radius);
  for (const Contact& c : r.contacts) {
    const Vec3 in =
        -(outward(a_, pose_a_, c.triangle_a, sign_a) + outward(b_, pose_b_, c.triangle_b, sign_b));
    if (!(in.norm() > 1e-6)) continue;
    for (const Scalar step : {1e-3, 1e-2}) seeds.push_back(c.point + step * size * in.normalized());
  }
}

DepthPoint DepthProbe::ascend(DepthPoint cur) const {
  Scalar step = cur.bound > 0 ? 0.25 * cur.bound : 1e-3 * scale_;
  const Scalar min_step = 1e-4 * std::max(cur.bound, 1e-6 * scale_);
  for (int it = 0; it < kAscentSteps && step > min_step; ++it) {
    std::vector<Vec3> trial;
    if (cur.dist_a > 0 && cur.dist_b > 0) {
      const Vec3 g = (cur.p - cur.closest_a) / cur.dist_a + (cur.p - cur.closest_b) / cur.dist_b;
      if (g.norm() > 1e-12) trial.push_back(cur.p + step * g.normalized());
    }
    for (int k = 0; k < 3; ++k) {
      trial.push_back(cur.p + step * Vec3::Unit(k));
      trial.push_back(cur.p - step * Vec3::Unit(k));
    }
    const std::vector<DepthPoint> r = evaluate(trial);
    const auto best = std::max_element(
        r.begin(), r.end(),
        [](const DepthPoint& x, const DepthPoint& y) { return x.bound < y.bound; });
    if (best->bound > cur.bound) {
      cur = *best;
      step *= 1.5;
    } else {
      step *= 0.5;
    }
    if (cur.bound == 0) break;  // ascent needs a start inside both
  }
  return cur;
}

DepthPoint DepthProbe::best_point(std::span<const Vec3> extra) const {
  std::vector<Vec3> seeds(extra.begin(), extra.end());
  vertex_seeds(a_, pose_a_, b_, pose_b_, seeds);
  vertex_seeds(b_, pose_b_, a_, pose_a_, seeds);
  contact_seeds(seeds);
  const Aabb ba = world_box(a_, pose_a_);
  const Aabb bb = world_box(b_, pose_b_);
  Aabb overlap;
  overlap.min = ba.min.cwiseMax(bb.min);
  overlap.max = ba.max.cwiseMin(bb.max);
  if (!overlap.empty()) {
    const Vec3 cell = overlap.extent() / kGrid;
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        for (int k = 0; k < kGrid; ++k) {
          seeds.push_back(overlap.min + cell.cwiseProduct(Vec3(i + 0.5, j + 0.5, k + 0.5)));
        }
      }
    }
  }
  std::vector<DepthPoint> evaluated = evaluate(seeds);
  const std::size_t keep = std::min(kAscents, evaluated.size());
  std::partial_sort(evaluated.begin(), evaluated.begin() + static_cast<std::ptrdiff_t>(keep),
                    evaluated.end(),
                    [](const DepthPoint& x, const DepthPoint& y) { return x.bound > y.bound; });
  DepthPoint best;
  for (std::size_t k = 0; k < keep; ++k) {
    if (!evaluated[k].inside) break;
    const DepthPoint refined = ascend(evaluated[k]);
    if (!best.inside || refined.bound > best.bound) best = refined;
  }
  return best;
}

}  // namespace antcd::detail
