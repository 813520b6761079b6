// The tolerance-band smoothing stage (netshape/motion/smoothing.hpp): smooth() walks the program —
// runs and corners: runs.cpp; a run's curve: run_fit.cpp (its fit fit.hpp, its check check.hpp, the
// spline spline.hpp) — then turns corners between lines into arcs (round.hpp). stage.hpp says which
// part does what.
#include "netshape/motion/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "motion/kernels/smoothing_kernels.hpp"
#include "motion/smoothing/round.hpp"
#include "motion/smoothing/stage.hpp"
#include "netshape/core/error.hpp"
#include "netshape/motion/segment.hpp"

namespace netshape::motion {

namespace detail {
const SmoothingKernels& smoothing_kernels_plain() { return baseline::smoothing_kernel_table; }

const SmoothingKernels& smoothing_kernels() {
  static const SmoothingKernels& chosen = NETSHAPE_SIMD_SELECT(detail, smoothing_kernel_table);
  return chosen;
}
}  // namespace detail

namespace {
SmoothResult smooth_program(const std::vector<toolpath::Block>& program, const SmoothOptions& opt,
                            const Vec3* first_start);
}  // namespace

SmoothResult smooth(const std::vector<toolpath::Block>& program, const SmoothOptions& opt) {
  return smooth_program(program, opt, nullptr);
}

SmoothResult smooth(const std::vector<toolpath::Block>& program, const SmoothOptions& opt, const Vec3& first_start) {
  // the first block is kept whole (no run takes it in), so its output block is the one that starts later
  NETSHAPE_CHECK(!program.empty(), "blocks", "empty", "must hold the line that first_start lies on");
  const toolpath::Block& b = program.front();
  const double len = b.length();
  NETSHAPE_CHECK(b.kind == toolpath::MotionKind::line && len > opt.max_segment, "blocks[0].kind",
                 b.kind == toolpath::MotionKind::line ? "line of " + std::to_string(len) + " mm" : "not line",
                 "must be a line longer than max_segment when first_start is given");
  NETSHAPE_CHECK(first_start.allFinite(), "first_start", "non-finite", "must be a point on blocks[0]");
  const Vec3 d = (b.end - b.start) / len;
  const double t = (first_start - b.start).dot(d), off = (first_start - b.start - t * d).norm();
  NETSHAPE_CHECK(off <= 1e-9 * (1.0 + len) && t >= -1e-9 * (1.0 + len) && t < len, "first_start",
                 "off blocks[0] by " + std::to_string(off) + " mm at " + std::to_string(t) + " mm along it",
                 "must be a point on blocks[0] before its end");
  return smooth_program(program, opt, &first_start);
}

namespace {
SmoothResult smooth_program(const std::vector<toolpath::Block>& program, const SmoothOptions& opt,
                            const Vec3* first_start) {
  opt.validate();
  const std::size_t nb = program.size();
  for (std::size_t i = 0; i < nb; ++i) {
    try {
      program[i].validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("blocks[" + std::to_string(i) + "]: " + e.what());
    }
  }
  const detail::ProgramView view(program, opt);
  detail::StageOutput out;
  out.res.blocks.reserve(nb);
  out.res.corners_kept = detail::count_feed_corners(view);
  if (first_start) {
    out.start_override_block = 0;
    out.start_override = *first_start;
  }
  std::size_t i = 0;
  while (i < nb) {
    if (!view.micro(i)) {
      out.keep(program, i);
      ++i;
      continue;
    }
    const detail::RunSpan run = detail::find_run(view, i);
    if (static_cast<long>(run.last - i) < opt.min_blocks && opt.space_flatness > 0) {
      // in no coordinate plane: a run in space, fitted in pieces close to planes of their own
      const std::size_t j = detail::find_space_run(view, i);
      if (static_cast<long>(j - i) >= opt.min_blocks) {
        detail::smooth_space_run(view, i, j, out);
        i = j;
        continue;
      }
    }
    if (static_cast<long>(run.last - i) < opt.min_blocks) {
      // too short to smooth; a micro-segment that is in no coordinate plane by itself (last == i) is
      // kept too, so every pass of this loop moves past at least one block
      const std::size_t j = std::max(run.last, i + 1);
      for (std::size_t q = i; q < j; ++q) out.keep(program, q);
      i = j;
      continue;
    }
    detail::smooth_run(view, run, out);
    i = run.last;
  }
  // corners between two program lines become arcs within the fit tolerance (round.hpp)
  if (opt.round_corners) round_line_corners(out.res, out.program_line, out.tangent_join, view.lead_min, opt);
  return std::move(out.res);
}
}  // namespace

}  // namespace netshape::motion
