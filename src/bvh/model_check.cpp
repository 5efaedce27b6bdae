// The model file reader's proofs about the tree it has read (bvh/model_check.hpp): its shape, and
// that every node's volumes hold its subtree's triangles, so that a file the reader accepts
// answers every query as the model rebuilt from its mesh would (docs/model_file.md).
//
// The volume check proves, for every node A and every vertex p of A's subtree, the point test
// T(A, p): p inside A's box and inside A's sphere, each widened by A's slack (kArithmetic of A's
// size, far inside the traversal's own tolerance::kVolume). Testing every such pair costs each
// vertex once per level of the tree, most of a load. Instead, for each node A its subtree is
// descended, and a descendant D whose volumes are already known to hold D's vertices is not
// descended further for a face (or the sphere) of A that D's sphere or box lies inside of, with
// half of A's slack to spare; whatever is left at a leaf is point-tested as before. The faces of
// A are only touched near A's own boundary, so few descendants are visited for each A. See
// holds_subtree for the argument that this accepts exactly the files the point tests accept.
#include "bvh/model_check.hpp"

#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>
#include <antcd/tolerances.hpp>

#include "util/parallel.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// x86-64 with GCC or Clang: the point tests also in AVX2, chosen at run time (holds_points).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__EMSCRIPTEN__)
#define ANTCD_CHECK_AVX2 1
#include <immintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <span>

namespace antcd::detail {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& problem) {
  throw MeshError(name, problem);
}

/// Whether the node's axes are orthonormal up to tolerance::kArithmetic.
bool orthonormal(const BvhNode& node) {
  const Scalar e = tolerance::kArithmetic;
  return std::abs(node.axis0.squaredNorm() - 1) <= e &&
         std::abs(node.axis1.squaredNorm() - 1) <= e && std::abs(node.axis0.dot(node.axis1)) <= e;
}

/// A node's point test, in quarter coordinates (which neither overflow nor make a NaN for any
/// finite ones; a stored +inf extent or radius holds everything along it): p is inside when
/// |a[k] . p - g[k]| <= l[k] for k = 0, 1, 2 and the squares of those three sum to at most
/// reach^2. a's rows are the box axes (orthonormal, checked before), g the box centre in their
/// frame, l the half extents and reach the radius, each widened by the slack: kArithmetic of the
/// node's size, for the rounding of a fit. `margin`: what holds_subtree keeps to spare.
struct Frame {
  Scalar a[3][3];
  Scalar g[3];
  Scalar l[3];
  Scalar reach;
  Scalar margin;
};

Frame frame_of(const BvhNode& node) {
  const Mat3 to_box = node.axes().transpose();
  const Vec3 center = node.center * 0.25;
  const Vec3 half = node.half_extents() * 0.25;
  const Scalar radius = 0.25 * static_cast<Scalar>(node.radius);
  // A valid node's points lie within its smaller volume's reach of its centre.
  const Scalar slack =
      tolerance::kArithmetic * (center.cwiseAbs().maxCoeff() + std::min(radius, half.norm())) +
      tolerance::kFloor;
  const Vec3 box_center = to_box * center;
  Frame f{};
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) f.a[k][j] = to_box(k, j);
    f.g[k] = box_center[k];
    f.l[k] = half[k] + slack;
  }
  f.reach = radius + slack;
  // Half a slack of the largest bound: far more than the rounding of any test against the node
  // of a point within its bounds (holds_subtree); +inf (no discharge at all) for an infinite one.
  f.margin = 0.5 * tolerance::kArithmetic *
                 (center.cwiseAbs().maxCoeff() + std::max({f.l[0], f.l[1], f.l[2], f.reach})) +
             tolerance::kFloor;
  return f;
}

/// The leaves' distinct vertices in quarter coordinates, laid out in leaf order: node i's are the
/// run [first[i], last[i]).
struct Points {
  std::unique_ptr<Scalar[]> x, y, z;
  std::unique_ptr<std::size_t[]> first, last;
};

/// Whether the point test of `f` holds for the points [first, last) (all of it, or with `Axis`
/// 0, 1 or 2 only the two faces across that axis). Inside: every comparison true (a NaN compares
/// false, so it counts as outside). Two points at a time with SSE2 (an odd run's last point
/// twice), exactly as one at a time.
template <int Axis = -1>
bool holds_points_sse2(const Frame& f, const Points& p, std::size_t first, std::size_t last) {
  const Scalar* x = p.x.get();
  const Scalar* y = p.y.get();
  const Scalar* z = p.z.get();
  constexpr int k0 = Axis < 0 ? 0 : Axis;  // the rows evaluated: k0 .. k1
  constexpr int k1 = Axis < 0 ? 2 : Axis;
#if defined(__SSE2__)
  __m128d a[3][3], g[3], l[3];
  for (int k = k0; k <= k1; ++k) {
    for (int j = 0; j < 3; ++j) a[k][j] = _mm_set1_pd(f.a[k][j]);
    g[k] = _mm_set1_pd(f.g[k]);
    l[k] = _mm_set1_pd(f.l[k]);
  }
  const __m128d reach2 = _mm_set1_pd(f.reach * f.reach);
  const __m128d sign = _mm_set1_pd(-0.0);
  __m128d all = _mm_castsi128_pd(_mm_set1_epi32(-1));
  const auto test = [&](__m128d px, __m128d py, __m128d pz) {
    __m128d d[3];
    for (int k = k0; k <= k1; ++k) {
      d[k] = _mm_sub_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(a[k][0], px), _mm_mul_pd(a[k][1], py)),
                                   _mm_mul_pd(a[k][2], pz)),
                        g[k]);
      all = _mm_and_pd(all, _mm_cmple_pd(_mm_andnot_pd(sign, d[k]), l[k]));
    }
    if constexpr (Axis < 0) {
      const __m128d r2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(d[0], d[0]), _mm_mul_pd(d[1], d[1])),
                                    _mm_mul_pd(d[2], d[2]));
      all = _mm_and_pd(all, _mm_cmple_pd(r2, reach2));
    }
  };
  std::size_t i = first;
  for (; i + 2 <= last; i += 2) test(_mm_loadu_pd(x + i), _mm_loadu_pd(y + i), _mm_loadu_pd(z + i));
  if (i < last) test(_mm_load1_pd(x + i), _mm_load1_pd(y + i), _mm_load1_pd(z + i));
  return _mm_movemask_pd(all) == 3;
#else
  bool inside = true;
  for (std::size_t i = first; i < last; ++i) {
    Scalar d[3] = {0, 0, 0};
    for (int k = k0; k <= k1; ++k) {
      d[k] = f.a[k][0] * x[i] + f.a[k][1] * y[i] + f.a[k][2] * z[i] - f.g[k];
      inside = inside && std::abs(d[k]) <= f.l[k];
    }
    if constexpr (Axis < 0) {
      inside = inside && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= f.reach * f.reach;
    }
  }
  return inside;
#endif
}

#if defined(ANTCD_CHECK_AVX2)
/// holds_points_sse2 four points at a time with AVX2 (the same operations in the same order: no
/// fused multiply-add), for the x86-64 processors that have it; the last 1 to 3 points repeat the
/// run's last one.
template <int Axis>
__attribute__((target("avx2"))) bool holds_points_avx2(const Frame& f, const Points& p,
                                                       std::size_t first, std::size_t last) {
  const Scalar* x = p.x.get();
  const Scalar* y = p.y.get();
  const Scalar* z = p.z.get();
  constexpr int k0 = Axis < 0 ? 0 : Axis;
  constexpr int k1 = Axis < 0 ? 2 : Axis;
  __m256d a[3][3], g[3], l[3];
  for (int k = k0; k <= k1; ++k) {
    for (int j = 0; j < 3; ++j) a[k][j] = _mm256_set1_pd(f.a[k][j]);
    g[k] = _mm256_set1_pd(f.g[k]);
    l[k] = _mm256_set1_pd(f.l[k]);
  }
  const __m256d reach2 = _mm256_set1_pd(f.reach * f.reach);
  const __m256d sign = _mm256_set1_pd(-0.0);
  __m256d all = _mm256_castsi256_pd(_mm256_set1_epi32(-1));
  for (std::size_t i = first; i < last; i += 4) {
    __m256d px, py, pz;
    if (i + 4 <= last) {
      px = _mm256_loadu_pd(x + i);
      py = _mm256_loadu_pd(y + i);
      pz = _mm256_loadu_pd(z + i);
    } else {
      const std::size_t i1 = std::min(i + 1, last - 1), i2 = std::min(i + 2, last - 1);
      px = _mm256_set_pd(x[last - 1], x[i2], x[i1], x[i]);
      py = _mm256_set_pd(y[last - 1], y[i2], y[i1], y[i]);
      pz = _mm256_set_pd(z[last - 1], z[i2], z[i1], z[i]);
    }
    __m256d d[3];
    for (int k = k0; k <= k1; ++k) {
      d[k] = _mm256_sub_pd(
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a[k][0], px), _mm256_mul_pd(a[k][1], py)),
                        _mm256_mul_pd(a[k][2], pz)),
          g[k]);
      all = _mm256_and_pd(all, _mm256_cmp_pd(_mm256_andnot_pd(sign, d[k]), l[k], _CMP_LE_OQ));
    }
    if constexpr (Axis < 0) {
      const __m256d r2 =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1])),
                        _mm256_mul_pd(d[2], d[2]));
      all = _mm256_and_pd(all, _mm256_cmp_pd(r2, reach2, _CMP_LE_OQ));
    }
  }
  return _mm256_movemask_pd(all) == 15;
}

/// Whether this processor runs AVX2 (asked once).
bool has_avx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
  return avx2;
}
#endif

/// Whether the point test of `f` holds for the points [first, last) (all of it, or with `Axis`
/// 0, 1 or 2 only the two faces across that axis).
template <int Axis = -1>
bool holds_points(const Frame& f, const Points& p, std::size_t first, std::size_t last) {
#if defined(ANTCD_CHECK_AVX2)
  if (has_avx2()) return holds_points_avx2<Axis>(f, p, first, last);
#endif
  return holds_points_sse2<Axis>(f, p, first, last);
}

// The constraints of a point test, as bits: the upper faces (a[k] . p - g[k] <= l[k]), the lower
// ones (>= -l[k]) and the sphere.
constexpr unsigned kUpper = 1, kLower = 8, kSphere = 64, kAll = 127;

/// The constraints of `f` that every point inside D's widened volumes satisfies with f.margin to
/// spare (holds_subtree).
unsigned discharged(const Frame& f, const BvhNode& d, unsigned mask) {
  // 16 kArithmetic covers the axes' departure from orthonormality (below), kArithmetic each.
  const Scalar e = 16 * tolerance::kArithmetic;
  const Scalar q[3] = {0.25 * d.center[0], 0.25 * d.center[1], 0.25 * d.center[2]};
  const Scalar h[3] = {0.25 * static_cast<Scalar>(d.half[0]), 0.25 * static_cast<Scalar>(d.half[1]),
                       0.25 * static_cast<Scalar>(d.half[2])};
  const Scalar radius = 0.25 * static_cast<Scalar>(d.radius);
  // At least twice D's slack (h0 + h1 + h2 >= |h|): room for the rounding of D's own tests.
  const Scalar slack =
      2 * (tolerance::kArithmetic * (std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2])}) +
                                     std::min(radius, h[0] + h[1] + h[2])) +
           tolerance::kFloor);
  const Scalar reach = (radius + slack) * (1 + e);
  Scalar w[3];
  for (int k = 0; k < 3; ++k)
    w[k] = f.a[k][0] * q[0] + f.a[k][1] * q[1] + f.a[k][2] * q[2] - f.g[k];
  unsigned bits = 0;
  for (int k = 0; k < 3; ++k) {
    const unsigned sides = mask & ((kUpper | kLower) << k);
    if (sides == 0) continue;
    const Scalar limit = f.l[k] - f.margin;
    Scalar extent = reach;  // D's sphere along a[k] (|a[k]| <= 1 + kArithmetic)
    const bool up = w[k] + extent <= limit, down = extent - w[k] <= limit;
    if (((sides & (kUpper << k)) != 0 && !up) || ((sides & (kLower << k)) != 0 && !down)) {
      const Vec3 b2 = d.axis0.cross(d.axis1);
      const Scalar* axis[3] = {d.axis0.data(), d.axis1.data(), b2.data()};
      Scalar box = 0;  // D's box along a[k]
      for (int j = 0; j < 3; ++j) {
        const Scalar m = f.a[k][0] * axis[j][0] + f.a[k][1] * axis[j][1] + f.a[k][2] * axis[j][2];
        box += (std::abs(m) + e) * (h[j] + slack);
      }
      extent = std::min(extent, box);
    }
    if (w[k] + extent <= limit) bits |= kUpper << k;
    if (extent - w[k] <= limit) bits |= kLower << k;
  }
  if ((mask & kSphere) != 0 &&
      std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) + reach * (1 + e) <= f.reach - f.margin) {
    bits |= kSphere;
  }
  return bits;
}

/// Whether the constraints `mask` of `f` hold for the points [first, last): the faces across
/// one or two axes alone when the sphere is not among them (cheaper), else the whole test.
bool holds_left(const Frame& f, const Points& p, std::size_t first, std::size_t last,
                unsigned mask) {
  const unsigned axes = (mask | mask >> 3) & 7;
  if ((mask & kSphere) != 0 || axes == 7) return holds_points(f, p, first, last);
  return ((axes & 1) == 0 || holds_points<0>(f, p, first, last)) &&
         ((axes & 2) == 0 || holds_points<1>(f, p, first, last)) &&
         ((axes & 4) == 0 || holds_points<2>(f, p, first, last));
}

/// Below this many points a subtree's points are tested directly: cheaper than its volumes.
constexpr std::size_t kDirect = 128;

/// Whether node i's point test holds for every point of its subtree, given (as an induction on
/// the height of the tree: the caller refuses the file if any node fails) that every descendant
/// D's point test holds for D's points.
///
/// Why this accepts exactly the files that point-testing every (node, vertex of its subtree) pair
/// accepts. Each point p of node i's subtree lies in one leaf, and every constraint of i's test
/// (a face or the sphere) is either point-tested at p, exactly as that pair's test, or
/// discharged at some descendant D above p's leaf: D's sphere (or box) widened by twice D's
/// slack lies inside that constraint by at least f.margin (kArithmetic / 2 of i's coordinates
/// and largest bound), `discharged` computing every bound rounded outwards. p passes D's computed
/// test (the induction), so p lies within D's widened volumes exactly, up to D's rounding (about
/// 1e-16 of the coordinates, inside the extra slack: p passes both D's box and D's sphere, so it
/// is as close to D's centre as the smaller of them reaches); then p satisfies the constraint
/// exactly with f.margin to spare, more than a thousand times the rounding of the computed test
/// of i at p (and of `discharged`'s own sums), so that test passes too. The bounds: with axes
/// orthonormal up to kArithmetic (checked), |a[k]| <= 1 + kArithmetic, a point of D's sphere lies
/// within D's radius (1 + 5 kArithmetic) of its centre along a[k] and in the frame of i's axes,
/// and a point t of D's box (its frame's coordinates t) lies within
/// sum_j (|a[k] . b_j| + 11 kArithmetic) |t_j| of D's centre along a[k] (the inverse of D's axes
/// differs from their transpose by at most 10 kArithmetic); `discharged` uses 16 kArithmetic.
/// Conversely a file the pair tests accept passes every point test made here. A NaN or an
/// infinity makes a bound compare false: nothing is discharged by it.
bool holds_subtree(std::span<const BvhNode> nodes, std::size_t i, const Points& p,
                   std::vector<std::pair<std::uint32_t, unsigned>>& stack) {
  const Frame f = frame_of(nodes[i]);
  if (nodes[i].is_leaf() || p.last[i] - p.first[i] <= kDirect) {
    return holds_points(f, p, p.first[i], p.last[i]);
  }
  stack.clear();
  stack.emplace_back(nodes[i].first_or_right, kAll);
  stack.emplace_back(static_cast<std::uint32_t>(i + 1), kAll);
  while (!stack.empty()) {
    const auto [d, mask] = stack.back();
    stack.pop_back();
    const BvhNode& node = nodes[d];
    if (node.is_leaf() || p.last[d] - p.first[d] <= kDirect) {
      if (!holds_left(f, p, p.first[d], p.last[d], mask)) return false;
      continue;
    }
    const unsigned left = mask & ~discharged(f, node, mask);
    if (left != 0) {
      stack.emplace_back(node.first_or_right, left);
      stack.emplace_back(d + 1, left);
    }
  }
  return true;
}

}  // namespace

std::size_t check_tree(const std::vector<BvhNode>& nodes, std::size_t leaf_count,
                       std::uint32_t leaf_size, bool finite_volumes, const std::string& name) {
  const std::size_t n = nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const BvhNode& node = nodes[i];
    const bool finite = node.center.allFinite() && node.axis0.allFinite() && node.axis1.allFinite();
    const bool sizes = node.radius >= 0 && node.half[0] >= 0 && node.half[1] >= 0 &&
                       node.half[2] >= 0;  // +inf allowed for huge meshes (float_at_least), NaN not
    const bool bounded =
        !finite_volumes || (std::isfinite(node.radius) && std::isfinite(node.half[0]) &&
                            std::isfinite(node.half[1]) && std::isfinite(node.half[2]));
    if (!finite || !sizes) {
      fail(name, "node " + std::to_string(i) + " has a non-finite or negative volume");
    }
    if (!bounded) {
      fail(name, "node " + std::to_string(i) +
                     " has an infinite radius or half extent, which the build makes only for "
                     "coordinates beyond 4.25e37");
    }
  }
  struct Visit {
    std::uint32_t node;
    std::uint32_t level;  // the root is level 1
  };
  std::vector<Visit> stack{{0, 1}};
  std::size_t expected = 0;
  std::size_t next_leaf = 0;
  std::size_t levels = 0;
  while (!stack.empty()) {
    const Visit visit = stack.back();
    const std::size_t i = visit.node;
    stack.pop_back();
    if (i != expected) {
      fail(name, "the tree is not in depth-first order: node " + std::to_string(i) +
                     " comes where node " + std::to_string(expected) + " should");
    }
    if (visit.level > kMaxTreeLevels) {
      fail(name, "the tree is deeper than " + std::to_string(kMaxTreeLevels) + " levels (node " +
                     std::to_string(i) + " is at level " + std::to_string(visit.level) +
                     "), more than the build makes");
    }
    ++expected;
    levels = std::max<std::size_t>(levels, visit.level);
    const BvhNode& node = nodes[i];
    if (node.is_leaf()) {
      if (node.count > leaf_size || node.first_or_right != next_leaf ||
          node.count > leaf_count - next_leaf) {
        fail(name, "leaf node " + std::to_string(i) + " holds leaf triangles [" +
                       std::to_string(node.first_or_right) + ", +" + std::to_string(node.count) +
                       "), expected " + std::to_string(next_leaf) + " onwards, at most " +
                       std::to_string(leaf_size) + ", of " + std::to_string(leaf_count));
      }
      next_leaf += node.count;
    } else {
      const std::size_t right = node.first_or_right;
      if (i + 1 >= n || right <= i + 1 || right >= n) {
        fail(name, "internal node " + std::to_string(i) + " has children " + std::to_string(i + 1) +
                       " and " + std::to_string(right) + ", out of range (" + std::to_string(n) +
                       " nodes)");
      }
      stack.push_back({static_cast<std::uint32_t>(right), visit.level + 1});
      stack.push_back({static_cast<std::uint32_t>(i + 1), visit.level + 1});
    }
  }
  if (expected != n || next_leaf != leaf_count) {
    fail(name, "the tree reaches " + std::to_string(expected) + " of " + std::to_string(n) +
                   " nodes and " + std::to_string(next_leaf) + " of " + std::to_string(leaf_count) +
                   " leaf triangles");
  }
  return levels;  // the deepest level visited: the tree's depth
}

void check_volumes(const Model& m, const std::vector<bool>& in_tree, const std::string& name) {
  const std::span<const BvhNode> nodes = m.nodes();
  const std::size_t n = nodes.size();
  const Mesh& mesh = m.mesh();
  const std::span<const std::uint32_t> leaf = m.leaf_triangles();
  // The build leaves out exactly the degenerate triangles (a zero-area triangle in a leaf is a
  // segment or a point the rebuilt model does not have: distance and collide would answer
  // differently).
  for (std::size_t t = 0; t < in_tree.size(); ++t) {
    const TriangleIndices& tri = mesh.triangles[t];
    const std::vector<Vec3>& v = mesh.vertices;
    const bool degenerate = geometry::is_degenerate_triangle(v[tri[0]], v[tri[1]], v[tri[2]]);
    if (!in_tree[t] && !degenerate) {
      fail(name,
           "triangle " + std::to_string(t) + " is left out of the tree but is not degenerate");
    }
    if (in_tree[t] && degenerate) {
      fail(name, "triangle " + std::to_string(t) +
                     " is in the tree but degenerate (zero area): the build leaves such triangles "
                     "out");
    }
  }
  // Each leaf's distinct vertices (a stamp per vertex: the last leaf that took it), in leaf
  // order, so that every node's are one run: [first[i], last[i]), children after their parent.
  Points p;
  p.x.reset(new Scalar[3 * leaf.size()]);
  p.y.reset(new Scalar[3 * leaf.size()]);
  p.z.reset(new Scalar[3 * leaf.size()]);
  p.first.reset(new std::size_t[n]);
  p.last.reset(new std::size_t[n]);
  {
    const std::unique_ptr<std::uint32_t[]> stamp(new std::uint32_t[mesh.vertices.size()]);
    std::fill_n(stamp.get(), mesh.vertices.size(), std::numeric_limits<std::uint32_t>::max());
    std::size_t size = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const BvhNode& node = nodes[i];
      if (!node.is_leaf()) continue;
      p.first[i] = size;
      const auto id = static_cast<std::uint32_t>(i);  // < 2^32 - 1: a node count is 32-bit
      for (std::uint32_t k = node.first_or_right; k < node.first_or_right + node.count; ++k) {
        for (const std::uint32_t v : mesh.triangles[leaf[k]]) {
          if (stamp[v] == id) continue;
          stamp[v] = id;
          p.x[size] = mesh.vertices[v].x() * 0.25;
          p.y[size] = mesh.vertices[v].y() * 0.25;
          p.z[size] = mesh.vertices[v].z() * 0.25;
          ++size;
        }
      }
      p.last[i] = size;
    }
  }
  for (std::size_t i = n; i-- > 0;) {
    if (!nodes[i].is_leaf()) {
      p.first[i] = p.first[i + 1];
      p.last[i] = p.last[nodes[i].first_or_right];
    }
  }
  // Orthonormal axes first, for every node: holds_subtree's bounds rely on them.
  std::atomic<std::size_t> bad{n};
  const auto lower_bad = [&](std::size_t i) {
    std::size_t seen = bad.load(std::memory_order_relaxed);
    while (i < seen && !bad.compare_exchange_weak(seen, i)) {
    }
  };
  const bool parallel = leaf.size() >= kParallelCheck;
  const auto ranges = [&](std::size_t grain, const auto& range) {
    if (parallel) {
      parallel::for_ranges(0, n, grain, range);
    } else {
      range(0, n);
    }
  };
  ranges(8192, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (!orthonormal(nodes[i])) {
        lower_bad(i);
        return;
      }
    }
  });
  if (bad.load() == n) {
    ranges(16, [&](std::size_t begin, std::size_t end) {
      std::vector<std::pair<std::uint32_t, unsigned>> stack;
      for (std::size_t i = begin; i < end && i < bad.load(std::memory_order_relaxed); ++i) {
        if (!holds_subtree(nodes, i, p, stack)) {
          lower_bad(i);
          return;
        }
      }
    });
  }
  if (const std::size_t i = bad.load(); i != n) {
    fail(name, "node " + std::to_string(i) +
                   "'s box or sphere does not hold its triangles (or its axes are not "
                   "orthonormal)");
  }
}

}  // namespace antcd::detail
