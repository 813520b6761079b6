// Bindings of the `cutter` area (netshape._core.cutter). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_cutter(py::module_& m) {
  (void)m;
}
