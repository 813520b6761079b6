// Bindings of the `toolpath` area (netshape._core.toolpath). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_toolpath(py::module_& m) {
  (void)m;
}
