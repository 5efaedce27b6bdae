// python/src/bind_penetration.cpp — antcd.penetration and its PenetrationResult, antcd.is_convex.
#include <antcd/penetration.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <sstream>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

py::array_t<double> to_vec(const Vec3& p) {
  return make_vector<double>(3, [&](std::size_t k) { return p[static_cast<int>(k)]; });
}

}  // namespace

void bind_penetration(py::module_& m) {
  py::class_<PenetrationResult>(
      m, "PenetrationResult",
      "The answer of penetration(): certified bounds lower <= depth <= upper of the penetration "
      "depth of two closed models (solids), the way to move A, and a point inside both. Not the "
      "per-triangle-pair depth of a contact.")
      .def_readonly("overlapping", &PenetrationResult::overlapping,
                    "The interiors certainly overlap (a point inside both was found).")
      .def_readonly("exact", &PenetrationResult::exact,
                    "Convex pair: lower == upper is the depth up to rounding.")
      .def_readonly("converged", &PenetrationResult::converged,
                    "upper - lower is within the requested tolerance.")
      .def_readonly("lower", &PenetrationResult::lower, "Proven lower bound of the depth.")
      .def_readonly("upper", &PenetrationResult::upper,
                    "Length of a translation of A verified to separate the solids.")
      .def_property_readonly(
          "direction", [](const PenetrationResult& r) { return to_vec(r.direction); },
          "float64[3], unit, world frame: the way to move A (by upper).")
      .def_property_readonly(
          "witness", [](const PenetrationResult& r) { return to_vec(r.witness); },
          "float64[3], world frame: a point inside both solids (when overlapping).")
      .def_property_readonly(
          "point_a", [](const PenetrationResult& r) { return to_vec(r.point_a); },
          "float64[3], world frame: a point of A's surface.")
      .def_property_readonly(
          "point_b", [](const PenetrationResult& r) { return to_vec(r.point_b); },
          "float64[3], world frame: a point of B's surface.")
      .def_readonly("evaluations", &PenetrationResult::evaluations, "Exact collide calls made.")
      .def("__float__", [](const PenetrationResult& r) { return r.upper; })
      .def("__repr__", [](const PenetrationResult& r) {
        std::ostringstream s;
        s.precision(17);
        s << "<antcd.PenetrationResult depth in [" << r.lower << ", " << r.upper << "]"
          << (r.exact ? " exact" : "") << (r.converged ? "" : " not converged") << ">";
        return s.str();
      });

  m.def(
      "penetration",
      [](const Model& a, const py::handle pose_a, const Model& b, const py::handle pose_b,
         double rel_tolerance, double abs_tolerance, std::uint32_t max_evaluations,
         const std::string& shape) {
        const Transform pa = to_transform(pose_a, "pose_a");
        const Transform pb = to_transform(pose_b, "pose_b");
        PenetrationRequest request;
        request.rel_tolerance = to_non_negative(rel_tolerance, "rel_tolerance");
        request.abs_tolerance = to_non_negative(abs_tolerance, "abs_tolerance");
        if (request.rel_tolerance >= 1) {
          throw py::value_error("rel_tolerance must be < 1, got " + std::to_string(rel_tolerance));
        }
        if (max_evaluations == 0) throw py::value_error("max_evaluations must be >= 1");
        if (shape == "convex") {
          request.shape = PenetrationRequest::Shape::Convex;
        } else if (shape == "general") {
          request.shape = PenetrationRequest::Shape::General;
        } else if (shape != "auto") {
          throw py::value_error("shape must be 'auto', 'convex' or 'general', got '" + shape + "'");
        }
        request.max_evaluations = max_evaluations;
        py::gil_scoped_release release;
        const ModelReadLock lock(a, b);
        return penetration(a, pa, b, pb, request);
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
      py::arg("rel_tolerance") = 0.01, py::kw_only(), py::arg("abs_tolerance") = 0.0,
      py::arg("max_evaluations") = 64, py::arg("shape") = "auto",
      "Penetration depth of two closed models (solids): the length of the shortest translation "
      "of A after which the interiors no longer overlap (0 when they do not). Convex pairs are "
      "exact; otherwise [lower, upper] is certified and refined until upper - lower <= "
      "max(abs_tolerance, rel_tolerance * upper) or max_evaluations collide calls. ValueError "
      "for an open model. The GIL is released while the query runs.");

  m.def(
      "is_convex",
      [](const Model& model) {
        py::gil_scoped_release release;
        const ModelReadLock lock(model);
        return is_convex(model);
      },
      py::arg("model"),
      "Whether a closed model is convex: one piece, no reflex edge (heights within 1e-10 of its "
      "size count as flat). False for an open model.");
}

}  // namespace antcd::python
