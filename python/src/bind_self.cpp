// python/src/bind_self.cpp — antcd.self_intersections and antcd.self_proximity (antcd/self.hpp):
// where one (deforming) Model meets or nears itself.
#include <antcd/self.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

/// A SelfProximityResult with the first edge-edge pair's index (the vertex-triangle pairs come
/// first).
struct PyProximity {
  SelfProximityResult r;
  std::size_t split = 0;
  [[nodiscard]] std::size_t vertex_triangle_count() const { return split; }
  [[nodiscard]] std::size_t edge_edge_count() const { return r.pairs.size() - split; }
};

py::array_t<std::uint32_t> index_pairs(const std::vector<std::array<std::uint32_t, 2>>& pairs) {
  return make_rows<std::uint32_t>(pairs.size(), 2, [&](std::size_t i, std::uint32_t* o) {
    o[0] = pairs[i][0];
    o[1] = pairs[i][1];
  });
}

/// Rows [first, first + count) of the proximity pairs, `get` giving each row's values.
template <typename T, typename Get>
py::array_t<T> proximity_rows(const PyProximity& p, std::size_t first, std::size_t count,
                              std::size_t cols, Get&& get) {
  return make_rows<T>(count, cols, [&](std::size_t i, T* o) { get(p.r.pairs[first + i], o); });
}

void point_row(const Vec3& v, double* o) {
  for (int k = 0; k < 3; ++k) o[k] = v[k];
}

}  // namespace

void bind_self(py::module_& m) {
  py::class_<SelfIntersectionResult>(
      m, "SelfIntersectionResult",
      "The answer of self_intersections(). bool(result) is result.intersecting; len(result) the "
      "number of pairs. Arrays are built when read.")
      .def_readonly("intersecting", &SelfIntersectionResult::intersecting)
      .def("__bool__", [](const SelfIntersectionResult& r) { return r.intersecting; })
      .def("__len__", [](const SelfIntersectionResult& r) { return r.pairs.size(); })
      .def_property_readonly(
          "pairs", [](const SelfIntersectionResult& r) { return index_pairs(r.pairs); },
          "uint32[k, 2]: the intersecting triangle pairs (i, j), indices into the model's faces, "
          "i < j, sorted; one pair with first_only=True.")
      .def_property_readonly(
          "degenerate_triangles",
          [](const SelfIntersectionResult& r) {
            return make_vector<std::uint32_t>(r.degenerate_triangles.size(), [&](std::size_t i) {
              return r.degenerate_triangles[i];
            });
          },
          "uint32[d]: the triangles of exactly zero area (collinear corners), ascending; they "
          "take part in no pair.")
      .def_property_readonly(
          "stats",
          [](const SelfIntersectionResult& r) {
            const SelfIntersectionStats& s = r.stats;
            py::dict d;
            d["node_pairs"] = s.node_pairs;
            d["volume_rejects"] = s.volume_rejects;
            d["triangle_pairs"] = s.triangle_pairs;
            d["adjacent_pairs"] = s.adjacent_pairs;
            d["cone_culled"] = s.cone_culled;
            d["cone_tests"] = s.cone_tests;
            d["cone_cache_bytes"] = s.cone_cache_bytes;
            return d;
          },
          "Counters (the same at any thread count): node_pairs, volume_rejects, triangle_pairs, "
          "adjacent_pairs, cone_culled, cone_tests, cone_cache_bytes.")
      .def("__repr__", [](const SelfIntersectionResult& r) {
        return std::string("<antcd.SelfIntersectionResult intersecting=") +
               (r.intersecting ? "True" : "False") + " pairs=" + std::to_string(r.pairs.size()) +
               ">";
      });

  m.def(
      "self_intersections",
      [](const Model& model, bool first_only, bool normal_cones) {
        SelfIntersectionRequest request;
        request.first_only = first_only;
        request.normal_cones = normal_cones;
        py::gil_scoped_release release;
        const ModelReadLock lock(model);
        return self_intersections(model, request);
      },
      py::arg("model"), py::kw_only(), py::arg("first_only") = false,
      py::arg("normal_cones") = true,
      "The triangle pairs of the model that intersect beyond what their shared vertices or edge "
      "require, decided with exact predicates (no tolerance).\n\n"
      "Sharing is by vertex index: triangles sharing a vertex count where they meet elsewhere "
      "(they overlap, or one folds through the other), triangles sharing an edge where they are "
      "folded flat onto each other, duplicated faces always; triangles of different vertices "
      "that touch at one point count too. Zero-area triangles take part in no pair (listed in "
      "result.degenerate_triangles). Meshes that are not manifold, hold duplicated faces or are "
      "triangle soups are answered.\n"
      "first_only: stop at the first pair found (the same pair at every call, not necessarily "
      "the smallest). normal_cones: skip subtrees that provably cannot meet themselves (never "
      "changes the pairs, only the cost).\n"
      "The GIL is released while it runs; parallel where the library has oneTBB, the same "
      "answer at any thread count.");

  py::class_<PyProximity>(
      m, "SelfProximityResult",
      "The answer of self_proximity(): vertex-triangle pairs (the vertex not a corner of the "
      "triangle) and edge-edge pairs (no common vertex) within delta, with closest points and "
      "distances (model frame). len(result) is the number of pairs of both kinds.")
      .def("__len__", [](const PyProximity& p) { return p.r.pairs.size(); })
      .def_property_readonly(
          "edges", [](const PyProximity& p) { return index_pairs(p.r.edges); },
          "uint32[e, 2]: the mesh's edges (vertex indices, lower first), each once, sorted; "
          "edge_edge_pairs index them.")
      .def_property_readonly(
          "vertex_triangle_pairs",
          [](const PyProximity& p) {
            return proximity_rows<std::uint32_t>(p, 0, p.vertex_triangle_count(), 2,
                                                 [](const SelfProximityPair& q, std::uint32_t* o) {
                                                   o[0] = q.a;
                                                   o[1] = q.b;
                                                 });
          },
          "uint32[k, 2]: (vertex, triangle) index pairs, sorted.")
      .def_property_readonly(
          "vertex_triangle_distances",
          [](const PyProximity& p) {
            return make_vector<double>(p.vertex_triangle_count(),
                                       [&](std::size_t i) { return p.r.pairs[i].distance; });
          },
          "float64[k]: each vertex's distance to its triangle.")
      .def_property_readonly(
          "vertex_triangle_points",
          [](const PyProximity& p) {
            return proximity_rows<double>(
                p, 0, p.vertex_triangle_count(), 3,
                [](const SelfProximityPair& q, double* o) { point_row(q.point_b, o); });
          },
          "float64[k, 3]: the point of each triangle closest to its vertex.")
      .def_property_readonly(
          "edge_edge_pairs",
          [](const PyProximity& p) {
            return proximity_rows<std::uint32_t>(p, p.split, p.edge_edge_count(), 2,
                                                 [](const SelfProximityPair& q, std::uint32_t* o) {
                                                   o[0] = q.a;
                                                   o[1] = q.b;
                                                 });
          },
          "uint32[l, 2]: (a, b) pairs of indices into `edges`, a < b, sorted.")
      .def_property_readonly(
          "edge_edge_distances",
          [](const PyProximity& p) {
            return make_vector<double>(p.edge_edge_count(), [&](std::size_t i) {
              return p.r.pairs[p.split + i].distance;
            });
          },
          "float64[l]: each edge pair's distance.")
      .def_property_readonly(
          "edge_edge_points_a",
          [](const PyProximity& p) {
            return proximity_rows<double>(
                p, p.split, p.edge_edge_count(), 3,
                [](const SelfProximityPair& q, double* o) { point_row(q.point_a, o); });
          },
          "float64[l, 3]: the closest point on edge a.")
      .def_property_readonly(
          "edge_edge_points_b",
          [](const PyProximity& p) {
            return proximity_rows<double>(
                p, p.split, p.edge_edge_count(), 3,
                [](const SelfProximityPair& q, double* o) { point_row(q.point_b, o); });
          },
          "float64[l, 3]: the closest point on edge b.")
      .def("__repr__", [](const PyProximity& p) {
        return "<antcd.SelfProximityResult vertex_triangle=" +
               std::to_string(p.vertex_triangle_count()) +
               " edge_edge=" + std::to_string(p.edge_edge_count()) + ">";
      });

  m.def(
      "self_proximity",
      [](const Model& model, double delta) {
        const double d = to_non_negative(delta, "delta");
        PyProximity out;
        {
          py::gil_scoped_release release;
          const ModelReadLock lock(model);
          out.r = self_proximity(model, d);
        }
        out.split = static_cast<std::size_t>(
            std::find_if(out.r.pairs.begin(), out.r.pairs.end(),
                         [](const SelfProximityPair& q) {
                           return q.kind == SelfProximityPair::Kind::edge_edge;
                         }) -
            out.r.pairs.begin());
        return out;
      },
      py::arg("model"), py::arg("delta"),
      "The vertex-triangle pairs (the vertex not a corner of the triangle, by index) and "
      "edge-edge pairs (no common vertex index) of the model within distance delta (a finite "
      "number >= 0, e.g. a cloth's thickness), with closest points and distances computed in "
      "doubles (not an exact verdict at distance == delta). Each pair of primitives once. The "
      "GIL is released while it runs.");
}

}  // namespace antcd::python
