// python/src/module.cpp — the extension module antcd._antcd (re-exported by the antcd package).
#include <antcd/error.hpp>
#include <antcd/file.hpp>
#include <antcd/version.hpp>

#include <pybind11/pybind11.h>

#include "bindings.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_antcd, m) {
  m.doc() =
      "antcd: exact and random (ant colony) mesh-vs-mesh collision detection.\n\n"
      "Frames: a Model's vertices are in its own frame; a pose maps them to the world "
      "(p_world = R p + t), as a 4x4 homogeneous matrix or a (R, t) pair. Contact points are in "
      "world coordinates. Queries release the GIL; a Model may be shared by any number of threads: "
      "queries hold a shared lock on it, Model.set_vertices the exclusive one.";

  m.attr("__version__") = antcd::kVersion;

  // Library errors are bad inputs (a mesh, a scene file, an argument): ValueError, with the
  // library's one-line message naming the input. File-system problems are checked before the
  // library is called and raise OSError subclasses.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const antcd::Error& e) {
      PyErr_SetString(PyExc_ValueError, antcd::printable_line(e.what()).c_str());
    }
  });

  antcd::python::bind_model(m);
  antcd::python::bind_collide(m);
  antcd::python::bind_random(m);
  antcd::python::bind_scene(m);
  antcd::python::bind_distance(m);
  antcd::python::bind_penetration(m);
  antcd::python::bind_manager(m);
  antcd::python::bind_batch(m);
  antcd::python::bind_ccd(m);
  antcd::python::bind_self(m);
  antcd::python::bind_deform(m);
}
