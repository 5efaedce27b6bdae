// python/src/bind_manager.cpp — antcd._World, the engine under antcd.CollisionManager
// (collision.py).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "convert.hpp"
#include "manager.hpp"

namespace antcd::python {

namespace {

ManagedWorld::Mode parse_mode(std::string_view mode) {
  if (mode == "verdict") return ManagedWorld::Mode::Verdict;
  if (mode == "pairs") return ManagedWorld::Mode::Pairs;
  if (mode == "contacts") return ManagedWorld::Mode::Contacts;
  throw py::value_error("mode must be 'verdict', 'pairs' or 'contacts', got '" + std::string(mode) +
                        "'");
}

py::list to_python(std::vector<ManagedWorld::Hit> hits) {
  py::list out;
  for (ManagedWorld::Hit& h : hits) {
    out.append(py::make_tuple(h.a, h.b, std::move(h.result),
                              std::const_pointer_cast<Model>(h.model_a), to_matrix(h.pose_a)));
  }
  return out;
}

py::object to_python(const ManagedWorld::Nearest& n) {
  if (!n.found) return py::none();
  return py::make_tuple(n.a, n.b, n.result);
}

// Runs a minimum-distance query without the GIL and converts its answer.
template <class Query>
py::object nearest(Query&& query) {
  ManagedWorld::Nearest n;
  {
    py::gil_scoped_release release;
    n = query();
  }
  return to_python(n);
}

}  // namespace

void bind_manager(py::module_& m) {
  py::class_<ManagedWorld>(
      m, "_World",
      "Posed shared Models in an antcd World (dynamic AABB tree broad phase, exact narrow phase). "
      "Internal: use CollisionManager. Queries release the GIL and may run while other threads "
      "move objects.")
      .def(py::init<>())
      .def(
          "add",
          [](ManagedWorld& w, std::shared_ptr<Model> model, const py::handle pose) {
            const Transform t = to_transform(pose, "transform");
            py::gil_scoped_release release;
            return w.add(std::move(model), t);
          },
          py::arg("model"), py::arg("transform"), "Adds an object, returns its id (never reused).")
      .def(
          "remove",
          [](ManagedWorld& w, ManagedWorld::Id id) {
            py::gil_scoped_release release;
            return w.remove(id);
          },
          py::arg("id"), "False when there is no such object.")
      .def(
          "set_pose",
          [](ManagedWorld& w, ManagedWorld::Id id, const py::handle pose) {
            const Transform t = to_transform(pose, "transform");
            py::gil_scoped_release release;
            return w.set_pose(id, t);
          },
          py::arg("id"), py::arg("transform"), "False when there is no such object.")
      .def("__len__", &ManagedWorld::size)
      .def(
          "collide_internal",
          [](const ManagedWorld& w, const std::string& mode, double delta) {
            const auto md = parse_mode(mode);
            const double d = to_non_negative(delta, "delta");
            std::vector<ManagedWorld::Hit> hits;
            {
              py::gil_scoped_release release;
              hits = w.collide_internal(md, d);
            }
            return to_python(std::move(hits));
          },
          py::arg("mode"), py::arg("delta") = 0.0,
          "[(id_a, id_b, CollisionResult, model_a, pose_a 4x4)] for colliding pairs, id_a < id_b; "
          "sorted. mode: "
          "'verdict' or 'pairs' (every pair, first contact each) or "
          "'contacts' (every pair, every contact).")
      .def(
          "collide_single",
          [](const ManagedWorld& w, const Model& model, const py::handle pose,
             const std::string& mode, double delta) {
            const Transform t = to_transform(pose, "transform");
            const auto md = parse_mode(mode);
            const double d = to_non_negative(delta, "delta");
            std::vector<ManagedWorld::Hit> hits;
            {
              py::gil_scoped_release release;
              hits = w.collide_single(model, t, md, d);
            }
            return to_python(std::move(hits));
          },
          py::arg("model"), py::arg("transform"), py::arg("mode"), py::arg("delta") = 0.0,
          "[(id, 0, CollisionResult, model, pose 4x4)]: objects colliding with the model (A = "
          "object, B = model).")
      .def(
          "collide_other",
          [](const ManagedWorld& w, const ManagedWorld& other, const std::string& mode,
             double delta) {
            const auto md = parse_mode(mode);
            const double d = to_non_negative(delta, "delta");
            std::vector<ManagedWorld::Hit> hits;
            {
              py::gil_scoped_release release;
              hits = w.collide_other(other, md, d);
            }
            return to_python(std::move(hits));
          },
          py::arg("other"), py::arg("mode"), py::arg("delta") = 0.0,
          "[(id_this, id_other, CollisionResult, model_this, pose_this)] for colliding pairs "
          "across two worlds; sorted.")
      .def(
          "distance_internal",
          [](const ManagedWorld& w) { return nearest([&] { return w.distance_internal(); }); },
          "(id_a, id_b, DistanceResult) of the closest pair of objects (A = id_a), or None with "
          "fewer than two objects.")
      .def(
          "distance_object",
          [](const ManagedWorld& w, ManagedWorld::Id id) {
            return nearest([&] { return w.distance_object(id); });
          },
          py::arg("id"),
          "(id, id_other, DistanceResult) of the object closest to object id (A = id), or None "
          "when there is no such object or no other.")
      .def(
          "distance_single",
          [](const ManagedWorld& w, const Model& model, const py::handle pose) {
            const Transform t = to_transform(pose, "transform");
            return nearest([&] { return w.distance_single(model, t); });
          },
          py::arg("model"), py::arg("transform"),
          "(id, 0, DistanceResult) of the object closest to the model (A = object, B = model), or "
          "None for an empty world.")
      .def(
          "distance_other",
          [](const ManagedWorld& w, const ManagedWorld& other) {
            return nearest([&] { return w.distance_other(other); });
          },
          py::arg("other"),
          "(id_this, id_other, DistanceResult) of the closest pair across two worlds (A = this "
          "world's object), or None when either is empty.");
}

}  // namespace antcd::python
