// Bindings of the `machine` area (netshape._core.machine). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"
#include "netshape/machine.hpp"

namespace py = pybind11;
using namespace netshape::machine;
using netshape::py_types::RefPoints3;
using netshape::py_types::RefVector;

void bind_machine(py::module_& m) {
  py::enum_<OutOfRange>(m, "OutOfRange", "What a table does outside its positions")
      .value("error", OutOfRange::error)
      .value("clamp", OutOfRange::clamp)
      .value("extrapolate", OutOfRange::extrapolate);

  py::class_<ErrorFunction> ef(m, "ErrorFunction",
                               "One error component e(q) of an axis: zero, polynomial (ascending powers of "
                               "q [mm]) or table (linear interpolation). Values [mm] or [rad].");
  py::enum_<ErrorFunction::Kind>(ef, "Kind")
      .value("zero", ErrorFunction::Kind::zero)
      .value("polynomial", ErrorFunction::Kind::polynomial)
      .value("table", ErrorFunction::Kind::table);
  ef.def(py::init<>())
      .def_static("zero_function", &ErrorFunction::zero_function, py::arg("name") = "")
      .def_static("polynomial", &ErrorFunction::polynomial, py::arg("coefficients"), py::arg("name") = "")
      .def_static("table", &ErrorFunction::table, py::arg("positions"), py::arg("values"),
                  py::arg_v("out_of_range", OutOfRange::error, "OutOfRange.error"), py::arg("name") = "")
      .def_readwrite("kind", &ErrorFunction::kind)
      .def_readwrite("coefficients", &ErrorFunction::coefficients)
      .def_readwrite("positions", &ErrorFunction::positions)
      .def_readwrite("values", &ErrorFunction::values)
      .def_readwrite("out_of_range", &ErrorFunction::out_of_range)
      .def_readwrite("name", &ErrorFunction::name)
      .def("validate", &ErrorFunction::validate)
      .def("is_zero", &ErrorFunction::is_zero)
      .def("__call__", [](const ErrorFunction& f, double q) { return f(q); }, py::arg("q"))
      .def(
          "evaluate",
          [](const ErrorFunction& f, const netshape::py_types::RefVector& q) {
            Eigen::VectorXd out(q.size());
            for (Eigen::Index i = 0; i < q.size(); ++i) out[i] = f(q[i]);
            return out;
          },
          py::arg("q"), "e(q) at many positions q [mm], (n,) → (n,)");

  py::enum_<Component>(m, "Component")
      .value("ex", Component::ex)
      .value("ey", Component::ey)
      .value("ez", Component::ez)
      .value("ea", Component::ea)
      .value("eb", Component::eb)
      .value("ec", Component::ec);
  py::enum_<Side>(m, "Side").value("tool", Side::tool).value("workpiece", Side::workpiece);
  py::enum_<Order>(m, "Order").value("exact", Order::exact).value("first", Order::first);

  m.def("component_name", &component_name, py::arg("component"), py::arg("axis"));

  py::class_<CyclicTerm>(m, "CyclicTerm", "Periodic positioning error amplitude·sin(2π·q/period + phase)")
      .def(py::init([](double amplitude, double period, double phase) { return CyclicTerm{amplitude, period, phase}; }),
           py::arg("amplitude") = 0.0, py::arg("period") = 1.0, py::arg("phase") = 0.0)
      .def_readwrite("amplitude", &CyclicTerm::amplitude, "[mm]")
      .def_readwrite("period", &CyclicTerm::period, "[mm]")
      .def_readwrite("phase", &CyclicTerm::phase, "[rad]");
  py::class_<ThermalDrift>(m, "ThermalDrift", "Tip drift along an axis: amplitude·(1 − exp(−t/time_constant))")
      .def(py::init([](int axis, double amplitude, double time_constant) {
             return ThermalDrift{axis, amplitude, time_constant};
           }),
           py::arg("axis") = 0, py::arg("amplitude") = 0.0, py::arg("time_constant") = 1.0)
      .def_readwrite("axis", &ThermalDrift::axis, "0 = X, 1 = Y, 2 = Z")
      .def_readwrite("amplitude", &ThermalDrift::amplitude, "[mm]")
      .def_readwrite("time_constant", &ThermalDrift::time_constant, "[s]");

  py::class_<Axis>(m, "Axis", "A linear axis: travel [mm], frame origin [mm], six error components")
      .def(py::init<>())
      .def_readwrite("cyclic", &Axis::cyclic, "periodic terms of the positioning component (a copy: assign back)")
      .def_readwrite("backlash", &Axis::backlash, "reversal value [mm]")
      .def_readwrite("travel_min", &Axis::travel_min)
      .def_readwrite("travel_max", &Axis::travel_max)
      .def_readwrite("origin", &Axis::origin)
      .def_property(
          "errors", [](const Axis& a) { return std::vector<ErrorFunction>(a.errors.begin(), a.errors.end()); },
          [](Axis& a, const std::vector<ErrorFunction>& v) {
            if (v.size() != 6) throw std::invalid_argument("errors: need 6 error functions (EX, EY, EZ, EA, EB, EC)");
            for (int i = 0; i < 6; ++i) a.errors[i] = v[i];
          },
          "EXk, EYk, EZk, EAk, EBk, ECk (a copy: change an element, then assign the list back)")
      .def("error", [](const Axis& a, Component c) { return a.error(c); }, py::arg("component"))
      .def("set_error", [](Axis& a, Component c, const ErrorFunction& f) { a.error(c) = f; },
           py::arg("component"), py::arg("function"));

  py::class_<Machine>(m, "Machine", "3-axis machine: two chains of linear axes from the bed with ISO 230-1 errors")
      .def(py::init<>())
      .def_readwrite("name", &Machine::name)
      .def_property(
          "axes", [](const Machine& mm) { return std::vector<Axis>(mm.axes.begin(), mm.axes.end()); },  // copies: assign back
          [](Machine& mm, const std::vector<Axis>& v) {
            if (v.size() != 3) throw std::invalid_argument("axes: need 3 axes (X, Y, Z)");
            for (int i = 0; i < 3; ++i) mm.axes[i] = v[i];
          },
          "X, Y, Z axes (a copy: change an element, then assign the list back)")
      .def("axis", [](const Machine& mm, int k) { return mm.axes.at(k); }, py::arg("index"))
      .def("set_axis", [](Machine& mm, int k, const Axis& a) { mm.axes.at(k) = a; }, py::arg("index"),
           py::arg("axis"))
      .def_readwrite("tool_chain", &Machine::tool_chain)
      .def_readwrite("workpiece_chain", &Machine::workpiece_chain)
      .def_readwrite("ec0y", &Machine::ec0y)
      .def_readwrite("eb0z", &Machine::eb0z)
      .def_readwrite("ea0z", &Machine::ea0z)
      .def_readwrite("spindle_tilt_a", &Machine::spindle_tilt_a)
      .def_readwrite("spindle_tilt_b", &Machine::spindle_tilt_b)
      .def_readwrite("spindle_nose", &Machine::spindle_nose)
      .def_readwrite("tool_length", &Machine::tool_length)
      .def_readwrite("tool_direction", &Machine::tool_direction)
      .def_readwrite("thermal", &Machine::thermal, "thermal drift terms (a copy: assign back)")
      .def("has_state_errors", &Machine::has_state_errors)
      .def("validate", &Machine::validate)
      .def("side", &Machine::side, py::arg("axis"))
      .def("nominal_tip", &Machine::nominal_tip);

  m.def("ideal_machine", &ideal_machine, py::arg("tool_chain"), py::arg("workpiece_chain"),
        py::arg("tool_length") = 0.0);
  m.def(
      "tip_error", [](const Machine& mm, const RefPoints3& p, Order o) { return tip_error(mm, p, o); },
      py::arg("machine"), py::arg("points"), py::arg_v("order", Order::exact, "Order.exact"),
      "Tool-tip error relative to the workpiece e(p) [mm], (n, 3) float64 → (n, 3)");
  m.def("actual_points", &actual_points, py::arg("machine"), py::arg("commanded"),
        py::arg_v("order", Order::exact, "Order.exact"), "Where the tip lands, p + e(p) [mm], (n, 3) → (n, 3)");
  m.def("volumetric_error", &volumetric_error, py::arg("machine"), py::arg("points"),
        py::arg_v("order", Order::exact, "Order.exact"), "|e(p)| [mm] (Yang & Kweon eq. 16), (n, 3) → (n,)");
  m.def(
      "state_error",
      [](const Machine& mm, const RefPoints3& d, const RefVector& t) { return state_error(mm, d, t); },
      py::arg("machine"), py::arg("directions"), py::arg("times"),
      "Backlash + thermal tip offset s(d, t) [mm]: directions (n, 3) (±1), times (n,) [s] → (n, 3)");
  m.def("approach_directions", &approach_directions, py::arg("path"),
        py::arg_v("initial", netshape::Vec3(1, 1, 1), "[1, 1, 1]"), py::arg("resolution") = 1e-9,
        "Per point of a path (n, 3) [mm]: the sign of each axis' last motion (n, 3)");
  m.def("rotation_zyx", &rotation_zyx, py::arg("a"), py::arg("b"), py::arg("c"),
        "Rz(c)·Ry(b)·Rx(a) [rad] → (3, 3)");
}
