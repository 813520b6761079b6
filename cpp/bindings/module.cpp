// The extension module netshape._core. Each area binds itself in bind_<area>.cpp; they are called
// here in the order data flows (README, "Areas"), so an area may use the types of the areas before it.
#include <pybind11/pybind11.h>

#include "netshape/core/error.hpp"
#include "netshape/core/isa.hpp"
#include "netshape/core/progress.hpp"

#include <thread>

namespace py = pybind11;

namespace {

// Ctrl-C and progress for long C++ calls. The core calls `progress_hook` from its loops (throttled
// to 20 calls/s, netshape/core/progress.hpp). In the thread that imported the module (the one Python
// delivers signals to) the hook takes the GIL, runs pending signal handlers and the optional Python
// callback. An exception from either (KeyboardInterrupt from Ctrl-C) is kept in `g_pending` and the
// hook answers false; the core unwinds with core::Interrupted, and the translator below raises the
// kept exception. Other threads (Dask workers) are never interrupted this way.
std::thread::id g_main_thread;
PyObject* g_callback = nullptr;  // owned reference, or nullptr
PyObject* g_pending[3] = {nullptr, nullptr, nullptr};

bool progress_hook(const char* what, std::size_t done, std::size_t total) {
  if (std::this_thread::get_id() != g_main_thread || !Py_IsInitialized()) return true;
  py::gil_scoped_acquire gil;
  bool ok = PyErr_CheckSignals() == 0;
  if (ok && g_callback != nullptr) {
    PyObject* r = PyObject_CallFunction(g_callback, "snn", what, static_cast<Py_ssize_t>(done),
                                        static_cast<Py_ssize_t>(total));
    ok = r != nullptr;
    Py_XDECREF(r);
  }
  if (!ok) {
    for (PyObject*& o : g_pending) Py_CLEAR(o);
    PyErr_Fetch(&g_pending[0], &g_pending[1], &g_pending[2]);
  }
  return ok;
}

void raise_pending() {
  if (g_pending[0] == nullptr) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    return;
  }
  PyErr_Restore(g_pending[0], g_pending[1], g_pending[2]);  // steals the references
  g_pending[0] = g_pending[1] = g_pending[2] = nullptr;
}

}  // namespace

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
    } catch (const netshape::core::Interrupted&) {
      raise_pending();
    }
  });

  g_main_thread = std::this_thread::get_id();
  netshape::core::set_progress_hook(&progress_hook);
  m.def(
      "set_progress",
      [](py::object callback) {
        PyObject* old = g_callback;
        g_callback = callback.is_none() ? nullptr : callback.release().ptr();
        Py_XDECREF(old);
      },
      py::arg("callback").none(true),
      "Sets the callable `callback(what: str, done: int, total: int)` that long C++ computations call "
      "from the importing thread, at most 20 times a second (None removes it). An exception it raises "
      "stops the computation and propagates; Ctrl-C does the same without a callback.");

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
