// The extension module netshape._core. Each area binds itself in bind_<area>.cpp; they are called
// here in the order data flows (README, "Areas"), so an area may use the types of the areas before it.
#include <pybind11/pybind11.h>

#include "netshape/core/error.hpp"
#include "netshape/core/isa.hpp"

namespace py = pybind11;

void bind_toolpath(py::module_& m);
void bind_cutter(py::module_& m);
void bind_stock(py::module_& m);
void bind_force(py::module_& m);
void bind_deflection(py::module_& m);
void bind_geometry(py::module_& m);
void bind_machine(py::module_& m);
void bind_compensation(py::module_& m);
void bind_motion(py::module_& m);
void bind_posture(py::module_& m);

PYBIND11_MODULE(_core, m) {
  m.doc() = "netshape C++ core (use the `netshape` package, not this module directly)";
  // The exception classes are defined in Python (netshape/errors.py) so they carry fields
  // (source, line, column) and pickle; C++ errors are translated into them here.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const netshape::ParseError& e) {
      py::object cls = py::module_::import("netshape.errors").attr("ParseError");
      py::object exc = cls(e.what(), e.source(), e.line(), e.column(), e.reason());
      PyErr_SetObject(cls.ptr(), exc.ptr());
    } catch (const netshape::Error& e) {
      py::object cls = py::module_::import("netshape.errors").attr("Error");
      PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
    }
  });

  m.def("kernel_isa", &netshape::kernel_isa,
        "Instruction set of the SIMD kernels in this process: 'baseline', 'avx2' or 'avx512' (the best the "
        "CPU runs unless NETSHAPE_ISA names a lower one).");

  auto sub = [&m](const char* name) { return m.def_submodule(name); };
  auto toolpath = sub("toolpath");
  bind_toolpath(toolpath);
  auto cutter = sub("cutter");
  bind_cutter(cutter);
  auto stock = sub("stock");
  bind_stock(stock);
  auto force = sub("force");
  bind_force(force);
  auto deflection = sub("deflection");
  bind_deflection(deflection);
  auto geometry = sub("geometry");
  bind_geometry(geometry);
  auto machine = sub("machine");
  bind_machine(machine);
  auto compensation = sub("compensation");
  bind_compensation(compensation);
  auto motion = sub("motion");
  bind_motion(motion);
  auto posture = sub("posture");
  bind_posture(posture);
}
