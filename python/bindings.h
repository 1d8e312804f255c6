#pragma once
// The parts of the module svbrdf (module.cpp), one file each.
#include <pybind11/pybind11.h>

namespace svbrdf::python {

void bind_bsdf(pybind11::module_& m);
void bind_material(pybind11::module_& m);
void bind_mip(pybind11::module_& m);
void bind_render(pybind11::module_& m);

}  // namespace svbrdf::python
