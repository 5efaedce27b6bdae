// python/src/bind_collide.cpp — antcd.collide and its CollisionResult.
#include <antcd/collide.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

CollisionRequest make_request(double delta, bool all_contacts, const py::handle max_contacts,
                              bool contact_normals, const py::handle manifold_points) {
  CollisionRequest request;
  request.contact_normals = contact_normals;
  request.manifold_points = static_cast<std::uint32_t>(
      to_count(manifold_points, "manifold_points", 0, std::uint64_t{1} << 20));
  request.delta = to_non_negative(delta, "delta");
  request.all_contacts = all_contacts;
  request.max_contacts = static_cast<std::size_t>(
      to_count(max_contacts, "max_contacts", 0, std::numeric_limits<std::uint32_t>::max()));
  return request;
}

}  // namespace

void bind_collide(py::module_& m) {
  py::class_<CollisionResult>(
      m, "CollisionResult",
      "The answer of collide(). bool(result) is result.colliding.\n\n"
      "Contacts are colliding triangle pairs: with all_contacts=False the one found first, else "
      "every pair (each once, up to max_contacts). Arrays are built when read.")
      .def_readonly("colliding", &CollisionResult::colliding)
      .def("__bool__", [](const CollisionResult& r) { return r.colliding; })
      .def(
          "__len__", [](const CollisionResult& r) { return r.contacts.size(); },
          "Number of contacts.")
      .def_property_readonly(
          "triangles_a",
          [](const CollisionResult& r) {
            return make_vector<std::uint32_t>(
                r.contacts.size(), [&](std::size_t i) { return r.contacts[i].triangle_a; });
          },
          "uint32[k]: each contact's triangle index in A's faces.")
      .def_property_readonly(
          "triangles_b",
          [](const CollisionResult& r) {
            return make_vector<std::uint32_t>(
                r.contacts.size(), [&](std::size_t i) { return r.contacts[i].triangle_b; });
          },
          "uint32[k]: each contact's triangle index in B's faces.")
      .def_property_readonly(
          "points",
          [](const CollisionResult& r) {
            return make_rows<double>(r.contacts.size(), 3, [&](std::size_t i, double* o) {
              for (int k = 0; k < 3; ++k) o[k] = r.contacts[i].point[k];
            });
          },
          "float64[k, 3], world frame: a common point of the two triangles, or (delta > 0, apart) "
          "the midpoint of their closest points.")
      .def_property_readonly(
          "distances",
          [](const CollisionResult& r) {
            return make_vector<double>(r.contacts.size(),
                                       [&](std::size_t i) { return r.contacts[i].distance; });
          },
          "float64[k]: triangle-triangle distance of each contact (0 when they intersect).")
      .def_property_readonly(
          "normals",
          [](const CollisionResult& r) {
            return make_rows<double>(r.contacts.size(), 3, [&](std::size_t i, double* o) {
              for (int k = 0; k < 3; ++k) o[k] = r.contacts[i].normal[k];
            });
          },
          "float64[k, 3], world frame, with contact_normals=True (zeros otherwise): each contact's "
          "unit normal, pointing from B towards A.")
      .def_property_readonly(
          "depths",
          [](const CollisionResult& r) {
            return make_vector<double>(r.contacts.size(),
                                       [&](std::size_t i) { return r.contacts[i].depth; });
          },
          "float64[k], with contact_normals=True (zeros otherwise): each triangle pair's "
          "penetration depth (the shortest separating translation; -distance when apart).")
      .def_property_readonly(
          "regions",
          [](const CollisionResult& r) {
            return make_vector<std::uint32_t>(r.contacts.size(),
                                              [&](std::size_t i) { return r.contacts[i].region; });
          },
          "uint32[k], with manifold_points > 0: each kept contact's touching region.")
      .def_property_readonly(
          "stats",
          [](const CollisionResult& r) {
            py::dict d;
            d["node_pairs"] = r.traversal.node_pairs;
            d["sphere_rejects"] = r.traversal.sphere_rejects;
            d["obb_rejects"] = r.traversal.obb_rejects;
            d["leaf_pairs"] = r.traversal.leaf_pairs;
            d["triangle_rejects"] = r.traversal.triangle_rejects;
            d["triangle_tests"] = r.triangle_tests;
            return d;
          },
          "Traversal counters: node_pairs, sphere_rejects, obb_rejects, leaf_pairs, "
          "triangle_rejects, triangle_tests.")
      .def("__repr__", [](const CollisionResult& r) {
        return std::string("<antcd.CollisionResult colliding=") + (r.colliding ? "True" : "False") +
               " contacts=" + std::to_string(r.contacts.size()) + ">";
      });

  m.def(
      "collide",
      [](const Model& a, const py::handle pose_a, const Model& b, const py::handle pose_b,
         double delta, bool all_contacts, const py::handle max_contacts, bool contact_normals,
         const py::handle manifold_points) {
        const Transform pa = to_transform(pose_a, "pose_a");
        const Transform pb = to_transform(pose_b, "pose_b");
        const CollisionRequest request =
            make_request(delta, all_contacts, max_contacts, contact_normals, manifold_points);
        CollisionResult result;
        {
          py::gil_scoped_release release;
          const ModelReadLock lock(a, b);
          collide(a, pa, b, pb, request, result);
        }
        return result;
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::kw_only(),
      py::arg("delta") = 0.0, py::arg("all_contacts") = false, py::arg("max_contacts") = 0,
      py::arg("contact_normals") = false, py::arg("manifold_points") = 0,
      "Exact collision query between two posed models.\n\n"
      "pose_a, pose_b: 4x4 homogeneous matrices, (rotation 3x3, translation 3) pairs, or None "
      "(identity); rigid motions only (ValueError otherwise).\n"
      "delta: collision threshold in mesh units (>= 0): the models collide when some triangle of "
      "A is within delta of some triangle of B (0: the surfaces share a point; touching counts).\n"
      "all_contacts: False stops at the first contact (boolean query); True reports every "
      "colliding triangle pair, up to max_contacts when that is > 0.\n"
      "contact_normals: also give each contact its normal (unit, from B towards A) and depth "
      "(result.normals, result.depths).\n"
      "manifold_points: > 0 keeps at most this many contacts per touching region (implies "
      "contact_normals; result.regions numbers the regions).\n"
      "Surfaces, not volumes: a model entirely inside another does not collide.\n"
      "The GIL is released while the query runs.");

  // For python/bench/overhead.py: the same query timed in a C++ loop (result storage reused, as a
  // C++ caller would), so the Python call's extra cost can be measured in one process and run.
  m.def(
      "_time_collide_cpp",
      [](const Model& a, const py::handle pose_a, const Model& b, const py::handle pose_b,
         const py::handle repeats_in) {
        const Transform pa = to_transform(pose_a, "pose_a");
        const Transform pb = to_transform(pose_b, "pose_b");
        const auto repeats = to_count(repeats_in, "repeats", 1, 1'000'000'000);
        py::gil_scoped_release release;
        const ModelReadLock lock(a, b);
        CollisionResult result;
        const CollisionRequest request;
        std::uint64_t hits = 0;
        const auto start = std::chrono::steady_clock::now();
        for (std::uint64_t i = 0; i < repeats; ++i)
          hits += collide(a, pa, b, pb, request, result) ? 1 : 0;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (hits != 0 && hits != repeats)
          throw std::logic_error("collide verdict changed between calls");
        return seconds / static_cast<double>(repeats);
      },
      py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), py::arg("repeats"),
      "Benchmark helper: mean seconds per boolean collide() over `repeats` calls in C++.");
}

}  // namespace antcd::python
