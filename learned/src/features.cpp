// The bounding-volume features of an object pair (see features.hpp for the contract).
#include <antcd/geometry.hpp>
#include <antcd_learned/features.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

namespace antcd::learned {
namespace {

/// Levels whose node-pair counts are also given as a share of all node pairs of the level.
constexpr int kShareDepth = 5;
/// Levels whose smallest sphere gap and SAT margin are given.
constexpr int kMarginDepth = 3;
/// Normalised separating margins are clipped to [-1, kMarginCap].
constexpr Scalar kMarginCap = 3;

struct NodePair {  // trivial, so that the level buffers below are not zero-filled per call
  std::uint32_t a;
  std::uint32_t b;
  /// Normalised sphere gap of the pair (negative: overlap).
  float key;
};

/// Deepest first; ties in node order, so that the kept set is a function of the pair alone.
bool deeper(const NodePair& x, const NodePair& y) {
  if (x.key != y.key) return x.key < y.key;
  return x.a != y.a ? x.a < y.a : x.b < y.b;
}

/// Keeps `keep` of the `n` pairs at `p`, evenly spread over them (in their order), so that the
/// kept ones cover the whole overlap region. Returns the count.
std::size_t keep_spread(NodePair* p, std::size_t n, std::size_t keep) {
  if (n <= keep) return n;
  for (std::size_t k = 0; k < keep; ++k) p[k] = p[k * n / keep];
  return keep;
}

/// The separating-axis margin of boxes `a` and `b` (same frame) along `axis` (need not be unit):
/// (|centre distance along the axis| - (a's + b's projected radius + delta)) divided by that
/// radius sum: negative while the projections overlap, -1 when the centres coincide, > 0 when
/// the axis separates. A (near-)null axis — a cross product of parallel edges — reports -1.
Scalar axis_margin(const Obb& a, const Obb& b, const Vec3& d, const Vec3& axis, Scalar delta) {
  const Scalar len = axis.norm();
  if (len < 1e-6) return -1;
  const Scalar ra = a.half_extents.dot((a.axes.transpose() * axis).cwiseAbs());
  const Scalar rb = b.half_extents.dot((b.axes.transpose() * axis).cwiseAbs());
  const Scalar r = ra + rb + delta * len;
  if (!(r > 0)) return -1;
  return std::min(kMarginCap, (std::abs(d.dot(axis)) - r) / r);
}

/// The 15 margins of the separating-axis test in the usual order: a's 3 axes, b's 3 axes, then
/// a_i x b_j for i, j = 0..2. Returns the largest (the most separating axis).
Scalar sat_margins(const Obb& a, const Obb& b, Scalar delta, Scalar* out) {
  const Vec3 d = b.center - a.center;
  Scalar worst = -std::numeric_limits<Scalar>::infinity();
  int k = 0;
  const auto put = [&](const Vec3& axis) {
    out[k] = axis_margin(a, b, d, axis, delta);
    worst = std::max(worst, out[k]);
    ++k;
  };
  for (int i = 0; i < 3; ++i) put(a.axes.col(i));
  for (int j = 0; j < 3; ++j) put(b.axes.col(j));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) put(a.axes.col(i).cross(b.axes.col(j)));
  }
  return worst;
}

Obb moved(const Obb& o, const Transform& t) {
  Obb out = o;
  out.center = t.apply(o.center);
  out.axes = t.rotation * o.axes;
  return out;
}

Sphere moved(const Sphere& s, const Transform& t) { return {t.apply(s.center), s.radius}; }

/// Children of node `i` of `nodes` one level down: its two children, or itself for a leaf (a
/// leaf stands for itself at every deeper level). Returns how many were written.
int children(std::span<const BvhNode> nodes, std::uint32_t i, std::uint32_t* out) {
  if (nodes[i].is_leaf()) {
    out[0] = i;
    return 1;
  }
  out[0] = i + 1;
  out[1] = nodes[i].first_or_right;
  return 2;
}

/// Nodes of a tree at each level 0..kShareDepth (leaves repeated below their level).
std::array<std::size_t, kShareDepth + 1> level_sizes(std::span<const BvhNode> nodes) {
  std::array<std::size_t, kShareDepth + 1> sizes{};
  // Depth-first walk to kShareDepth with an explicit stack (at most 2 * depth + 1 entries).
  std::array<std::pair<std::uint32_t, int>, 2 * kShareDepth + 2> stack{};
  std::size_t top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const auto [i, level] = stack[--top];
    if (nodes[i].is_leaf()) {
      for (int l = level; l <= kShareDepth; ++l) ++sizes[static_cast<std::size_t>(l)];
      continue;
    }
    ++sizes[static_cast<std::size_t>(level)];
    if (level == kShareDepth) continue;
    stack[top++] = {nodes[i].first_or_right, level + 1};
    stack[top++] = {i + 1, level + 1};
  }
  return sizes;
}

struct ShapeStats {
  Scalar min_gap = 4;            ///< smallest corner distance / the two leaves' radius sum
  Scalar mean_gap = 4;           ///< its mean over the leaf pairs
  Scalar leaf_straddle = 0;      ///< share of leaf pairs with a triangle pair straddling
  Scalar triangle_straddle = 0;  ///< share of triangle pairs straddling each other's planes
  Scalar straddling = 0;         ///< log(1 + straddling triangle pairs)
  /// Smallest centroid distance of a straddling triangle pair over the sum of the two triangles'
  /// centroid-to-corner radii (4 when none straddles): below 1 the triangles likely cross.
  Scalar straddle_gap = 4;
  Scalar normal_cos = 0;  ///< mean |cos| between the leaves' mean normals
  Scalar spread_a = 0;    ///< mean 1 - |sum of area normals| / sum of their lengths, A
  Scalar spread_b = 0;    ///< same for B
};

/// Most triangles read per leaf (a leaf holds BuildOptions::leaf_size, 4 by default).
constexpr std::size_t kLeafTriangles = 8;

/// The shape statistics of leaf pairs `pairs` (see ShapeStats), B's corners in A's frame.
ShapeStats leaf_shapes(const Model& a, const Model& b, const Transform& b_to_a, Scalar delta,
                       std::span<const NodePair> pairs) {
  ShapeStats out;
  if (pairs.empty()) return out;
  const auto na = a.nodes();
  const auto nb = b.nodes();
  const LeafCorners ka = a.leaf_corners();
  const LeafCorners kb = b.leaf_corners();
  Scalar gap_sum = 0;
  Scalar cos_sum = 0;
  Scalar spread_sum_a = 0;
  Scalar spread_sum_b = 0;
  std::size_t straddling_leaves = 0;
  std::size_t straddling = 0;
  std::size_t tested = 0;
  for (const NodePair& p : pairs) {
    std::array<std::array<Vec3, 3>, kLeafTriangles> ta;
    std::array<std::array<Vec3, 3>, kLeafTriangles> tb;
    const std::size_t nta = std::min<std::size_t>(na[p.a].count, kLeafTriangles);
    const std::size_t ntb = std::min<std::size_t>(nb[p.b].count, kLeafTriangles);
    for (std::size_t t = 0; t < nta; ++t) ta[t] = ka.triangle(na[p.a].first_or_right + t);
    for (std::size_t t = 0; t < ntb; ++t) {
      const auto tri = kb.triangle(nb[p.b].first_or_right + t);
      for (int c = 0; c < 3; ++c) tb[t][static_cast<std::size_t>(c)] = b_to_a.apply(tri[c]);
    }
    // Smallest corner-to-corner distance, over the two leaves' radius sum.
    Scalar best = std::numeric_limits<Scalar>::infinity();
    for (std::size_t i = 0; i < nta; ++i) {
      for (std::size_t j = 0; j < ntb; ++j) {
        for (const Vec3& u : ta[i]) {
          for (const Vec3& v : tb[j]) best = std::min(best, (u - v).squaredNorm());
        }
      }
    }
    const Scalar rr = std::max<Scalar>(na[p.a].radius + nb[p.b].radius, 1e-300);
    const Scalar g = std::min<Scalar>(std::sqrt(best) / rr, 4);
    out.min_gap = std::min(out.min_gap, g);
    gap_sum += g;
    // Plane step of the triangle-triangle test: each triangle's corners on both sides of (or
    // within delta of) the other's plane.
    const auto straddles = [delta](const std::array<Vec3, 3>& t, const std::array<Vec3, 3>& u) {
      const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
      const Scalar len = n.norm();
      if (!(len > 0)) return true;
      Scalar lo = std::numeric_limits<Scalar>::infinity();
      Scalar hi = -lo;
      for (const Vec3& c : u) {
        const Scalar v = n.dot(c - t[0]) / len;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      return lo <= delta && hi >= -delta;
    };
    bool any = false;
    for (std::size_t i = 0; i < nta; ++i) {
      for (std::size_t j = 0; j < ntb; ++j) {
        ++tested;
        if (straddles(ta[i], tb[j]) && straddles(tb[j], ta[i])) {
          ++straddling;
          const auto centre_radius = [](const std::array<Vec3, 3>& t, Vec3& c) {
            c = (t[0] + t[1] + t[2]) / 3;
            return std::max({(t[0] - c).norm(), (t[1] - c).norm(), (t[2] - c).norm()});
          };
          Vec3 ci;
          Vec3 cj;
          const Scalar r = centre_radius(ta[i], ci) + centre_radius(tb[j], cj);
          if (r > 0) out.straddle_gap = std::min<Scalar>(out.straddle_gap, (ci - cj).norm() / r);
          any = true;
        }
      }
    }
    straddling_leaves += any ? 1 : 0;
    // Normals: each leaf's sum of area normals, its spread and the angle between the two.
    const auto sum_normals = [](const auto& tris, std::size_t n, Scalar& spread) {
      Vec3 sum = Vec3::Zero();
      Scalar lengths = 0;
      for (std::size_t t = 0; t < n; ++t) {
        const Vec3 v = (tris[t][1] - tris[t][0]).cross(tris[t][2] - tris[t][0]);
        sum += v;
        lengths += v.norm();
      }
      spread += lengths > 0 ? 1 - sum.norm() / lengths : 0;
      return sum;
    };
    const Vec3 ma = sum_normals(ta, nta, spread_sum_a);
    const Vec3 mb = sum_normals(tb, ntb, spread_sum_b);
    const Scalar lens = ma.norm() * mb.norm();
    cos_sum += lens > 0 ? std::abs(ma.dot(mb)) / lens : 0;
  }
  const auto n = static_cast<Scalar>(pairs.size());
  out.mean_gap = gap_sum / n;
  out.leaf_straddle = static_cast<Scalar>(straddling_leaves) / n;
  out.triangle_straddle =
      tested > 0 ? static_cast<Scalar>(straddling) / static_cast<Scalar>(tested) : 0;
  out.straddling = std::log1p(static_cast<Scalar>(straddling));
  out.normal_cos = cos_sum / n;
  out.spread_a = spread_sum_a / n;
  out.spread_b = spread_sum_b / n;
  return out;
}

}  // namespace

FeatureVector pair_features(const Model& a, const Transform& pose_a, const Model& b,
                            const Transform& pose_b, Scalar delta) {
  FeatureVector f{};
  std::size_t k = 0;
  const auto put = [&](Scalar v) { f[k++] = static_cast<float>(v); };

  // Everything in A's model frame: B's volumes are carried there by b_to_a.
  const Transform b_to_a = pose_a.inverse() * pose_b;
  const auto na = a.nodes();
  const auto nb = b.nodes();
  const Sphere sa = na[0].sphere();
  const Sphere sb = moved(nb[0].sphere(), b_to_a);
  const Obb oa = na[0].obb();
  const Obb ob = moved(nb[0].obb(), b_to_a);
  const Scalar s = std::max(sa.radius + sb.radius, std::numeric_limits<Scalar>::min());

  // Root spheres.
  const Scalar d = (sb.center - sa.center).norm();
  put(d / s);
  put(std::clamp(
      (sa.radius + sb.radius + delta - d) / std::max(std::min(sa.radius, sb.radius), 1e-12 * s),
      -4.0, 4.0));
  put(sa.radius / s);

  // The 15 separating-axis margins of the root OBBs, the largest, the smallest face margin.
  std::array<Scalar, 15> m{};
  const Scalar worst = sat_margins(oa, ob, delta, m.data());
  for (const Scalar v : m) put(v);
  put(worst);
  put(*std::min_element(m.begin(), m.begin() + 6));

  // Relative placement and orientation of the root OBBs: centre offset along A's box axes, and
  // |cos| of the angles between the two boxes' axes (sign-free: box axes have no direction).
  const Vec3 offset = oa.axes.transpose() * (ob.center - oa.center);
  put(offset.norm() / s);
  for (int i = 0; i < 3; ++i) put(std::abs(offset[i]) / s);
  const Mat3 c = oa.axes.transpose() * ob.axes;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) put(std::abs(c(i, j)));
  }

  // Sizes and volume ratios.
  const Scalar vol_a = std::max(oa.volume(), 1e-300);
  const Scalar vol_b = std::max(ob.volume(), 1e-300);
  put(std::clamp(std::log(vol_a / vol_b), -10.0, 10.0) / 10);
  Vec3 ha = oa.half_extents;
  Vec3 hb = ob.half_extents;
  std::sort(ha.data(), ha.data() + 3, std::greater<>());
  std::sort(hb.data(), hb.data() + 3, std::greater<>());
  for (int i = 0; i < 3; ++i) put(ha[i] / s);
  for (int i = 0; i < 3; ++i) put(hb[i] / s);
  const auto ball = [](Scalar r) { return 4.18879020478639098 * r * r * r; };  // 4/3 pi r^3
  put(std::min(1.0, oa.volume() / std::max(ball(sa.radius), 1e-300)));
  put(std::min(1.0, ob.volume() / std::max(ball(sb.radius), 1e-300)));

  // Level by level: node pairs whose spheres and OBBs both overlap, down to the leaves. The
  // front carried to the next level holds at most kFeatureFront pairs, evenly spread over those
  // found (keeping the deepest-overlapping ones instead lost the contact region on the held-out
  // meshes: docs/learned-baselines.md); pairs of two leaves leave it for `leaves`
  // (kFeatureSamples kept, spread likewise). Counts of
  // levels 1..kFeatureDepth, their share of all node pairs for the first levels, and (first
  // three levels) the smallest sphere gap and smallest largest-SAT-margin of the examined pairs.
  const auto size_a = level_sizes(na);
  const auto size_b = level_sizes(nb);
  std::array<NodePair, kFeatureFront> front;  // NOLINT: filled before read
  std::array<NodePair, 4 * kFeatureFront> next;
  std::array<NodePair, 4 * kFeatureFront + kFeatureSamples> leaves;
  std::size_t front_n = 0;
  std::size_t leaf_n = 0;      // kept in `leaves`
  std::size_t leaf_total = 0;  // found
  bool truncated = false;
  Scalar leaf_penetration = 0;
  const auto sphere_gap = [&](std::uint32_t x, std::uint32_t y) {
    const Sphere s1 = na[x].sphere();
    const Sphere s2 = moved(nb[y].sphere(), b_to_a);
    const Scalar rr = s1.radius + s2.radius;
    return ((s2.center - s1.center).norm() - rr - delta) / std::max(rr, 1e-12 * s);
  };
  const auto add_leaf_pair = [&](std::uint32_t x, std::uint32_t y, Scalar gap) {
    ++leaf_total;
    leaves[leaf_n++] = {x, y, static_cast<float>(gap)};
    const Sphere s1 = na[x].sphere();
    const Sphere s2 = moved(nb[y].sphere(), b_to_a);
    const Scalar pen = (s1.radius + s2.radius + delta - (s2.center - s1.center).norm()) /
                       std::max<Scalar>(std::min(s1.radius, s2.radius), 1e-12 * s);
    leaf_penetration = std::max(leaf_penetration, std::min<Scalar>(pen, 4));
  };
  if (worst <= 0 && d <= sa.radius + sb.radius + delta) {
    if (na[0].is_leaf() && nb[0].is_leaf()) {
      add_leaf_pair(0, 0, sphere_gap(0, 0));
    } else {
      front[front_n++] = {0, 0, 0};
    }
  }
  std::array<Scalar, kFeatureDepth> counts{};
  std::array<Scalar, kMarginDepth> min_gap{};
  std::array<Scalar, kMarginDepth> min_sat{};
  for (int level = 1; front_n > 0 || level <= kFeatureDepth; ++level) {
    Scalar gap = 4;
    Scalar sat = kMarginCap;
    std::size_t next_n = 0;
    std::size_t found = 0;
    for (std::size_t p = 0; p < front_n; ++p) {
      std::uint32_t ca[2];
      std::uint32_t cb[2];
      const int nca = children(na, front[p].a, ca);
      const int ncb = children(nb, front[p].b, cb);
      for (int x = 0; x < nca; ++x) {
        for (int y = 0; y < ncb; ++y) {
          const Scalar g = sphere_gap(ca[x], cb[y]);
          if (level <= kMarginDepth) gap = std::min(gap, g);
          if (g > 0) continue;
          const Obb box_b = moved(nb[cb[y]].obb(), b_to_a);
          if (level <= kMarginDepth) {
            std::array<Scalar, 15> mm;
            const Scalar w = sat_margins(na[ca[x]].obb(), box_b, delta, mm.data());
            sat = std::min(sat, w);
            if (w > 0) continue;
          } else if (!geometry::obb_overlap(na[ca[x]].obb(), box_b, delta)) {
            continue;  // deeper levels only count overlaps: the library's test, no margins
          }
          ++found;
          if (na[ca[x]].is_leaf() && nb[cb[y]].is_leaf()) {
            add_leaf_pair(ca[x], cb[y], g);
          } else {
            next[next_n++] = {ca[x], cb[y], static_cast<float>(g)};
          }
        }
      }
    }
    if (level <= kFeatureDepth)
      counts[static_cast<std::size_t>(level - 1)] = static_cast<Scalar>(found);
    if (level <= kMarginDepth) {
      min_gap[static_cast<std::size_t>(level - 1)] = std::min<Scalar>(gap, 4);
      min_sat[static_cast<std::size_t>(level - 1)] = sat;
    }
    truncated = truncated || next_n > kFeatureFront;
    front_n = keep_spread(next.data(), next_n, kFeatureFront);
    std::copy_n(next.begin(), front_n, front.begin());
    leaf_n = keep_spread(leaves.data(), leaf_n, kFeatureSamples);
  }
  for (int level = 1; level <= kShareDepth; ++level) {
    const auto l = static_cast<std::size_t>(level);
    const Scalar all = static_cast<Scalar>(size_a[l]) * static_cast<Scalar>(size_b[l]);
    put(counts[l - 1] / std::max<Scalar>(all, 1));
  }
  for (int level = 1; level <= kShareDepth; ++level) put(std::log1p(counts[level - 1]));
  for (std::size_t l = 0; l < kMarginDepth; ++l) {
    put(min_gap[l]);
    put(min_sat[l]);
  }
  for (int level = kShareDepth + 1; level <= kFeatureDepth; ++level) {
    put(std::log1p(counts[level - 1]));
  }
  put(std::log1p(static_cast<Scalar>(leaf_total)));
  put(truncated ? 1 : 0);
  put(leaf_penetration);

  // Shape: the kept leaf pairs, read through their triangles (sorted, so that the statistics'
  // rounding does not depend on the order they were kept in).
  std::sort(leaves.begin(), leaves.begin() + static_cast<std::ptrdiff_t>(leaf_n), deeper);
  const std::span<const NodePair> picked(leaves.data(), leaf_n);
  const std::size_t picked_n = leaf_n;
  const ShapeStats shape = leaf_shapes(a, b, b_to_a, delta, picked);
  put(static_cast<Scalar>(picked_n) / kFeatureSamples);
  put(shape.min_gap);
  put(shape.mean_gap);
  put(shape.leaf_straddle);
  put(shape.triangle_straddle);
  put(shape.straddling);
  put(shape.straddle_gap);
  put(shape.normal_cos);
  put(shape.spread_a);
  put(shape.spread_b);
  return f;
}

const std::array<std::string_view, kFeatureCount>& feature_names() {
  // clang-format off
  static const std::array<std::string_view, kFeatureCount> names = {
      "sphere_distance", "sphere_penetration", "radius_share",
      "sat_a0", "sat_a1", "sat_a2", "sat_b0", "sat_b1", "sat_b2",
      "sat_a0xb0", "sat_a0xb1", "sat_a0xb2", "sat_a1xb0", "sat_a1xb1", "sat_a1xb2",
      "sat_a2xb0", "sat_a2xb1", "sat_a2xb2", "sat_max", "sat_face_min",
      "offset", "offset_a0", "offset_a1", "offset_a2",
      "cos00", "cos01", "cos02", "cos10", "cos11", "cos12", "cos20", "cos21", "cos22",
      "log_volume_ratio", "half_a0", "half_a1", "half_a2", "half_b0", "half_b1", "half_b2",
      "fill_a", "fill_b",
      "share_l1", "share_l2", "share_l3", "share_l4", "share_l5",
      "log_count_l1", "log_count_l2", "log_count_l3", "log_count_l4", "log_count_l5",
      "gap_l1", "sat_l1", "gap_l2", "sat_l2", "gap_l3", "sat_l3",
      "log_count_l6", "log_count_l7", "log_count_l8", "log_count_l9", "log_count_l10",
      "log_leaf_pairs", "front_left", "leaf_penetration",
      "samples", "point_gap_min", "point_gap_mean", "leaf_straddle", "triangle_straddle",
      "log_straddling", "straddle_gap",
      "normal_cos", "normal_spread_a", "normal_spread_b"};
  // clang-format on
  return names;
}

const std::array<FeatureGroup, kFeatureGroups>& feature_groups() {
  static const std::array<FeatureGroup, kFeatureGroups> groups = {{
      {"root", 0, 42},
      {"levels1-5", 42, 16},
      {"levels6-10", 58, 5},
      {"leaves", 63, 3},
      {"shape", 66, 10},
  }};
  return groups;
}

}  // namespace antcd::learned
