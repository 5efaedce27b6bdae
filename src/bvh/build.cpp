// Top-down construction of the hybrid Sphere-OBB hierarchy (paper, section 2).
//
// Paper → code:
//   Eq. 1 (vertex mean) and Eq. 2 (vertex covariance)      → fit_axes(),
//   CovarianceMethod::VertexMean Eq. 3 (area-weighted combined centroid) into Eq. 2     →
//   fit_axes(), AreaWeightedCentroid OBB axes = unit eigenvectors, size = min/max projection →
//   fit_node() split axis = largest centroid variance, point = mean   → split_range()
#include <antcd/bvh.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <stdexcept>

namespace antcd {

namespace {

// Beyond this depth the split point is always the median, so the depth stays below
// kMedianDepth + log2(n) + 1 whatever the triangle distribution, and the build O(n log n).
constexpr std::size_t kMedianDepth = 40;

struct BuildTriangle {
  std::uint32_t index;  // in the mesh
  Vec3 v[3];
  Vec3 centroid;
  Scalar area;
};

class Builder {
 public:
  Builder(std::vector<BuildTriangle>& tris, const BuildOptions& options,
          std::vector<BvhNode>& nodes)
      : tris_(tris), options_(options), nodes_(nodes) {}

  std::size_t build(std::size_t begin, std::size_t end, std::size_t depth) {
    const std::size_t index = nodes_.size();
    nodes_.emplace_back();
    BvhNode node = fit_node(begin, end);
    std::size_t height = 1;
    if (end - begin <= options_.leaf_size) {
      node.first_or_right = static_cast<std::uint32_t>(begin);
      node.count = static_cast<std::uint32_t>(end - begin);
    } else {
      const std::size_t mid = split_range(begin, end, depth);
      const std::size_t left_height = build(begin, mid, depth + 1);
      node.first_or_right = static_cast<std::uint32_t>(nodes_.size());
      const std::size_t right_height = build(mid, end, depth + 1);
      height += std::max(left_height, right_height);
    }
    nodes_[index] = node;
    return height;
  }

 private:
  // Mean and covariance of the triangles in [begin, end) per the chosen method; returns the
  // eigenvectors as a right-handed orthonormal basis (columns).
  Mat3 fit_axes(std::size_t begin, std::size_t end) const {
    Vec3 mean = Vec3::Zero();
    Mat3 cov = Mat3::Zero();
    if (options_.covariance == CovarianceMethod::VertexMean) {
      // Eq. 1: m = Σ (p + q + r) / 3n;  Eq. 2: C = Σ (p̄ p̄ᵀ + q̄ q̄ᵀ + r̄ r̄ᵀ) / 3n.
      for (std::size_t i = begin; i < end; ++i) {
        mean += tris_[i].v[0] + tris_[i].v[1] + tris_[i].v[2];
      }
      mean /= static_cast<Scalar>(3 * (end - begin));
      for (std::size_t i = begin; i < end; ++i) {
        for (const Vec3& v : tris_[i].v) {
          const Vec3 d = v - mean;
          cov.noalias() += d * d.transpose();
        }
      }
    } else {
      // Eq. 3: the combined centroid m = Σ A_i c_i / Σ A_i. Into Eq. 2: the covariance of the
      // surface itself about m, each triangle weighted by its area. A triangle's second moment
      // about m is A/12 (9 d_c d_cᵀ + Σ_v d_v d_vᵀ) with d = x − m, which integrates the whole
      // triangle rather than its three corners, so the result does not depend on how the surface
      // is cut into triangles.
      Scalar total_area = 0;
      for (std::size_t i = begin; i < end; ++i) {
        mean += tris_[i].area * tris_[i].centroid;
        total_area += tris_[i].area;
      }
      mean /= total_area;
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 dc = tris_[i].centroid - mean;
        Mat3 moment = 9 * dc * dc.transpose();
        for (const Vec3& v : tris_[i].v) {
          const Vec3 d = v - mean;
          moment.noalias() += d * d.transpose();
        }
        cov += (tris_[i].area / 12) * moment;
      }
    }
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(cov);
    Mat3 axes = solver.eigenvectors();
    if (!axes.allFinite() || std::abs(axes.determinant()) < 0.5) {
      // computeDirect can lose orthogonality on near-repeated eigenvalues: fall back to the
      // iterative solver, then to the world axes.
      solver.compute(cov);
      axes = solver.eigenvectors();
      if (!axes.allFinite()) axes = Mat3::Identity();
    }
    axes.col(0).normalize();
    axes.col(1) = (axes.col(1) - axes.col(1).dot(axes.col(0)) * axes.col(0)).normalized();
    axes.col(2) = axes.col(0).cross(axes.col(1));
    return axes;
  }

  BvhNode fit_node(std::size_t begin, std::size_t end) const {
    BvhNode node;
    const Mat3 axes = fit_axes(begin, end);
    Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
    Vec3 hi = -lo;
    for (std::size_t i = begin; i < end; ++i) {
      for (const Vec3& v : tris_[i].v) {
        const Vec3 p = axes.transpose() * v;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    node.obb.axes = axes;
    node.obb.center = axes * (0.5 * (lo + hi));
    node.obb.half_extents = 0.5 * (hi - lo);
    // Sphere about the box centre through the farthest vertex: never larger than the box's
    // circumscribed sphere, and a cheap first reject in the traversal.
    Scalar r2 = 0;
    for (std::size_t i = begin; i < end; ++i) {
      for (const Vec3& v : tris_[i].v) r2 = std::max(r2, (v - node.obb.center).squaredNorm());
    }
    node.sphere.center = node.obb.center;
    node.sphere.radius = std::sqrt(r2);
    return node;
  }

  // Partitions [begin, end) and returns the first index of the right part (begin < mid < end).
  std::size_t split_range(std::size_t begin, std::size_t end, std::size_t depth) {
    // Split axis: the direction of largest variance of the triangle centroids, i.e. the
    // principal eigenvector of their covariance. It follows the shape whatever its orientation,
    // and does not depend on the OBB fit method, so both fits see the same tree.
    const std::size_t n = end - begin;
    Vec3 mean = Vec3::Zero();
    for (std::size_t i = begin; i < end; ++i) mean += tris_[i].centroid;
    mean /= static_cast<Scalar>(n);
    Mat3 cov = Mat3::Zero();
    for (std::size_t i = begin; i < end; ++i) {
      const Vec3 d = tris_[i].centroid - mean;
      cov.noalias() += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Mat3> solver;
    solver.computeDirect(cov);
    Vec3 dir = solver.eigenvectors().col(2);  // eigenvalues ascend: the last is the largest
    if (!dir.allFinite() || dir.squaredNorm() < 0.5) {
      int axis = 0;
      cov.diagonal().maxCoeff(&axis);
      dir = Vec3::Unit(axis);
    }
    dir.normalize();
    const Scalar split = dir.dot(mean);

    // Split point: the mean of the projections (paper), unless one side would be empty or the
    // tree is already deep — then the median.
    auto first = tris_.begin() + static_cast<std::ptrdiff_t>(begin);
    auto last = tris_.begin() + static_cast<std::ptrdiff_t>(end);
    if (depth < kMedianDepth) {
      auto mid = std::partition(
          first, last, [&](const BuildTriangle& t) { return dir.dot(t.centroid) < split; });
      if (mid != first && mid != last) return begin + static_cast<std::size_t>(mid - first);
    }
    auto mid = first + static_cast<std::ptrdiff_t>(n / 2);
    std::nth_element(first, mid, last, [&](const BuildTriangle& x, const BuildTriangle& y) {
      return dir.dot(x.centroid) < dir.dot(y.centroid);
    });
    return begin + n / 2;
  }

  std::vector<BuildTriangle>& tris_;
  const BuildOptions& options_;
  std::vector<BvhNode>& nodes_;
};

}  // namespace

Model::Model(Mesh mesh, const BuildOptions& options, std::string source)
    : mesh_(std::move(mesh)), source_(std::move(source)), options_(options) {
  const auto start = std::chrono::steady_clock::now();
  if (options_.leaf_size == 0) {
    throw std::invalid_argument(source_ + ": leaf size must be at least 1");
  }
  validate_mesh(mesh_, source_);

  std::vector<BuildTriangle> tris;
  tris.reserve(mesh_.triangles.size());
  for (std::uint32_t i = 0; i < mesh_.triangles.size(); ++i) {
    const auto& t = mesh_.triangles[i];
    BuildTriangle bt{
        i, {mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]}, Vec3::Zero(), 0};
    if (geometry::is_degenerate_triangle(bt.v[0], bt.v[1], bt.v[2])) {
      ++stats_.degenerate_triangles;
      continue;
    }
    // The centroid of a triangle (its static moments over its area) is its vertex mean.
    bt.centroid = (bt.v[0] + bt.v[1] + bt.v[2]) / 3.0;
    bt.area = 0.5 * (bt.v[1] - bt.v[0]).cross(bt.v[2] - bt.v[0]).norm();
    tris.push_back(bt);
  }
  if (tris.empty()) {
    throw MeshError(source_, "has no triangle of non-zero area");
  }

  nodes_.reserve(2 * (tris.size() / options_.leaf_size + 1));
  Builder builder(tris, options_, nodes_);
  stats_.depth = builder.build(0, tris.size(), 0);
  nodes_.shrink_to_fit();

  leaf_triangles_.resize(tris.size());
  leaf_vertices_.resize(3 * tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    leaf_triangles_[i] = tris[i].index;
    for (int k = 0; k < 3; ++k) leaf_vertices_[3 * i + k] = tris[i].v[k];
  }

  stats_.triangles = mesh_.triangles.size();
  stats_.nodes = nodes_.size();
  for (const BvhNode& node : nodes_) {
    stats_.obb_volume_sum += node.obb.volume();
    if (node.is_leaf()) {
      ++stats_.leaves;
      stats_.max_leaf_size = std::max<std::size_t>(stats_.max_leaf_size, node.count);
    }
  }
  stats_.memory_bytes =
      mesh_.vertices.capacity() * sizeof(Vec3) +
      mesh_.triangles.capacity() * sizeof(TriangleIndices) + nodes_.capacity() * sizeof(BvhNode) +
      leaf_triangles_.capacity() * sizeof(std::uint32_t) + leaf_vertices_.capacity() * sizeof(Vec3);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace antcd
