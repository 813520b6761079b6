// Bindings of the `machine` area (netshape._core.machine). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_machine(py::module_& m) {
  (void)m;
}
