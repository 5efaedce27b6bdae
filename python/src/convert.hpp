// python/src/convert.hpp — numpy/Python values to antcd types, with the checks the bindings share.
//
// Every check raises ValueError (pybind11::value_error) whose message names the argument and the
// problem, never lets a bad array reach the library.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace antcd::python {

namespace py = pybind11;

/// A pose: None (identity), a 4x4 homogeneous matrix, or a (rotation 3x3, translation 3) pair.
/// The rotation must be orthonormal with determinant +1 (within 1e-6), the last row of a 4x4
/// [0, 0, 0, 1], every entry finite. `name` is the argument's name in messages.
Transform to_transform(py::handle pose, std::string_view name);

/// `count` value meaning "not fixed yet" for to_transforms.
inline constexpr std::size_t kAnyCount = static_cast<std::size_t>(-1);

/// A batch of poses: a numeric (n, 4, 4) array of homogeneous matrices, each checked as by
/// to_transform (messages name `name[i]`), or one (4, 4) matrix or None standing for every pose
/// (then one Transform is returned and `count` is left alone). When `count` is not kAnyCount the
/// batch must hold exactly `count` poses; otherwise `count` is set to its size.
std::vector<Transform> to_transforms(py::handle poses, std::string_view name, std::size_t& count);

/// The 4x4 homogeneous matrix of a transform.
py::array_t<double> to_matrix(const Transform& t);

/// vertices: numeric (n, 3), finite; faces: integer (m, 3), indices in [0, n). Copied once.
Mesh to_mesh(py::handle vertices, py::handle faces);

/// New positions for a Model's vertices: numeric (count, 3), finite, copied once. ValueError
/// naming `name` for a wrong shape or dtype, a row count other than `count`, a non-finite entry.
std::vector<Vec3> to_positions(py::handle vertices, std::string_view name, std::size_t count);

/// Positions for one end of a deforming motion (deform_ccd.hpp, World::sweep_motion):
/// to_positions' checks, then every |coordinate| <= kDeformMaxCoordinate, each naming `name`.
std::vector<Vec3> to_deform_positions(py::handle vertices, std::string_view name,
                                      std::size_t count);

/// "area" (area-weighted centroid, the paper's Eq. 3; default) or "vertex" (Eqs. 1-2).
CovarianceMethod parse_covariance(std::string_view name);
std::string_view covariance_name(CovarianceMethod method);

/// An integer argument that must lie in [lo, hi]; a clear ValueError otherwise.
std::uint64_t to_count(py::handle value, std::string_view name, std::uint64_t lo, std::uint64_t hi);
/// A finite float >= 0.
double to_non_negative(double value, std::string_view name);
/// A finite float > 0 (a time tolerance).
double to_positive(double value, std::string_view name);

/// A read-only numpy view of `count` x `cols` elements at `data`, kept alive by `owner`.
template <typename T>
py::array_t<T> readonly_view(const T* data, std::size_t count, std::size_t cols, py::handle owner) {
  py::array_t<T> a(
      {static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(cols)},
      {static_cast<py::ssize_t>(cols * sizeof(T)), static_cast<py::ssize_t>(sizeof(T))}, data,
      owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

/// A fresh numpy array of `count` x `cols` elements filled by fill(row, out_row_pointer).
template <typename T, typename Fill>
py::array_t<T> make_rows(std::size_t count, std::size_t cols, Fill&& fill) {
  py::array_t<T> a({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(cols)});
  T* out = a.mutable_data();
  for (std::size_t i = 0; i < count; ++i) fill(i, out + i * cols);
  return a;
}

/// A fresh 1-D numpy array of `count` elements, element i = value(i).
template <typename T, typename Value>
py::array_t<T> make_vector(std::size_t count, Value&& value) {
  py::array_t<T> a(static_cast<py::ssize_t>(count));
  T* out = a.mutable_data();
  for (std::size_t i = 0; i < count; ++i) out[i] = value(i);
  return a;
}

/// A fresh float64[3] array holding p (a point or a vector).
inline py::array_t<double> to_point(const Vec3& p) {
  return make_vector<double>(3, [&](std::size_t k) { return p[static_cast<int>(k)]; });
}

}  // namespace antcd::python
