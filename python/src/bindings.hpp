// python/src/bindings.hpp — the module's parts, each registered by one function (module.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace antcd::python {

void bind_model(pybind11::module_& m);
void bind_collide(pybind11::module_& m);
void bind_random(pybind11::module_& m);
void bind_scene(pybind11::module_& m);
void bind_distance(pybind11::module_& m);
void bind_penetration(pybind11::module_& m);
void bind_manager(pybind11::module_& m);
void bind_batch(pybind11::module_& m);
void bind_ccd(pybind11::module_& m);
void bind_self(pybind11::module_& m);
void bind_deform(pybind11::module_& m);

}  // namespace antcd::python
