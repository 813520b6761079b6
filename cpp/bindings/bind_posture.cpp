// Bindings of the `posture` area (netshape._core.posture). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_posture(py::module_& m) {
  (void)m;
}
