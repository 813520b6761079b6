// Bindings of the `deflection` area (netshape._core.deflection). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"
#include "netshape/deflection.hpp"

namespace py = pybind11;

void bind_deflection(py::module_& m) {
  using namespace netshape::deflection;
  using netshape::py_types::RefVector;
  py::enum_<InertiaModel>(m, "InertiaModel", "Second moment of the fluted section: square D^4/48 or equivalent 0.8 D")
      .value("square", InertiaModel::square)
      .value("equivalent", InertiaModel::equivalent);
  py::enum_<LoadModel>(m, "LoadModel", "resultant at L - A/2 (eq. 7) or distributed element loads")
      .value("resultant", LoadModel::resultant)
      .value("distributed", LoadModel::distributed);
  py::enum_<WallSide>(m, "WallSide", "left wall (+Y_c, phi = 0, up milling) or right wall (-Y_c, phi = pi, down milling)")
      .value("left", WallSide::left)
      .value("right", WallSide::right);
  m.def("inertia_model_from_string", &inertia_model_from_string, py::arg("name"));
  m.def("load_model_from_string", &load_model_from_string, py::arg("name"));
  m.def("wall_side_from_string", &wall_side_from_string, py::arg("name"));
  m.def("wall_angle", &wall_angle, py::arg("side"), "wall angle phi_w [rad]: 0 (left) or pi (right)");
  m.def("second_moment", &second_moment, py::arg("diameter"), py::arg("model"), "I [mm^4] of a tool of diameter [mm]");

  py::class_<Cantilever>(m, "Cantilever", "Uniform cantilever clamped at x = 0; x from the clamp [mm]")
      .def(py::init<>())
      .def(py::init([](double length, double e, double inertia) {
             Cantilever c{length, e, inertia};
             c.validate();
             return c;
           }),
           py::arg("length"), py::arg("youngs_modulus"), py::arg("inertia"))
      .def_readwrite("length", &Cantilever::length, "L, holder face to tip [mm]")
      .def_readwrite("youngs_modulus", &Cantilever::youngs_modulus, "E [MPa]")
      .def_readwrite("inertia", &Cantilever::inertia, "I [mm^4]")
      .def("validate", &Cantilever::validate)
      .def("rigidity", &Cantilever::rigidity, "E I [N mm^2]")
      .def("influence", &Cantilever::influence, py::arg("x"), py::arg("a"),
           "deflection at x per unit load at a (both from the clamp) [mm/N]")
      .def("deflection", &Cantilever::deflection, py::arg("force"), py::arg("x"), py::arg("l"),
           "eq. 6: deflection at x of a load force [N] at l [mm]")
      .def_static("tool", &Cantilever::tool, py::arg("diameter"), py::arg("stick_out"), py::arg("youngs_modulus"),
                  py::arg("model"));

  py::class_<DeflectionModel>(m, "DeflectionModel", "Force model of the cut + the cantilever that carries it")
      .def(py::init<>())
      .def_readwrite("force", &DeflectionModel::force)
      .def_readwrite("beam", &DeflectionModel::beam)
      .def_readwrite("load", &DeflectionModel::load)
      .def_readwrite("smooth_edges", &DeflectionModel::smooth_edges)
      .def_readwrite("holder_compliance", &DeflectionModel::holder_compliance,
                     "clamp/holder compliance [mm/N]: the tool also translates by holder_compliance * F")
      .def_readwrite("chip", &DeflectionModel::chip, "runout and chip-size effect of the element chips")
      .def("validate", &DeflectionModel::validate);
  py::class_<DeflectionWorkspace>(m, "DeflectionWorkspace")
      .def(py::init<>())
      .def(py::init<const DeflectionModel&>(), py::arg("model"))
      .def("reset", &DeflectionWorkspace::reset, py::arg("model"))
      .def_property_readonly("disks", &DeflectionWorkspace::disks)
      .def_property_readonly("heights", &DeflectionWorkspace::heights)
      .def_property_readonly("disk_height", &DeflectionWorkspace::disk_height)
      .def_property_readonly("forces", &DeflectionWorkspace::forces);
  m.def(
      "disk_forces",
      [](const DeflectionModel& model, DeflectionWorkspace& ws, double theta) {
        disk_forces(model, ws, theta);
        return ws.forces();
      },
      py::arg("model"), py::arg("workspace"), py::arg("theta"), "(disks, 2) forces (Fx_c, Fy_c) [N] at rotation theta [rad]");
  m.def(
      "deflection_at",
      [](const DeflectionModel& model, DeflectionWorkspace& ws, double theta, double z) {
        disk_forces(model, ws, theta);
        return deflection_from_forces(model, ws, z);
      },
      py::arg("model"), py::arg("workspace"), py::arg("theta"), py::arg("z"),
      "(dx_c, dy_c) [mm] at height z [mm] above the tip at rotation theta [rad]");
  m.def("generation_angle", &generation_angle, py::arg("model"), py::arg("side"), py::arg("z"),
        "rotation angle [rad] at which flute 1 generates the wall at height z [mm]");
  py::class_<WallErrors>(m, "WallErrors")
      .def_readonly("z", &WallErrors::z)
      .def_readonly("error", &WallErrors::error)
      .def_readonly("deflection", &WallErrors::deflection)
      .def_readonly("force", &WallErrors::force);
  m.def(
      "wall_errors",
      [](const DeflectionModel& model, DeflectionWorkspace& ws, WallSide side, const RefVector& z) {
        return wall_errors(model, ws, side, z);
      },
      py::arg("model"), py::arg("workspace"), py::arg("side"), py::arg("z"),
      "wall error e = -delta.n [mm] (+ material left) at heights z [mm]");
  m.def("cut_levels", &cut_levels, py::arg("axial_depth"), "(bottom, middle, top) heights [mm]");
  m.def("max_force", &max_force, py::arg("model"), py::arg("workspace"), py::arg("samples") = 720,
        "largest |(Fx, Fy)| [N] over one tooth period");
}
