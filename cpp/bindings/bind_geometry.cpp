// Bindings of the `geometry` area (netshape._core.geometry). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_geometry(py::module_& m) {
  (void)m;
}
