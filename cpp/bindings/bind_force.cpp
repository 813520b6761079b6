// Bindings of the `force` area (netshape._core.force). Thin: lambdas only turn out-parameters into
// returns and supply keyword constructors.
#include "default_types.hpp"
#include "netshape/force.hpp"
#include "netshape/stock/zmap.hpp"
#include "netshape/toolpath/toolpath.hpp"
#include "netshape/cutter/cutter.hpp"

namespace py = pybind11;
using namespace pybind11::literals;
using netshape::Points3;
using netshape::VectorXd;
using netshape::py_types::RefPoints3;
using netshape::py_types::RefVector;
namespace nf = netshape::force;

namespace {
template <class T>
T validated(T v) {
  v.validate();
  return v;
}
py::dict summary_dict(const nf::ForceSummary& s) {
  return py::dict("mean"_a = s.mean, "peak"_a = s.peak, "peak_resultant"_a = s.peak_resultant,
                  "mean_resultant"_a = s.mean_resultant, "peak_resultant_xy"_a = s.peak_resultant_xy);
}
}  // namespace

void bind_force(py::module_& m) {
  py::enum_<nf::MillingMode>(m, "MillingMode", "Up, down or slot milling (docs/conventions.md §2).")
      .value("up", nf::MillingMode::up)
      .value("down", nf::MillingMode::down)
      .value("slot", nf::MillingMode::slot);
  m.def("milling_mode_from_string", &nf::milling_mode_from_string, "text"_a);

  py::enum_<nf::FlatCoefficientModel>(m, "FlatCoefficientModel")
      .value("linear_edge", nf::FlatCoefficientModel::linear_edge)
      .value("kline_devor", nf::FlatCoefficientModel::kline_devor);

  py::class_<nf::LinearEdgeCoefficients>(m, "LinearEdgeCoefficients",
                                         "Linear edge-force coefficients: ktc krc kac [N/mm²], kte kre kae [N/mm].")
      .def(py::init([](double ktc, double krc, double kac, double kte, double kre, double kae) {
             return validated(nf::LinearEdgeCoefficients{ktc, krc, kac, kte, kre, kae});
           }),
           "ktc"_a = 0.0, "krc"_a = 0.0, "kac"_a = 0.0, "kte"_a = 0.0, "kre"_a = 0.0, "kae"_a = 0.0)
      .def_readwrite("ktc", &nf::LinearEdgeCoefficients::ktc)
      .def_readwrite("krc", &nf::LinearEdgeCoefficients::krc)
      .def_readwrite("kac", &nf::LinearEdgeCoefficients::kac)
      .def_readwrite("kte", &nf::LinearEdgeCoefficients::kte)
      .def_readwrite("kre", &nf::LinearEdgeCoefficients::kre)
      .def_readwrite("kae", &nf::LinearEdgeCoefficients::kae)
      .def("validate", &nf::LinearEdgeCoefficients::validate)
      .def("as_array", &nf::LinearEdgeCoefficients::as_array)
      .def("to_dict", [](const nf::LinearEdgeCoefficients& k) {
        return py::dict("ktc"_a = k.ktc, "krc"_a = k.krc, "kac"_a = k.kac, "kte"_a = k.kte, "kre"_a = k.kre,
                        "kae"_a = k.kae);
      })
      .def("__repr__", [](const nf::LinearEdgeCoefficients& k) {
        return py::str("LinearEdgeCoefficients(ktc={:.6g}, krc={:.6g}, kac={:.6g}, kte={:.6g}, kre={:.6g}, kae={:.6g})")
            .format(k.ktc, k.krc, k.kac, k.kte, k.kre, k.kae);
      });

  py::class_<nf::KlineDevorCoefficients>(m, "KlineDevorCoefficients",
                                         "Kline–DeVor K_T [N/mm²] and K_R [-] (Cho & Suh eq. 1).")
      .def(py::init([](double kt, double kr) { return validated(nf::KlineDevorCoefficients{kt, kr}); }), "kt"_a,
           "kr"_a)
      .def_readwrite("kt", &nf::KlineDevorCoefficients::kt)
      .def_readwrite("kr", &nf::KlineDevorCoefficients::kr)
      .def("validate", &nf::KlineDevorCoefficients::validate)
      .def("to_linear_edge", &nf::KlineDevorCoefficients::to_linear_edge);

  py::class_<nf::BallEndCoefficients>(m, "BallEndCoefficients",
                                      "Feng–Menq ball-end coefficients (Kim et al. eq. 6–7): K_T(ψ) = Σ a_i ψ^i, "
                                      "K_R(ψ) = Σ b_i ψ^i, exponents m_t, m_r.")
      .def(py::init([](std::array<double, 4> a, std::array<double, 4> b, double m_t, double m_r) {
             return validated(nf::BallEndCoefficients{a, b, m_t, m_r});
           }),
           "a"_a, "b"_a, "m_t"_a, "m_r"_a)
      .def_readwrite("a", &nf::BallEndCoefficients::a)
      .def_readwrite("b", &nf::BallEndCoefficients::b)
      .def_readwrite("m_t", &nf::BallEndCoefficients::m_t)
      .def_readwrite("m_r", &nf::BallEndCoefficients::m_r)
      .def("validate", &nf::BallEndCoefficients::validate)
      .def("kt", py::vectorize(&nf::BallEndCoefficients::kt), "psi"_a, "K_T(ψ), ψ [rad]")
      .def("kr", py::vectorize(&nf::BallEndCoefficients::kr), "psi"_a, "K_R(ψ), ψ [rad]")
      .def("to_dict", [](const nf::BallEndCoefficients& k) {
        return py::dict("a"_a = k.a, "b"_a = k.b, "m_t"_a = k.m_t, "m_r"_a = k.m_r);
      });

  py::class_<nf::BallEndCoefficientSet>(m, "BallEndCoefficientSet")
      .def_readonly("name", &nf::BallEndCoefficientSet::name)
      .def_readonly("coefficients", &nf::BallEndCoefficientSet::coefficients)
      .def_readonly("diameter", &nf::BallEndCoefficientSet::diameter)
      .def_readonly("flutes", &nf::BallEndCoefficientSet::flutes)
      .def_readonly("helix", &nf::BallEndCoefficientSet::helix)
      .def_readonly("source", &nf::BallEndCoefficientSet::source);
  py::class_<nf::LinearEdgeCoefficientSet>(m, "LinearEdgeCoefficientSet")
      .def_readonly("name", &nf::LinearEdgeCoefficientSet::name)
      .def_readonly("coefficients", &nf::LinearEdgeCoefficientSet::coefficients)
      .def_readonly("source", &nf::LinearEdgeCoefficientSet::source);
  m.def("ball_end_coefficient_set", &nf::ball_end_coefficient_set, "name"_a);
  m.def("linear_edge_coefficient_set", &nf::linear_edge_coefficient_set, "name"_a);
  m.def("ball_end_coefficient_set_names", &nf::ball_end_coefficient_set_names);
  m.def("linear_edge_coefficient_set_names", &nf::linear_edge_coefficient_set_names);

  py::class_<nf::AngularEngagement>(m, "AngularEngagement",
                                    "Engagement window [phi_st, phi_ex] [rad], immersion clockwise from +Y.")
      .def(py::init([](double st, double ex) { return validated(nf::AngularEngagement{st, ex}); }),
           "phi_st"_a = 0.0, "phi_ex"_a = netshape::pi)
      .def_readwrite("phi_st", &nf::AngularEngagement::phi_st)
      .def_readwrite("phi_ex", &nf::AngularEngagement::phi_ex)
      .def("validate", &nf::AngularEngagement::validate)
      .def_static("from_mode", &nf::AngularEngagement::from_mode, "mode"_a, "radius"_a, "radial_depth"_a = 0.0)
      .def("__repr__", [](const nf::AngularEngagement& e) {
        return py::str("AngularEngagement(phi_st={:.6g}, phi_ex={:.6g})").format(e.phi_st, e.phi_ex);
      });

  py::class_<nf::EngagementMap>(m, "EngagementMap",
                                "Per-disk (row) angular bins in material, mask (rows, bins) uint8.")
      .def(py::init([](const Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>& mask) {
             nf::EngagementMap e;
             e.mask = mask;
             return e;
           }),
           "mask"_a)
      .def_readwrite("mask", &nf::EngagementMap::mask)
      .def("bins", &nf::EngagementMap::bins)
      .def("disks", &nf::EngagementMap::disks)
      .def_static("from_window", &nf::EngagementMap::from_window, "window"_a, "disks"_a, "bins"_a);

  py::class_<nf::FlatEndModel>(m, "FlatEndModel", "Flat end mill force model (immutable inputs of a sweep).")
      .def(py::init([](double radius, int flutes, double helix, double axial_depth, double feed_per_tooth,
                       nf::AngularEngagement engagement, nf::FlatCoefficientModel coefficient_model,
                       nf::LinearEdgeCoefficients linear_edge, nf::KlineDevorCoefficients kline_devor,
                       double disk_height) {
             return validated(nf::FlatEndModel{radius, flutes, helix, axial_depth, feed_per_tooth, engagement,
                                               coefficient_model, linear_edge, kline_devor, disk_height});
           }),
           "radius"_a = 5.0, "flutes"_a = 2, "helix"_a = 0.5235987755982988, "axial_depth"_a = 1.0,
           "feed_per_tooth"_a = 0.05, py::arg_v("engagement", nf::AngularEngagement{}, "AngularEngagement()"),
           py::arg_v("coefficient_model", nf::FlatCoefficientModel::linear_edge, "FlatCoefficientModel.linear_edge"),
           py::arg_v("linear_edge", nf::LinearEdgeCoefficients{}, "LinearEdgeCoefficients()"), py::arg_v("kline_devor", nf::KlineDevorCoefficients{1.0, 0.0}, "KlineDevorCoefficients(1.0, 0.0)"),
           "disk_height"_a = 0.05)
      .def_readwrite("radius", &nf::FlatEndModel::radius)
      .def_readwrite("flutes", &nf::FlatEndModel::flutes)
      .def_readwrite("helix", &nf::FlatEndModel::helix)
      .def_readwrite("axial_depth", &nf::FlatEndModel::axial_depth)
      .def_readwrite("feed_per_tooth", &nf::FlatEndModel::feed_per_tooth)
      .def_readwrite("engagement", &nf::FlatEndModel::engagement)
      .def_readwrite("coefficient_model", &nf::FlatEndModel::coefficient_model)
      .def_readwrite("linear_edge", &nf::FlatEndModel::linear_edge)
      .def_readwrite("kline_devor", &nf::FlatEndModel::kline_devor)
      .def_readwrite("disk_height", &nf::FlatEndModel::disk_height)
      .def("validate", &nf::FlatEndModel::validate)
      .def("disks", &nf::FlatEndModel::disks)
      .def("k_beta", &nf::FlatEndModel::k_beta);

  py::class_<nf::FlatEndWorkspace>(m, "FlatEndWorkspace", "Preallocated buffers for a FlatEndModel.")
      .def(py::init<const nf::FlatEndModel&>(), "model"_a)
      .def("reset", &nf::FlatEndWorkspace::reset, "model"_a)
      .def("disks", &nf::FlatEndWorkspace::disks)
      .def("elements", &nf::FlatEndWorkspace::elements)
      .def("heights", &nf::FlatEndWorkspace::heights)
      .def("disk_height", &nf::FlatEndWorkspace::disk_height);

  m.def(
      "flat_end_forces",
      [](const nf::FlatEndModel& model, RefVector angles, nf::FlatEndWorkspace* ws, const nf::EngagementMap* map) {
        Points3 out(angles.size(), 3);
        if (ws) {
          py::gil_scoped_release rel;
          nf::flat_end_forces(model, *ws, angles, out, map);
        } else {
          nf::FlatEndWorkspace w(model);
          py::gil_scoped_release rel;
          nf::flat_end_forces(model, w, angles, out, map);
        }
        return out;
      },
      "model"_a, "angles"_a, "workspace"_a = nullptr, "engagement_map"_a = nullptr,
      "Forces on the cutter (n, 3) [N] at rotation angles (n) [rad] (flute 1 at the tip).");
  py::class_<nf::RunoutSizeEffect>(m, "RunoutSizeEffect",
                                   "Cutter runout (rho [mm], lambda [rad]) and chip-size effect (exponent p, "
                                   "reference chip [mm], 0: the feed per tooth)")
      .def(py::init<>())
      .def(py::init([](double rho, double lam, double p, double href) {
             nf::RunoutSizeEffect e{rho, lam, p, href};
             e.validate();
             return e;
           }),
           "runout_rho"_a = 0.0, "runout_lambda"_a = 0.0, "chip_exponent"_a = 1.0, "reference_chip"_a = 0.0)
      .def_readwrite("runout_rho", &nf::RunoutSizeEffect::runout_rho, "[mm]")
      .def_readwrite("runout_lambda", &nf::RunoutSizeEffect::runout_lambda, "[rad]")
      .def_readwrite("chip_exponent", &nf::RunoutSizeEffect::chip_exponent, "p in (0, 2]")
      .def_readwrite("reference_chip", &nf::RunoutSizeEffect::reference_chip, "h_ref [mm]; 0: the feed per tooth")
      .def("validate", &nf::RunoutSizeEffect::validate)
      .def("none", &nf::RunoutSizeEffect::none);
  m.def(
      "flat_end_forces_extended",
      [](const nf::FlatEndModel& model, const nf::RunoutSizeEffect& extension, RefVector angles) {
        py::gil_scoped_release rel;
        return nf::flat_end_forces_extended(model, extension, angles);
      },
      "model"_a, "extension"_a, "angles"_a,
      "Forces on the cutter (n, 3) [N] at rotation angles (n) [rad] with cutter runout and the chip-size "
      "effect (netshape/force/runout_size_effect.hpp).");
  m.def(
      "flat_end_moments",
      [](const nf::FlatEndModel& model, RefVector angles) {
        nf::FlatEndWorkspace ws(model);
        netshape::MatrixXdR out(angles.size(), 6);
        nf::flat_end_moments(model, ws, angles, out);
        return out;
      },
      "model"_a, "angles"_a);
  m.def("rotation_angles", &nf::rotation_angles, "count"_a, "revolutions"_a = 1.0);

  py::class_<nf::BallEndModel>(m, "BallEndModel", "Ball end mill force model (Kim et al.).")
      .def(py::init([](double radius, int flutes, double helix, double axial_depth, double feed_per_tooth,
                       double inclination, nf::AngularEngagement engagement, nf::BallEndCoefficients coefficients,
                       double element_angle, double disk_height, double runout_rho, double runout_lambda) {
             return validated(nf::BallEndModel{radius, flutes, helix, axial_depth, feed_per_tooth,
                                               inclination, engagement, coefficients, element_angle,
                                               disk_height, runout_rho, runout_lambda});
           }),
           "radius"_a = 6.0, "flutes"_a = 2, "helix"_a = 0.5235987755982988, "axial_depth"_a = 3.0,
           "feed_per_tooth"_a = 0.05, "inclination"_a = 0.0, py::arg_v("engagement", nf::AngularEngagement{}, "AngularEngagement()"),
           py::arg_v("coefficients", nf::ball_end_coefficient_set("kim_zas_ball12").coefficients,
                     "ball_end_coefficient_set('kim_zas_ball12').coefficients"),
           "element_angle"_a = 0.0174532925199432957, "disk_height"_a = 0.05, "runout_rho"_a = 0.0,
           "runout_lambda"_a = 0.0)
      .def_readwrite("radius", &nf::BallEndModel::radius)
      .def_readwrite("flutes", &nf::BallEndModel::flutes)
      .def_readwrite("helix", &nf::BallEndModel::helix)
      .def_readwrite("axial_depth", &nf::BallEndModel::axial_depth)
      .def_readwrite("feed_per_tooth", &nf::BallEndModel::feed_per_tooth)
      .def_readwrite("inclination", &nf::BallEndModel::inclination)
      .def_readwrite("engagement", &nf::BallEndModel::engagement)
      .def_readwrite("coefficients", &nf::BallEndModel::coefficients)
      .def_readwrite("element_angle", &nf::BallEndModel::element_angle)
      .def_readwrite("disk_height", &nf::BallEndModel::disk_height)
      .def_readwrite("runout_rho", &nf::BallEndModel::runout_rho,
                     "rho, offset of the tool axis [mm]; flute j cuts at + rho cos(lambda - j 2pi/N)")
      .def_readwrite("runout_lambda", &nf::BallEndModel::runout_lambda, "lambda [rad]")
      .def("validate", &nf::BallEndModel::validate)
      .def("k_beta", &nf::BallEndModel::k_beta);

  py::class_<nf::BallEndWorkspace>(m, "BallEndWorkspace")
      .def(py::init<const nf::BallEndModel&>(), "model"_a)
      .def("reset", &nf::BallEndWorkspace::reset, "model"_a)
      .def("rows", &nf::BallEndWorkspace::rows)
      .def("heights", &nf::BallEndWorkspace::heights)
      .def("radii", &nf::BallEndWorkspace::radii)
      .def("position_angles", &nf::BallEndWorkspace::position_angles)
      .def("widths", &nf::BallEndWorkspace::widths);

  m.def(
      "ball_end_forces",
      [](const nf::BallEndModel& model, RefVector angles, nf::BallEndWorkspace* ws, const nf::EngagementMap* map) {
        Points3 out(angles.size(), 3);
        if (ws) {
          py::gil_scoped_release rel;
          nf::ball_end_forces(model, *ws, angles, out, map);
        } else {
          nf::BallEndWorkspace w(model);
          py::gil_scoped_release rel;
          nf::ball_end_forces(model, w, angles, out, map);
        }
        return out;
      },
      "model"_a, "angles"_a, "workspace"_a = nullptr, "engagement_map"_a = nullptr,
      "Forces on the cutter (n, 3) [N] (Fz = 0) at rotation angles (n) [rad].");

  m.def("resultant", &nf::resultant, "forces"_a);
  m.def("summarize", [](RefPoints3 f) { return summary_dict(nf::summarize(f)); }, "forces"_a,
        "dict: mean (3), peak (3), peak_resultant, mean_resultant, peak_resultant_xy [N]");
  m.def(
      "summarize_revolutions",
      [](RefVector angles, RefPoints3 f) {
        py::list out;
        for (const auto& s : nf::summarize_revolutions(angles, f)) out.append(summary_dict(s));
        return out;
      },
      "angles"_a, "forces"_a);

  m.def("mean_force_matrix", &nf::mean_force_matrix, "engagement"_a, "feed_per_tooth"_a, "flutes"_a,
        "axial_depth"_a);
  m.def("mean_force", &nf::mean_force, "coefficients"_a, "engagement"_a, "feed_per_tooth"_a, "flutes"_a,
        "axial_depth"_a);
  py::class_<nf::LinearEdgeFit>(m, "LinearEdgeFit")
      .def_readonly("coefficients", &nf::LinearEdgeFit::coefficients)
      .def_readonly("r2", &nf::LinearEdgeFit::r2)
      .def_readonly("residuals", &nf::LinearEdgeFit::residuals);
  m.def("fit_linear_edge_mean_forces", &nf::fit_linear_edge_mean_forces, "engagement"_a, "flutes"_a,
        "axial_depth"_a, "feeds"_a, "mean_forces"_a);
  m.def("ball_end_mean_slot_force", &nf::ball_end_mean_slot_force, "model"_a);
  py::class_<nf::BallEndFit>(m, "BallEndFit")
      .def_readonly("coefficients", &nf::BallEndFit::coefficients)
      .def_readonly("rms_x", &nf::BallEndFit::rms_x)
      .def_readonly("rms_y", &nf::BallEndFit::rms_y);
  m.def("fit_ball_end_mean_forces", &nf::fit_ball_end_mean_forces, "geometry"_a, "depths"_a, "feeds"_a,
        "mean_fx"_a, "mean_fy"_a, "m_min"_a = 0.05, "m_max"_a = 1.5, py::call_guard<py::gil_scoped_release>());
  m.def(
      "linear_edge_basis",
      [](const nf::FlatEndModel& model, RefVector angles) {
        auto B = nf::linear_edge_basis(model, angles);
        py::array_t<double> out({py::ssize_t(6), py::ssize_t(angles.size()), py::ssize_t(3)});
        auto r = out.mutable_unchecked<3>();
        for (int k = 0; k < 6; ++k)
          for (Eigen::Index i = 0; i < angles.size(); ++i)
            for (int j = 0; j < 3; ++j) r(k, i, j) = B[k](i, j);
        return out;
      },
      "model"_a, "angles"_a, "(6, n, 3): force per unit ktc, krc, kac, kte, kre, kae");
  py::class_<nf::TimeSeriesFit>(m, "TimeSeriesFit")
      .def_readonly("coefficients", &nf::TimeSeriesFit::coefficients)
      .def_readonly("phase", &nf::TimeSeriesFit::phase)
      .def_readonly("rms", &nf::TimeSeriesFit::rms)
      .def_readonly("rms_total", &nf::TimeSeriesFit::rms_total);
  m.def("fit_linear_edge_time_series", &nf::fit_linear_edge_time_series, "model"_a, "angles"_a, "forces"_a,
        "phase_steps"_a = 90, py::call_guard<py::gil_scoped_release>());

  py::class_<nf::ProgramForceOptions>(m, "ProgramForceOptions", "Options of simulate_program (sizes [mm], angles [rad]).")
      .def(py::init([](double step, int spr, int bins, double dz, double dpsi, double c, double rpm) {
             return validated(nf::ProgramForceOptions{step, spr, bins, dz, dpsi, c, rpm});
           }),
           "step"_a = 0.5, "samples_per_revolution"_a = 72, "bins"_a = 360, "disk_height"_a = 0.1,
           "element_angle"_a = 0.0349065850398866, "feed_per_tooth"_a = 0.0, "spindle_rpm"_a = 0.0)
      .def_readwrite("step", &nf::ProgramForceOptions::step)
      .def_readwrite("samples_per_revolution", &nf::ProgramForceOptions::samples_per_revolution)
      .def_readwrite("bins", &nf::ProgramForceOptions::bins)
      .def_readwrite("disk_height", &nf::ProgramForceOptions::disk_height)
      .def_readwrite("element_angle", &nf::ProgramForceOptions::element_angle)
      .def_readwrite("feed_per_tooth", &nf::ProgramForceOptions::feed_per_tooth)
      .def_readwrite("spindle_rpm", &nf::ProgramForceOptions::spindle_rpm);
  m.def(
      "simulate_program_core",
      [](netshape::stock::ZMap& stock, const netshape::cutter::Cutter& cutter,
         const netshape::toolpath::Toolpath& program, const nf::LinearEdgeCoefficients* linear_edge,
         const nf::BallEndCoefficients* ball_end, const nf::ProgramForceOptions& options,
         const nf::RunoutSizeEffect* chip) {
        nf::ProgramCoefficients k;
        if (linear_edge) k.linear_edge = *linear_edge;
        if (ball_end) k.ball_end = *ball_end;
        if (chip) k.chip = *chip;
        nf::ProgramForces r;
        {
          py::gil_scoped_release rel;
          r = nf::simulate_program(stock, cutter, program, k, options);
        }
        return py::dict("positions"_a = r.positions, "block"_a = r.block, "feed_direction"_a = r.feed_direction,
                        "mean"_a = r.mean, "peak"_a = r.peak, "peak_resultant"_a = r.peak_resultant,
                        "mean_resultant"_a = r.mean_resultant, "engaged_fraction"_a = r.engaged_fraction,
                        "removed_volume"_a = r.removed_volume);
      },
      "stock"_a, "cutter"_a, "program"_a, "linear_edge"_a = nullptr, "ball_end"_a = nullptr,
      py::arg_v("options", nf::ProgramForceOptions{}, "ProgramForceOptions()"), "chip"_a = nullptr);
}
