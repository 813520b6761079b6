// Bindings of the `stock` area (netshape._core.stock). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_stock(py::module_& m) {
  (void)m;
}
