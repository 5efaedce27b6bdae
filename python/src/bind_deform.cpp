// python/src/bind_deform.cpp — antcd.deform_sweep and antcd.collision_free_step
// (antcd/deform_ccd.hpp): continuous collision of meshes whose vertices move one by one from V0 to
// V1 (cloth, cables, soft parts), with its DeformSweepResult and DeformPair.
#include <antcd/deform_ccd.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

DeformSweepRequest to_request(double min_separation, double time_tolerance, bool all_pairs,
                              double pose_path_tolerance) {
  DeformSweepRequest r;
  r.min_separation = to_non_negative(min_separation, "min_separation");
  r.time_tolerance = to_positive(time_tolerance, "time_tolerance");
  r.all_pairs = all_pairs;
  r.pose_path_tolerance = to_non_negative(pose_path_tolerance, "pose_path_tolerance");
  return r;
}

const char* kind_name(DeformPairKind k) {
  return k == DeformPairKind::VertexFace ? "vertex_face" : "edge_edge";
}

py::tuple pair_indices(const DeformPair& p) {
  if (p.kind == DeformPairKind::VertexFace) return py::make_tuple(p.indices[0], p.indices[1]);
  return py::make_tuple(p.indices[0], p.indices[1], p.indices[2], p.indices[3]);
}

std::string pair_repr(const DeformPair& p) {
  std::ostringstream s;
  s.precision(17);
  s << "<antcd.DeformPair " << kind_name(p.kind) << " "
    << py::repr(pair_indices(p)).cast<std::string>() << " toi=" << p.toi
    << (p.tolerance_decided ? " (tolerance)" : " (proven)") << ">";
  return s.str();
}

}  // namespace

void bind_deform(py::module_& m) {
  py::class_<DeformPair>(
      m, "DeformPair",
      "One primitive pair of a deforming sweep: a vertex against a triangle, or an edge against "
      "an edge, with its time of impact. Indices are the meshes' own.")
      .def_property_readonly(
          "kind", [](const DeformPair& p) { return kind_name(p.kind); },
          "'vertex_face' or 'edge_edge'.")
      .def_property_readonly("indices", &pair_indices,
                             "vertex_face: (vertex, triangle); edge_edge: (a0, a1, b0, b1), each "
                             "edge's ends ascending (self: edge (a0, a1) first lexicographically; "
                             "two meshes: edge (a0, a1) is the first mesh's).")
      .def_readonly("vertex_in_first", &DeformPair::vertex_in_first,
                    "Two meshes, vertex_face: the vertex is the first mesh's (else the triangle "
                    "is). True for self pairs.")
      .def_readonly("toi", &DeformPair::toi, "The pair's time of impact in [0, 1].")
      .def_readonly("tolerance_decided", &DeformPair::tolerance_decided,
                    "The hit rests on the time tolerance, not on a proof of contact.")
      .def_readonly("budget_exhausted", &DeformPair::budget_exhausted,
                    "The primitive's box budget ran out (very degenerate input); "
                    "tolerance_decided is then True.")
      .def("__repr__", &pair_repr);

  py::class_<DeformSweepResult>(
      m, "DeformSweepResult",
      "The answer of deform_sweep(): whether and when (toi in [0, 1]) some primitive pair first "
      "comes within min_separation. bool(result) is result.hit.")
      .def_readonly("hit", &DeformSweepResult::hit,
                    "Some pair comes within min_separation (or within the tolerance's reach, see "
                    "tolerance_decided). A miss is a proof that none does.")
      .def_readonly("toi", &DeformSweepResult::toi,
                    "Time of impact, never later than the first contact (1 when no hit).")
      .def_readonly("tolerance_decided", &DeformSweepResult::tolerance_decided,
                    "The earliest pair's hit came from the tolerance, not from a proof.")
      .def_property_readonly(
          "pair",
          [](const DeformSweepResult& r) -> py::object {
            return r.hit ? py::cast(r.pair) : py::none();
          },
          "The earliest DeformPair, or None without a hit.")
      .def_readonly("pairs", &DeformSweepResult::pairs,
                    "all_pairs=True: every hit DeformPair, sorted by toi, then kind (vertex_face "
                    "first), then vertex_in_first (True first), then indices. Empty otherwise.")
      .def_readonly("node_pairs", &DeformSweepResult::node_pairs,
                    "Hierarchy node pairs whose bounds were compared.")
      .def_readonly("primitive_queries", &DeformSweepResult::primitive_queries,
                    "Vertex-face and edge-edge primitive queries made.")
      .def_readonly("tasks", &DeformSweepResult::tasks,
                    "Parallel tasks the traversal was cut into.")
      .def_readonly("scratch_bytes", &DeformSweepResult::scratch_bytes,
                    "Bytes the call held (outputs excluded).")
      .def("__bool__", [](const DeformSweepResult& r) { return r.hit; })
      .def("__repr__", [](const DeformSweepResult& r) {
        std::ostringstream s;
        s.precision(17);
        s << "<antcd.DeformSweepResult hit=" << (r.hit ? "True" : "False");
        if (r.hit) s << " toi=" << r.toi << (r.tolerance_decided ? " (tolerance)" : " (proven)");
        s << ">";
        return s.str();
      });

  m.def(
      "deform_sweep",
      [](const Model& a, const py::handle a0_in, const py::handle a1_in, const py::object& b_in,
         const py::handle b0_in, const py::handle b1_in, const py::handle pose_b0_in,
         const py::handle pose_b1_in, double min_separation, double time_tolerance, bool all_pairs,
         double pose_path_tolerance) {
        const bool deforming_b = !b0_in.is_none() || !b1_in.is_none();
        const bool rigid_b = !pose_b0_in.is_none() || !pose_b1_in.is_none();
        if (b_in.is_none() && (deforming_b || rigid_b)) {
          throw py::value_error(
              "deform_sweep: b0/b1 and pose_b0/pose_b1 need a second model b (got b=None)");
        }
        if (!b_in.is_none()) {
          if (deforming_b == rigid_b) {
            throw py::value_error(
                "deform_sweep: with a second model b give either b0 and b1 (b deforming) or "
                "pose_b0 and pose_b1 (b rigid), not " +
                std::string(deforming_b ? "both" : "neither"));
          }
          if (deforming_b && (b0_in.is_none() || b1_in.is_none())) {
            throw py::value_error(std::string("deform_sweep: ") + (b0_in.is_none() ? "b0" : "b1") +
                                  " is missing (b deforming)");
          }
          if (rigid_b && (pose_b0_in.is_none() || pose_b1_in.is_none())) {
            throw py::value_error(std::string("deform_sweep: ") +
                                  (pose_b0_in.is_none() ? "pose_b0" : "pose_b1") +
                                  " is missing (b rigid)");
          }
          if (!py::isinstance<Model>(b_in)) {
            throw py::type_error(
                "deform_sweep: b must be an antcd.Model or None, got " +
                py::str(py::type::handle_of(b_in).attr("__name__")).cast<std::string>());
          }
        }
        const DeformSweepRequest request =
            to_request(min_separation, time_tolerance, all_pairs, pose_path_tolerance);
        const std::vector<Vec3> a0 = to_deform_positions(a0_in, "a0", a.mesh().vertices.size());
        const std::vector<Vec3> a1 = to_deform_positions(a1_in, "a1", a.mesh().vertices.size());
        if (b_in.is_none()) {
          py::gil_scoped_release release;
          const ModelReadLock lock(a);
          return deform_sweep(a, a0, a1, request);
        }
        const Model& b = b_in.cast<const Model&>();
        if (deforming_b) {
          const std::vector<Vec3> b0 = to_deform_positions(b0_in, "b0", b.mesh().vertices.size());
          const std::vector<Vec3> b1 = to_deform_positions(b1_in, "b1", b.mesh().vertices.size());
          py::gil_scoped_release release;
          const ModelReadLock lock(a, b);
          return deform_sweep(a, a0, a1, b, b0, b1, request);
        }
        const Transform pose_b0 = to_transform(pose_b0_in, "pose_b0");
        const Transform pose_b1 = to_transform(pose_b1_in, "pose_b1");
        py::gil_scoped_release release;
        const ModelReadLock lock(a, b);
        return deform_sweep(a, a0, a1, b, pose_b0, pose_b1, request);
      },
      py::arg("a"), py::arg("a0"), py::arg("a1"), py::arg("b") = py::none(),
      py::arg("b0") = py::none(), py::arg("b1") = py::none(), py::kw_only(),
      py::arg("pose_b0") = py::none(), py::arg("pose_b1") = py::none(),
      py::arg("min_separation") = 0.0, py::arg("time_tolerance") = 1e-6,
      py::arg("all_pairs") = false, py::arg("pose_path_tolerance") = 0.0,
      "Continuous collision of a deforming mesh: vertex i of model a moves linearly from a0[i] "
      "at t = 0 to a1[i] at t = 1 (the model's triangles; its stored positions are not read). "
      "The first time some primitive pair (a vertex against a triangle it is not a corner of, an "
      "edge against an edge with no shared vertex) comes within min_separation.\n\n"
      "Three forms: deform_sweep(a, a0, a1): self; deform_sweep(a, a0, a1, b, b0, b1): against a "
      "second deforming model b (pairs across the two only); deform_sweep(a, a0, a1, b, "
      "pose_b0=P0, pose_b1=P1): against a rigid model b moving between two poses (as sweep(); "
      "b's own vertices, followed along chords within pose_path_tolerance, 0: 1e-3 times b's "
      "radius, so its hits are tolerance_decided).\n"
      "Positions are float64 arrays of shape (n, 3), n the model's vertex count, finite, every "
      "|coordinate| <= 1e150 (ValueError naming the argument otherwise). Conservative: a contact "
      "is never missed, toi is never later than it and within time_tolerance of it when the "
      "reported pair makes contact; tolerance_decided says when the tolerance, not a proof, "
      "made the hit. all_pairs: every hit pair in result.pairs. The GIL is released while it "
      "runs; the same answer at any thread count.");

  m.def(
      "collision_free_step",
      [](const Model& model, const py::handle v0_in, const py::handle v1_in, double min_separation,
         double time_tolerance) {
        const DeformSweepRequest request = to_request(min_separation, time_tolerance, false, 0.0);
        const std::vector<Vec3> v0 = to_deform_positions(v0_in, "v0", model.mesh().vertices.size());
        const std::vector<Vec3> v1 = to_deform_positions(v1_in, "v1", model.mesh().vertices.size());
        py::gil_scoped_release release;
        const ModelReadLock lock(model);
        return collision_free_step(model, v0, v1, request.min_separation, request.time_tolerance);
      },
      py::arg("model"), py::arg("v0"), py::arg("v1"), py::arg("min_separation"), py::kw_only(),
      py::arg("time_tolerance") = 1e-6,
      "The collision-free step in IPC's terms: a step s in [0, 1] such that over [0, s] no self "
      "pair of the model moving from v0 to v1 comes closer than min_separation (a finite number "
      ">= 0); s is never larger than the true largest such step and within time_tolerance of it "
      "(as deform_sweep's toi). 1.0 when no pair comes that close. Arguments checked as for "
      "deform_sweep; the GIL is released while it runs.");
}

}  // namespace antcd::python
