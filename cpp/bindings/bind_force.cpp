// Bindings of the `force` area (netshape._core.force). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_force(py::module_& m) {
  (void)m;
}
