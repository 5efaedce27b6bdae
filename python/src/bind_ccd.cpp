// python/src/bind_ccd.cpp — antcd.sweep (continuous collision between moving models), its
// SweepResult and the SweepContact at the time of impact.
#include <antcd/sweep.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <sstream>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

void bind_ccd(py::module_& m) {
  py::class_<Contact>(m, "SweepContact",
                      "Where a sweep first touched: a triangle pair at the time of impact.")
      .def_readonly("triangle_a", &Contact::triangle_a, "Index of the triangle in A's faces.")
      .def_readonly("triangle_b", &Contact::triangle_b, "Index of the triangle in B's faces.")
      .def_property_readonly(
          "point", [](const Contact& c) { return to_point(c.point); },
          "float64[3], world frame: a common point, or the closest points' midpoint.")
      .def_property_readonly(
          "normal", [](const Contact& c) { return to_point(c.normal); },
          "float64[3], world frame, unit: from B towards A (as collide's contact normals).")
      .def_readonly("distance", &Contact::distance, "Triangle distance at the time of impact.")
      .def_readonly("depth", &Contact::depth,
                    "Penetration depth of the pair (>= 0), -distance when apart.");

  py::class_<SweepResult>(
      m, "SweepResult",
      "The answer of sweep(): whether and when (toi in [0, 1]) two moving models first come "
      "within min_separation, and the contact there.")
      .def_readonly("hit", &SweepResult::hit,
                    "The motions touch (or come within the tolerance's reach, see "
                    "tolerance_decided). A miss is a proof that they never do.")
      .def_readonly("toi", &SweepResult::toi,
                    "Time of impact, never later than the first contact (1 when no hit).")
      .def_property_readonly(
          "contact",
          [](const SweepResult& r) -> py::object {
            return r.hit ? py::cast(r.contact) : py::none();
          },
          "The SweepContact at toi, or None without a hit.")
      .def_readonly("tolerance_decided", &SweepResult::tolerance_decided,
                    "The hit rests on the time tolerance, not on a proof of contact.")
      .def_readonly("budget_exhausted", &SweepResult::budget_exhausted,
                    "The iteration budget ran out (a conservative stop).")
      .def_readonly("distance", &SweepResult::distance,
                    "Distance at toi when hit; else a proven lower bound (>= min_separation).")
      .def_readonly("motion_bound", &SweepResult::motion_bound,
                    "Bound on the surfaces' relative speed (mesh units per unit time).")
      .def_readonly("iterations", &SweepResult::iterations,
                    "Iterations made: interval tests, distance queries and traversals.")
      .def("__bool__", [](const SweepResult& r) { return r.hit; })
      .def("__repr__", [](const SweepResult& r) {
        std::ostringstream s;
        s.precision(17);
        s << "<antcd.SweepResult hit=" << (r.hit ? "True" : "False");
        if (r.hit) s << " toi=" << r.toi << (r.tolerance_decided ? " (tolerance)" : " (proven)");
        s << ">";
        return s.str();
      });

  m.def(
      "sweep",
      [](const Model& a, const py::handle pose_a0, const py::handle pose_a1, const Model& b,
         const py::handle pose_b0, const py::handle pose_b1, double min_separation,
         double time_tolerance) {
        const Transform a0 = to_transform(pose_a0, "pose_a0");
        const Transform a1 = to_transform(pose_a1, "pose_a1");
        const Transform b0 = to_transform(pose_b0, "pose_b0");
        const Transform b1 = to_transform(pose_b1, "pose_b1");
        SweepRequest request;
        request.min_separation = to_non_negative(min_separation, "min_separation");
        request.time_tolerance = to_positive(time_tolerance, "time_tolerance");
        py::gil_scoped_release release;
        const ModelReadLock lock(a, b);
        return sweep(a, a0, a1, b, b0, b1, request);
      },
      py::arg("a"), py::arg("pose_a0"), py::arg("pose_a1"), py::arg("b"), py::arg("pose_b0"),
      py::arg("pose_b1"), py::kw_only(), py::arg("min_separation") = 0.0,
      py::arg("time_tolerance") = 1e-6,
      "Continuous collision: the first time t in [0, 1] at which A, moving from pose_a0 to "
      "pose_a1, and B, moving from pose_b0 to pose_b1, come within min_separation.\n\n"
      "Poses as for collide(). Each motion interpolates its translation linearly and turns at "
      "constant angular velocity about the model's origin (slerp). Conservative: a contact is "
      "never missed and toi is never later than it; tolerance_decided says when the time "
      "tolerance, not a proof, made the hit. The GIL is released while the query runs.");
}

}  // namespace antcd::python
