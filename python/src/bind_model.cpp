// python/src/bind_model.cpp — antcd.load_mesh and antcd.Model (built, or read from a model file or
// bytes: Model::save / load / to_bytes / from_bytes, which pickling uses too).
#include <antcd/bvh.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"
#include "paths.hpp"

namespace antcd::python {

namespace {

BuildOptions build_options(py::handle leaf_size, const std::string& covariance) {
  BuildOptions o;
  o.leaf_size = static_cast<std::uint32_t>(to_count(leaf_size, "leaf_size", 1, 1u << 20));
  o.covariance = parse_covariance(covariance);
  return o;
}

std::shared_ptr<Model> build(Mesh mesh, const BuildOptions& options, std::string name) {
  py::gil_scoped_release release;  // O(n log n): let other Python threads run
  return std::make_shared<Model>(std::move(mesh), options, std::move(name));
}

/// The Model of a model file (bvh.hpp, Model::load), the GIL released while it is read.
std::shared_ptr<Model> load_saved(const std::filesystem::path& path) {
  require_readable_file(path, "model file");
  py::gil_scoped_release release;
  return std::make_shared<Model>(Model::load(path));
}

/// A bytes-like object's bytes as a Model (Model::from_bytes); TypeError for anything else.
std::shared_ptr<Model> from_bytes(const py::handle data) {
  if (!PyObject_CheckBuffer(data.ptr())) {
    throw py::type_error("data must be bytes-like (bytes, bytearray, memoryview), got " +
                         std::string(py::str(py::type::of(data).attr("__name__"))));
  }
  const py::buffer_info info = py::reinterpret_borrow<py::buffer>(data).request();
  if (info.ndim != 1 || info.itemsize != 1 || info.strides[0] != 1) {
    throw py::type_error("data must be a contiguous buffer of bytes");
  }
  const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(info.ptr),
                                            static_cast<std::size_t>(info.size));
  py::gil_scoped_release release;
  return std::make_shared<Model>(Model::from_bytes(bytes));
}

py::bytes to_bytes(const Model& model) {
  std::vector<std::uint8_t> bytes;
  {
    py::gil_scoped_release release;
    const ModelReadLock lock(model);
    bytes = model.to_bytes();
  }
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

/// Model.set_vertices: the checks, then Model::refit under the Model's exclusive lock, the GIL
/// released. On any error the Model keeps its positions (refit checks everything first).
void set_vertices(Model& model, const py::handle vertices) {
  const std::vector<Vec3> positions =
      to_positions(vertices, "vertices", model.mesh().vertices.size());
  bool pinned = false;
  {
    py::gil_scoped_release release;
    const ModelWriteLock lock(model);
    pinned = model_pinned(model);
    if (!pinned) model.refit(positions);
  }
  if (pinned) {
    throw py::value_error(
        "set_vertices: model '" + model.source() +
        "' is held by a CollisionManager or a Scene, whose broad phase keeps the bounds of its "
        "current positions; deform the object with CollisionManager.set_vertices, or remove it "
        "from the manager first (or build a new Model)");
  }
}

Mesh load(const py::handle path_in) {
  const std::filesystem::path path = to_path(path_in);
  require_readable_file(path, "mesh file");
  py::gil_scoped_release release;
  return load_mesh(path);
}

}  // namespace

void bind_model(py::module_& m) {
  m.def(
      "load_mesh",
      [](const py::object& path) {
        const Mesh mesh = load(path);
        auto vertices = make_rows<double>(mesh.vertices.size(), 3, [&](std::size_t i, double* out) {
          for (int k = 0; k < 3; ++k) out[k] = mesh.vertices[i][k];
        });
        auto faces = make_rows<std::int64_t>(mesh.triangles.size(), 3,
                                             [&](std::size_t i, std::int64_t* out) {
                                               for (std::size_t k = 0; k < 3; ++k)
                                                 out[k] = mesh.triangles[i][k];
                                             });
        return py::make_tuple(vertices, faces);
      },
      py::arg("path"),
      "Loads every triangle of a mesh file (OBJ, STL, PLY, OFF, glTF/GLB and the other formats "
      "assimp reads), with the file's node transforms applied, polygons triangulated and identical "
      "vertices joined. OBJ coordinates are the nearest doubles to the file's text; the other "
      "formats are read by assimp in single precision.\n\n"
      "Returns (vertices float64[n, 3], faces int64[m, 3]).\n"
      "Raises FileNotFoundError / IsADirectoryError / PermissionError (OSError) when the file "
      "cannot be opened, ValueError when it is not a readable triangle mesh.");

  py::class_<Model, std::shared_ptr<Model>>(
      m, "Model",
      "A triangle mesh and its Sphere-OBB hierarchy, built once. Its triangles are fixed; its "
      "vertex positions change only through set_vertices (a deforming mesh).\n\n"
      "Queries only read a Model, so one Model may be used by any number of threads at once and "
      "by any number of objects in a CollisionManager. Its arrays are stored once (never copied "
      "per query); `vertices` and `faces` are read-only views of them.\n"
      "Threads and set_vertices: each query holds a shared lock on the Models it reads while it "
      "runs, set_vertices the exclusive one while it refits, so a query answers on the positions "
      "before or after a set_vertices, never a mix of them.")
      .def(py::init([](const py::object& vertices, const py::object& faces,
                       const py::object& leaf_size, const std::string& covariance,
                       std::string name) {
             const BuildOptions options = build_options(leaf_size, covariance);
             return build(to_mesh(vertices, faces), options, std::move(name));
           }),
           py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("leaf_size") = 4,
           py::arg("covariance") = "area", py::arg("name") = "mesh",
           "Builds the hierarchy over a mesh.\n\n"
           "vertices: (n, 3) real numbers, finite. faces: (m, 3) integers in [0, n), m >= 1.\n"
           "leaf_size: most triangles in a leaf (>= 1). covariance: how OBB axes are fitted, "
           "'area' (area-weighted centroid, the paper's Eq. 3) or 'vertex' (Eqs. 1-2).\n"
           "name: how errors and repr name the model.\n"
           "Zero-area triangles are kept in `faces` but left out of every query.\n"
           "Raises ValueError naming the problem (shape, dtype, non-finite value, index out of "
           "range, no triangle of non-zero area).")
      .def_static(
          "load",
          [](const py::object& path, const py::object& leaf_size, const std::string& covariance) {
            const BuildOptions options = build_options(leaf_size, covariance);
            if (is_model_path(to_path(path))) return load_saved(to_path(path));
            return build(load(path), options, to_path(path).string());
          },
          py::arg("path"), py::kw_only(), py::arg("leaf_size") = 4, py::arg("covariance") = "area",
          "Loads a mesh file (see load_mesh) and builds its Model, named after the path. A model "
          "file (.antcd, written by Model.save) is read as saved, without building anything "
          "(leaf_size and covariance are then the saved model's).")
      .def(
          "save",
          [](const Model& model, const py::object& path) {
            const std::filesystem::path p = to_path(path);
            py::gil_scoped_release release;
            const ModelReadLock lock(model);
            model.save(p);
          },
          py::arg("path"),
          "Writes the model (mesh, options and built hierarchy) to a model file, atomically; "
          "Model.load and every mesh argument read it back without building (name the file "
          "*.antcd). The format is versioned, little-endian and checksummed (docs/model_file.md). "
          "Raises ValueError when the file cannot be written.")
      .def("to_bytes", &to_bytes,
           "The model file's bytes (what save writes, and what pickling stores).")
      .def_static("from_bytes", &from_bytes, py::arg("data"),
                  "The Model of a model file's bytes (Model.to_bytes), bit for bit the saved one; "
                  "nothing is built. Raises ValueError for truncated, corrupted, other-version or "
                  "inconsistent data, TypeError when data is not bytes-like.")
      .def(py::pickle([](const Model& model) { return py::make_tuple(to_bytes(model)); },
                      [](const py::tuple& state) {
                        if (state.size() != 1) {
                          throw py::value_error("antcd.Model pickle state must be a 1-tuple");
                        }
                        return from_bytes(state[0]);
                      }))
      .def_property_readonly(
          "vertices",
          [](const py::object& self) {
            const Mesh& mesh = self.cast<const Model&>().mesh();
            return readonly_view<double>(mesh.vertices.front().data(), mesh.vertices.size(), 3,
                                         self);
          },
          "float64[n, 3], model frame (read-only view, no copy). set_vertices writes the new "
          "positions into this same storage, so a view shows them afterwards; the view itself is "
          "not locked: read it (or copy it, numpy.array(model.vertices)) when no set_vertices "
          "runs on the model in another thread.")
      .def("set_vertices", &set_vertices, py::arg("vertices"),
           "New positions for the vertices (same count and order; the faces are fixed): a "
           "deforming mesh. vertices: (n, 3) real numbers, finite, n = vertex_count; copied "
           "once.\n\n"
           "Refits the hierarchy in O(n): its topology is kept, every volume recomputed to hold "
           "its triangles at the new positions; every query then answers exactly as on a Model "
           "built from the moved mesh (only its cost may differ: see refit_growth). The GIL is "
           "released during the refit.\n"
           "Thread-safe: it waits for the queries in flight on this model and holds later ones "
           "until it is done (an exclusive lock per model; queries share it).\n"
           "Raises ValueError naming the problem, the model unchanged: a wrong shape, dtype or "
           "row count, a non-finite entry, a triangle of zero area at build time that has an "
           "area now (build a new Model), or a model held by a CollisionManager or a Scene "
           "(their broad phase keeps its bounds; use CollisionManager.set_vertices, or remove it "
           "from the manager first).")
      .def_property_readonly(
          "refit_growth",
          [](const Model& model) {
            py::gil_scoped_release release;
            const ModelReadLock lock(model);
            return model.refit_growth();
          },
          "How much looser set_vertices has made the hierarchy since it was built (1 for a built "
          "one): the internal boxes' summed extents now over then, relative to the leaves'. A "
          "Model built afresh, Model(model.vertices, model.faces), is tight again.")
      .def_property_readonly(
          "faces",
          [](const py::object& self) {
            const Mesh& mesh = self.cast<const Model&>().mesh();
            return readonly_view<std::uint32_t>(mesh.triangles.front().data(),
                                                mesh.triangles.size(), 3, self);
          },
          "uint32[m, 3] vertex indices (read-only view, no copy).")
      .def_property_readonly("name", &Model::source,
                             "The name given at construction (a path for Model.load).")
      .def_property_readonly("leaf_size",
                             [](const Model& model) { return model.options().leaf_size; })
      .def_property_readonly("covariance",
                             [](const Model& model) {
                               return std::string(covariance_name(model.options().covariance));
                             })
      .def_property_readonly("triangle_count",
                             [](const Model& model) { return model.mesh().triangles.size(); })
      .def_property_readonly("vertex_count",
                             [](const Model& model) { return model.mesh().vertices.size(); })
      .def_property_readonly(
          "degenerate_triangles",
          [](const Model& model) { return model.stats().degenerate_triangles; },
          "Zero-area triangles, left out of the hierarchy and of every query.")
      .def_property_readonly(
          "bounds",
          [](const Model& model) {
            Aabb box;
            {
              py::gil_scoped_release release;
              const ModelReadLock lock(model);
              box = model.mesh().bounds();
            }
            return make_rows<double>(2, 3, [&](std::size_t row, double* out) {
              for (int k = 0; k < 3; ++k) out[k] = row == 0 ? box.min[k] : box.max[k];
            });
          },
          "float64[2, 3]: the axis-aligned box [min, max] of the vertices, model frame.")
      .def_property_readonly(
          "stats",
          [](const Model& model) {
            BvhStats s;
            {
              py::gil_scoped_release release;
              const ModelReadLock lock(model);
              s = model.stats();
            }
            py::dict d;
            d["triangles"] = s.triangles;
            d["degenerate_triangles"] = s.degenerate_triangles;
            d["nodes"] = s.nodes;
            d["leaves"] = s.leaves;
            d["depth"] = s.depth;
            d["max_leaf_size"] = s.max_leaf_size;
            d["obb_volume_sum"] = s.obb_volume_sum;
            d["build_ms"] = s.build_ms;
            d["memory_bytes"] = s.memory_bytes;
            return d;
          },
          "Hierarchy statistics: triangles, nodes, leaves, depth, build time (ms), memory "
          "(bytes)...")
      .def("__repr__", [](const Model& model) {
        return "<antcd.Model '" + model.source() +
               "': " + std::to_string(model.mesh().vertices.size()) + " vertices, " +
               std::to_string(model.mesh().triangles.size()) + " triangles>";
      });
}

}  // namespace antcd::python
