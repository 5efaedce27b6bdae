// Exact detection: the dual traversal's overlapping leaves, then triangle–triangle tests.
#include <antcd/collide.hpp>

#include "bvh/traverse.hpp"
#include "exact/manifold.hpp"
#include "geometry/penetration.hpp"
#include "points/point_index.hpp"
#include "util/check.hpp"

#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

namespace antcd {

namespace {

// Normal and depth of a pair reported only because it is within delta (distance > 0).
geometry::TrianglePenetration apart(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                    const Vec3& b1, const Vec3& b2) {
  const geometry::TriangleDistance td = geometry::triangle_distance(a0, a1, a2, b0, b1, b2);
  if (!(td.distance > 0)) return geometry::detail::intersecting_penetration(a0, a1, a2, b0, b1, b2);
  return geometry::detail::apart_penetration(td.pa, td.pb);
}

// The exact query with the walk `walk(frame, on_leaf, limit)` -> TraversalStats, which calls
// on_leaf(leaf_a, leaf_b, live_a, live_b) on the leaf pairs to test and stops when it returns true.
template <class Walk>
bool collide_walk(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
                  const CollisionRequest& request, CollisionResult& result, Walk&& walk) {
  detail::require_non_negative("collide", "request.delta", request.delta);
  detail::require_in_range("collide", "request.manifold_angle", request.manifold_angle, 0,
                           std::numbers::pi, false, "[0, pi] radians");
  result.clear();
  const bool normals = request.contact_normals || request.manifold_points > 0;
  const detail::PairFrame frame(a, pose_a, b, pose_b, request.delta);
  const LeafCorners verts_a = a.leaf_corners();
  const LeafCorners verts_b = b.leaf_corners();
  const auto tris_a = a.leaf_triangles();
  const auto tris_b = b.leaf_triangles();
  const auto nodes_a = a.nodes();
  const auto nodes_b = b.nodes();
  const Scalar delta = request.delta;
  const std::size_t limit = request.all_contacts ? request.max_contacts : 1;

  // B's leaf triangles mapped into A's frame, with their boxes, kept while consecutive leaf pairs
  // share B's leaf (the traversal descends A under a fixed B node). Leaves are small (leaf_size);
  // larger ones are transformed triangle by triangle.
  constexpr std::uint32_t kCached = 8;
  std::array<Vec3, 3 * kCached> cache_b;
  std::array<Vec3, kCached> lo_b;
  std::array<Vec3, kCached> hi_b;
  std::uint32_t cached_leaf = UINT32_MAX;

  // live_a / live_b: the leaves' triangles the traversal has not ruled out (dual_traverse).
  const auto on_leaf = [&](std::uint32_t la, std::uint32_t lb, std::uint32_t live_a,
                           std::uint32_t live_b) {
    const BvhNode& na = nodes_a[la];
    const BvhNode& nb = nodes_b[lb];
    const bool cached = nb.count <= kCached;
    if (cached && cached_leaf != lb) {
      for (std::uint32_t k = 0; k < nb.count; ++k) {
        const std::uint32_t jb = nb.first_or_right + k;
        for (int v = 0; v < 3; ++v) cache_b[3 * k + v] = frame.b_to_a.apply(verts_b(jb, v));
        lo_b[k] = cache_b[3 * k].cwiseMin(cache_b[3 * k + 1]).cwiseMin(cache_b[3 * k + 2]);
        hi_b[k] = cache_b[3 * k].cwiseMax(cache_b[3 * k + 1]).cwiseMax(cache_b[3 * k + 2]);
      }
      cached_leaf = lb;
    }
    for (std::uint32_t ia = na.first_or_right; ia < na.first_or_right + na.count; ++ia) {
      const std::uint32_t ka = ia - na.first_or_right;
      if (ka < detail::kMaskedLeaf && (live_a >> ka & 1u) == 0) continue;
      const Vec3& a0 = verts_a(ia, 0);
      const Vec3& a1 = verts_a(ia, 1);
      const Vec3& a2 = verts_a(ia, 2);
      const Vec3 lo_a = a0.cwiseMin(a1).cwiseMin(a2);
      const Vec3 hi_a = a0.cwiseMax(a1).cwiseMax(a2);
      for (std::uint32_t k = 0; k < nb.count; ++k) {
        if (k < detail::kMaskedLeaf && (live_b >> k & 1u) == 0) continue;
        const std::uint32_t jb = nb.first_or_right + k;
        Vec3 tb[3];
        const Vec3* b0 = nullptr;
        const Vec3* b1 = nullptr;
        const Vec3* b2 = nullptr;
        if (cached) {
          // Exact box rejection: a gap larger than delta along one axis (the subtraction rounds
          // monotonically, so fl(x - y) > delta implies x - y > delta) means no point of the two
          // triangles is within delta. Same coordinates as the triangle test below.
          if (lo_b[k].x() - hi_a.x() > delta || lo_a.x() - hi_b[k].x() > delta ||
              lo_b[k].y() - hi_a.y() > delta || lo_a.y() - hi_b[k].y() > delta ||
              lo_b[k].z() - hi_a.z() > delta || lo_a.z() - hi_b[k].z() > delta) {
            continue;
          }
          b0 = &cache_b[3 * k];
          b1 = &cache_b[3 * k + 1];
          b2 = &cache_b[3 * k + 2];
        } else {
          for (int v = 0; v < 3; ++v) tb[v] = frame.b_to_a.apply(verts_b(jb, v));
          b0 = &tb[0];
          b1 = &tb[1];
          b2 = &tb[2];
        }
        ++result.triangle_tests;
        Vec3 point;
        Scalar distance = 0;
        if (geometry::triangles_within(a0, a1, a2, *b0, *b1, *b2, delta, &point, &distance)) {
          result.colliding = true;
          Contact& c = result.contacts.emplace_back();
          c.triangle_a = tris_a[ia];
          c.triangle_b = tris_b[jb];
          c.point = pose_a.apply(point);
          c.distance = distance;
          if (normals) {
            const geometry::TrianglePenetration pen =
                distance > 0
                    ? apart(a0, a1, a2, *b0, *b1, *b2)
                    : geometry::detail::intersecting_penetration(a0, a1, a2, *b0, *b1, *b2);
            c.normal = pose_a.apply_vector(pen.normal);
            c.depth = pen.depth;
          }
          if (limit != 0 && result.contacts.size() >= limit) return true;
        }
      }
    }
    return false;
  };
  result.traversal = walk(frame, on_leaf, limit);
  if (request.manifold_points > 0) {
    result.regions = detail::reduce_to_manifold(result.contacts, request.manifold_points,
                                                std::cos(request.manifold_angle));
  }
  if (request.volume) {
    if (!a.is_closed() || !b.is_closed()) {
      result.surface_only = true;
    } else if (!result.colliding) {
      // Surfaces apart: the solids meet only if one lies wholly inside the other, which one
      // vertex of each tells (a vertex on the other surface would have been a surface contact).
      const Vec3 va_in_b = frame.b_to_a.inverse().apply(a.leaf_corners()(0, 0));
      const Vec3 vb_in_a = frame.b_to_a.apply(b.leaf_corners()(0, 0));
      result.contained = detail::inside_solid(b, va_in_b) || detail::inside_solid(a, vb_in_a);
      result.colliding = result.contained;
    }
  }
  return result.colliding;
}

// The leaves' exact triangle tests decide, so the boxes need only their face axes.
constexpr auto kFaces = detail::BoxTest::faces;

}  // namespace

bool collide(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
             const CollisionRequest& request, CollisionResult& result) {
  // A query that stops at its first contact visits the nearer children first.
  return collide_walk(a, pose_a, b, pose_b, request, result,
                      [&](const detail::PairFrame& frame, auto& on_leaf, std::size_t limit) {
                        return limit == 1
                                   ? detail::dual_traverse<true, kFaces>(a, b, frame, on_leaf)
                                   : detail::dual_traverse<false, kFaces>(a, b, frame, on_leaf);
                      });
}

bool collide(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b,
             const CollisionRequest& request, CollisionResult& result, PairWitness& witness) {
  if (request.all_contacts || request.manifold_points != 0) {
    return collide(a, pose_a, b, pose_b, request, result);
  }
  if (witness.a != &a || witness.b != &b) witness = {&a, &b, false, 0, 0};
  // A front of the last walk (Ehmann and Lin's generalised front tracking) was tried as well: on
  // the generated VR scenes (docs/performance.md) it visited more node pairs than a walk from the
  // root, since a front only deepens while objects approach and leave it again.
  const auto walk = [&](const detail::PairFrame& frame, auto& on_leaf, std::size_t) {
    constexpr std::uint32_t kAll = ~std::uint32_t{0};  // every triangle of both leaves
    const bool tried = witness.valid;
    if (tried && on_leaf(witness.leaf_a, witness.leaf_b, kAll, kAll)) {
      TraversalStats stats;
      stats.leaf_pairs = 1;
      return stats;
    }
    witness.valid = false;
    TraversalStats stats = detail::dual_traverse<true, kFaces>(
        a, b, frame,
        [&](std::uint32_t la, std::uint32_t lb, std::uint32_t live_a, std::uint32_t live_b) {
          if (!on_leaf(la, lb, live_a, live_b)) return false;
          witness = {&a, &b, true, la, lb};
          return true;
        });
    if (tried) ++stats.leaf_pairs;
    return stats;
  };
  return collide_walk(a, pose_a, b, pose_b, request, result, walk);
}

CollisionResult collide(const Model& a, const Transform& pose_a, const Model& b,
                        const Transform& pose_b, const CollisionRequest& request) {
  CollisionResult result;
  collide(a, pose_a, b, pose_b, request, result);
  return result;
}

}  // namespace antcd
