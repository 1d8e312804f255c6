// The Python module svbrdf: the BRDF models, a material's pyramids and the renderer for numpy users
// (README.md, "Python"). Every svbrdf::Error becomes a Python exception carrying the programs' one
// line: svbrdf.InputError (also a ValueError) for bad input, svbrdf.Error for the rest, as the
// programs' exit 2 and exit 1.
#include <pybind11/pybind11.h>

#include <Python.h>

#include "base/error.h"
#include "base/message_line.h"
#include "python/arrays.h"
#include "python/bindings.h"

namespace svbrdf::python {

namespace {

// Made once and never released: the module is never unloaded, and a reference dropped after the
// interpreter has finalized would touch freed memory.
PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;

}  // namespace

}  // namespace svbrdf::python

PYBIND11_MODULE(svbrdf, m) {
  namespace py = pybind11;
  using namespace svbrdf::python;
  m.doc() = "svbrdf: BRDF models, BRDF-averaging MIP maps and a path tracer for spatially varying materials.";
  // Made once, kept for the interpreter's life (the module is never unloaded).
  g_error = PyErr_NewExceptionWithDoc("svbrdf.Error", "A failure of the machine or of svbrdf (the programs' exit 1).",
                                      PyExc_RuntimeError, nullptr);
  if (!g_error) throw py::error_already_set();
  const py::tuple bases = py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError));
  g_input_error = PyErr_NewExceptionWithDoc(
      "svbrdf.InputError", "Bad input: an argument, a file, a value out of range (the programs' exit 2).",
      bases.ptr(), nullptr);
  if (!g_input_error) throw py::error_already_set();
  m.attr("Error") = py::handle(g_error);
  m.attr("InputError") = py::handle(g_input_error);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const svbrdf::Error& e) {
      PyErr_SetString(e.kind() == svbrdf::Error::Kind::bad_input ? g_input_error : g_error,
                      svbrdf::message_line(e.what()).c_str());
    }
  });
  bind_bsdf(m);
  bind_material(m);
  bind_mip(m);
  bind_render(m);
}
