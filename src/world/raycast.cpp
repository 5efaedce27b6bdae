// Ray casts against one posed model: the ray is taken into the model's frame, the hierarchy is
// walked with conservative sphere and box tests, and the leaf triangles are tested with the
// Möller–Trumbore construction (barycentric coordinates by triple products).
#include <antcd/world.hpp>

#include <algorithm>
#include <antcd/error.hpp>
#include <antcd/tolerances.hpp>
#include <array>
#include <cmath>
#include <string>

#include "util/check.hpp"
#include "world/ray_check.hpp"

namespace antcd {

namespace {

struct LocalRay {
  Vec3 origin;     // model frame
  Vec3 direction;  // model frame, unit
  Scalar max_distance;
};

// Closed triangle hit: distance s >= 0 along the unit direction and <= s_max, or no hit. A ray in
// the triangle's plane (zero determinant) does not hit it.
bool ray_triangle(const LocalRay& r, const Vec3& v0, const Vec3& v1, const Vec3& v2, Scalar s_max,
                  Scalar& s) {
  const Vec3 e1 = v1 - v0;
  const Vec3 e2 = v2 - v0;
  const Vec3 p = r.direction.cross(e2);
  const Scalar det = e1.dot(p);
  if (det == 0) return false;
  const Scalar inv = 1 / det;
  const Vec3 tv = r.origin - v0;
  const Scalar u = tv.dot(p) * inv;
  if (!(u >= 0 && u <= 1)) return false;
  const Vec3 q = tv.cross(e1);
  const Scalar v = r.direction.dot(q) * inv;
  if (!(v >= 0 && u + v <= 1)) return false;
  s = e2.dot(q) * inv;
  return s >= 0 && s <= s_max;
}

// Conservative node test: the segment [0, s_max] of the ray against the node's sphere, then its
// box (slab test in the box's frame), both widened by a relative rounding allowance.
bool ray_meets_node(const LocalRay& r, const BvhNode& n, Scalar s_max, Scalar slack) {
  const Vec3 oc = n.center - r.origin;
  const Scalar along = std::clamp(oc.dot(r.direction), Scalar{0}, s_max);
  const Scalar rad = n.radius + slack;
  if ((oc - along * r.direction).squaredNorm() > rad * rad) return false;
  Scalar lo = 0;
  Scalar hi = s_max;
  const Mat3 axes = n.axes();
  const Vec3 o = axes.transpose() * (r.origin - n.center);
  const Vec3 d = axes.transpose() * r.direction;
  const Vec3 half = n.half_extents();
  for (int k = 0; k < 3; ++k) {
    const Scalar h = half[k] + slack;
    if (std::abs(d[k]) < 1e-300) {
      if (std::abs(o[k]) > h) return false;
      continue;
    }
    Scalar t0 = (-h - o[k]) / d[k];
    Scalar t1 = (h - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0 - slack);
    hi = std::min(hi, t1 + slack);
    if (lo > hi) return false;
  }
  return true;
}

// Walks the hierarchy; on_hit(k, s) for each leaf triangle k hit within *s_max (which on_hit may
// lower to prune).
template <class OnHit>
void walk(const Model& model, const LocalRay& r, const Scalar* s_max, OnHit&& on_hit) {
  const auto nodes = model.nodes();
  const LeafCorners verts = model.leaf_corners();
  const BvhNode& root = model.root();
  // Rounding allowance for the node tests: relative to the model's size and the ray's distance.
  const Scalar slack =
      tolerance::volume_allowance(root.radius + root.center.norm() + r.origin.norm());
  // Each step pops a node and pushes its two children: at most one sibling per level of the path
  // plus one, the depth at most kMaxTreeLevels (antcd/bvh.hpp).
  std::array<std::uint32_t, 256> stack;
  static_assert(std::tuple_size_v<decltype(stack)> >= kMaxTreeLevels + 1);
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = nodes[stack[--top]];
    if (!ray_meets_node(r, n, *s_max, slack)) continue;
    if (n.is_leaf()) {
      for (std::uint32_t k = n.first_or_right; k < n.first_or_right + n.count; ++k) {
        Scalar s = 0;
        if (ray_triangle(r, verts(k, 0), verts(k, 1), verts(k, 2), *s_max, s)) {
          on_hit(k, s);
        }
      }
      continue;
    }
    const std::uint32_t self = static_cast<std::uint32_t>(&n - nodes.data());
    stack[top++] = n.first_or_right;
    stack[top++] = self + 1;
  }
}

RayHit make_hit(const Model& model, const Transform& pose, const Ray& ray, const Vec3& unit_dir,
                std::uint32_t k, Scalar s) {
  const LeafCorners verts = model.leaf_corners();
  const Vec3 n_local = (verts(k, 1) - verts(k, 0)).cross(verts(k, 2) - verts(k, 0));
  Vec3 normal = pose.apply_vector(n_local).normalized();
  if (normal.dot(unit_dir) > 0) normal = -normal;
  RayHit hit;
  hit.triangle = model.leaf_triangles()[k];
  hit.distance = s;
  hit.point = ray.origin + s * unit_dir;
  hit.normal = normal;
  return hit;
}

LocalRay to_local(const Transform& pose, const Ray& ray, const Vec3& unit_dir) {
  const Mat3 rt = pose.rotation.transpose();
  return {rt * (ray.origin - pose.translation), rt * unit_dir, ray.max_distance};
}

}  // namespace

namespace detail {

Vec3 checked_ray_direction(const Ray& ray, const char* function) {
  const std::string fn(function);
  if (!ray.origin.allFinite()) {
    throw ArgumentError(fn + ": ray.origin is not finite");
  }
  if (!ray.direction.allFinite() || ray.direction.squaredNorm() == 0) {
    const Vec3& d = ray.direction;
    detail::argument_error(
        fn, "ray.direction", "finite and non-zero",
        "(" + number_text(d.x()) + ", " + number_text(d.y()) + ", " + number_text(d.z()) + ")");
  }
  detail::require_bound(fn, "ray.max_distance", ray.max_distance);
  return ray.direction.normalized();
}

void model_ray_hits(const Model& model, const Transform& pose, const Ray& ray, const Vec3& unit_dir,
                    std::vector<RayHit>& out) {
  const LocalRay r = to_local(pose, ray, unit_dir);
  const std::size_t first = out.size();
  walk(model, r, &r.max_distance, [&](std::uint32_t k, Scalar s) {
    out.push_back(make_hit(model, pose, ray, unit_dir, k, s));
  });
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
            [](const RayHit& a, const RayHit& b) {
              return a.distance < b.distance ||
                     (a.distance == b.distance && a.triangle < b.triangle);
            });
}

std::optional<RayHit> model_ray_first(const Model& model, const Transform& pose, const Ray& ray,
                                      const Vec3& unit_dir, Scalar s_max) {
  LocalRay r = to_local(pose, ray, unit_dir);
  r.max_distance = std::min(r.max_distance, s_max);
  Scalar best = r.max_distance;
  std::uint32_t best_k = UINT32_MAX;
  std::uint32_t best_tri = UINT32_MAX;
  const auto tris = model.leaf_triangles();
  walk(model, r, &best, [&](std::uint32_t k, Scalar s) {
    if (best_k == UINT32_MAX || s < best || (s == best && tris[k] < best_tri)) {
      best = s;
      best_k = k;
      best_tri = tris[k];
    }
  });
  if (best_k == UINT32_MAX) return std::nullopt;
  return make_hit(model, pose, ray, unit_dir, best_k, best);
}

}  // namespace detail

std::vector<RayHit> raycast_all(const Model& model, const Transform& pose, const Ray& ray) {
  const Vec3 d = detail::checked_ray_direction(ray, "raycast_all");
  std::vector<RayHit> out;
  detail::model_ray_hits(model, pose, ray, d, out);
  return out;
}

std::optional<RayHit> raycast(const Model& model, const Transform& pose, const Ray& ray) {
  const Vec3 d = detail::checked_ray_direction(ray, "raycast");
  return detail::model_ray_first(model, pose, ray, d, ray.max_distance);
}

}  // namespace antcd
