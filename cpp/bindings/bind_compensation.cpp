// Bindings of the `compensation` area (netshape._core.compensation). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_compensation(py::module_& m) {
  (void)m;
}
