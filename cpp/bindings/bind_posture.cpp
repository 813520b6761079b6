// Bindings of the `posture` area (netshape._core.posture). Thin: lambdas only turn out-parameters into
// returns and std::vector<bool> / structs of boundary points into NumPy arrays.
#include "default_types.hpp"
#include "netshape/geometry/triangle_mesh.hpp"
#include "netshape/posture.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::posture;
using netshape::py_types::RefPoints3;
using netshape::py_types::RefVector;

namespace {
py::array_t<bool> bools(const std::vector<bool>& v) {
  py::array_t<bool> out(static_cast<py::ssize_t>(v.size()));
  auto* p = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) p[i] = v[i];
  return out;
}
}  // namespace

void bind_posture(py::module_& m) {
  py::class_<CutterAssembly>(m, "CutterAssembly",
                             "Ball-end cutter assembly: ball + shank cylinder + holder (flat-faced cylinder or a "
                             "(z, r) profile of frustums), solids of revolution; lengths from the tip [mm]")
      .def(py::init<>())
      .def(py::init([](double R, double rs, double ls, double rh, double lh) {
             CutterAssembly a{R, rs, ls, rh, lh, {}};
             a.validate();
             return a;
           }),
           py::arg("ball_radius"), py::arg("shank_radius"), py::arg("shank_length"), py::arg("holder_radius"),
           py::arg("holder_length"))
      .def_readwrite("ball_radius", &CutterAssembly::ball_radius, "[mm]")
      .def_readwrite("shank_radius", &CutterAssembly::shank_radius, "[mm]")
      .def_readwrite("shank_length", &CutterAssembly::shank_length, "tip to the end of the shank [mm]")
      .def_readwrite("holder_radius", &CutterAssembly::holder_radius, "[mm]")
      .def_readwrite("holder_length", &CutterAssembly::holder_length, "tip to the end of the holder [mm]")
      .def_readwrite("holder_profile", &CutterAssembly::holder_profile,
                     "(k, 2) (z [mm] from the tip, r [mm]) of the holder; empty = the flat-faced cylinder")
      .def("validate", &CutterAssembly::validate)
      .def("reach", &CutterAssembly::reach, "largest distance of a point of the solid from the tip [mm]")
      .def("distance", &CutterAssembly::distance, py::arg("z"), py::arg("rho"),
           "exact distance [mm] from the meridian point (z, rho) to the solid (0 inside)")
      .def_property_readonly("sections", [](const CutterAssembly& a) {
        const auto secs = a.sections();
        MatrixXdR out(static_cast<Eigen::Index>(secs.size()), 4);
        for (std::size_t i = 0; i < secs.size(); ++i) {
          out.row(static_cast<Eigen::Index>(i)) << secs[i].z0, secs[i].z1, secs[i].r0, secs[i].r1;
        }
        return out;
      }, "(k, 4): z0, z1, r0, r1 [mm] of the shank and holder frustums, bottom to top (the ball is separate)");

  py::class_<InterferenceChecker>(m, "InterferenceChecker")
      .def(py::init<geometry::TriangleMesh, CutterAssembly, double, double>(), py::arg("obstacles"),
           py::arg("assembly"), py::arg("clearance"), py::arg("tolerance") = 1e-3)
      .def_property_readonly("obstacles", &InterferenceChecker::obstacles)
      .def_property_readonly("assembly", &InterferenceChecker::assembly)
      .def_property_readonly("clearance", &InterferenceChecker::clearance)
      .def_property_readonly("tolerance", &InterferenceChecker::tolerance)
      .def("collides", [](const InterferenceChecker& c, RefPoints3 tips, RefPoints3 axes) {
             std::vector<bool> r;
             {
               py::gil_scoped_release rel;
               r = c.collides(tips, axes);
             }
             return bools(r);
           }, py::arg("tips"), py::arg("axes"), "(n,) bool: closer than the clearance, tips/axes (n, 3)")
      .def("gap", &InterferenceChecker::gap, py::arg("tip"), py::arg("axis"),
           "least distance between assembly and mesh [mm] (to the tolerance)")
      .def("clear_by", &InterferenceChecker::clear_by, py::arg("tip"), py::arg("axis"), py::arg("margin"),
           "+1 gap certainly >= clearance + margin, -1 certainly < clearance, 0 undecided")
      .def_property_readonly("gjk_runs", &InterferenceChecker::gjk_runs,
                             "frustum-triangle GJK runs of all queries so far (the work; shared by copies)");

  py::class_<CSpaceOptions>(m, "CSpaceOptions")
      .def(py::init<>())
      .def_readwrite("theta_max", &CSpaceOptions::theta_max, "[rad]")
      .def_readwrite("theta_step", &CSpaceOptions::theta_step, "[rad]")
      .def_readwrite("phi_step", &CSpaceOptions::phi_step, "[rad]")
      .def_readwrite("tolerance", &CSpaceOptions::tolerance, "bisection tolerance [rad]")
      .def("validate", &CSpaceOptions::validate);

  py::class_<PostureFrame>(m, "PostureFrame")
      .def_static("make", [](const Vec3& cc, const Vec3& n, const Vec3& f) { return PostureFrame::make(cc, n, f); },
                  py::arg("cc"), py::arg("normal"), py::arg("feed"))
      .def_readonly("cc", &PostureFrame::cc)
      .def_readonly("normal", &PostureFrame::normal)
      .def_readonly("feed", &PostureFrame::feed)
      .def_readonly("left", &PostureFrame::left)
      .def("axis", &PostureFrame::axis, py::arg("theta"), py::arg("phi"))
      .def("posture", &PostureFrame::posture, py::arg("axis"));

  py::class_<CSpace>(m, "CSpace")
      .def_readonly("frame", &CSpace::frame)
      .def_readonly("options", &CSpace::options)
      .def_readonly("checks", &CSpace::checks)
      .def_property_readonly("thetas", [](const CSpace& c) {
        VectorXd t(c.count_theta);
        for (int k = 0; k < c.count_theta; ++k) t[k] = c.theta(k);
        return t;
      }, "(count_theta,) [rad]")
      .def_property_readonly("phis", [](const CSpace& c) {
        VectorXd t(c.count_phi);
        for (int j = 0; j < c.count_phi; ++j) t[j] = c.phi(j);
        return t;
      }, "(count_phi,) [rad]")
      .def_property_readonly("states", [](const CSpace& c) {
        py::array_t<std::int8_t> out({static_cast<py::ssize_t>(c.count_phi), static_cast<py::ssize_t>(c.count_theta)});
        auto* p = out.mutable_data();
        for (std::size_t i = 0; i < c.states.size(); ++i) p[i] = static_cast<std::int8_t>(c.states[i]);
        return out;
      }, "(count_phi, count_theta) int8: 0 free, 1 CA1 (left), 2 CA2 (right)")
      .def_property_readonly("boundary", [](const CSpace& c) {
        MatrixXdR b(static_cast<Eigen::Index>(c.boundary.size()), 3);
        for (std::size_t i = 0; i < c.boundary.size(); ++i) {
          b.row(static_cast<Eigen::Index>(i)) << c.boundary[i].theta, c.boundary[i].phi, c.boundary[i].obstacle;
        }
        return b;
      }, "(m, 3): theta [rad], phi [rad], obstacle (1 or 2)")
      .def("mc_posture", &CSpace::mc_posture, py::arg("posture"))
      .def("nearest_boundary", &CSpace::nearest_boundary, py::arg("posture"), py::arg("obstacle"));

  m.def("classify", [](const InterferenceChecker& c, const PostureFrame& f, double t, double p) {
    return static_cast<int>(classify(c, f, t, p));
  }, py::arg("checker"), py::arg("frame"), py::arg("theta"), py::arg("phi"), "0 free, 1 CA1, 2 CA2");
  m.def("compute_cspace", [](const InterferenceChecker& c, const PostureFrame& f, const CSpaceOptions& o) {
    return compute_cspace(c, f, o);
  }, py::arg("checker"), py::arg("frame"), py::arg_v("options", CSpaceOptions(), "CSpaceOptions()"),
        py::call_guard<py::gil_scoped_release>());

  m.def("mb_spline_point", &mb_spline_point, py::arg("control"), py::arg("span"), py::arg("u"));
  m.def("mb_spline_derivative", &mb_spline_derivative, py::arg("control"), py::arg("span"), py::arg("u"));
  m.def("mb_spline_joins", &mb_spline_joins, py::arg("control"));
  m.def("mb_smooth", &mb_smooth, py::arg("points"), py::arg("passes") = 1);

  py::class_<PlanOptions>(m, "PlanOptions")
      .def(py::init<>())
      .def_readwrite("cspace", &PlanOptions::cspace)
      .def_readwrite("passes", &PlanOptions::passes, "MB-spline smoothing passes")
      .def_readwrite("vector_length", &PlanOptions::vector_length, "posture vector length [mm], 0 = holder_length")
      .def("validate", &PlanOptions::validate);

  py::class_<PostureSet>(m, "PostureSet")
      .def_readonly("tips", &PostureSet::tips, "(n, 3) [mm]")
      .def_readonly("axes", &PostureSet::axes, "(n, 3) unit")
      .def_readonly("angles", &PostureSet::angles, "(n, 2) theta, phi [rad]")
      .def_property_readonly("collides", [](const PostureSet& s) { return bools(s.collides); })
      .def("collision_count", &PostureSet::collision_count);

  py::class_<PlanResult>(m, "PlanResult")
      .def_readonly("s", &PlanResult::s, "(n,) path length [mm]")
      .def_readonly("cc", &PlanResult::cc)
      .def_readonly("normals", &PlanResult::normals)
      .def_readonly("feeds", &PlanResult::feeds)
      .def_readonly("raw", &PlanResult::raw)
      .def_readonly("mc", &PlanResult::mc)
      .def_readonly("smoothed", &PlanResult::smoothed)
      .def_readonly("final", &PlanResult::final_)
      .def_property_readonly("repaired", [](const PlanResult& r) { return bools(r.repaired); })
      .def_readonly("cspaces", &PlanResult::cspaces)
      .def_readonly("checks", &PlanResult::checks)
      .def("repaired_count", &PlanResult::repaired_count);

  m.def("plan", [](const InterferenceChecker& c, RefPoints3 cc, RefPoints3 normals, const PlanOptions& o) {
    return plan(c, cc, normals, o);
  }, py::arg("checker"), py::arg("cc"), py::arg("normals"), py::arg_v("options", PlanOptions(), "PlanOptions()"),
        py::call_guard<py::gil_scoped_release>());
  m.def("max_posture_change", &max_posture_change, py::arg("s"), py::arg("axes"), "[rad/mm]");

  py::enum_<MachineKind>(m, "MachineKind")
      .value("table_ac", MachineKind::table_ac)
      .value("head_bc", MachineKind::head_bc);
  py::class_<Kinematics>(m, "Kinematics")
      .def(py::init<>())
      .def_readwrite("kind", &Kinematics::kind)
      .def_readwrite("table_centre", &Kinematics::table_centre, "[mm]")
      .def_readwrite("pivot_length", &Kinematics::pivot_length, "[mm]")
      .def_readwrite("tilt_min", &Kinematics::tilt_min, "[rad]")
      .def_readwrite("tilt_max", &Kinematics::tilt_max, "[rad]")
      .def("validate", &Kinematics::validate);
  m.def("inverse_kinematics", &inverse_kinematics, py::arg("kinematics"), py::arg("tips"), py::arg("axes"),
        py::arg("c_start") = 0.0, "(n, 5): X, Y, Z [mm], tilt (A or B) [rad], C [rad]");
  m.def("forward_kinematics", [](const Kinematics& k, Eigen::Ref<const MatrixXdR> j) {
    Points3 t, a;
    forward_kinematics(k, j, t, a);
    return py::make_tuple(t, a);
  }, py::arg("kinematics"), py::arg("joints"), "(tips (n, 3), axes (n, 3))");
  py::class_<MoveCheck>(m, "MoveCheck")
      .def_readonly("collides", &MoveCheck::collides)
      .def_readonly("at", &MoveCheck::at, "lambda of the colliding pose found")
      .def_readonly("checks", &MoveCheck::checks);
  py::class_<MovePlan>(m, "MovePlan")
      .def_readonly("tips", &MovePlan::tips, "(m, 3) [mm]")
      .def_readonly("axes", &MovePlan::axes, "(m, 3) unit")
      .def_readonly("source", &MovePlan::source, "(m,) CC index + fraction to the next (-1 approach, n retract)")
      .def_readonly("joints", &MovePlan::joints, "(m, 5) X, Y, Z [mm], tilt, C [rad]")
      .def_property_readonly("move_collides", [](const MovePlan& p) { return bools(p.move_collides); },
                             "(m - 1,) bool: certified check of every move")
      .def_readonly("colliding_before", &MovePlan::colliding_before)
      .def_readonly("inserted", &MovePlan::inserted)
      .def_readonly("checks", &MovePlan::checks);
  m.def("move_speed_bound", &move_speed_bound, py::arg("kinematics"), py::arg("assembly"), py::arg("j0"),
        py::arg("j1"), "largest displacement of any assembly point per unit lambda [mm]");
  m.def("check_move", &check_move, py::arg("checker"), py::arg("kinematics"), py::arg("j0"), py::arg("j1"),
        py::arg("min_step") = 1e-4, py::call_guard<py::gil_scoped_release>());
  m.def("check_moves", [](const InterferenceChecker& c, const Kinematics& k, Eigen::Ref<const MatrixXdR> j,
                          double min_step) {
    std::vector<MoveCheck> r;
    {
      py::gil_scoped_release rel;
      r = check_moves(c, k, j, min_step);
    }
    std::vector<bool> hit;
    for (const auto& x : r) hit.push_back(x.collides);
    return bools(hit);
  }, py::arg("checker"), py::arg("kinematics"), py::arg("joints"), py::arg("min_step") = 1e-4,
        "(n - 1,) bool: certified check of the joint-linear moves between joints (n, 5)");
  m.def("plan_program", &plan_program, py::arg("checker"), py::arg("kinematics"), py::arg("plan"),
        py::arg_v("options", PlanOptions(), "PlanOptions()"), py::arg("approach") = 10.0, py::arg("chord") = 0.01,
        py::arg("max_depth") = 4, py::call_guard<py::gil_scoped_release>());
  m.def("subdivide_rotary", [](const Kinematics& k, RefPoints3 tips, RefPoints3 axes, double chord) {
    Points3 t, a;
    VectorXd src;
    subdivide_rotary(k, tips, axes, chord, t, a, &src);
    return py::make_tuple(t, a, src);
  }, py::arg("kinematics"), py::arg("tips"), py::arg("axes"), py::arg("chord"),
        "(tips (m, 3), axes (m, 3), source (m,)): CL points inserted where the tip leaves a chord by > chord mm");
}
