// Bindings of the `motion` area (netshape._core.motion). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"

namespace py = pybind11;

void bind_motion(py::module_& m) {
  (void)m;
}
