// Bindings of the `compensation` area (netshape._core.compensation). Thin: lambdas only turn out-parameters into returns.
#include "default_types.hpp"
#include "netshape/compensation/deflection_compensation.hpp"
#include "netshape/compensation/program_compensation.hpp"
#include "netshape/compensation/volumetric_compensation.hpp"

namespace py = pybind11;

namespace {

// --- volumetric compensation (machine geometric errors, Yang & Kweon) --------------------------------
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


// --- deflection compensation (tool deflection, Cho & Suh 1993) -------------------------------------
void bind_deflection_compensation(py::module_& m) {
  using namespace netshape::compensation;
  using netshape::py_types::RefPoints2;
  using netshape::py_types::RefPoints3;
  using netshape::py_types::RefVector;
  py::enum_<ReferenceLevel>(m, "ReferenceLevel")
      .value("bottom", ReferenceLevel::bottom)
      .value("middle", ReferenceLevel::middle)
      .value("top", ReferenceLevel::top);
  py::enum_<DeflectionScheme>(m, "DeflectionScheme")
      .value("one_d", DeflectionScheme::one_d)
      .value("integrated", DeflectionScheme::integrated)
      .value("sectional", DeflectionScheme::sectional)
      .value("accelerated", DeflectionScheme::accelerated);
  m.def("reference_level_from_string", &reference_level_from_string, py::arg("name"));
  m.def("deflection_scheme_from_string", &deflection_scheme_from_string, py::arg("name"));
  m.def("wall_normals", &wall_normals, py::arg("nominal"), py::arg("side"), "(n, 2) unit wall normals of a polyline");
  py::class_<PathOptions>(m, "PathOptions")
      .def(py::init<>())
      .def_readwrite("side", &PathOptions::side)
      .def_readwrite("profile_levels", &PathOptions::profile_levels)
      .def_readwrite("immersion", &PathOptions::immersion)
      .def_readwrite("exact_self_removal", &PathOptions::exact_self_removal)
      .def("validate", &PathOptions::validate);
  py::class_<PathWallErrors>(m, "PathWallErrors")
      .def_readonly("positions", &PathWallErrors::positions)
      .def_readonly("error", &PathWallErrors::error)
      .def_readonly("deflection", &PathWallErrors::deflection)
      .def_readonly("normal_deflection", &PathWallErrors::normal_deflection)
      .def_readonly("tangential_deflection", &PathWallErrors::tangential_deflection)
      .def_readonly("force", &PathWallErrors::force)
      .def_readonly("width", &PathWallErrors::width)
      .def_readonly("depth", &PathWallErrors::depth)
      .def_readonly("phi_st", &PathWallErrors::phi_st)
      .def_readonly("phi_ex", &PathWallErrors::phi_ex)
      .def_readonly("engaged", &PathWallErrors::engaged)
      .def_readonly("wall_flags", &PathWallErrors::wall_flags)
      .def_readonly("profile", &PathWallErrors::profile);
  m.def(
      "path_wall_errors",
      [](const netshape::deflection::DeflectionModel& model, const netshape::cutter::Cutter& cutter,
         const netshape::stock::ZMap& stock, const RefPoints3& nominal, const RefPoints2& normals,
         const RefVector& offsets, const PathOptions& options) {
        py::gil_scoped_release release;
        return path_wall_errors(model, cutter, stock, nominal, normals, offsets, options);
      },
      py::arg("model"), py::arg("cutter"), py::arg("stock"), py::arg("nominal"), py::arg("normals"),
      py::arg("offsets"), py::arg_v("options", PathOptions{}, "PathOptions()"),
      "wall error along P_i = R_i + C_i n_i over a copy of the stock swept move by move");
  m.def("one_d_compensation", &one_d_compensation, py::arg("model"), py::arg("side"), py::arg("width"),
        py::arg("level_z"), py::arg("tolerance") = 1e-7, py::arg("max_iterations") = 100,
        "C [mm] with D[W + C] - C = 0 for a steady cut of width W [mm] (eq. 8)");
  py::class_<DeflectionCompensationOptions>(m, "DeflectionCompensationOptions")
      .def(py::init<>())
      .def_readwrite("scheme", &DeflectionCompensationOptions::scheme)
      .def_readwrite("level", &DeflectionCompensationOptions::level)
      .def_readwrite("tolerance", &DeflectionCompensationOptions::tolerance)
      .def_readwrite("discount", &DeflectionCompensationOptions::discount)
      .def_readwrite("max_iterations", &DeflectionCompensationOptions::max_iterations)
      .def_readwrite("anderson_depth", &DeflectionCompensationOptions::anderson_depth)
      .def_readwrite("active", &DeflectionCompensationOptions::active)
      .def_readwrite("path", &DeflectionCompensationOptions::path)
      .def("validate", &DeflectionCompensationOptions::validate);
  py::class_<DeflectionCompensationResult>(m, "DeflectionCompensationResult")
      .def_readonly("converged", &DeflectionCompensationResult::converged)
      .def_readonly("message", &DeflectionCompensationResult::message)
      .def_readonly("scheme", &DeflectionCompensationResult::scheme)
      .def_readonly("iterations", &DeflectionCompensationResult::iterations)
      .def_readonly("path_evaluations", &DeflectionCompensationResult::path_evaluations)
      .def_readonly("point_evaluations", &DeflectionCompensationResult::point_evaluations)
      .def_readonly("worst_index", &DeflectionCompensationResult::worst_index)
      .def_readonly("offsets", &DeflectionCompensationResult::offsets)
      .def_readonly("positions", &DeflectionCompensationResult::positions)
      .def_readonly("normals", &DeflectionCompensationResult::normals)
      .def_readonly("history", &DeflectionCompensationResult::history)
      .def_readonly("before", &DeflectionCompensationResult::before)
      .def_readonly("after", &DeflectionCompensationResult::after);
  m.def(
      "compensate_deflection",
      [](const netshape::deflection::DeflectionModel& model, const netshape::cutter::Cutter& cutter,
         const netshape::stock::ZMap& stock, const RefPoints3& nominal, const DeflectionCompensationOptions& o) {
        py::gil_scoped_release release;
        return compensate_deflection(model, cutter, stock, nominal, o);
      },
      py::arg("model"), py::arg("cutter"), py::arg("stock"), py::arg("nominal"),
      py::arg_v("options", DeflectionCompensationOptions{}, "DeflectionCompensationOptions()"),
      "compensate the path (n, 3) for tool deflection; converged = False with a message when it fails");
  m.def(
      "wall_remains",
      [](const RefPoints3& wall, const RefVector& top, const Eigen::VectorXi& first_later, const RefPoints3& path,
         const Eigen::VectorXi& cutting, double radius, double clearance) {
        py::gil_scoped_release release;
        return wall_remains(wall, top, first_later, path, cutting, radius, clearance);
      },
      py::arg("wall"), py::arg("top"), py::arg("first_later"), py::arg("path"), py::arg("cutting"),
      py::arg("radius"), py::arg("clearance"),
      "(n) 1 where wall point k (XY, bottom z; top[k]) is not cut away by a cutting move j >= first_later[k]");
  py::class_<DrawingOffsets>(m, "DrawingOffsets")
      .def_readonly("offsets", &DrawingOffsets::offsets)
      .def_readonly("normals", &DrawingOffsets::normals)
      .def_readonly("s", &DrawingOffsets::s)
      .def_readonly("foot_distance", &DrawingOffsets::foot_distance);
  m.def(
      "drawing_offsets",
      [](const RefPoints3& points, const RefPoints3& drawing, netshape::deflection::WallSide side, double window) {
        py::gil_scoped_release release;
        return drawing_offsets(points, drawing, side, window);
      },
      py::arg("points"), py::arg("drawing"), py::arg("side"), py::arg("window") = 2.0,
      "signed offsets C, normals and foot arc lengths of program points against a drawing's contour");
}

// --- volumetric compensation of a whole program (post-processor) ---------------------------------------
void bind_program_compensation(py::module_& m) {
  using namespace netshape::compensation;
  py::class_<ProgramOptions>(m, "ProgramOptions", "Options of compensate_program (lengths [mm]).")
      .def(py::init<>())
      .def(py::init([](double chord_tolerance, const VolumetricOptions& point, int max_halvings) {
             ProgramOptions o;
             o.chord_tolerance = chord_tolerance;
             o.point = point;
             o.max_halvings = max_halvings;
             o.validate();
             return o;
           }),
           py::arg("chord_tolerance") = 0.002, py::arg_v("point", VolumetricOptions{}, "VolumetricOptions()"),
           py::arg("max_halvings") = 30)
      .def_readwrite("chord_tolerance", &ProgramOptions::chord_tolerance, "[mm]")
      .def_readwrite("point", &ProgramOptions::point)
      .def_readwrite("max_halvings", &ProgramOptions::max_halvings)
      .def_readwrite("block_times", &ProgramOptions::block_times,
                     "program time at each block's end [s] (empty: from the programmed feeds)")
      .def_readwrite("rapid_feed", &ProgramOptions::rapid_feed, "[mm/s]")
      .def_readwrite("initial_direction", &ProgramOptions::initial_direction, "(3,) each −1, 0 or +1")
      .def("validate", &ProgramOptions::validate);
  py::class_<ProgramReport>(m, "ProgramReport", "What compensate_program did (lengths [mm]).")
      .def_readonly("source", &ProgramReport::source)
      .def_readonly("blocks_in", &ProgramReport::blocks_in)
      .def_readonly("blocks_out", &ProgramReport::blocks_out)
      .def_readonly("lines_split", &ProgramReport::lines_split)
      .def_readonly("arcs_kept", &ProgramReport::arcs_kept)
      .def_readonly("arcs_split", &ProgramReport::arcs_split)
      .def_readonly("max_correction", &ProgramReport::max_correction, "[mm]")
      .def_readonly("max_residual", &ProgramReport::max_residual, "[mm]")
      .def_readonly("max_path_deviation", &ProgramReport::max_path_deviation, "[mm]")
      .def_readonly("commands", &ProgramReport::commands)
      .def_readonly("takeup_moves", &ProgramReport::takeup_moves);
  m.def("block_end_times", &block_end_times, py::arg("program"), py::arg("rapid_feed") = 250.0,
        "program time at each block's end [s] from the programmed feeds (rapids at rapid_feed [mm/s])");
  m.def(
      "compensate_program",
      [](const netshape::machine::Machine& mm, const netshape::toolpath::Toolpath& program, const ProgramOptions& o) {
        ProgramResult r;
        {
          py::gil_scoped_release release;
          r = compensate_program(mm, program, o);
        }
        return py::make_tuple(std::move(r.toolpath), std::move(r.report));
      },
      py::arg("machine"), py::arg("program"), py::arg_v("options", ProgramOptions{}, "ProgramOptions()"),
      "(Toolpath, ProgramReport): the program compensated so the actual tip follows it within chord_tolerance");
}

}  // namespace

void bind_feed_schedule(py::module_& m);  // bind_feed_schedule.cpp

void bind_compensation(py::module_& m) {
  bind_volumetric_compensation(m);
  bind_program_compensation(m);
  bind_deflection_compensation(m);
  bind_feed_schedule(m);
}
