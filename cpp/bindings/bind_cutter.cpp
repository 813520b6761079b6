// Bindings of the `cutter` area (netshape._core.cutter). Thin.
#include <cstdio>
#include <string>

#include "default_types.hpp"
#include "netshape/cutter/cutter.hpp"

namespace py = pybind11;
using netshape::cutter::Cutter;
using netshape::cutter::CutterKind;

void bind_cutter(py::module_& m) {
  m.doc() = "End mills: flat, ball and bull-nose (C++ netshape::cutter).";
  py::enum_<CutterKind>(m, "CutterKind").value("flat", CutterKind::flat).value("ball", CutterKind::ball)
      .value("bull", CutterKind::bull);
  py::class_<Cutter>(m, "Cutter", "An end mill; lengths [mm], helix [rad], Young's modulus [MPa].")
      .def(py::init<>())
      .def_readwrite("kind", &Cutter::kind)
      .def_readwrite("radius", &Cutter::radius, "nominal radius R = D/2 [mm]")
      .def_readwrite("corner_radius", &Cutter::corner_radius, "[mm]: flat 0, ball = radius, bull 0 < r < radius")
      .def_readwrite("flutes", &Cutter::flutes)
      .def_readwrite("helix", &Cutter::helix, "helix angle [rad]")
      .def_readwrite("flute_length", &Cutter::flute_length, "[mm]")
      .def_readwrite("stick_out", &Cutter::stick_out, "holder face to tip [mm]")
      .def_readwrite("youngs_modulus", &Cutter::youngs_modulus, "[MPa]")
      .def_readwrite("holder_compliance", &Cutter::holder_compliance,
                     "clamp/holder compliance [mm/N]: the tool translates by holder_compliance * F")
      .def_readwrite("runout_rho", &Cutter::runout_rho, "radial runout, tool-axis offset [mm]")
      .def_readwrite("runout_lambda", &Cutter::runout_lambda,
                     "runout angle [rad]: flute j cuts at R + rho cos(lambda - j 2 pi / N)")
      .def("validate", &Cutter::validate)
      .def("diameter", &Cutter::diameter, "[mm]")
      .def("radius_at", &Cutter::radius_at, py::arg("z"), "envelope radius at height z above the tip [mm]")
      .def("helix_lag", &Cutter::helix_lag, "tan(helix) / R [rad/mm]")
      .def_static("flat_end", &Cutter::flat_end, py::arg("diameter"), py::arg("flutes"), py::arg("helix"))
      .def_static("ball_end", &Cutter::ball_end, py::arg("diameter"), py::arg("flutes"), py::arg("helix"))
      .def_static("bull_nose", &Cutter::bull_nose, py::arg("diameter"), py::arg("corner_radius"), py::arg("flutes"),
                  py::arg("helix"))
      .def("__repr__", [](const Cutter& c) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "Cutter(%s, diameter=%.6g mm, corner_radius=%.6g mm, flutes=%d, helix=%.6g deg, "
                      "flute_length=%.6g mm, stick_out=%.6g mm, youngs_modulus=%.6g MPa)",
                      netshape::cutter::to_string(c.kind), c.diameter(), c.corner_radius, c.flutes,
                      c.helix * 180.0 / netshape::pi, c.flute_length, c.stick_out, c.youngs_modulus);
        return std::string(buf);
      });
  m.def("cutter_kind_from_string", &netshape::cutter::cutter_kind_from_string, py::arg("name"));
  m.def("check_flutes", [](int flutes, const std::string& field) { netshape::cutter::check_flutes(flutes, field.c_str()); },
        py::arg("flutes"), py::arg("field") = "flutes",
        "ValueError 'field = N: must be between 1 and 64' unless 1 <= flutes <= 64 (the one flute-count check)");
}
