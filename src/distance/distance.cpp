// Minimum distance between two posed models: branch-and-bound over the two Sphere-OBB
// hierarchies, exact triangle–triangle distances at the leaves.
//
// Every node pair carries a lower bound of the distance between its contents (the larger of the
// sphere gap and the OBB separating-axis gap, minus a rounding allowance). The walk is depth
// first, descending both nodes of a pair at once, nearest child pair first (by signed gap), so a
// close leaf pair is reached early and its distance prunes most of the rest; at the leaves, cheap
// box, plane and centroid-axis gaps screen the exact triangle distances. A pair is pruned when
// its bound cannot beat the best distance found (minus the request's tolerance) or exceeds the
// request's upper bound; the smallest bound pruned below the best distance is kept, which makes
// DistanceResult::lower_bound a proof.
#include <antcd/distance.hpp>

#include "bvh/traverse.hpp"
#include "distance/node_bound.hpp"
#include "distance/seeded.hpp"
#include "util/check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace antcd {

namespace {

constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();

void check_request(const DistanceRequest& r) {
  detail::require_bound("distance", "upper_bound", r.upper_bound);
  detail::require_non_negative("distance", "abs_tolerance", r.abs_tolerance);
  detail::require_in_range("distance", "rel_tolerance", r.rel_tolerance, 0, 1, true, "[0, 1)");
}

// The search state: best pair so far and the pruning rule.
class Search {
 public:
  // `seed`: a triangle pair's distance at these poses (nullptr: none), see distance/seeded.hpp.
  Search(const DistanceRequest& r, const detail::DistanceSeed* seed) : request_(r), seed_(seed) {
    if (seed_ != nullptr) best_ = seed_->distance;
  }

  // True when a pair whose distance is at least `lb` need not be examined. Remembers the bound
  // when it was below the best distance (skipped on the tolerance or upper-bound ground).
  bool prune(Scalar lb) {
    // A best distance that only rounded to 0 (no exact intersection found yet): every pair that
    // may touch is still examined, so that `intersecting` stays an exact answer.
    if (hunting()) return lb > 0;
    if (lb >= best_) return true;
    const Scalar tol = std::max(request_.abs_tolerance, request_.rel_tolerance * best_);
    if (lb > request_.upper_bound || lb >= best_ - tol) {
      min_skipped_ = std::min(min_skipped_, lb);
      return true;
    }
    return false;
  }

  // `d` for the triangles (a0, a1, a2), (b0, b1, b2): leaf-order indices ia, jb.
  void offer(const geometry::TriangleDistance& d, const Vec3* ta, const Vec3* tb, std::uint32_t ia,
             std::uint32_t jb) {
    if (d.distance == 0 && !intersecting_) {
      // Zero is either an exact intersection or the rounding of a tiny positive distance; only
      // the exact predicate tells them apart (the rare case: surfaces within rounding).
      if (geometry::triangles_intersect(ta[0], ta[1], ta[2], tb[0], tb[1], tb[2])) {
        intersecting_ = true;
        best_ = kInf;  // the intersecting pair replaces any zero-rounded one
      }
    }
    if (d.distance < best_) {
      best_ = d.distance;
      seed_ = nullptr;  // the seed's pair is no longer the best
      pa_ = d.pa;
      pb_ = d.pb;
      ia_ = ia;
      jb_ = jb;
    }
  }

  [[nodiscard]] bool done() const { return intersecting_; }
  /// Any pair whose bound exceeds this is pruned.
  [[nodiscard]] Scalar cutoff() const {
    if (hunting()) return 0;
    const Scalar tol = std::max(request_.abs_tolerance, request_.rel_tolerance * best_);
    return std::min(best_ - tol, request_.upper_bound);
  }
  /// Looking for an exact intersection: the best distance rounded to 0 without one.
  [[nodiscard]] bool hunting() const { return best_ == 0 && !intersecting_; }

  void finish(const Transform& pose_a, std::span<const std::uint32_t> tris_a,
              std::span<const std::uint32_t> tris_b, DistanceResult& out) const {
    out.distance = best_;
    out.lower_bound = std::min(best_, min_skipped_);
    out.intersecting = intersecting_;
    out.beyond_upper_bound = out.lower_bound > request_.upper_bound;
    out.approximate = !out.beyond_upper_bound && out.lower_bound < out.distance;
    if (seed_ != nullptr) {
      out.point_a = seed_->point_a;
      out.point_b = seed_->point_b;
      out.triangle_a = seed_->triangle_a;
      out.triangle_b = seed_->triangle_b;
    } else if (best_ < kInf) {
      out.point_a = pose_a.apply(pa_);
      out.point_b = pose_a.apply(pb_);
      out.triangle_a = tris_a[ia_];
      out.triangle_b = tris_b[jb_];
    }
  }

 private:
  const DistanceRequest& request_;
  const detail::DistanceSeed* seed_;  // while the seed's pair is the best one
  Scalar best_ = kInf;
  Scalar min_skipped_ = kInf;
  bool intersecting_ = false;
  Vec3 pa_ = Vec3::Zero();  // A's model frame
  Vec3 pb_ = Vec3::Zero();
  std::uint32_t ia_ = 0;  // leaf-order triangle indices
  std::uint32_t jb_ = 0;
};

DistanceResult surface_distance(const Model& a, const Transform& pose_a, const Model& b,
                                const Transform& pose_b, const DistanceRequest& request,
                                const detail::DistanceSeed* seed) {
  DistanceResult result;
  Search search(request, seed);
  // delta 0: the frame's margin is then only the rounding allowance of the volume tests.
  const detail::PairFrame frame(a, pose_a, b, pose_b, 0);
  const Mat3& rot = frame.b_to_a.rotation;
  const Vec3& trans = frame.b_to_a.translation;
  const auto nodes_a = a.nodes();
  const auto nodes_b = b.nodes();
  const LeafCorners verts_a = a.leaf_corners();
  const LeafCorners verts_b = b.leaf_corners();

  // A node of B with its volumes mapped into A's frame (the box only when needed): while the walk
  // descends A, both child pairs share it.
  struct MappedNode {
    std::uint32_t index = UINT32_MAX;
    Vec3 sphere_center;
    Mat3 axes;
    Vec3 center;
    bool has_box = false;
  };
  const auto map_node = [&](std::uint32_t ib, MappedNode& m) {
    if (m.index == ib) return;
    m.index = ib;
    m.sphere_center = rot * nodes_b[ib].center + trans;
    m.has_box = false;
  };
  // A node pair's bound: `lb` a lower bound of the distance between the contents (>= 0), `key`
  // the order of visit: the gap when the volumes are apart, else the signed sphere gap, which
  // ranks overlapping pairs by how far their centres are apart for their size (the boxes'
  // overlap depth ranks them worse: it favours large boxes). The OBB gap is only computed when
  // the sphere gap cannot prune.
  struct Bound {
    Scalar lb, key;
  };
  const auto bound = [&](std::uint32_t ia, MappedNode& mb) {
    ++result.node_pairs;
    const BvhNode& na = nodes_a[ia];
    const BvhNode& nb = nodes_b[mb.index];
    const Scalar sphere =
        detail::sphere_gap(na.sphere(), mb.sphere_center, nb.radius) - frame.margin;
    if (search.prune(std::max(sphere, Scalar{0})))
      return Bound{std::max(sphere, Scalar{0}), sphere};
    if (!mb.has_box) {
      mb.axes = rot * nb.axes();
      mb.center = mb.sphere_center;
      mb.has_box = true;
    }
    const Scalar obb = detail::obb_gap(na.obb(), mb.axes, mb.center, nb.half_extents(),
                                       search.cutoff() + frame.margin) -
                       frame.margin;
    const Scalar key = obb > 0 ? std::max(sphere, obb) : sphere;
    return Bound{std::max(key, Scalar{0}), key};
  };

  // B's leaf triangles in A's frame with their boxes and unit normals, in chunks of kCached,
  // kept while consecutive leaf pairs share the chunk (the walk descends A under a fixed B node).
  struct Mapped {
    std::array<Vec3, 3> v;
    Vec3 lo, hi, n, c;  // box, unit normal, centroid
  };
  constexpr std::uint32_t kCached = 8;
  std::array<Mapped, kCached> chunk;
  std::uint32_t chunk_first = UINT32_MAX;  // leaf-order index of chunk[0]
  const auto unit_normal = [](const Vec3* t) {
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
    const Scalar len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
  };
  const auto leaf_pair = [&](std::uint32_t la, std::uint32_t lb) {
    const BvhNode& na = nodes_a[la];
    const BvhNode& nb = nodes_b[lb];
    for (std::uint32_t first = nb.first_or_right; first < nb.first_or_right + nb.count;
         first += kCached) {
      const std::uint32_t count = std::min(kCached, nb.first_or_right + nb.count - first);
      if (chunk_first != first) {
        for (std::uint32_t k = 0; k < count; ++k) {
          Mapped& m = chunk[k];
          for (int v = 0; v < 3; ++v) m.v[v] = frame.b_to_a.apply(verts_b(first + k, v));
          m.lo = m.v[0].cwiseMin(m.v[1]).cwiseMin(m.v[2]);
          m.hi = m.v[0].cwiseMax(m.v[1]).cwiseMax(m.v[2]);
          m.n = unit_normal(m.v.data());
          m.c = (m.v[0] + m.v[1] + m.v[2]) / 3;
        }
        chunk_first = first;
      }
      for (std::uint32_t ia = na.first_or_right; ia < na.first_or_right + na.count; ++ia) {
        const Vec3 ta[3] = {verts_a(ia, 0), verts_a(ia, 1), verts_a(ia, 2)};
        const Vec3 lo_a = ta[0].cwiseMin(ta[1]).cwiseMin(ta[2]);
        const Vec3 hi_a = ta[0].cwiseMax(ta[1]).cwiseMax(ta[2]);
        const Vec3 n_a = unit_normal(ta);
        const Vec3 c_a = (ta[0] + ta[1] + ta[2]) / 3;
        for (std::uint32_t k = 0; k < count; ++k) {
          const Mapped& m = chunk[k];
          // The box gap is exact in its sign (monotone rounding). The plane and centroid-axis
          // gaps are rounded: they are lowered by the frame's rounding allowance, so that no pair
          // whose computed distance could beat the best is skipped, and left out while an exact
          // intersection is being looked for. The cheaper ones go first.
          Scalar lb = detail::box_gap(lo_a, hi_a, m.lo, m.hi);
          if (search.prune(lb)) continue;
          if (!search.hunting()) {
            lb = std::max({lb, detail::plane_gap(n_a, ta[0], m.v.data()) - frame.margin,
                           detail::plane_gap(m.n, m.v[0], ta) - frame.margin});
            if (search.prune(lb)) continue;
            lb = std::max(lb, detail::centroid_axis_gap(c_a, m.c, ta, m.v.data()) - frame.margin);
            if (search.prune(lb)) continue;
          }
          ++result.triangle_tests;
          search.offer(geometry::triangle_distance(ta[0], ta[1], ta[2], m.v[0], m.v[1], m.v[2]), ta,
                       m.v.data(), ia, first + k);
          if (search.done()) return;
        }
      }
    }
  };

  struct Item {
    std::uint32_t ia, ib;
    Scalar lb;
  };
  // Each step pops one pair and pushes at most four, its children one level down in each tree, so
  // the stack holds at most three siblings per level of the current path: 3 (depth(A) + depth(B))
  // + 1 entries; every Model's depth is at most kMaxTreeLevels (antcd/bvh.hpp).
  std::array<Item, 512> stack;
  static_assert(std::tuple_size_v<decltype(stack)> >= 3 * 2 * kMaxTreeLevels + 1);
  std::size_t top = 0;
  MappedNode mapped[2];
  map_node(0, mapped[0]);
  if (const Bound b = bound(0, mapped[0]); !search.prune(b.lb)) stack[top++] = {0, 0, b.lb};
  while (top > 0 && !search.done()) {
    const Item item = stack[--top];
    if (search.prune(item.lb)) continue;  // the best distance may have dropped since the push
    const BvhNode& na = nodes_a[item.ia];
    const BvhNode& nb = nodes_b[item.ib];
    if (na.is_leaf() && nb.is_leaf()) {
      leaf_pair(item.ia, item.ib);
      continue;
    }
    // Descend both nodes at once (a leaf stays): up to four child pairs, ranked by signed gap.
    std::uint32_t kids_a[2] = {item.ia, item.ia};
    std::uint32_t kids_b[2] = {item.ib, item.ib};
    const int n_a = na.is_leaf() ? 1 : 2;
    const int n_b = nb.is_leaf() ? 1 : 2;
    if (n_a == 2) kids_a[0] = item.ia + 1, kids_a[1] = na.first_or_right;
    if (n_b == 2) kids_b[0] = item.ib + 1, kids_b[1] = nb.first_or_right;
    Item kids[4];
    Scalar keys[4];
    int n = 0;
    for (int j = 0; j < n_b; ++j) {
      map_node(kids_b[j], mapped[j]);
      for (int i = 0; i < n_a; ++i) {
        const Bound bd = bound(kids_a[i], mapped[j]);
        if (search.prune(bd.lb)) continue;
        // Insertion by key, farthest first, so the nearest pair is pushed last.
        int k = n++;
        for (; k > 0 && keys[k - 1] < bd.key; --k) {
          kids[k] = kids[k - 1];
          keys[k] = keys[k - 1];
        }
        kids[k] = {kids_a[i], kids_b[j], bd.lb};
        keys[k] = bd.key;
      }
    }
    for (int k = 0; k < n; ++k) stack[top++] = kids[k];
  }
  search.finish(pose_a, a.leaf_triangles(), b.leaf_triangles(), result);
  return result;
}

}  // namespace

DistanceResult distance(const Model& a, const Transform& pose_a, const Model& b,
                        const Transform& pose_b, const DistanceRequest& request) {
  check_request(request);
  return surface_distance(a, pose_a, b, pose_b, request, nullptr);
}

DistanceResult detail::seeded_distance(const Model& a, const Transform& pose_a, const Model& b,
                                       const Transform& pose_b, const DistanceRequest& request,
                                       const DistanceSeed& seed) {
  check_request(request);
  const bool usable = seed.distance > 0 && seed.distance < kInf;
  return surface_distance(a, pose_a, b, pose_b, request, usable ? &seed : nullptr);
}

}  // namespace antcd
