// Bindings of feed scheduling (netshape._core.compensation): the sample pass and the pieces.
#include "default_types.hpp"
#include "netshape/compensation/feed_schedule.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

void bind_feed_schedule(py::module_& m) {
  namespace nc = netshape::compensation;
  namespace nf = netshape::force;
  py::enum_<nc::FeedLimit>(m, "FeedLimit", "What sets a piece's feed (docs/feeds.md).")
      .value("force", nc::FeedLimit::force)
      .value("chip", nc::FeedLimit::chip)
      .value("deflection", nc::FeedLimit::deflection)
      .value("wall_error", nc::FeedLimit::wall_error)
      .value("power", nc::FeedLimit::power)
      .value("torque", nc::FeedLimit::torque)
      .value("max_feed", nc::FeedLimit::max_feed)
      .value("air", nc::FeedLimit::air)
      .value("programmed", nc::FeedLimit::programmed);
  m.def("feed_limit_name", [](int k) { return std::string(nc::to_string(static_cast<nc::FeedLimit>(k))); },
        "code"_a, "The limit's key (max_force_N, …, air_feed_mm_min, programmed) of a FeedLimit code.");
  py::class_<nc::FeedLimits>(m, "FeedLimits", "Limits of a feed schedule (forces [N], lengths [mm], feeds [mm/s], "
                                              "power [W], torque [N·m]); inf: not stated.")
      .def(py::init<>())
      .def_readwrite("max_force", &nc::FeedLimits::max_force)
      .def_readwrite("max_chip", &nc::FeedLimits::max_chip)
      .def_readwrite("min_chip", &nc::FeedLimits::min_chip)
      .def_readwrite("max_deflection", &nc::FeedLimits::max_deflection)
      .def_readwrite("max_wall_error", &nc::FeedLimits::max_wall_error)
      .def_readwrite("max_power", &nc::FeedLimits::max_power)
      .def_readwrite("max_torque", &nc::FeedLimits::max_torque)
      .def_readwrite("min_feed", &nc::FeedLimits::min_feed)
      .def_readwrite("max_feed", &nc::FeedLimits::max_feed)
      .def_readwrite("air_feed", &nc::FeedLimits::air_feed)
      .def("validate", &nc::FeedLimits::validate);
  m.def(
      "feed_samples_core",
      [](netshape::stock::ZMap& stock, const netshape::cutter::Cutter& cutter,
         const netshape::toolpath::Toolpath& program, const nc::FeedLimits& limits,
         const nf::ProgramForceOptions& sampling, const nf::LinearEdgeCoefficients* linear_edge,
         const nf::BallEndCoefficients* ball_end) {
        nf::ProgramCoefficients k;
        if (linear_edge) k.linear_edge = *linear_edge;
        if (ball_end) k.ball_end = *ball_end;
        nc::FeedScheduleOptions opt;
        opt.sampling = sampling;
        nc::FeedSamples r;
        {
          py::gil_scoped_release rel;
          r = nc::feed_samples(stock, cutter, program, k, limits, opt);
        }
        return py::dict("positions"_a = r.positions, "block"_a = r.block, "fraction"_a = r.fraction,
                        "feed_direction"_a = r.feed_direction, "spindle_rpm"_a = r.spindle_rpm,
                        "engaged"_a = r.engaged, "walls"_a = r.walls, "depth"_a = r.depth,
                        "chip_factor"_a = r.chip_factor, "engaged_share"_a = r.engaged_share,
                        "allowed"_a = r.allowed, "lowest"_a = r.lowest,
                        "force"_a = r.force, "deflection"_a = r.deflection,
                        "wall_error"_a = r.wall_error, "removed_volume"_a = r.removed_volume);
      },
      "stock"_a, "cutter"_a, "program"_a, "limits"_a, "sampling"_a, "linear_edge"_a = nullptr,
      "ball_end"_a = nullptr, "Per force sample, the largest feed [mm/s] each limit allows (netshape.compensation.feeds).");
  m.def(
      "feed_pieces_core",
      [](const netshape::toolpath::Toolpath& program, const Eigen::Ref<const Eigen::VectorXi>& block,
         const Eigen::Ref<const netshape::VectorXd>& fraction, const Eigen::Ref<const Eigen::VectorXi>& engaged,
         const Eigen::Ref<const Eigen::VectorXi>& walls, const Eigen::Ref<const netshape::VectorXd>& depth,
         const Eigen::Ref<const netshape::VectorXd>& chip_factor,
         const Eigen::Ref<const netshape::VectorXd>& engaged_share,
         const Eigen::Ref<const netshape::MatrixXdR>& allowed, const nc::FeedLimits& limits, double tolerance,
         double min_length) {
        nc::FeedSamples s;
        s.block = block;
        s.fraction = fraction;
        s.engaged = engaged;
        s.walls = walls;
        s.depth = depth;
        s.chip_factor = chip_factor;
        s.engaged_share = engaged_share;
        const nc::FeedPieces r = nc::feed_pieces(program, s, allowed, limits, tolerance, min_length);
        return py::dict("block"_a = r.block, "start"_a = r.start, "end"_a = r.end, "feed"_a = r.feed,
                        "binding"_a = r.binding, "sample"_a = r.sample);
      },
      "program"_a, "block"_a, "fraction"_a, "engaged"_a, "walls"_a, "depth"_a, "chip_factor"_a, "engaged_share"_a,
      "allowed"_a,
      "limits"_a, "tolerance"_a = 0.1, "min_length"_a = 1.0,
      "Pieces of the feed blocks and their feeds [mm/s] (netshape.compensation.feeds).");
}
