// Block arrays with cubic rows into blocks and CubicControls for the planner (motion_arrays.hpp).
#include "motion_arrays.hpp"

#include <string>

#include "netshape/core/error.hpp"

namespace netshape::motion_arrays {

std::vector<toolpath::Block> planned_blocks_from_arrays(
    const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
    py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
    const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
    py_types::RefVector feed, py_types::RefMatrix ctrl, std::vector<motion::CubicControls>& controls) {
  const Eigen::Index n = kind.size();
  NETSHAPE_CHECK(start.rows() == n && end.rows() == n && center.rows() == n && clockwise.size() == n &&
                     plane.size() == n && turns.size() == n && feed.size() == n,
                 "blocks", n, "all block arrays must have the same length");
  NETSHAPE_CHECK(ctrl.rows() == n && ctrl.cols() == 6, "ctrl rows", ctrl.rows(),
                 "ctrl must be (n, 2, 3) (P1, P2 of each block), n = the number of blocks");
  std::vector<toolpath::Block> out(static_cast<std::size_t>(n));
  controls.clear();
  for (Eigen::Index i = 0; i < n; ++i) {
    auto& b = out[static_cast<std::size_t>(i)];
    const auto field = [i](const char* name) { return std::string(name) + "[" + std::to_string(i) + "]"; };
    if (kind[i] < 0 || kind[i] > 3)
      detail::throw_invalid(field("kind").c_str(), kind[i], "must be 0 (rapid), 1 (line), 2 (arc) or 3 (cubic)");
    if (plane[i] < 0 || plane[i] > 2)
      detail::throw_invalid(field("plane").c_str(), plane[i], "must be 0 (xy), 1 (zx) or 2 (yz)");
    const bool cubic = kind[i] == 3;
    b.kind = cubic ? toolpath::MotionKind::line : static_cast<toolpath::MotionKind>(kind[i]);
    b.start = start.row(i).transpose();
    b.end = end.row(i).transpose();
    b.center = center.row(i).transpose();
    b.clockwise = clockwise[i] != 0;
    b.plane = static_cast<toolpath::Plane>(plane[i]);
    b.turns = turns[i];
    b.feed = feed[i];
    b.line = static_cast<long>(i) + 1;
    if (!cubic) continue;
    if (controls.empty()) controls.resize(static_cast<std::size_t>(n));
    motion::CubicControls& c = controls[static_cast<std::size_t>(i)];
    c.cubic = true;
    c.c1 = ctrl.row(i).head<3>().transpose();
    c.c2 = ctrl.row(i).tail<3>().transpose();
    if (!c.c1.allFinite() || !c.c2.allFinite())
      detail::throw_invalid(field("ctrl").c_str(), "non-finite", "the control points P1, P2 must be finite [mm]");
  }
  return out;
}

pybind11::dict block_arrays(const std::vector<toolpath::Block>& blocks,
                            const std::vector<motion::CubicControls>& controls) {
  const auto n = static_cast<Eigen::Index>(blocks.size());
  Eigen::VectorXi k(n), cw(n), pl(n), tu(n);
  Points3 s(n, 3), e(n, 3), c(n, 3);
  VectorXd f(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& b = blocks[static_cast<std::size_t>(i)];
    k[i] = static_cast<int>(b.kind);
    cw[i] = b.clockwise ? 1 : 0;
    pl[i] = static_cast<int>(b.plane);
    tu[i] = b.turns;
    s.row(i) = b.start.transpose();
    e.row(i) = b.end.transpose();
    c.row(i) = b.center.transpose();
    f[i] = b.feed;
  }
  pybind11::array_t<double> ctrl({static_cast<pybind11::ssize_t>(n), pybind11::ssize_t{2}, pybind11::ssize_t{3}});
  auto cv = ctrl.mutable_unchecked<3>();
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto idx = static_cast<std::size_t>(i);
    const bool cubic = idx < controls.size() && controls[idx].cubic;
    if (cubic) k[i] = 3;
    for (int a = 0; a < 3; ++a) {
      cv(i, 0, a) = cubic ? controls[idx].c1[a] : 0.0;
      cv(i, 1, a) = cubic ? controls[idx].c2[a] : 0.0;
    }
  }
  pybind11::dict arrays;
  arrays["kind"] = k;
  arrays["start"] = s;
  arrays["end"] = e;
  arrays["center"] = c;
  arrays["clockwise"] = cw;
  arrays["plane"] = pl;
  arrays["turns"] = tu;
  arrays["feed"] = f;
  arrays["ctrl"] = ctrl;
  return arrays;
}

std::vector<toolpath::Block> program_blocks_from_arrays(
    const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
    py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
    const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
    py_types::RefVector feed) {
  const Eigen::Index n = kind.size();
  for (Eigen::Index i = 0; i < n; ++i)
    if (kind[i] < 0 || kind[i] > 2)
      netshape::detail::throw_invalid(("kind[" + std::to_string(i) + "]").c_str(), kind[i],
                                      "must be 0 (rapid), 1 (line) or 2 (arc) in a program (cubic blocks, kind 3, "
                                      "only where the arrays are planned)");
  const MatrixXdR no_ctrl = MatrixXdR::Zero(n, 6);
  std::vector<motion::CubicControls> controls;
  return planned_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns, feed, no_ctrl, controls);
}

std::vector<toolpath::Block> program_blocks(const std::vector<toolpath::Block>& blocks) {
  std::vector<toolpath::Block> out(blocks);
  const toolpath::Block fresh;
  for (std::size_t i = 0; i < out.size(); ++i) {  // what the columns do not carry: as a fresh Block
    out[i].spindle_rpm = fresh.spindle_rpm;
    out[i].tool = fresh.tool;
    out[i].line = static_cast<long>(i) + 1;
  }
  return out;
}

motion::Status drain(motion::Planner& p, motion::PlannedSegment& seg, long& segments, double& t_end) {
  for (;;) {
    const motion::Status st = p.next_segment(seg);
    if (st != motion::Status::ok) return st;
    ++segments;
    t_end = seg.t0 + seg.profile.duration;
  }
}

}  // namespace netshape::motion_arrays
