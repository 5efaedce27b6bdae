// The bounding-volume features of an object pair (see features.hpp for the contract).
#include <antcd/geometry.hpp>
#include <antcd_learned/features.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace antcd::learned {
namespace {

/// Largest number of node pairs one level can hold (2^kFeatureDepth squared).
constexpr std::size_t kMaxLevelPairs = std::size_t{1} << (2 * kFeatureDepth);
/// Normalised separating margins are clipped to [-1, kMarginCap].
constexpr Scalar kMarginCap = 3;

struct NodePair {  // trivial, so that the level buffers below are not zero-filled per call
  std::uint32_t a;
  std::uint32_t b;
};

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

/// Nodes of a tree at each level 0..kFeatureDepth (leaves repeated below their level).
std::array<std::size_t, kFeatureDepth + 1> level_sizes(std::span<const BvhNode> nodes) {
  std::array<std::size_t, kFeatureDepth + 1> sizes{};
  // Depth-first walk to kFeatureDepth with an explicit stack (at most 2 * depth + 1 entries).
  std::array<std::pair<std::uint32_t, int>, 2 * kFeatureDepth + 2> stack{};
  std::size_t top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const auto [i, level] = stack[--top];
    if (nodes[i].is_leaf()) {
      for (int l = level; l <= kFeatureDepth; ++l) ++sizes[static_cast<std::size_t>(l)];
      continue;
    }
    ++sizes[static_cast<std::size_t>(level)];
    if (level == kFeatureDepth) continue;
    stack[top++] = {nodes[i].first_or_right, level + 1};
    stack[top++] = {i + 1, level + 1};
  }
  return sizes;
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

  // Level by level: node pairs whose spheres and OBBs both overlap, their share of all node
  // pairs of that level, and (first three levels) the smallest sphere gap and smallest
  // largest-SAT-margin among the examined pairs.
  const auto size_a = level_sizes(na);
  const auto size_b = level_sizes(nb);
  std::array<NodePair, kMaxLevelPairs> buf0;  // NOLINT: filled before read
  std::array<NodePair, kMaxLevelPairs> buf1;
  NodePair* cur = buf0.data();
  NodePair* next = buf1.data();
  std::size_t cur_n = worst <= 0 && d <= sa.radius + sb.radius + delta ? 1 : 0;
  cur[0] = {0, 0};
  std::array<Scalar, kFeatureDepth> counts{};
  std::array<Scalar, 3> min_gap{};
  std::array<Scalar, 3> min_sat{};
  for (int level = 1; level <= kFeatureDepth; ++level) {
    Scalar gap = 4;
    Scalar sat = kMarginCap;
    std::size_t next_n = 0;
    for (std::size_t p = 0; p < cur_n; ++p) {
      std::uint32_t ca[2];
      std::uint32_t cb[2];
      const int nca = children(na, cur[p].a, ca);
      const int ncb = children(nb, cur[p].b, cb);
      for (int x = 0; x < nca; ++x) {
        for (int y = 0; y < ncb; ++y) {
          const Sphere s1 = na[ca[x]].sphere();
          const Sphere s2 = moved(nb[cb[y]].sphere(), b_to_a);
          const Scalar rr = s1.radius + s2.radius;
          if (level > 3) {
            // Deeper levels only count overlaps: the library's tests, no margins.
            if (!geometry::sphere_overlap(s1, s2, delta)) continue;
            if (!geometry::obb_overlap(na[ca[x]].obb(), moved(nb[cb[y]].obb(), b_to_a), delta)) {
              continue;
            }
            next[next_n++] = {ca[x], cb[y]};
            continue;
          }
          const Scalar g = ((s2.center - s1.center).norm() - rr - delta) / std::max(rr, 1e-12 * s);
          gap = std::min(gap, g);
          if (g > 0) continue;
          std::array<Scalar, 15> mm;
          const Scalar w =
              sat_margins(na[ca[x]].obb(), moved(nb[cb[y]].obb(), b_to_a), delta, mm.data());
          sat = std::min(sat, w);
          if (w > 0) continue;
          next[next_n++] = {ca[x], cb[y]};
        }
      }
    }
    const auto l = static_cast<std::size_t>(level);
    counts[l - 1] = static_cast<Scalar>(next_n);
    if (level <= 3) {
      min_gap[l - 1] = std::min<Scalar>(gap, 4);
      min_sat[l - 1] = sat;
    }
    std::swap(cur, next);
    cur_n = next_n;
  }
  for (int level = 1; level <= kFeatureDepth; ++level) {
    const auto l = static_cast<std::size_t>(level);
    const Scalar all = static_cast<Scalar>(size_a[l]) * static_cast<Scalar>(size_b[l]);
    put(counts[l - 1] / std::max<Scalar>(all, 1));
    put(std::log1p(counts[l - 1]));
  }
  for (std::size_t l = 0; l < 3; ++l) {
    put(min_gap[l]);
    put(min_sat[l]);
  }
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
      "share_l1", "log_count_l1", "share_l2", "log_count_l2", "share_l3", "log_count_l3",
      "share_l4", "log_count_l4", "share_l5", "log_count_l5",
      "gap_l1", "sat_l1", "gap_l2", "sat_l2", "gap_l3", "sat_l3"};
  // clang-format on
  return names;
}

}  // namespace antcd::learned
