// Bindings of the `compensation` area (netshape._core.compensation). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"
#include "netshape/compensation/volumetric_compensation.hpp"

namespace py = pybind11;

namespace {

// --- volumetric compensation (machine geometric errors, seeds/003) --------------------------------
void bind_volumetric_compensation(py::module_& m) {
  using namespace netshape::compensation;
  using netshape::py_types::RefPoints3;
  py::class_<VolumetricOptions>(m, "VolumetricOptions")
      .def(py::init<>())
      .def(py::init([](double tolerance, int max_iterations, bool check_travel) {
             VolumetricOptions o;
             o.tolerance = tolerance;
             o.max_iterations = max_iterations;
             o.check_travel = check_travel;
             o.validate();
             return o;
           }),
           py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 50, py::arg("check_travel") = true)
      .def_readwrite("tolerance", &VolumetricOptions::tolerance)
      .def_readwrite("max_iterations", &VolumetricOptions::max_iterations)
      .def_readwrite("check_travel", &VolumetricOptions::check_travel)
      .def("validate", &VolumetricOptions::validate);
  py::enum_<VolumetricStatus>(m, "VolumetricStatus")
      .value("ok", VolumetricStatus::ok)
      .value("not_converged", VolumetricStatus::not_converged)
      .value("outside_travel", VolumetricStatus::outside_travel)
      .value("outside_table", VolumetricStatus::outside_table);
  py::class_<VolumetricResult>(m, "VolumetricResult")
      .def_readonly("commanded", &VolumetricResult::commanded)
      .def_readonly("residual", &VolumetricResult::residual)
      .def_readonly("iterations", &VolumetricResult::iterations)
      .def_property_readonly("status",
                             [](const VolumetricResult& r) {
                               Eigen::VectorXi s(static_cast<Eigen::Index>(r.status.size()));
                               for (std::size_t i = 0; i < r.status.size(); ++i) s[i] = static_cast<int>(r.status[i]);
                               return s;
                             })
      .def_readonly("axis", &VolumetricResult::axis)
      .def("all_ok", &VolumetricResult::all_ok)
      .def("first_failure", &VolumetricResult::first_failure);
  m.def(
      "compensate_points",
      [](const netshape::machine::Machine& mm, const RefPoints3& p, const VolumetricOptions& o) {
        py::gil_scoped_release release;
        return compensate_points(mm, p, o);
      },
      py::arg("machine"), py::arg("nominal"), py::arg_v("options", VolumetricOptions{}, "VolumetricOptions()"),
      "Commanded points [mm] so the actual tip lands on the nominal (n, 3) points; raises on failure");
  m.def(
      "compensate_points_status",
      [](const netshape::machine::Machine& mm, const RefPoints3& p, const VolumetricOptions& o) {
        py::gil_scoped_release release;
        return compensate_points_status(mm, p, o);
      },
      py::arg("machine"), py::arg("nominal"), py::arg_v("options", VolumetricOptions{}, "VolumetricOptions()"),
      "Like compensate_points, with per-point status instead of raising");
}

}  // namespace

void bind_compensation(py::module_& m) {
  bind_volumetric_compensation(m);
  // (deflection compensation binds here too, in its own function)
}
