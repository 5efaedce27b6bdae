// python/src/bind_random.cpp — antcd.random_collide: the paper's random (feature-pair) detection.
#include <antcd/method.hpp>
#include <antcd/random.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <string>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

Method parse_search_method(std::string_view name) {
  const Method method = parse_method(name);  // ArgumentError (ValueError) for an unknown name
  if (!is_search_method(method)) {
    throw py::value_error(
        "random_collide needs a search method (maco, aco, pso, ga or exhaustive), got '" +
        std::string(name) + "': use collide() for exact detection");
  }
  return method;
}

const char* stop_name(StopReason reason) {
  switch (reason) {
    case StopReason::EmptySpace:
      return "empty-space";
    case StopReason::FirstHit:
      return "first-hit";
    case StopReason::Target:
      return "target";
    case StopReason::Iterations:
      return "iterations";
    case StopReason::Evaluations:
      return "evaluations";
    case StopReason::Time:
      return "time";
  }
  return "unknown";
}

/// SearchResult plus the method that produced it.
struct RandomResult {
  SearchResult search;
  Method method = Method::Maco;
  double delta = 0;  ///< collide()'s threshold the flow ran with
};

}  // namespace

void bind_random(py::module_& m) {
  py::class_<RandomResult>(
      m, "RandomResult",
      "The answer of random_collide(): the colliding feature pairs the search met.\n\n"
      "A feature is a triangle centroid (world frame); a feature pair collides when the two "
      "centroids are within `delta`. Random detection is approximate by design; collide() is "
      "exact. bool(result) is result.found.")
      .def_property_readonly("found", [](const RandomResult& r) { return r.search.found; })
      .def("__bool__", [](const RandomResult& r) { return r.search.found; })
      .def_property_readonly(
          "method", [](const RandomResult& r) { return std::string(method_name(r.method)); })
      .def_property_readonly(
          "triangles_a",
          [](const RandomResult& r) {
            return make_vector<std::uint32_t>(
                r.search.hits.size(), [&](std::size_t i) { return r.search.hits[i].triangle_a; });
          },
          "uint32[k]: A's triangle of each distinct colliding feature pair, in the order found.")
      .def_property_readonly(
          "triangles_b",
          [](const RandomResult& r) {
            return make_vector<std::uint32_t>(
                r.search.hits.size(), [&](std::size_t i) { return r.search.hits[i].triangle_b; });
          },
          "uint32[k]: B's triangle of each hit.")
      .def_property_readonly(
          "distances",
          [](const RandomResult& r) {
            return make_vector<double>(r.search.hits.size(),
                                       [&](std::size_t i) { return r.search.hits[i].distance; });
          },
          "float64[k]: centroid distance of each hit (<= delta).")
      .def_property_readonly(
          "cells",
          [](const RandomResult& r) {
            return make_rows<std::uint32_t>(r.search.hits.size(), 2,
                                            [&](std::size_t i, std::uint32_t* o) {
                                              o[0] = r.search.hits[i].i;
                                              o[1] = r.search.hits[i].j;
                                            });
          },
          "uint32[k, 2]: the grid cell (i, j) of each hit in the feature space.")
      .def_property_readonly(
          "best_distance", [](const RandomResult& r) { return r.search.best_distance; },
          "Smallest centroid distance evaluated (inf when nothing was).")
      .def_property_readonly(
          "evaluations", [](const RandomResult& r) { return r.search.evaluations; },
          "Fitness evaluations, repeats included.")
      .def_property_readonly("iterations",
                             [](const RandomResult& r) { return r.search.iterations; })
      .def_property_readonly("runs", [](const RandomResult& r) { return r.search.runs; })
      .def_property_readonly(
          "delta", [](const RandomResult& r) { return r.delta; },
          "collide()'s threshold the flow ran with (culling and witness test).")
      .def_property_readonly(
          "stop", [](const RandomResult& r) { return std::string(stop_name(r.search.stop)); },
          "Why the search stopped: empty-space, first-hit, target, iterations, "
          "evaluations or time.")
      .def("__repr__", [](const RandomResult& r) {
        return "<antcd.RandomResult method=" + std::string(method_name(r.method)) +
               " found=" + (r.search.found ? "True" : "False") +
               " hits=" + std::to_string(r.search.hits.size()) +
               " evaluations=" + std::to_string(r.search.evaluations) + ">";
      });

  m.def(
      "random_collide",
      [](const Model& a, const py::handle pose_a, const Model& b, const py::handle pose_b,
         const std::string& method, const py::handle seed, const py::object& delta,
         const py::handle samples_per_side, const py::handle iterations, const py::handle agents,
         bool first_hit, const py::handle max_evaluations, const py::handle restarts) {
        const Transform pa = to_transform(pose_a, "pose_a");
        const Transform pb = to_transform(pose_b, "pose_b");
        SearchRequest request;
        SamplingOptions sampling;
        request.method = parse_search_method(method);
        request.seed = to_count(seed, "seed", 0, std::numeric_limits<std::uint64_t>::max());
        if (!delta.is_none()) {
          const double d = PyFloat_AsDouble(delta.ptr());  // TypeError for a non-number
          if (d == -1.0 && PyErr_Occurred() != nullptr) throw py::error_already_set();
          sampling.delta = to_non_negative(d, "delta");
        }
        request.iterations =
            static_cast<std::uint32_t>(to_count(iterations, "iterations", 1, 1'000'000'000));
        const auto m_agents = static_cast<std::uint32_t>(to_count(agents, "agents", 2, 1'000'000));
        request.ant.ants = m_agents;
        request.pso.particles = m_agents;
        request.ga.population = m_agents;
        request.stop.first_hit = first_hit;
        request.stop.max_evaluations = to_count(max_evaluations, "max_evaluations", 0,
                                                std::numeric_limits<std::uint64_t>::max());
        request.restarts = static_cast<std::uint32_t>(to_count(restarts, "restarts", 0, 1'000'000));
        sampling.samples_per_side = static_cast<std::uint32_t>(
            to_count(samples_per_side, "samples_per_side", 1, 10'000'000));
        RandomResult result;
        result.method = request.method;
        result.delta = sampling.delta;
        {
          py::gil_scoped_release release;
          const ModelReadLock lock(a, b);
          result.search = random_collide(a, pa, b, pb, request, sampling);
        }
        return result;
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::kw_only(),
      py::arg("method") = "maco", py::arg("seed") = 0, py::arg("delta") = py::none(),
      py::arg("samples_per_side") = 1000, py::arg("iterations") = 100, py::arg("agents") = 60,
      py::arg("first_hit") = false, py::arg("max_evaluations") = 0, py::arg("restarts") = 0,
      "Random collision detection (the paper's sections 3-4): preliminary Sphere-OBB detection, "
      "triangles of the overlapping leaves sampled into a feature grid (samples_per_side per "
      "model), then a search for feature pairs whose triangles the exact test confirms within "
      "delta (the witness verdict).\n\n"
      "method: 'maco' (the paper's improved ant colony), 'aco', 'pso', 'ga' or 'exhaustive' "
      "(every pair: the reference).\n"
      "seed: same inputs and seed give the same result, on any thread.\n"
      "delta: collide()'s threshold, >= 0 (None: 0).\n"
      "iterations: N per run; agents: ants / particles / population (>= 2); first_hit: stop at "
      "the first colliding pair; max_evaluations: budget (0 = none); restarts: fresh runs after "
      "the first one ends without meeting another criterion.\n"
      "The GIL is released while the search runs.");
}

}  // namespace antcd::python
