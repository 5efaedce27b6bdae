// Private: fitting an oriented bounding box to a set of triangles (paper, Eqs. 1–3; obb_fit.cpp).
#pragma once

#include <antcd/geometry.hpp>

#include <cstdint>
#include <span>

namespace antcd::geometry::detail {

/// One triangle of the surface a box is fitted to. `index` is the caller's (the hierarchy keeps
/// the mesh's triangle index in it); the centroid is the vertex mean and the area is > 0.
struct FitTriangle {
  std::uint32_t index;
  Vec3 v[3];
  Vec3 centroid;
  Scalar area;
};

/// The box axes: the unit eigenvectors of the covariance of `tris` (not empty) as chosen by
/// `method`, as a right-handed orthonormal basis (columns).
Mat3 fit_obb_axes(std::span<const FitTriangle> tris, CovarianceMethod method);

/// The smallest box with the given axes holding every vertex of `tris` (not empty): its extent
/// along each axis is the min/max projection of the vertices.
Obb fit_obb(std::span<const FitTriangle> tris, const Mat3& axes);

}  // namespace antcd::geometry::detail
