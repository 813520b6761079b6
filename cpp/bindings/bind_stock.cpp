// Bindings of the `stock` area (netshape._core.stock). Thin: lambdas only turn out-parameters into
// returns, expose the heights as a NumPy view and release the GIL around the sweeps.
#include <string>

#include "default_types.hpp"
#include "netshape/stock.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::stock;
using netshape::cutter::Cutter;
using netshape::cutter::CutterKind;

namespace {

py::dict stats_dict(const SweepStats& s) {
  py::dict d;
  d["moves"] = s.moves;
  d["nodes_visited"] = s.nodes_visited;
  d["nodes_lowered"] = s.nodes_lowered;
  d["removed_volume"] = s.removed_volume;
  d["rapids_cutting"] = s.rapids_cutting;
  return d;
}

py::dict immersion_dict(const Immersion& s) {
  py::dict d;
  d["engaged"] = s.engaged;
  d["phi_st"] = s.phi_st;
  d["phi_ex"] = s.phi_ex;
  d["axial_depth"] = s.axial_depth;
  d["radial_depth"] = s.radial_depth;
  return d;
}

}  // namespace

void bind_stock(py::module_& m) {

  py::class_<ZMap>(m, "ZMap",
                   "Z-map workpiece: node heights [mm] on a cell-centred grid over [x0, x1] x [y0, y1] [mm].")
      .def(py::init<double, double, double, double, double, double, double>(), py::arg("x0"), py::arg("x1"),
           py::arg("y0"), py::arg("y1"), py::arg("spacing"), py::arg("top"), py::arg("bottom"),
           "Flat block: footprint [mm], node spacing at most `spacing` [mm], top and bottom z [mm].")
      .def_static("from_heights", &ZMap::from_heights, py::arg("heights"), py::arg("x0"), py::arg("x1"),
                  py::arg("y0"), py::arg("y1"), py::arg("bottom"),
                  "Z-map from an (ny, nx) array of node heights [mm] (copied).")
      .def_property_readonly("nx", &ZMap::nx)
      .def_property_readonly("ny", &ZMap::ny)
      .def_property_readonly("x0", &ZMap::x0)
      .def_property_readonly("x1", &ZMap::x1)
      .def_property_readonly("y0", &ZMap::y0)
      .def_property_readonly("y1", &ZMap::y1)
      .def_property_readonly("dx", &ZMap::dx, "cell size along X [mm]")
      .def_property_readonly("dy", &ZMap::dy, "cell size along Y [mm]")
      .def_property_readonly("bottom", &ZMap::bottom, "underside of the stock [mm]")
      .def_property_readonly(
          "heights",
          [](py::object self) {
            const ZMap& z = self.cast<const ZMap&>();
            py::array_t<double> a({static_cast<py::ssize_t>(z.ny()), static_cast<py::ssize_t>(z.nx())},
                                  {static_cast<py::ssize_t>(z.nx() * sizeof(double)),
                                   static_cast<py::ssize_t>(sizeof(double))},
                                  z.heights().data(), self);
            a.attr("setflags")(py::arg("write") = false);
            return a;
          },
          "(ny, nx) float64 node heights [mm]: a live read-only view (no copy) that follows the sweeps; "
          "use .copy() to keep a snapshot")
      .def("set_heights", &ZMap::set_heights, py::arg("heights"), "replace all heights ((ny, nx), >= bottom) [mm]")
      .def("volume", &ZMap::volume, "material volume above the bottom [mm^3]")
      .def("min_height", &ZMap::min_height)
      .def("max_height", &ZMap::max_height)
      .def("height_bound", &ZMap::height_bound, py::arg("i0"), py::arg("i1"),
           "upper bound of the heights of rows i0..i1 [mm] used by the quick reject (>= their maximum)")
      .def("node_x", &ZMap::node_x, py::arg("j"))
      .def("node_y", &ZMap::node_y, py::arg("i"))
      .def("height_at", py::overload_cast<double, double>(&ZMap::height_at, py::const_), py::arg("x"), py::arg("y"),
           "bilinear node height at (x, y) [mm]; NaN outside the footprint")
      .def("cell_height", py::overload_cast<double, double>(&ZMap::cell_height, py::const_), py::arg("x"),
           py::arg("y"), "pillar height of the cell holding (x, y) [mm]; NaN outside the footprint")
      .def("is_material", py::overload_cast<const Vec3&>(&ZMap::is_material, py::const_), py::arg("p"),
           "True if p (3,) [mm] is inside the footprint and bottom <= z < pillar height")
      .def("height_at_points", &ZMap::height_at_points, py::arg("points"), "(n,) bilinear heights at (n, 2|3) points")
      .def("cell_height_points", &ZMap::cell_height_points, py::arg("points"), "(n,) pillar heights")
      .def("is_material_points", &ZMap::is_material_points, py::arg("points"), "(n,) bool for (n, 3) points")
      .def("copy", [](const ZMap& z) { return ZMap(z); }, "a deep copy")
      .def("__copy__", [](const ZMap& z) { return ZMap(z); })
      .def("__deepcopy__", [](const ZMap& z, py::dict) { return ZMap(z); }, py::arg("memo"))
      .def("__repr__", [](const ZMap& z) {
        return "ZMap(" + std::to_string(z.ny()) + "x" + std::to_string(z.nx()) + " nodes, [" +
               std::to_string(z.x0()) + ", " + std::to_string(z.x1()) + "] x [" + std::to_string(z.y0()) + ", " +
               std::to_string(z.y1()) + "] mm)";
      });

  py::class_<TipProfile>(m, "TipProfile", "Lower surface g(d) of a cutter above its tip [mm].")
      .def_static("of", &TipProfile::of, py::arg("cutter"))
      .def_readonly("radius", &TipProfile::radius)
      .def_readonly("corner_radius", &TipProfile::corner_radius)
      .def_readonly("flat_radius", &TipProfile::flat_radius)
      .def("lift", &TipProfile::lift, py::arg("d"))
      .def("slope", &TipProfile::slope, py::arg("d"));

  py::class_<SweepOptions>(m, "SweepOptions", "Options of program sweeps.")
      .def(py::init<>())
      .def_readwrite("chord_tolerance", &SweepOptions::chord_tolerance, "[mm] for arcs split into chords")
      .def_readwrite("include_rapids", &SweepOptions::include_rapids)
      .def_readwrite("merge_collinear", &SweepOptions::merge_collinear)
      .def("validate", &SweepOptions::validate);

  py::class_<SweepStats>(m, "SweepStats", "What a sweep did: counts and removed volume [mm^3].")
      .def(py::init<>())
      .def_readonly("moves", &SweepStats::moves)
      .def_readonly("nodes_visited", &SweepStats::nodes_visited)
      .def_readonly("nodes_lowered", &SweepStats::nodes_lowered)
      .def_readonly("removed_volume", &SweepStats::removed_volume)
      .def_readonly("rapids_cutting", &SweepStats::rapids_cutting)
      .def("to_dict", &stats_dict)
      .def("__repr__", [](const SweepStats& s) { return "SweepStats(" + py::str(stats_dict(s)).cast<std::string>() + ")"; });

  m.def("lowest_reach_line", &lowest_reach_line, py::arg("profile"), py::arg("a"), py::arg("b"), py::arg("x"),
        py::arg("y"), "lowest z [mm] of the tip surface above (x, y) along the line a -> b (inf if never over it)");
  m.def("sweep_line", &sweep_line, py::arg("zmap"), py::arg("cutter"), py::arg("a"), py::arg("b"),
        py::call_guard<py::gil_scoped_release>(), "sweep the tip along the line a -> b [mm]");
  m.def("sweep_lines", &sweep_lines, py::arg("zmap"), py::arg("cutter"), py::arg("starts"), py::arg("ends"),
        py::call_guard<py::gil_scoped_release>(),
        "sweep the tip along the lines starts[k] -> ends[k] ((n, 3) each [mm]) in order, in one call; "
        "the same heights as n sweep_line calls, summed stats");
  m.def("sweep_polyline", &sweep_polyline, py::arg("zmap"), py::arg("cutter"), py::arg("points"),
        py::arg("merge_collinear") = true, py::call_guard<py::gil_scoped_release>(),
        "sweep the tip along the polyline through (n, 3) points [mm]");
  m.def("sweep_block", &sweep_block, py::arg("zmap"), py::arg("cutter"), py::arg("block"),
        py::arg_v("options", SweepOptions{}, "SweepOptions()"), py::call_guard<py::gil_scoped_release>());
  m.def("sweep", &sweep, py::arg("zmap"), py::arg("cutter"), py::arg("program"), py::arg_v("options", SweepOptions{}, "SweepOptions()"),
        py::call_guard<py::gil_scoped_release>(), "sweep a whole Toolpath in order");

  m.def("cutting_frame", [](const Vec3& f) {
        Vec3 x, y;
        cutting_frame(f, x, y);
        return py::make_tuple(x, y);
      }, py::arg("feed_direction"), "(X_c, Y_c) unit axes of the cutting frame (docs/conventions.md §2)");
  m.def("element_point", &element_point, py::arg("cutter"), py::arg("tip"), py::arg("feed_direction"), py::arg("phi"),
        py::arg("z"), "point (3,) [mm] of the element at immersion phi [rad], height z [mm] above the tip");
  m.def("engaged_elements", &engaged_elements, py::arg("zmap"), py::arg("cutter"), py::arg("tip"),
        py::arg("feed_direction"), py::arg("phi"), py::arg("z"),
        "(k, m) bool: element at height z[k] [mm] and angle phi[m] [rad] lies in material");

  py::class_<ImmersionOptions>(m, "ImmersionOptions")
      .def(py::init<>())
      .def_readwrite("angles", &ImmersionOptions::angles)
      .def_readwrite("probe_height", &ImmersionOptions::probe_height, "[mm]");
  py::class_<Immersion>(m, "Immersion", "Radial (phi_st, phi_ex [rad]) and axial [mm] immersion from a Z-map.")
      .def(py::init<>())
      .def_readonly("engaged", &Immersion::engaged)
      .def_readonly("phi_st", &Immersion::phi_st)
      .def_readonly("phi_ex", &Immersion::phi_ex)
      .def_readonly("axial_depth", &Immersion::axial_depth)
      .def_readonly("radial_depth", &Immersion::radial_depth)
      .def("to_dict", &immersion_dict)
      .def("__repr__", [](const Immersion& s) { return "Immersion(" + py::str(immersion_dict(s)).cast<std::string>() + ")"; });
  m.def("immersion", &immersion, py::arg("zmap"), py::arg("cutter"), py::arg("tip"), py::arg("feed_direction"),
        py::arg_v("options", ImmersionOptions{}, "ImmersionOptions()"));

  m.def("stl_triangle_count", &stl_triangle_count, py::arg("zmap"));
  m.def("write_stl", &write_stl, py::arg("zmap"), py::arg("path"), py::call_guard<py::gil_scoped_release>(),
        "binary STL of the closed solid, written atomically");
}
