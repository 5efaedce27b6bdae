// Feature sampling (paper, sections 3.1–3.2 and section 4 steps 1–2): from the leaf pairs of the
// preliminary detection at delta to the 2-D grid of centroid pairs, with each triangle's radius and
// world vertices for the witness test.
#include <antcd/error.hpp>

#include "bvh/traverse.hpp"
#include "random/engines.hpp"
#include "util/check.hpp"
#include "util/grid_cell.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace antcd {

float FeatureSpace::distance(std::uint32_t i, std::uint32_t j) const {
  const float dx = a.x[i] - b.x[j];
  const float dy = a.y[i] - b.y[j];
  const float dz = a.z[i] - b.z[j];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool FeatureSpace::collides(std::uint32_t i, std::uint32_t j, Verdict verdict,
                            std::optional<Scalar> centroid_threshold) const {
  const detail::Thresholds t =
      detail::thresholds(*this, verdict, centroid_threshold, "FeatureSpace::collides");
  const float dx = a.x[i] - b.x[j];
  const float dy = a.y[i] - b.y[j];
  const float dz = a.z[i] - b.z[j];
  const float d2 = dx * dx + dy * dy + dz * dz;
  if (verdict == Verdict::PaperCentroid) return d2 <= t.centroid2;
  const float reach = a.radius[i] + b.radius[j] + t.delta;
  return d2 <= reach * reach && detail::witness_test(*this, i, j);
}

Scalar feature_radius(const Model& model) {
  const LeafCorners verts = model.leaf_corners();
  const std::size_t n = verts.size();
  std::vector<Scalar> radii(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& v0 = verts(k, 0);
    const Vec3& v1 = verts(k, 1);
    const Vec3& v2 = verts(k, 2);
    const Vec3 c = (v0 + v1 + v2) / 3;
    radii[k] = std::sqrt(
        std::max({(v0 - c).squaredNorm(), (v1 - c).squaredNorm(), (v2 - c).squaredNorm()}));
  }
  if (radii.empty()) return 0;  // a Model always holds a triangle; kept for safety
  const auto mid = radii.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(radii.begin(), mid, radii.end());
  return *mid;
}

Scalar default_delta(const Model& a, const Model& b) {
  return default_delta(feature_radius(a), feature_radius(b));
}

Scalar default_delta(Scalar radius_a, Scalar radius_b) {
  const Scalar d = radius_a + radius_b;
  // Non-degenerate triangles have a positive radius, so d > 0; the fallback only guards a model
  // made of numerically tiny triangles.
  return d > 0 ? d : std::numeric_limits<Scalar>::min();
}

namespace {

/// One candidate triangle: its index in Model::leaf_triangles() and its reported leaf (local id).
struct Candidate {
  std::uint32_t position = 0;
  std::uint32_t leaf = 0;
};

/// Sorts and deduplicates `leaves` (node indices) and lists their triangles in leaf order.
std::vector<Candidate> candidates_of(const Model& model, std::vector<std::uint32_t>& leaves) {
  std::sort(leaves.begin(), leaves.end());
  leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
  std::vector<Candidate> out;
  const auto nodes = model.nodes();
  for (std::uint32_t k = 0; k < leaves.size(); ++k) {
    const BvhNode& node = nodes[leaves[k]];
    for (std::uint32_t t = 0; t < node.count; ++t) out.push_back({node.first_or_right + t, k});
  }
  return out;
}

std::uint32_t local_leaf(const std::vector<std::uint32_t>& leaves, std::uint32_t node) {
  return static_cast<std::uint32_t>(std::lower_bound(leaves.begin(), leaves.end(), node) -
                                    leaves.begin());
}

/// Stratified sample: `count` runs of (almost) equal length over `candidates`, one uniformly
/// random element from each. Keeps leaf order and covers every region of the candidate set.
std::vector<Candidate> stratified_sample(const std::vector<Candidate>& candidates,
                                         std::uint32_t count, Rng& rng) {
  const std::size_t n = candidates.size();
  if (n <= count) return candidates;
  std::vector<Candidate> out(count);
  for (std::uint32_t s = 0; s < count; ++s) {
    const std::size_t lo = n * s / count;
    const std::size_t hi = n * (s + 1) / count;  // > lo because n > count
    out[s] = candidates[lo + rng.below(hi - lo)];
  }
  return out;
}

/// Spreads the low 10 bits of v so that two zero bits separate consecutive ones.
std::uint32_t spread_bits(std::uint32_t v) {
  v &= 0x3FF;
  v = (v | (v << 16)) & 0x030000FF;
  v = (v | (v << 8)) & 0x0300F00F;
  v = (v | (v << 4)) & 0x030C30C3;
  v = (v | (v << 2)) & 0x09249249;
  return v;
}

/// A double rounded up to the next float, then widened by `slack` relative: keeps float
/// comparisons against it conservative.
float round_up(Scalar value, Scalar slack) {
  const auto f = static_cast<float>(value * (1 + slack));
  return static_cast<Scalar>(f) >= value ? f : std::nextafter(f, std::numeric_limits<float>::max());
}

/// `pose`: model to world (centroids); `to_test`: model to the frame of the witness test (model
/// A's frame, as in collide()).
FeatureSide make_side(const Model& model, const Transform& pose, const Transform& to_test,
                      const std::vector<Candidate>& picked, std::size_t leaf_count,
                      FeatureOrder order) {
  const std::size_t n = picked.size();
  std::vector<Vec3> centroids(n);
  std::vector<Vec3> world(3 * n);
  const LeafCorners verts = model.leaf_corners();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = picked[k].position;
    for (int v = 0; v < 3; ++v) world[3 * k + v] = pose.apply(verts(p, v));
    centroids[k] = (world[3 * k] + world[3 * k + 1] + world[3 * k + 2]) / 3;
  }

  std::vector<std::uint32_t> perm(n);
  for (std::size_t k = 0; k < n; ++k) perm[k] = static_cast<std::uint32_t>(k);
  if (order == FeatureOrder::Morton && n > 1) {
    Aabb box;
    for (const Vec3& c : centroids) box.extend(c);
    const Vec3 ext = box.extent();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
    for (std::size_t k = 0; k < n; ++k) {
      std::uint32_t code = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const Scalar t = ext[axis] > 0 ? (centroids[k][axis] - box.min[axis]) / ext[axis] : 0;
        // t is NaN for a box wider than the double range.
        const auto q = detail::clamped_cell<std::uint32_t>(t * 1023, 0, 1023);
        code |= spread_bits(q) << axis;
      }
      keyed[k] = {code, static_cast<std::uint32_t>(k)};
    }
    std::sort(keyed.begin(), keyed.end());  // ties broken by leaf order: deterministic
    for (std::size_t k = 0; k < n; ++k) perm[k] = keyed[k].second;
  }

  FeatureSide side;
  side.x.resize(n);
  side.y.resize(n);
  side.z.resize(n);
  side.radius.resize(n);
  side.vertices.resize(3 * n);
  side.triangle.resize(n);
  side.position.resize(n);
  side.model_triangles = static_cast<std::uint32_t>(model.leaf_triangles().size());
  const auto tris = model.leaf_triangles();
  std::vector<std::uint32_t> leaf_count_of(leaf_count + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t src = perm[k];
    const Vec3& c = centroids[src];
    side.x[k] = static_cast<float>(c.x());
    side.y[k] = static_cast<float>(c.y());
    side.z[k] = static_cast<float>(c.z());
    Scalar r2 = 0;
    for (int v = 0; v < 3; ++v) {
      side.vertices[3 * k + v] = to_test.apply(verts(std::size_t{picked[src].position}, v));
      r2 = std::max(r2, (world[3 * src + v] - c).squaredNorm());
    }
    // The float centroid is off by up to ~1e-7 of its coordinates; the radius absorbs it, so
    // that the reach test f <= r_i + r_j + delta never rejects a pair the exact test accepts.
    const Scalar r = std::sqrt(r2);
    side.radius[k] = round_up(r + 1e-6 * (c.cwiseAbs().maxCoeff() + r), 1e-6);
    side.triangle[k] = tris[picked[src].position];
    side.position[k] = picked[src].position;
    ++leaf_count_of[picked[src].leaf + 1];
  }
  // Features per reported leaf (counting sort; features keep their order inside a leaf).
  side.leaf_start.assign(leaf_count + 1, 0);
  for (std::size_t l = 0; l < leaf_count; ++l) {
    side.leaf_start[l + 1] = side.leaf_start[l] + leaf_count_of[l + 1];
  }
  side.leaf_features.resize(n);
  std::vector<std::uint32_t> fill(side.leaf_start.begin(), side.leaf_start.end() - 1);
  for (std::size_t k = 0; k < n; ++k) {
    side.leaf_features[fill[picked[perm[k]].leaf]++] = static_cast<std::uint32_t>(k);
  }
  return side;
}

}  // namespace

FeatureSpace build_feature_space(const Model& a, const Transform& pose_a, const Model& b,
                                 const Transform& pose_b, const SamplingOptions& options,
                                 std::uint64_t seed) {
  detail::require_at_least("build_feature_space", "samples_per_side", options.samples_per_side, 1);
  detail::require_non_negative("build_feature_space", "delta", options.delta);
  if (options.centroid_delta) {
    detail::require_positive("build_feature_space", "centroid_delta", *options.centroid_delta);
  }
  FeatureSpace space;
  space.delta = options.delta;
  space.centroid_delta =
      options.centroid_delta.value_or(0) > 0 ? *options.centroid_delta : default_delta(a, b);

  // Section 4 step 1: preliminary detection at the collision threshold itself.
  std::vector<LeafPair> pairs;
  {
    const detail::PairFrame frame(a, pose_a, b, pose_b, space.delta);
    auto collect = [&](std::uint32_t la, std::uint32_t lb) {
      pairs.push_back({la, lb});
      if (options.max_leaf_pairs == 0) return false;
      space.complete = pairs.size() < options.max_leaf_pairs;
      return !space.complete;
    };
    // The masks only decide which leaf pairs are reported (the triangles of a reported pair are
    // all sampled as before). Every leaf pair: overlapping_leaves' order; the first ones: nearest
    // children first.
    auto masked = [&](std::uint32_t la, std::uint32_t lb, std::uint32_t, std::uint32_t) {
      return collect(la, lb);
    };
    auto traverse = [&](auto& on_leaf) {
      if (options.max_leaf_pairs == 0) {
        detail::dual_traverse<false>(a, b, frame, on_leaf);
      } else {
        detail::dual_traverse<true>(a, b, frame, on_leaf);
      }
    };
    if (options.triangle_masks) {
      traverse(masked);
    } else {
      traverse(collect);
    }
  }
  space.leaf_pairs = pairs.size();
  if (pairs.empty()) return space;  // no leaf pair: separate, nothing to search

  std::vector<std::uint32_t> leaves_a, leaves_b;
  leaves_a.reserve(pairs.size());
  leaves_b.reserve(pairs.size());
  for (const LeafPair& p : pairs) {
    leaves_a.push_back(p.node_a);
    leaves_b.push_back(p.node_b);
  }
  const std::vector<Candidate> cand_a = candidates_of(a, leaves_a);
  const std::vector<Candidate> cand_b = candidates_of(b, leaves_b);
  space.candidates_a = cand_a.size();
  space.candidates_b = cand_b.size();
  space.overlaps.reserve(pairs.size());
  for (const LeafPair& p : pairs) {
    space.overlaps.emplace_back(local_leaf(leaves_a, p.node_a), local_leaf(leaves_b, p.node_b));
  }

  // Section 4 step 2: sample the primitives of the colliding leaves.
  Rng rng(seed ^ 0x5A3B1E0FEA7ULL);
  const auto sample_a = stratified_sample(cand_a, options.samples_per_side, rng);
  const auto sample_b = stratified_sample(cand_b, options.samples_per_side, rng);
  // The witness test runs in A's model frame with B mapped into it, as collide() does, so that a
  // confirmed pair is one collide() reports.
  const Transform b_to_a = detail::relative_pose(pose_a, pose_b);
  space.a = make_side(a, pose_a, Transform::identity(), sample_a, leaves_a.size(), options.order);
  space.b = make_side(b, pose_b, b_to_a, sample_b, leaves_b.size(), options.order);
  return space;
}

std::uint64_t FeatureSpace::leaf_pair_cells() const {
  std::uint64_t total = 0;
  for (const auto& [la, lb] : overlaps) {
    total += std::uint64_t{a.leaf_start[la + 1] - a.leaf_start[la]} *
             (b.leaf_start[lb + 1] - b.leaf_start[lb]);
  }
  return total;
}

namespace detail {

bool witness_test(const FeatureSpace& space, std::uint32_t i, std::uint32_t j) {
  const Vec3* va = &space.a.vertices[3 * std::size_t{i}];
  const Vec3* vb = &space.b.vertices[3 * std::size_t{j}];
  return geometry::triangles_within(va[0], va[1], va[2], vb[0], vb[1], vb[2], space.delta);
}

Thresholds thresholds(const FeatureSpace& space, Verdict verdict,
                      std::optional<Scalar> centroid_delta, const char* caller) {
  if (centroid_delta) detail::require_positive(caller, "centroid_delta", *centroid_delta);
  Thresholds t;
  t.verdict = verdict;
  t.delta = round_up(space.delta, 1e-6);
  const Scalar c = centroid_delta.value_or(space.centroid_delta);
  t.centroid = static_cast<float>(c);
  t.centroid2 = t.centroid * t.centroid;
  return t;
}

}  // namespace detail

std::string_view to_string(Verdict verdict) {
  return verdict == Verdict::Witness ? "witness" : "paper-centroid";
}

Verdict parse_verdict(std::string_view text) {
  for (const Verdict v : {Verdict::Witness, Verdict::PaperCentroid}) {
    if (text == to_string(v)) return v;
  }
  throw ArgumentError("unknown verdict '" + std::string(text) +
                      "' (expected witness or paper-centroid)");
}

}  // namespace antcd
