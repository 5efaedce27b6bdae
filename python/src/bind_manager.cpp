// python/src/bind_manager.cpp — antcd._World, the engine under antcd.CollisionManager
// (collision.py).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

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

py::object to_python(const std::shared_ptr<const Model>& model) {
  if (!model) return py::none();
  return py::cast(std::const_pointer_cast<Model>(model));
}

py::list to_python(std::vector<ManagedWorld::Hit> hits) {
  py::list out;
  for (ManagedWorld::Hit& h : hits) {
    out.append(py::make_tuple(h.a, h.b, std::move(h.result), to_python(h.model_a),
                              to_matrix(h.pose_a), to_python(h.model_b), to_matrix(h.pose_b)));
  }
  return out;
}

const char* kind_name(MotionToiKind kind) {
  switch (kind) {
    case MotionToiKind::RigidSweep:
      return "rigid_sweep";
    case MotionToiKind::StartContact:
      return "start_contact";
    case MotionToiKind::Deform:
      return "deform";
  }
  return "unknown";
}

// (id_a, id_b, kind, toi, tolerance_decided, point, triangles or None, DeformPair or None,
// SweepResult or None): see _World.sweep_motion's docstring.
py::list to_python(std::vector<ManagedWorld::MotionHit> hits) {
  py::list out;
  for (ManagedWorld::MotionHit& h : hits) {
    const MotionToi& t = h.toi;
    py::object triangles = py::none();
    if (t.kind == MotionToiKind::StartContact) {
      triangles = py::make_tuple(t.triangles[0], t.triangles[1]);
    } else if (t.kind == MotionToiKind::RigidSweep) {
      triangles = py::make_tuple(t.sweep.contact.triangle_a, t.sweep.contact.triangle_b);
    }
    out.append(py::make_tuple(
        h.a, h.b, kind_name(t.kind), t.toi, t.tolerance_decided, to_point(t.point), triangles,
        t.kind == MotionToiKind::Deform ? py::cast(t.primitive) : py::none(),
        t.kind == MotionToiKind::RigidSweep ? py::cast(t.sweep) : py::none()));
  }
  return out;
}

// The (id, name, value) entries CollisionManager passes: id and name, the name for messages.
std::pair<ManagedWorld::Id, std::string> entry_of(const py::handle entry, std::string_view what) {
  const auto t = py::reinterpret_borrow<py::tuple>(entry);
  if (!py::isinstance<py::tuple>(entry) || t.size() != 3) {
    throw py::type_error(std::string(what) + " entries must be (id, name, value) tuples");
  }
  return {t[0].cast<ManagedWorld::Id>(), t[1].cast<std::string>()};
}

/// sweep_motion's and set_motion_continuous' arguments, checked with the GIL held (messages:
/// "<function>: poses['name'] ..." / "<function>: vertices['name'] ...").
ManagedWorld::Motion to_motion(const ManagedWorld& w, const std::string& function,
                               const py::list& poses, const py::list& vertices,
                               double min_separation, double time_tolerance,
                               const py::handle max_iterations) {
  ManagedWorld::Motion m;
  m.request.min_separation = to_non_negative(min_separation, function + ": min_separation");
  m.request.time_tolerance = to_positive(time_tolerance, function + ": time_tolerance");
  m.request.max_iterations = static_cast<std::uint32_t>(
      to_count(max_iterations, function + ": max_iterations", 1, UINT32_MAX));
  for (const py::handle entry : poses) {
    const auto [id, name] = entry_of(entry, "poses");
    m.pose_ids.push_back(id);
    m.poses.push_back(
        to_transform(entry.cast<py::tuple>()[2], function + ": poses['" + name + "']"));
  }
  for (const py::handle entry : vertices) {
    const auto [id, name] = entry_of(entry, "vertices");
    const std::string label = function + ": vertices['" + name + "']";
    const std::optional<std::size_t> count = w.vertex_count(id);
    if (!count) throw py::value_error(label + ": " + name + " not in collision manager!");
    m.vertex_ids.push_back(id);
    m.vertices.push_back(to_deform_positions(entry.cast<py::tuple>()[2], label, *count));
  }
  return m;
}

/// Runs a continuous-motion call without the GIL and converts its answer.
template <class Call>
py::list motion(Call&& call) {
  std::vector<ManagedWorld::MotionHit> hits;
  {
    py::gil_scoped_release release;
    hits = call();
  }
  return to_python(std::move(hits));
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
          [](ManagedWorld& w, std::shared_ptr<Model> model, const py::handle pose, std::string name,
             bool self_collision, double rebuild_above) {
            const Transform t = to_transform(pose, "transform");
            ObjectOptions options;
            options.name = std::move(name);
            options.self_collision = self_collision;
            options.rebuild_above = to_non_negative(rebuild_above, "rebuild_above");
            py::gil_scoped_release release;
            return w.add(std::move(model), t, std::move(options));
          },
          py::arg("model"), py::arg("transform"), py::arg("name") = "",
          py::arg("self_collision") = false, py::arg("rebuild_above") = 0.0,
          "Adds an object, returns its id (never reused). name: how errors name it; "
          "self_collision: collide_internal also tests it against itself; rebuild_above: "
          "set_vertices rebuilds its hierarchy when refitting loosened it more (0: never).")
      .def(
          "set_vertices",
          [](ManagedWorld& w, ManagedWorld::Id id, const py::handle vertices,
             const std::string& name) {
            const std::optional<std::size_t> count = w.vertex_count(id);
            if (!count) return false;
            const std::vector<Vec3> v =
                to_positions(vertices, "set_vertices: vertices of '" + name + "'", *count);
            py::gil_scoped_release release;
            return w.set_vertices(id, v);
          },
          py::arg("id"), py::arg("vertices"), py::arg("name"),
          "New model-frame vertex positions of object id (World::set_vertices: its Model is "
          "copied on the first call). False when there is no such object; ValueError naming "
          "`name` for bad vertices, nothing changed.")
      .def(
          "model",
          [](const ManagedWorld& w, ManagedWorld::Id id) {
            std::shared_ptr<const Model> model;
            {
              py::gil_scoped_release release;
              model = w.model(id);
            }
            return to_python(model);
          },
          py::arg("id"), "The object's current Model, or None when there is no such object.")
      .def(
          "sweep_motion",
          [](const ManagedWorld& w, const py::list& poses, const py::list& vertices,
             double min_separation, double time_tolerance, const py::handle max_iterations) {
            const ManagedWorld::Motion m = to_motion(
                w, "sweep_motion", poses, vertices, min_separation, time_tolerance, max_iterations);
            return motion([&] { return w.sweep_motion(m); });
          },
          py::arg("poses"), py::arg("vertices"), py::arg("min_separation"),
          py::arg("time_tolerance"), py::arg("max_iterations"),
          "World::sweep_motion. poses: [(id, name, pose)], vertices: [(id, name, (n, 3) model "
          "frame)]. Returns [(id_a, id_b, kind, toi, tolerance_decided, point, triangles, "
          "primitive, sweep)], id_a < id_b or id_a == id_b (a self pair), sorted; kind "
          "'rigid_sweep' (triangles from sweep.contact, sweep a SweepResult), 'start_contact' "
          "(triangles at t = 0) or 'deform' (primitive a DeformPair). The world is not changed.")
      .def(
          "set_motion_continuous",
          [](ManagedWorld& w, const py::list& poses, const py::list& vertices,
             double min_separation, double time_tolerance, const py::handle max_iterations) {
            const ManagedWorld::Motion m =
                to_motion(w, "set_motion_continuous", poses, vertices, min_separation,
                          time_tolerance, max_iterations);
            return motion([&] { return w.set_motion_continuous(m); });
          },
          py::arg("poses"), py::arg("vertices"), py::arg("min_separation"),
          py::arg("time_tolerance"), py::arg("max_iterations"),
          "sweep_motion, then the poses and vertices applied (World::set_motion_continuous); on "
          "error nothing is changed.")
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
          "[(id_a, id_b, CollisionResult, model_a, pose_a 4x4, model_b, pose_b)] for colliding "
          "pairs, id_a < id_b, and self pairs (id, id) of self_collision objects (one contact per "
          "intersecting triangle pair); sorted. mode: "
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
          "[(id, 0, CollisionResult, model, pose 4x4, None, identity)]: objects colliding with "
          "the model (A = object, B = model).")
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
          "[(id_this, id_other, CollisionResult, model_this, pose_this, model_other, "
          "pose_other)] for colliding pairs across two worlds; sorted.")
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
