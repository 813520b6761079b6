// Bindings of the `motion` area (netshape._core.motion). Thin: lambdas turn out-parameters into returns;
// the bench drivers (_smooth_plan, _throughput) loop in C++ so that Python stays out of what they time.
#include <atomic>
#include <chrono>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "default_types.hpp"
#include "motion_arrays.hpp"
#include "netshape/core/error.hpp"
#include "netshape/motion.hpp"
#include "netshape/toolpath/block_arrays.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::motion;

using motion_arrays::drain;

void bind_motion_smooth(py::module_& m);  // bind_motion_smooth.cpp

namespace {

// plan() of blocks with their cubic controls as the tuple (t, position, velocity, feed, block, stats).
py::tuple plan_tuple(const std::vector<toolpath::Block>& blocks, const std::vector<CubicControls>& controls,
                     const AxisLimits& limits, const PlanOptions& options, bool with_deviation, long max_samples) {
  Trajectory tr;
  {
    py::gil_scoped_release release;
    tr = plan(blocks, controls, limits, options, with_deviation, max_samples);
  }
  const auto& s = tr.stats;
  py::dict stats;
  stats["blocks"] = s.blocks;
  stats["samples"] = s.samples;
  stats["cycle_time_s"] = s.cycle_time;
  stats["max_axis_velocity_mm_s"] = s.max_axis_velocity;
  stats["max_axis_accel_mm_s2"] = s.max_axis_acceleration;
  stats["max_axis_jerk_mm_s3"] = s.max_axis_jerk;
  stats["axis_velocity_mm_s"] = std::vector<double>{s.axis_velocity[0], s.axis_velocity[1], s.axis_velocity[2]};
  stats["axis_accel_mm_s2"] = std::vector<double>{s.axis_acceleration[0], s.axis_acceleration[1], s.axis_acceleration[2]};
  stats["axis_jerk_mm_s3"] = std::vector<double>{s.axis_jerk[0], s.axis_jerk[1], s.axis_jerk[2]};
  stats["max_path_deviation_mm"] = s.max_path_deviation;
  stats["end_error_mm"] = s.end_error;
  return py::make_tuple(std::move(tr.t), std::move(tr.position), std::move(tr.velocity), std::move(tr.feed),
                        std::move(tr.block), stats);
}

}  // namespace

void bind_motion(py::module_& m) {
  py::class_<AxisLimits>(m, "AxisLimits", "Per-axis limits: velocity [mm/s], acceleration [mm/s^2], jerk [mm/s^3] (inf: none).")
      .def(py::init<>())
      .def(py::init([](const Vec3& v, const Vec3& a, const Vec3& j) {
             AxisLimits l;
             l.velocity = v;
             l.acceleration = a;
             l.jerk = j;
             l.validate();
             return l;
           }),
           py::arg("velocity"), py::arg("acceleration"),
           py::arg("jerk") = Vec3::Constant(std::numeric_limits<double>::infinity()))
      .def_static("uniform", &AxisLimits::uniform, py::arg("vmax"), py::arg("amax"),
                  py::arg("jmax") = std::numeric_limits<double>::infinity())
      .def_readwrite("velocity", &AxisLimits::velocity)
      .def_readwrite("acceleration", &AxisLimits::acceleration)
      .def_readwrite("jerk", &AxisLimits::jerk)
      .def("jerk_limited", &AxisLimits::jerk_limited)
      .def("validate", &AxisLimits::validate);

  py::enum_<CornerRule>(m, "CornerRule")
      .value("paper", CornerRule::paper)
      .value("vector", CornerRule::vector)
      .value("per_axis", CornerRule::per_axis)
      .value("junction_deviation", CornerRule::junction_deviation)
      .value("blend", CornerRule::blend);
  m.def("rule_name", &rule_name);
  m.def("parse_rule", &parse_rule, py::arg("name"));
  py::enum_<JunctionAccel>(m, "JunctionAccel")
      .value("min_moving_axis", JunctionAccel::min_moving_axis)
      .value("along_change", JunctionAccel::along_change);
  m.def("junction_accel_name", &junction_accel_name);
  m.def("parse_junction_accel", &parse_junction_accel, py::arg("name"));

  py::class_<PlanOptions>(m, "PlanOptions", "Planner options (periods [s], look-ahead [blocks], tolerances [mm]).")
      .def(py::init<>())
      .def_readwrite("rule", &PlanOptions::rule)
      .def_readwrite("ts1", &PlanOptions::ts1)
      .def_readwrite("ts2", &PlanOptions::ts2)
      .def_readwrite("lookahead", &PlanOptions::lookahead)
      .def_readwrite("allowable_speed_difference", &PlanOptions::allowable_speed_difference)
      .def_readwrite("tolerance", &PlanOptions::tolerance)
      .def_readwrite("corner_tolerance", &PlanOptions::corner_tolerance)
      .def_readwrite("junction_deviation", &PlanOptions::junction_deviation)
      .def_readwrite("square_corner_velocity", &PlanOptions::square_corner_velocity)
      .def_readwrite("junction_accel", &PlanOptions::junction_accel)
      .def_readwrite("centripetal_fraction", &PlanOptions::centripetal_fraction)
      .def("validate", &PlanOptions::validate)
      .def("fine_steps", &PlanOptions::fine_steps);

  m.def("turn_angle", &turn_angle, py::arg("u1"), py::arg("u2"));
  m.def("paper_corner_speed", &paper_corner_speed, py::arg("acc"), py::arg("ts"), py::arg("theta"));
  m.def("vector_corner_speed", &vector_corner_speed, py::arg("u1"), py::arg("u2"), py::arg("acc"), py::arg("ts"));
  m.def("per_axis_corner_speed", &per_axis_corner_speed, py::arg("u1"), py::arg("u2"), py::arg("acc"), py::arg("ts"));
  m.def("junction_deviation_speed", &junction_deviation_speed, py::arg("acc"), py::arg("deviation"), py::arg("turn"));
  m.def("junction_acceleration", &junction_acceleration, py::arg("acc"), py::arg("u1"), py::arg("u2"),
        py::arg("mode"));
  m.def("junction_deviation_corner_speed", &junction_deviation_corner_speed, py::arg("u1"), py::arg("u2"),
        py::arg("acc"), py::arg("deviation"), py::arg("mode"));
  m.def("klipper_junction_deviation", &klipper_junction_deviation, py::arg("square_corner_velocity"), py::arg("acc"));
  m.def("reach_speed", &reach_speed, py::arg("v"), py::arg("length"), py::arg("a"),
        py::arg("j") = std::numeric_limits<double>::infinity());

  py::enum_<Status>(m, "Status")
      .value("ok", Status::ok)
      .value("buffer_full", Status::buffer_full)
      .value("need_blocks", Status::need_blocks)
      .value("finished", Status::finished)
      .value("invalid_input", Status::invalid_input);

  py::class_<Sample>(m, "Sample")
      .def(py::init<>())
      .def_readonly("t", &Sample::t)
      .def_readonly("position", &Sample::position)
      .def_readonly("velocity", &Sample::velocity)
      .def_readonly("feed", &Sample::feed)
      .def_readonly("path_acceleration", &Sample::path_acceleration)
      .def_readonly("block", &Sample::block);

  py::class_<Planner>(m, "Planner", "Streaming planner: push blocks, pull fine samples (see docs/motion.md).")
      .def(py::init<const AxisLimits&, const PlanOptions&>(), py::arg("limits"), py::arg("options"))
      .def("push_arrays",
           [](Planner& p, int kind, const Vec3& start, const Vec3& end, const Vec3& center, bool clockwise, int plane,
              int turns, double feed) {
             toolpath::Block b;
             NETSHAPE_CHECK(kind >= 0 && kind <= 2, "kind", kind, "must be 0 (rapid), 1 (line) or 2 (arc)");
             NETSHAPE_CHECK(plane >= 0 && plane <= 2, "plane", plane, "must be 0, 1 or 2");
             b.kind = static_cast<toolpath::MotionKind>(kind);
             b.start = start;
             b.end = end;
             b.center = center;
             b.clockwise = clockwise;
             b.plane = static_cast<toolpath::Plane>(plane);
             b.turns = turns;
             b.feed = feed;
             return p.push(b);
           },
           py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center") = Vec3::Zero(),
           py::arg("clockwise") = false, py::arg("plane") = 0, py::arg("turns") = 1, py::arg("feed") = 0.0)
      .def("finish", &Planner::finish)
      .def("next", [](Planner& p) {
        Sample s;
        const Status st = p.next(s);
        return py::make_tuple(st, s);
      })
      .def("reset", &Planner::reset)
      .def("free_blocks", &Planner::free_blocks)
      .def("end_time", &Planner::end_time)
      .def("last_error", [](const Planner& p) { return std::string(p.last_error()); });

  m.def(
      "_plan_arrays",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, py_types::RefMatrix ctrl, const AxisLimits& limits, const PlanOptions& options,
         bool with_deviation, long max_samples) {
        std::vector<CubicControls> controls;
        const auto blocks = motion_arrays::planned_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns,
                                                                      feed, ctrl, controls);
        return plan_tuple(blocks, controls, limits, options, with_deviation, max_samples);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("ctrl"), py::arg("limits"), py::arg("options"),
      py::arg("with_deviation") = true, py::arg("max_samples") = 0L);
  // _plan_arrays on a Toolpath or BlockArrays as it is (no cubic blocks; no columns through Python).
  m.def(
      "_plan_program",
      [](const toolpath::Toolpath& program, const AxisLimits& limits, const PlanOptions& options, bool with_deviation,
         long max_samples) {
        return plan_tuple(motion_arrays::program_blocks(program.blocks), {}, limits, options, with_deviation,
                          max_samples);
      },
      py::arg("program"), py::arg("limits"), py::arg("options"), py::arg("with_deviation") = true,
      py::arg("max_samples") = 0L);
  m.def(
      "_plan_program",
      [](const toolpath::BlockArrays& program, const AxisLimits& limits, const PlanOptions& options,
         bool with_deviation, long max_samples) {
        return plan_tuple(motion_arrays::program_blocks(program.to_blocks()), {}, limits, options, with_deviation,
                          max_samples);
      },
      py::arg("program"), py::arg("limits"), py::arg("options"), py::arg("with_deviation") = true,
      py::arg("max_samples") = 0L);

  m.def(
      "_throughput",
      [](py_types::RefPoints3 points, double feed, const AxisLimits& limits, const PlanOptions& options, int repeat) {
        // planning only (push + look-ahead + freeze of every segment), no sampling: blocks per second
        Planner p(limits, options);
        PlannedSegment seg;
        long segments = 0;
        double t_end = 0;
        const Eigen::Index n = points.rows();
        py::gil_scoped_release release;
        for (int r = 0; r < repeat; ++r) {
          p.reset();
          toolpath::Block b;
          b.kind = toolpath::MotionKind::line;
          b.feed = feed;
          Eigen::Index i = 1;
          for (;;) {
            const Status st = drain(p, seg, segments, t_end);
            if (st != Status::need_blocks) break;
            while (i < n) {
              b.start = points.row(i - 1).transpose();
              b.end = points.row(i).transpose();
              if (p.push(b) == Status::buffer_full) break;
              ++i;
            }
            if (i >= n) p.finish();
          }
        }
        py::gil_scoped_acquire acquire;
        return py::make_tuple(segments, t_end);
      },
      py::arg("points"), py::arg("feed"), py::arg("limits"), py::arg("options"), py::arg("repeat") = 1);
  m.def(
      "_path_points",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, py_types::RefMatrix ctrl, const AxisLimits& limits, const PlanOptions& options,
         double ds) {
        // The planned (for the blend rule: blended) path, sampled every ds [mm] of arc length and at every
        // segment end: (m, 3) points and their (m,) arc lengths; plus the planned cycle time [s].
        NETSHAPE_CHECK(ds > 0, "ds", ds, "must be positive [mm]");
        std::vector<CubicControls> controls;
        const auto blocks = motion_arrays::planned_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns,
                                                                      feed, ctrl, controls);
        static const CubicControls none;
        Planner p(limits, options);
        PlannedSegment seg;
        std::vector<Vec3> pts;
        std::vector<double> arc;
        double s0 = 0, t_end = 0;
        std::size_t i = 0;
        for (;;) {
          const Status st = p.next_segment(seg);
          if (st == Status::ok) {
            const double L = seg.segment.length();
            t_end = seg.t0 + seg.profile.duration;
            if (L <= 0) continue;
            const int n = std::max(1, static_cast<int>(std::ceil(L / ds)));
            for (int k = pts.empty() ? 0 : 1; k <= n; ++k) {
              pts.push_back(seg.segment.point_at(L * k / n));
              arc.push_back(s0 + L * k / n);
            }
            s0 += L;
            continue;
          }
          if (st == Status::finished) break;
          while (i < blocks.size()) {
            const Status ps = p.push(blocks[i], controls.empty() ? none : controls[i]);
            if (ps == Status::buffer_full) break;
            if (ps == Status::invalid_input) throw std::invalid_argument(p.last_error());
            ++i;
          }
          if (i == blocks.size()) p.finish();
        }
        Points3 out(static_cast<Eigen::Index>(pts.size()), 3);
        for (std::size_t k = 0; k < pts.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = pts[k].transpose();
        Eigen::VectorXd s = Eigen::Map<Eigen::VectorXd>(arc.data(), static_cast<Eigen::Index>(arc.size()));
        return py::make_tuple(out, s, t_end);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("ctrl"), py::arg("limits"), py::arg("options"), py::arg("ds"));
  bind_motion_smooth(m);
}
