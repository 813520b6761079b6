// deviation_to_program() (netshape/motion/smoothing.hpp): samples of a smoothed path against the
// program blocks they replace.
#include <algorithm>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/motion/segment.hpp"
#include "netshape/motion/smoothing.hpp"

namespace netshape::motion {

double deviation_to_program(const std::vector<toolpath::Block>& program, const Points3& points,
                            const std::vector<long>& first, const std::vector<long>& last) {
  NETSHAPE_CHECK(static_cast<Eigen::Index>(first.size()) == points.rows() && first.size() == last.size(), "first",
                 first.size(), "must have one entry per point (and match last)");
  const long nb = static_cast<long>(program.size());
  double dev = 0;
  std::vector<Segment> segs;
  segs.reserve(program.size());
  for (const auto& b : program)
    segs.push_back(b.kind == toolpath::MotionKind::arc ? Segment::arc(b, 0) : Segment::line(b, 0));
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Vec3 p = points.row(k).transpose();
    const auto kk = static_cast<std::size_t>(k);
    double best = 1e300;
    for (long q = std::max(0L, first[kk] - 1); q <= std::min(nb - 1, last[kk] + 1); ++q) {
      const Segment& s = segs[static_cast<std::size_t>(q)];
      if (s.full_length <= 0) continue;
      best = std::min(best, s.distance_to_piece(p, 0.0, s.full_length));
    }
    if (best < 1e300) dev = std::max(dev, best);
  }
  return dev;
}

}  // namespace netshape::motion
