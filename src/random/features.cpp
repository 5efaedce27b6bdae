// Feature sampling (paper, sections 3.1–3.2 and section 4 step 2): from the leaf pairs of the
// preliminary detection to the 2-D grid of centroid pairs.
#include <antcd/random.hpp>
#include <antcd/rng.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace antcd {

Scalar FeatureSpace::distance(std::uint32_t i, std::uint32_t j) const {
  const Scalar dx = a.x[i] - b.x[j];
  const Scalar dy = a.y[i] - b.y[j];
  const Scalar dz = a.z[i] - b.z[j];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

Scalar feature_radius(const Model& model) {
  const auto verts = model.leaf_vertices();
  const std::size_t n = verts.size() / 3;
  std::vector<Scalar> radii(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& v0 = verts[3 * k];
    const Vec3& v1 = verts[3 * k + 1];
    const Vec3& v2 = verts[3 * k + 2];
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

/// Positions (into Model::leaf_triangles()) of every triangle in the given leaves, in leaf order.
std::vector<std::uint32_t> candidate_positions(const Model& model,
                                               std::vector<std::uint32_t>& leaves) {
  std::sort(leaves.begin(), leaves.end());
  leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
  std::vector<std::uint32_t> out;
  const auto nodes = model.nodes();
  for (const std::uint32_t leaf : leaves) {
    const BvhNode& node = nodes[leaf];
    for (std::uint32_t k = 0; k < node.count; ++k) out.push_back(node.first_or_right + k);
  }
  return out;
}

/// Stratified sample: `count` runs of (almost) equal length over `positions`, one uniformly random
/// element from each. Keeps leaf order and covers every region of the candidate set.
std::vector<std::uint32_t> stratified_sample(const std::vector<std::uint32_t>& positions,
                                             std::uint32_t count, Rng& rng) {
  const std::size_t n = positions.size();
  if (n <= count) return positions;
  std::vector<std::uint32_t> out(count);
  for (std::uint32_t s = 0; s < count; ++s) {
    const std::size_t lo = n * s / count;
    const std::size_t hi = n * (s + 1) / count;  // > lo because n > count
    out[s] = positions[lo + rng.below(hi - lo)];
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

FeatureSide make_side(const Model& model, const Transform& pose,
                      const std::vector<std::uint32_t>& positions, FeatureOrder order) {
  const std::size_t n = positions.size();
  std::vector<Vec3> centroids(n);
  const auto verts = model.leaf_vertices();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = positions[k];
    centroids[k] = pose.apply((verts[3 * p] + verts[3 * p + 1] + verts[3 * p + 2]) / 3);
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
        const auto q = static_cast<std::uint32_t>(std::clamp<Scalar>(t * 1023, 0, 1023));
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
  side.triangle.resize(n);
  const auto tris = model.leaf_triangles();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& c = centroids[perm[k]];
    side.x[k] = c.x();
    side.y[k] = c.y();
    side.z[k] = c.z();
    side.triangle[k] = tris[positions[perm[k]]];
  }
  return side;
}

}  // namespace

FeatureSpace build_feature_space(const Model& a, const Transform& pose_a, const Model& b,
                                 const Transform& pose_b, const SamplingOptions& options,
                                 std::uint64_t seed) {
  if (options.samples_per_side == 0) {
    throw antcd::ArgumentError("build_feature_space: samples_per_side must be >= 1");
  }
  if (std::isnan(options.delta) || std::isinf(options.delta)) {
    throw antcd::ArgumentError("build_feature_space: delta must be finite (negative = default)");
  }
  FeatureSpace space;
  space.delta = options.delta < 0 ? default_delta(a, b) : options.delta;

  std::vector<LeafPair> pairs;
  overlapping_leaves(a, pose_a, b, pose_b, space.delta, pairs);
  space.leaf_pairs = pairs.size();
  if (pairs.empty()) return space;

  std::vector<std::uint32_t> leaves_a, leaves_b;
  leaves_a.reserve(pairs.size());
  leaves_b.reserve(pairs.size());
  for (const LeafPair& p : pairs) {
    leaves_a.push_back(p.node_a);
    leaves_b.push_back(p.node_b);
  }
  const std::vector<std::uint32_t> cand_a = candidate_positions(a, leaves_a);
  const std::vector<std::uint32_t> cand_b = candidate_positions(b, leaves_b);
  space.candidates_a = cand_a.size();
  space.candidates_b = cand_b.size();

  Rng rng(seed ^ 0x5A3B1E0FEA7ULL);
  const auto sample_a = stratified_sample(cand_a, options.samples_per_side, rng);
  const auto sample_b = stratified_sample(cand_b, options.samples_per_side, rng);
  space.a = make_side(a, pose_a, sample_a, options.order);
  space.b = make_side(b, pose_b, sample_b, options.order);
  return space;
}

}  // namespace antcd
