#pragma once
// Row-major array typedefs and reference types shared by all bindings, so that NumPy's C-ordered
// arrays pass into C++ without copies (Eigen::Ref of a row-major map).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "netshape/core/types.hpp"

namespace netshape::py_types {
namespace py = pybind11;
using RefPoints3 = Eigen::Ref<const netshape::Points3>;
using RefPoints2 = Eigen::Ref<const netshape::Points2>;
using RefMatrix = Eigen::Ref<const netshape::MatrixXdR>;
using RefVector = Eigen::Ref<const Eigen::VectorXd>;
}  // namespace netshape::py_types
