// Split of a hierarchy node (paper, section 2): axis = direction of largest variance of the
// triangle centroids, point = mean of their projections; the median when the mean leaves one side
// empty or the tree is already deep.
#include "bvh/split.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>

namespace antcd::detail {

using geometry::detail::FitTriangle;

namespace {

template <class Item>
std::size_t split_items(std::span<Item> tris, std::size_t depth) {
  // Split axis: the direction of largest variance of the triangle centroids, i.e. the
  // principal eigenvector of their covariance. It follows the shape whatever its orientation,
  // and does not depend on the OBB fit method, so both fits see the same tree.
  const std::size_t n = tris.size();
  Vec3 mean = Vec3::Zero();
  for (const Item& t : tris) mean += t.centroid;
  mean /= static_cast<Scalar>(n);
  Mat3 cov = Mat3::Zero();
  for (const Item& t : tris) {
    const Vec3 d = t.centroid - mean;
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
  const auto first = tris.begin();
  const auto last = tris.end();
  if (depth < kMedianDepth) {
    auto mid =
        std::partition(first, last, [&](const Item& t) { return dir.dot(t.centroid) < split; });
    if (mid != first && mid != last) return static_cast<std::size_t>(mid - first);
  }
  const auto mid = first + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(first, mid, last, [&](const Item& x, const Item& y) {
    return dir.dot(x.centroid) < dir.dot(y.centroid);
  });
  return n / 2;
}

}  // namespace

std::size_t split_triangles(std::span<FitTriangle> tris, std::size_t depth) {
  return split_items(tris, depth);
}

std::size_t split_triangles(std::span<SplitCentroid> tris, std::size_t depth) {
  return split_items(tris, depth);
}

}  // namespace antcd::detail
