#include "netshape/force/program_walk.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "netshape/stock/sweep.hpp"

namespace netshape::force {

double walk_program(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                    double step, const std::function<void(const WalkSample&)>& visit, const char* progress_name) {
  NETSHAPE_CHECK(std::isfinite(step) && step > 0.0, "step", step, "must be positive [mm]");
  const double top = stock.max_height();
  double removed = 0.0;
  core::Progress progress(progress_name, program.blocks.size());
  WalkSample w;
  for (std::size_t bi = 0; bi < program.blocks.size(); ++bi) {
    progress.report(bi);
    const toolpath::Block& b = program.blocks[bi];
    const double len = b.length();
    if (len <= 0.0) continue;
    if (b.kind == toolpath::MotionKind::rapid) {
      removed += stock::sweep_line(stock, cutter, b.start, b.end).removed_volume;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(len / step - 1e-9)));
    Vec3 prev = b.start;
    for (int s = 1; s <= n; ++s) {
      w.block = bi;
      w.fraction = static_cast<double>(s) / n;
      w.tip = b.point_at(w.fraction);
      w.tangent = b.tangent_at(w.fraction);
      const Vec3 th(w.tangent.x(), w.tangent.y(), 0.0);
      w.depth = std::min(cutter.flute_length, top - w.tip.z());
      if (th.norm() > 1e-9 && w.depth > 0.0) {
        w.feed_direction = th.normalized();
        visit(w);
      }
      removed += stock::sweep_line(stock, cutter, prev, w.tip).removed_volume;
      prev = w.tip;
    }
  }
  return removed;
}

}  // namespace netshape::force
