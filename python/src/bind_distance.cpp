// python/src/bind_distance.cpp — antcd.distance and its DistanceResult.
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

void bind_distance(py::module_& m) {
  py::class_<DistanceResult>(
      m, "DistanceResult",
      "The answer of distance(): the minimum distance between two models' surfaces, the triangles "
      "and world-frame points where it is reached.")
      .def_readonly("distance", &DistanceResult::distance,
                    "Minimum surface distance (0 when the surfaces meet; negative only for "
                    "signed=True: minus "
                    "the solids' penetration depth). With "
                    "beyond_upper_bound, only the closest pair seen (possibly inf).")
      .def_readonly("lower_bound", &DistanceResult::lower_bound,
                    "A proven lower bound of the distance.")
      .def_property_readonly(
          "point_a", [](const DistanceResult& r) { return to_point(r.point_a); },
          "float64[3], world frame: the closest point on A's triangle_a.")
      .def_property_readonly(
          "point_b", [](const DistanceResult& r) { return to_point(r.point_b); },
          "float64[3], world frame: the closest point on B's triangle_b.")
      .def_readonly("triangle_a", &DistanceResult::triangle_a,
                    "Index of the closest triangle in A's faces.")
      .def_readonly("triangle_b", &DistanceResult::triangle_b,
                    "Index of the closest triangle in B's faces.")
      .def_readonly("intersecting", &DistanceResult::intersecting,
                    "The surfaces share a point (exact decision; distance is then 0).")
      .def_readonly("approximate", &DistanceResult::approximate,
                    "A tolerance let the search skip a pair that might have been closer.")
      .def_readonly(
          "beyond_upper_bound", &DistanceResult::beyond_upper_bound,
          "The distance is larger than the request's upper_bound (lower_bound > upper_bound).")
      .def_readonly("node_pairs", &DistanceResult::node_pairs, "Node pairs examined.")
      .def_readonly("triangle_tests", &DistanceResult::triangle_tests,
                    "Triangle-triangle distances computed.")
      .def("__float__", [](const DistanceResult& r) { return r.distance; })
      .def("__repr__", [](const DistanceResult& r) {
        std::ostringstream s;
        s.precision(17);
        s << "<antcd.DistanceResult distance=" << r.distance << " triangles=(" << r.triangle_a
          << ", " << r.triangle_b << ")" << (r.intersecting ? " intersecting" : "") << ">";
        return s.str();
      });

  m.def(
      "distance",
      [](const Model& a, const py::handle pose_a, const Model& b, const py::handle pose_b,
         double upper_bound, double abs_tolerance, double rel_tolerance, bool signed_distance) {
        const Transform pa = to_transform(pose_a, "pose_a");
        const Transform pb = to_transform(pose_b, "pose_b");
        if (!(upper_bound >= 0)) {
          throw py::value_error("upper_bound must be >= 0 (inf: no bound), got " +
                                std::to_string(upper_bound));
        }
        DistanceRequest request;
        request.upper_bound = upper_bound;
        request.abs_tolerance = to_non_negative(abs_tolerance, "abs_tolerance");
        request.rel_tolerance = to_non_negative(rel_tolerance, "rel_tolerance");
        if (request.rel_tolerance >= 1) {
          throw py::value_error("rel_tolerance must be < 1, got " + std::to_string(rel_tolerance));
        }
        py::gil_scoped_release release;
        const ModelReadLock lock(a, b);
        return signed_distance ? antcd::signed_distance(a, pa, b, pb, request)
                               : distance(a, pa, b, pb, request);
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::kw_only(),
      py::arg("upper_bound") = std::numeric_limits<double>::infinity(),
      py::arg("abs_tolerance") = 0.0, py::arg("rel_tolerance") = 0.0, py::arg("signed") = false,
      "Minimum distance between the surfaces of two posed models (0 when they meet).\n\n"
      "pose_a, pose_b: as for collide(). Exact by default; abs_tolerance / rel_tolerance (>= 0, "
      "rel < 1) accept an answer within max(abs, rel * distance) above the true distance; "
      "upper_bound (>= 0) stops once the distance is known to exceed it (beyond_upper_bound). "
      "A mesh wholly inside another is at a positive distance: this is a surface query, unless "
      "signed=True: then both models must be closed, and overlapping solids (nested included) "
      "give minus their penetration depth (see penetration()). "
      "The GIL is released while the query runs.");
}

}  // namespace antcd::python
