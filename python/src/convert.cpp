// python/src/convert.cpp — see convert.hpp.
#include "convert.hpp"

#include <antcd/deform_ccd.hpp>
#include <antcd/pose.hpp>
#include <antcd/tolerances.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace antcd::python {

namespace {

std::string str(std::string_view s) { return std::string(s); }

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) {
    if (k > 0) s += ", ";
    s += std::to_string(a.shape(k));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_of(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

/// Converts to a numpy array without copying when possible; ValueError if it is not array-like.
py::array as_array(py::handle value, std::string_view name) {
  if (value.is_none()) throw py::value_error(str(name) + " must be an array, got None");
  // numpy.asarray, looked up once (intentionally leaked: no destructor runs after Python's exit).
  static const py::object* const asarray =
      new py::object(py::module_::import("numpy").attr("asarray"));
  try {
    return (*asarray)(value);
  } catch (py::error_already_set& e) {
    throw py::value_error(str(name) + " is not array-like: " + e.what());
  }
}

/// A float64 C-contiguous copy/view of a numeric (not bool, not object) array.
py::array_t<double, py::array::c_style> as_float64(const py::array& a, std::string_view name) {
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::value_error(str(name) + " must hold real numbers, got dtype " + dtype_of(a));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

void require_finite(const double* v, std::size_t count, std::string_view name) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(v[i])) {
      throw py::value_error(str(name) + " has a non-finite entry (" + std::to_string(v[i]) +
                            " at flat index " + std::to_string(i) + ")");
    }
  }
}

Transform rigid(const double* r, std::ptrdiff_t r_row, const double* t, std::string_view name) {
  Transform out;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out.rotation(i, j) = r[i * r_row + j];
    out.translation[i] = t[i];
  }
  if (const PoseCheck c = check_pose(out); !c.rigid()) {
    throw py::value_error(str(name) + " " + c.problem());
  }
  return out;
}

Transform from_homogeneous(const double* d) {
  Transform out;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out.rotation(i, j) = d[i * 4 + j];
    out.translation[i] = d[i * 4 + 3];
  }
  return out;
}

/// What homogeneous() accepts, decided without building a message.
bool acceptable_homogeneous(const double* d) {
  return check_pose(from_homogeneous(d), d[12], d[13], d[14], d[15]).rigid();
}

/// A row-major 4x4 homogeneous matrix, checked: finite, last row [0, 0, 0, 1], rigid rotation.
Transform homogeneous(const double* d, std::string_view name) {
  require_finite(d, 16, name);
  const Transform out = from_homogeneous(d);
  if (const PoseCheck c = check_pose(out, d[12], d[13], d[14], d[15]); !c.rigid()) {
    throw py::value_error(str(name) + " " + c.problem());
  }
  return out;
}

/// The common case on the per-query path: a float64 numpy array of shape (rows, cols) (or (rows,)
/// when cols is 1), any strides, read straight from its buffer: no conversion, no temporary array,
/// no Python call. False when `h` is anything else (the caller then converts and checks it).
bool read_in_place(py::handle h, py::ssize_t rows, py::ssize_t cols, double* out) {
  const auto& api = py::detail::npy_api::get();
  if (!api.PyArray_Check_(h.ptr())) return false;
  const auto* a = py::detail::array_proxy(h.ptr());
  const auto* descr = py::detail::array_descriptor_proxy(a->descr);
  constexpr char kNativeOrder = std::endian::native == std::endian::little ? '<' : '>';
  if (descr->type_num != py::detail::npy_api::NPY_DOUBLE_ ||
      (descr->byteorder != '=' && descr->byteorder != kNativeOrder)) {
    return false;
  }
  const bool matrix = a->nd == 2 && a->dimensions[0] == rows && a->dimensions[1] == cols;
  const bool vector = cols == 1 && a->nd == 1 && a->dimensions[0] == rows;
  if (!matrix && !vector) return false;
  const py::ssize_t col_stride = matrix ? a->strides[1] : 0;
  for (py::ssize_t i = 0; i < rows; ++i) {
    for (py::ssize_t j = 0; j < cols; ++j) {
      std::memcpy(&out[i * cols + j], a->data + i * a->strides[0] + j * col_stride, sizeof(double));
    }
  }
  return true;
}

}  // namespace

Transform to_transform(py::handle pose, std::string_view name) {
  if (pose.is_none()) return Transform::identity();
  // (rotation, translation) pair. A 4x4 given as nested lists has 4 rows, never 2.
  if ((py::isinstance<py::tuple>(pose) || py::isinstance<py::list>(pose)) && py::len(pose) == 2) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(pose);
    double r_fast[9];
    double t_fast[3];
    if (read_in_place(pair[0], 3, 3, r_fast) && read_in_place(pair[1], 3, 1, t_fast)) {
      require_finite(r_fast, 9, str(name) + " rotation");
      require_finite(t_fast, 3, str(name) + " translation");
      return rigid(r_fast, 3, t_fast, name);
    }
    const std::string rname = str(name) + " rotation";
    const std::string tname = str(name) + " translation";
    const auto r = as_float64(as_array(pair[0], rname), rname);
    const auto t = as_float64(as_array(pair[1], tname), tname);
    if (r.ndim() != 2 || r.shape(0) != 3 || r.shape(1) != 3) {
      throw py::value_error(rname + " must have shape (3, 3), got " + shape_of(r));
    }
    if (t.size() != 3 || t.ndim() > 2) {
      throw py::value_error(tname + " must have 3 entries, got shape " + shape_of(t));
    }
    require_finite(r.data(), 9, rname);
    require_finite(t.data(), 3, tname);
    return rigid(r.data(), 3, t.data(), name);
  }
  double d[16];
  if (!read_in_place(pose, 4, 4, d)) {
    const auto m = as_float64(as_array(pose, name), name);
    if (m.ndim() != 2 || m.shape(0) != 4 || m.shape(1) != 4) {
      throw py::value_error(str(name) +
                            " must be a 4x4 homogeneous matrix or a (rotation 3x3, translation 3) "
                            "pair, got shape " +
                            shape_of(m));
    }
    std::copy_n(m.data(), 16, d);
  }
  return homogeneous(d, name);
}

std::vector<Transform> to_transforms(py::handle poses, std::string_view name, std::size_t& count) {
  if (poses.is_none()) return {Transform::identity()};
  const auto a = as_float64(as_array(poses, name), name);
  if (a.ndim() == 2 && a.shape(0) == 4 && a.shape(1) == 4) return {homogeneous(a.data(), name)};
  if (a.ndim() != 3 || a.shape(1) != 4 || a.shape(2) != 4) {
    throw py::value_error(str(name) +
                          " must have shape (n, 4, 4) (or (4, 4) for one pose for all), got " +
                          shape_of(a));
  }
  const auto n = static_cast<std::size_t>(a.shape(0));
  if (count != kAnyCount && n != count) {
    throw py::value_error(str(name) + " has " + std::to_string(n) + " poses, the other poses " +
                          std::to_string(count));
  }
  count = n;
  std::vector<Transform> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The indexed name is built only when the pose is bad: no allocation per good pose.
    const double* d = a.data() + 16 * i;
    if (!acceptable_homogeneous(d)) (void)homogeneous(d, str(name) + "[" + std::to_string(i) + "]");
    out.push_back(from_homogeneous(d));
  }
  return out;
}

py::array_t<double> to_matrix(const Transform& t) {
  py::array_t<double> m({4, 4});
  double* d = m.mutable_data();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      d[i * 4 + j] = i == 3 ? (j == 3 ? 1.0 : 0.0) : (j == 3 ? t.translation[i] : t.rotation(i, j));
    }
  }
  return m;
}

Mesh to_mesh(py::handle vertices_in, py::handle faces_in) {
  const auto vertices = as_float64(as_array(vertices_in, "vertices"), "vertices");
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw py::value_error("vertices must have shape (n, 3), got " + shape_of(vertices));
  }
  const py::array faces_any = as_array(faces_in, "faces");
  const char kind = faces_any.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw py::value_error("faces must have an integer dtype, got " + dtype_of(faces_any));
  }
  if (faces_any.ndim() != 2 || faces_any.shape(1) != 3) {
    throw py::value_error("faces must have shape (m, 3), got " + shape_of(faces_any));
  }
  if (faces_any.shape(0) == 0) throw py::value_error("faces is empty: a mesh needs a triangle");
  const auto n = static_cast<std::size_t>(vertices.shape(0));
  if (n > std::numeric_limits<std::uint32_t>::max()) {
    throw py::value_error("too many vertices (" + std::to_string(n) + "): at most 2^32 - 1");
  }
  require_finite(vertices.data(), n * 3, "vertices");
  const auto faces =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(faces_any);
  const auto m = static_cast<std::size_t>(faces.shape(0));

  Mesh mesh;
  mesh.vertices.resize(n);
  const double* v = vertices.data();
  for (std::size_t i = 0; i < n; ++i) mesh.vertices[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  mesh.triangles.resize(m);
  const std::int64_t* f = faces.data();
  for (std::size_t i = 0; i < m; ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t index = f[3 * i + k];
      if (index < 0 || static_cast<std::uint64_t>(index) >= n) {
        throw py::value_error("faces[" + std::to_string(i) + "] has vertex index " +
                              std::to_string(index) + ", out of range [0, " + std::to_string(n) +
                              ")");
      }
      mesh.triangles[i][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(index);
    }
  }
  return mesh;
}

std::vector<Vec3> to_positions(py::handle vertices_in, std::string_view name, std::size_t count) {
  const auto vertices = as_float64(as_array(vertices_in, name), name);
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw py::value_error(str(name) + " must have shape (n, 3), got " + shape_of(vertices));
  }
  const auto n = static_cast<std::size_t>(vertices.shape(0));
  if (n != count) {
    throw py::value_error(str(name) + " has " + std::to_string(n) + " rows, the model has " +
                          std::to_string(count) + " vertices");
  }
  require_finite(vertices.data(), n * 3, name);
  std::vector<Vec3> out(n);
  const double* v = vertices.data();
  for (std::size_t i = 0; i < n; ++i) out[i] = Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  return out;
}

std::vector<Vec3> to_deform_positions(py::handle vertices, std::string_view name,
                                      std::size_t count) {
  std::vector<Vec3> out = to_positions(vertices, name, count);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].cwiseAbs().maxCoeff() > kDeformMaxCoordinate) {
      throw py::value_error(str(name) + "[" + std::to_string(i) +
                            "] has a coordinate beyond the deforming sweep's range (|x| <= 1e150)");
    }
  }
  return out;
}

CovarianceMethod parse_covariance(std::string_view name) {
  if (name == "area") return CovarianceMethod::AreaWeightedCentroid;
  if (name == "vertex") return CovarianceMethod::VertexMean;
  throw py::value_error("covariance must be 'area' or 'vertex', got '" + str(name) + "'");
}

std::string_view covariance_name(CovarianceMethod method) {
  return method == CovarianceMethod::VertexMean ? "vertex" : "area";
}

std::uint64_t to_count(py::handle value, std::string_view name, std::uint64_t lo,
                       std::uint64_t hi) {
  // Python ints and numpy integers (anything with __index__), never bools or floats.
  if (py::isinstance<py::bool_>(value) || PyIndex_Check(value.ptr()) == 0) {
    throw py::value_error(str(name) + " must be an integer, got " +
                          py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  }
  const auto big = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!big) throw py::error_already_set();
  // Fast path (the common small non-negative int): compared in C, no Python objects made.
  int overflow = 0;
  const long long small = PyLong_AsLongLongAndOverflow(big.ptr(), &overflow);
  if (overflow == 0 && small >= 0 && static_cast<std::uint64_t>(small) >= lo &&
      static_cast<std::uint64_t>(small) <= hi) {
    return static_cast<std::uint64_t>(small);
  }
  if (big < py::int_(lo) || big > py::int_(hi)) {
    throw py::value_error(str(name) + " must be in [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "], got " + py::repr(big).cast<std::string>());
  }
  return big.cast<std::uint64_t>();
}

double to_positive(double value, std::string_view name) {
  if (!std::isfinite(value) || !(value > 0)) {
    throw py::value_error(str(name) + " must be finite and > 0, got " + std::to_string(value));
  }
  return value;
}

double to_non_negative(double value, std::string_view name) {
  if (!std::isfinite(value) || value < 0) {
    throw py::value_error(str(name) + " must be a finite number >= 0, got " +
                          std::to_string(value));
  }
  return value;
}

}  // namespace antcd::python
