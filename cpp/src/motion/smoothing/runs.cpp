// The smoothing stage's runs and corners (stage.hpp): queries on the program's blocks, the run search
// and a run's plane.
#include <algorithm>
#include <cmath>

#include "motion/smoothing/corner.hpp"
#include "motion/smoothing/stage.hpp"

namespace netshape::motion::detail {

using toolpath::MotionKind;

ProgramView::ProgramView(const std::vector<toolpath::Block>& program_, const SmoothOptions& opt_)
    : program(program_), opt(opt_), nb(program_.size()), lead_min(std::max(0.02, 2.0 * opt_.tolerance)),
      turn_memo_(program_.size(), -1.0) {}

bool ProgramView::micro(std::size_t i) const {
  const auto& b = program[i];
  const double l = b.length();
  return b.kind == MotionKind::line && l > 1e-9 && l <= opt.max_segment;
}

Vec3 ProgramView::dir(std::size_t i) const {
  return ((program[i].end - program[i].start) / program[i].length()).eval();
}

double ProgramView::turn_at(std::size_t q) const {
  double& t = turn_memo_[q];
  if (t < 0) t = turn_between(dir(q - 1), dir(q));
  return t;
}

bool ProgramView::straight_pair(long a) const {
  if (a < 0 || a + 1 >= static_cast<long>(nb)) return false;
  const auto ua = static_cast<std::size_t>(a);
  const auto &b0 = program[ua], &b1 = program[ua + 1];
  return b0.kind == MotionKind::line && b1.kind == MotionKind::line && b0.length() > 1e-9 &&
         b1.length() > 1e-9 && (b1.start - b0.end).norm() <= 1e-9 && turn_at(ua + 1) < 1e-3;
}

bool ProgramView::straight_side(long q, long step) const {
  auto tiny = [&](long b) { return program[static_cast<std::size_t>(b)].length() < lead_min; };
  for (int k = 0; k < 3 && q >= 0 && q < static_cast<long>(nb) && tiny(q); ++k) q += step;
  return straight_pair(step > 0 ? q : q - 1);
}

bool ProgramView::kept_corner(std::size_t q) const {
  const double th = turn_at(q);
  if (th <= opt.max_turn) return false;
  if (th > opt.max_fit_turn) return true;
  return straight_side(static_cast<long>(q) - 1, -1) && straight_side(static_cast<long>(q), 1);
}

double ProgramView::vertex_turn(std::size_t c) const {
  if (c == 0 || c >= nb) return 0.0;
  const auto &b0 = program[c - 1], &b1 = program[c];
  if (b0.kind == MotionKind::rapid || b1.kind == MotionKind::rapid || b0.length() <= 1e-9 ||
      b1.length() <= 1e-9 || (b1.start - b0.end).norm() > 1e-9)
    return 0.0;
  return turn_between(b0.tangent_at(1.0), b1.tangent_at(0.0));
}

double ProgramView::corner_need(std::size_t c) const {
  const double th = vertex_turn(c);
  if (!(th > 1e-3) || th > pi - 1e-3) return 0.0;
  return corner_arc_radius(th, opt.fit_tolerance()) * std::tan(0.5 * th);
}

double ProgramView::lead_part(std::size_t q, double beside, double need) const {
  const double len = program[q].length();
  const double a = std::min(opt.lead_length, 0.5 * len);
  return std::min(a, std::max(0.1 * len, len + beside - need));
}

bool ProgramView::corner_at(std::size_t q, bool at_start) const {
  return vertex_turn(at_start ? q : q + 1) >= 1e-3;
}

bool ProgramView::lends(std::size_t q, std::size_t r) const {
  const std::size_t q0 = std::min(q, r), q1 = std::max(q, r);
  return program[q].length() >= lead_min &&
         (q1 == q0 + 1 ? turn_at(q1) : turn_between(dir(q0), dir(q1))) <= 0.5 * opt.max_turn;
}

bool ProgramView::corner_lead(std::size_t q, std::size_t r) const {
  return corner_at(q, r > q) && lends(q, r);
}

std::size_t ProgramView::corner_skip(std::size_t q, int step, std::size_t room) const {
  if (!corner_at(q, step > 0)) return std::size_t{0};
  for (std::size_t k = 1; k <= 3 && k + 1 <= room; ++k) {
    const std::size_t t = q + (step > 0 ? k - 1 : 1 - k);  // the k-th block from the corner
    if (program[t].length() >= lead_min) return std::size_t{0};
    const std::size_t r = step > 0 ? t + 1 : t - 1, r2 = step > 0 ? r + 1 : r - 1;
    if (lends(r, r2)) return k;
  }
  return std::size_t{0};
}

bool ProgramView::corner_end(std::size_t q, bool at_start) const {
  return vertex_turn(at_start ? q : q + 1) > opt.max_turn;
}

bool ProgramView::continues(std::size_t i, std::size_t j) const {
  return program[j].feed == program[i].feed && (program[j].start - program[j - 1].end).norm() <= 1e-9 &&
         !kept_corner(j);
}

long count_feed_corners(const ProgramView& view) {
  long corners = 0;
  long prev = -1;
  for (std::size_t i = 0; i < view.nb; ++i) {
    const auto& b = view.program[i];
    if (b.length() <= 1e-9) continue;
    if (b.kind == MotionKind::rapid) {
      prev = -1;
      continue;
    }
    if (prev >= 0) {
      const Vec3 u1 = view.program[static_cast<std::size_t>(prev)].tangent_at(1.0), u2 = b.tangent_at(0.0);
      if (turn_between(u1, u2) > view.opt.max_turn) ++corners;
    }
    prev = static_cast<long>(i);
  }
  return corners;
}

namespace {
// bit a: coordinate a of p and q differ by at most tol [mm]
int plane_bits(const Vec3& p, const Vec3& q, double tol) {
  int m = 0;
  for (int a = 0; a < 3; ++a)
    if (std::abs(p[a] - q[a]) <= tol) m |= 1 << a;
  return m;
}
}  // namespace

RunSpan find_run(const ProgramView& view, std::size_t i) {
  const auto& program = view.program;
  int planes = 7;  // bit a: coordinate a constant
  const Vec3 origin = program[i].start;
  std::size_t j = i;
  while (j < view.nb && static_cast<long>(j - i) < view.opt.window && view.micro(j)) {
    if (j > i && !view.continues(i, j)) break;
    const int m = planes & plane_bits(origin, program[j].end, view.opt.plane_tolerance);
    if (m == 0) break;
    planes = m;
    ++j;
  }
  return RunSpan{i, j, planes};
}

RunPlane run_plane(const ProgramView& view, const RunSpan& run) {
  const auto& program = view.program;
  const std::size_t i = run.first, j = run.last;
  const Vec3 origin = program[i].start;
  int planes = run.planes;
  auto joined_line_bits = [&](long q) {
    if (q < 0 || q >= static_cast<long>(view.nb)) return 7;
    const auto& b = program[static_cast<std::size_t>(q)];
    if (b.kind != MotionKind::line || b.feed != program[i].feed) return 7;
    const double tol = view.opt.plane_tolerance;
    return plane_bits(origin, b.start, tol) & plane_bits(origin, b.end, tol);
  };
  const int before = joined_line_bits(static_cast<long>(i) - 1);
  const int after = joined_line_bits(static_cast<long>(j));
  for (int m : {planes & before & after, planes & before, planes & after})
    if (m != 0) {
      planes = m;
      break;
    }
  const toolpath::Plane plane =
      (planes & 4) ? toolpath::Plane::xy : (planes & 2) ? toolpath::Plane::zx : toolpath::Plane::yz;
  RunPlane out;
  out.ax = toolpath::plane_axes(plane);
  out.nval = program[i].start[out.ax.n];
  return out;
}

void StageOutput::keep(const std::vector<toolpath::Block>& program, std::size_t i) {
  res.blocks.push_back(program[i]);
  res.controls.emplace_back();
  if (static_cast<long>(i) == start_override_block) res.blocks.back().start = start_override;
  res.source_first.push_back(static_cast<long>(i));
  res.source_last.push_back(static_cast<long>(i));
  program_line.push_back(program[i].kind == MotionKind::line);
  tangent_join.push_back(0);
}

void StageOutput::pop_back() {
  res.blocks.pop_back();
  res.controls.pop_back();
  res.source_first.pop_back();
  res.source_last.pop_back();
  program_line.pop_back();
  tangent_join.pop_back();
}

}  // namespace netshape::motion::detail
