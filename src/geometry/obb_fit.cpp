// The OBB of a set of triangles (paper, section 2):
//   Eq. 1 (vertex mean) and Eq. 2 (vertex covariance)       -> CovarianceMethod::VertexMean
//   Eq. 3 (area-weighted combined centroid) into Eq. 2       ->
//   CovarianceMethod::AreaWeightedCentroid box axes = unit eigenvectors of the covariance, extents
//   = min/max projection of the vertices.
#include "geometry/obb_fit.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

namespace antcd::geometry::detail {

Mat3 fit_obb_axes(std::span<const FitTriangle> tris, CovarianceMethod method) {
  Vec3 mean = Vec3::Zero();
  Mat3 cov = Mat3::Zero();
  if (method == CovarianceMethod::VertexMean) {
    // Eq. 1: m = Σ (p + q + r) / 3n;  Eq. 2: C = Σ (p̄ p̄ᵀ + q̄ q̄ᵀ + r̄ r̄ᵀ) / 3n.
    for (const FitTriangle& t : tris) mean += t.v[0] + t.v[1] + t.v[2];
    mean /= static_cast<Scalar>(3 * tris.size());
    for (const FitTriangle& t : tris) {
      for (const Vec3& v : t.v) {
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
    for (const FitTriangle& t : tris) {
      mean += t.area * t.centroid;
      total_area += t.area;
    }
    mean /= total_area;
    for (const FitTriangle& t : tris) {
      const Vec3 dc = t.centroid - mean;
      Mat3 moment = 9 * dc * dc.transpose();
      for (const Vec3& v : t.v) {
        const Vec3 d = v - mean;
        moment.noalias() += d * d.transpose();
      }
      cov += (t.area / 12) * moment;
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

Obb fit_obb(std::span<const FitTriangle> tris, const Mat3& axes) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  Vec3 hi = -lo;
  for (const FitTriangle& t : tris) {
    for (const Vec3& v : t.v) {
      const Vec3 p = axes.transpose() * v;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  Obb box;
  box.axes = axes;
  box.center = axes * (0.5 * (lo + hi));
  box.half_extents = 0.5 * (hi - lo);
  return box;
}

}  // namespace antcd::geometry::detail
