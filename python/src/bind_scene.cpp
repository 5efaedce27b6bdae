// python/src/bind_scene.cpp — antcd.Scene, antcd.SceneRun and antcd.run_scene.
#include <antcd/scene.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"
#include "paths.hpp"

namespace antcd::python {

namespace {

struct PyScene {
  std::shared_ptr<Scene> scene;
  std::string path;
};

struct SceneRun {
  std::string method;
  bool continuous = false;
  std::vector<FrameResult> frames;
  std::vector<std::string> names;
};

PyScene open_scene(const py::handle path_in, const py::handle leaf_size,
                   const std::string& covariance) {
  BuildOptions options;
  options.leaf_size = static_cast<std::uint32_t>(to_count(leaf_size, "leaf_size", 1, 1u << 20));
  options.covariance = parse_covariance(covariance);
  const std::filesystem::path path = to_path(path_in);
  require_readable_file(path, "scene file");
  py::gil_scoped_release release;
  // Every object's Model is pinned while the scene lives (its broad phase fits boxes to the
  // positions at build time, so Model.set_vertices refuses them). No other thread can reach these
  // Models before this returns: no lock needed to pin them.
  auto scene = std::shared_ptr<Scene>(new Scene(load_scene(path), options), [](Scene* dead) {
    for (std::size_t o = 0; o < dead->object_count(); ++o) unpin_model(dead->model_of(o));
    delete dead;
  });
  for (std::size_t o = 0; o < scene->object_count(); ++o) pin_model(scene->model_of(o));
  return PyScene{std::move(scene), path.string()};
}

py::array_t<std::uint32_t> pair_array(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  return make_rows<std::uint32_t>(pairs.size(), 2, [&](std::size_t i, std::uint32_t* o) {
    o[0] = pairs[i].first;
    o[1] = pairs[i].second;
  });
}

SceneRun run(const PyScene& s, const std::string& method, const py::object& frames_in, double delta,
             std::optional<double> feature_delta, const py::handle samples_per_side,
             const py::handle seed, const py::handle iterations, const py::handle agents,
             bool search_all, const py::handle threads, bool continuous) {
  SceneQuery query;
  query.continuous = continuous;
  query.method = parse_method(method);
  query.delta = to_non_negative(delta, "delta");
  if (feature_delta) {
    if (!(*feature_delta > 0) || !std::isfinite(*feature_delta)) {
      throw py::value_error(
          "feature_delta must be a finite number > 0 (or None: derived from "
          "triangle sizes)");
    }
    query.random.search.centroid_delta = *feature_delta;
  }
  query.random.samples_per_side =
      static_cast<std::uint32_t>(to_count(samples_per_side, "samples_per_side", 1, 10'000'000));
  query.seed = to_count(seed, "seed", 0, std::numeric_limits<std::uint64_t>::max());
  query.random.search.iterations =
      static_cast<std::uint32_t>(to_count(iterations, "iterations", 1, 1'000'000'000));
  query.random.search.set_agents(
      static_cast<std::uint32_t>(to_count(agents, "agents", 1, 1'000'000)));
  query.random.all_witnesses = search_all;
  query.threads = static_cast<int>(to_count(threads, "threads", 1, 256));

  const std::size_t total = s.scene->description().frames;
  std::vector<std::size_t> frames;
  if (frames_in.is_none()) {
    for (std::size_t f = 0; f < total; ++f) frames.push_back(f);
  } else if (PyIndex_Check(frames_in.ptr()) != 0 && !py::isinstance<py::bool_>(frames_in)) {
    frames.push_back(to_count(frames_in, "frames", 0, total - 1));
  } else {
    for (const py::handle f : frames_in) frames.push_back(to_count(f, "frame", 0, total - 1));
  }
  SceneRun out;
  out.method = std::string(method_name(query.method));
  out.continuous = continuous;
  for (const SceneObject& o : s.scene->description().objects) out.names.push_back(o.name);
  out.frames.reserve(frames.size());
  py::gil_scoped_release release;
  for (const std::size_t f : frames) out.frames.push_back(s.scene->run_frame(f, query));
  return out;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<SceneRun>(m, "SceneRun",
                       "Per-frame answers of Scene.run(): colliding object pairs and times.\n\n"
                       "Pairs are object indices (i < j) into object_names, sorted.")
      .def_readonly("method", &SceneRun::method)
      .def_readonly("continuous", &SceneRun::continuous,
                    "True when run with continuous=True (pairs touching during each step).")
      .def_readonly("object_names", &SceneRun::names)
      .def(
          "__len__", [](const SceneRun& r) { return r.frames.size(); }, "Number of frames run.")
      .def_property_readonly(
          "frames",
          [](const SceneRun& r) {
            return make_vector<std::int64_t>(r.frames.size(), [&](std::size_t i) {
              return static_cast<std::int64_t>(r.frames[i].frame);
            });
          },
          "int64[f]: the frame numbers run, in order.")
      .def_property_readonly(
          "pairs",
          [](const SceneRun& r) {
            py::list out;
            for (const FrameResult& f : r.frames) out.append(pair_array(f.pairs));
            return out;
          },
          "One uint32[k, 2] array per frame: the colliding object pairs.")
      .def_property_readonly(
          "candidates",
          [](const SceneRun& r) {
            py::list out;
            for (const FrameResult& f : r.frames) out.append(pair_array(f.candidates));
            return out;
          },
          "One uint32[k, 2] array per frame: the broad phase's survivors (pairs the narrow phase "
          "examined).")
      .def_property_readonly(
          "times_ms",
          [](const SceneRun& r) {
            return make_vector<double>(r.frames.size(),
                                       [&](std::size_t i) { return r.frames[i].time_ms; });
          },
          "float64[f]: wall time of each frame (pose update + broad phase + narrow phase), ms.")
      .def_property_readonly(
          "feature_hits",
          [](const SceneRun& r) {
            return make_vector<std::uint64_t>(
                r.frames.size(), [&](std::size_t i) { return r.frames[i].feature_hits; });
          },
          "uint64[f]: random methods: colliding feature pairs found per frame.")
      .def_property_readonly(
          "toi",
          [](const SceneRun& r) {
            py::list out;
            for (const FrameResult& f : r.frames) {
              out.append(
                  make_vector<double>(f.toi.size(), [&](std::size_t i) { return f.toi[i]; }));
            }
            return out;
          },
          "Continuous runs: one float64[k] array per frame, each pair's first time of impact in "
          "[0, 1] over the step from the previous frame (0: at frame - 1, 1: at the frame; "
          "frame 0: 0), in the order of pairs; never later than the true first contact. Empty "
          "arrays otherwise.")
      .def_property_readonly(
          "contact_points",
          [](const SceneRun& r) {
            py::list out;
            for (const FrameResult& f : r.frames) {
              out.append(
                  make_rows<double>(f.contact_points.size(), 3, [&](std::size_t i, double* o) {
                    for (int k = 0; k < 3; ++k) o[k] = f.contact_points[i][k];
                  }));
            }
            return out;
          },
          "Continuous runs: one float64[k, 3] array per frame, each pair's contact point at its "
          "toi (world frame), in the order of pairs. Empty arrays otherwise.")
      .def(
          "pair_names",
          [](const SceneRun& r, std::size_t index) {
            if (index >= r.frames.size()) {
              throw py::index_error("frame index " + std::to_string(index) + " out of range [0, " +
                                    std::to_string(r.frames.size()) + ")");
            }
            py::list out;
            for (const auto& [i, j] : r.frames[index].pairs)
              out.append(py::make_tuple(r.names[i], r.names[j]));
            return out;
          },
          py::arg("index"),
          "The colliding pairs of the index-th frame run, as (name, name) tuples.")
      .def("__repr__", [](const SceneRun& r) {
        return "<antcd.SceneRun method=" + r.method + (r.continuous ? " continuous" : "") +
               " frames=" + std::to_string(r.frames.size()) + ">";
      });

  py::class_<PyScene>(
      m, "Scene",
      "A scene file (antcd-scene/1 JSON) loaded with one Model per distinct mesh file and "
      "scale.\n\n"
      "Each frame: poses -> broad phase (sweep and prune, root spheres, root OBBs) -> the chosen "
      "narrow phase on each surviving pair.")
      .def(
          py::init(&open_scene), py::arg("path"), py::kw_only(), py::arg("leaf_size") = 4,
          py::arg("covariance") = "area",
          "Loads the scene and builds its models. Raises FileNotFoundError (OSError) when the file "
          "is missing, ValueError naming the object or field when the scene or a mesh is invalid.")
      .def_readonly("path", &PyScene::path)
      .def_property_readonly("frames",
                             [](const PyScene& s) { return s.scene->description().frames; })
      .def_property_readonly("object_count",
                             [](const PyScene& s) { return s.scene->object_count(); })
      .def_property_readonly("model_count", [](const PyScene& s) { return s.scene->model_count(); })
      .def_property_readonly("build_ms", [](const PyScene& s) { return s.scene->build_ms(); })
      .def_property_readonly("object_names",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               for (const SceneObject& o : s.scene->description().objects)
                                 names.push_back(o.name);
                               return names;
                             })
      .def(
          "model",
          [](const PyScene& s, std::size_t object) {
            if (object >= s.scene->object_count())
              throw py::index_error("object index out of range");
            // Shares ownership of the scene: the Model stays valid as long as it is referenced.
            return std::shared_ptr<Model>(s.scene, const_cast<Model*>(&s.scene->model_of(object)));
          },
          py::arg("object"),
          "The Model of an object (shared by objects with the same mesh and scale).")
      .def(
          "pose",
          [](const PyScene& s, std::size_t object, std::size_t frame) {
            if (object >= s.scene->object_count())
              throw py::index_error("object index out of range");
            if (frame >= s.scene->description().frames) throw py::index_error("frame out of range");
            return to_matrix(s.scene->description().objects[object].pose(frame));
          },
          py::arg("object"), py::arg("frame"),
          "4x4 pose of an object at a frame (scale not included).")
      .def("run", &run, py::kw_only(), py::arg("method") = "exact", py::arg("frames") = py::none(),
           py::arg("delta") = 0.0, py::arg("feature_delta") = py::none(),
           py::arg("samples_per_side") = 1000, py::arg("seed") = 1, py::arg("iterations") = 100,
           py::arg("agents") = 60, py::arg("search_all") = false, py::arg("threads") = 1,
           py::arg("continuous") = false,
           "Runs frames (None: all; an int; or an iterable of ints) with a method: 'exact' "
           "(default, ground truth), 'sphere-obb', 'aco', 'maco', 'pso', 'ga' or 'exhaustive'.\n"
           "delta: exact/sphere-obb threshold; feature_delta: random methods' centroid threshold "
           "(> 0; None: derived from triangle sizes); samples_per_side, seed, iterations, agents: "
           "random "
           "methods; search_all: random methods search every pair for N iterations instead of "
           "stopping at the first hit; threads: narrow-phase workers (same answer at any count).\n"
           "continuous: exact method only (ValueError otherwise): each frame reports the pairs "
           "whose "
           "surfaces come within delta during the step from the previous frame (conservative "
           "sweeps, "
           "never a missed contact), with toi and contact_points per pair.\n"
           "The GIL is released while frames run.")
      .def("__repr__", [](const PyScene& s) {
        return "<antcd.Scene '" + s.path + "': " + std::to_string(s.scene->object_count()) +
               " objects, " + std::to_string(s.scene->description().frames) + " frames>";
      });

  m.def(
      "run_scene",
      [](const py::object& path, const std::string& method, const py::object& frames, double delta,
         std::optional<double> feature_delta, const py::handle samples_per_side,
         const py::handle seed, const py::handle iterations, const py::handle agents,
         bool search_all, const py::handle threads, bool continuous) {
        const PyScene s = open_scene(path, py::int_(4), "area");
        return run(s, method, frames, delta, feature_delta, samples_per_side, seed, iterations,
                   agents, search_all, threads, continuous);
      },
      py::arg("path"), py::kw_only(), py::arg("method") = "exact", py::arg("frames") = py::none(),
      py::arg("delta") = 0.0, py::arg("feature_delta") = py::none(),
      py::arg("samples_per_side") = 1000, py::arg("seed") = 1, py::arg("iterations") = 100,
      py::arg("agents") = 60, py::arg("search_all") = false, py::arg("threads") = 1,
      py::arg("continuous") = false,
      "Scene(path).run(...): loads a scene file and runs its frames with a method. See Scene.run.");
}

}  // namespace antcd::python
