// Bindings of the `deflection` area (netshape._core.deflection). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_deflection(py::module_& m) {
  (void)m;
}
