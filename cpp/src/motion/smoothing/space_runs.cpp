// The smoothing stage's runs in space (stage.hpp): micro-segments in no coordinate plane, fitted in
// pieces each lying close to a plane of its own.
//
// Bound: a piece's vertices x lie within h of its plane Π (the piece's end points on it), so every point
// of its polyline X is within h of its projection π(X) (projection is affine). The fit in Π is checked
// both ways against π(X) within e' = ε_fit − h (chain_check), so every point of the curve is within
// e' + h = ε_fit of X and every point of X within h + e' of the curve.
#include <algorithm>
#include <cmath>
#include <vector>

#include "motion/smoothing/fit.hpp"
#include "motion/smoothing/stage.hpp"

namespace netshape::motion::detail {

namespace {

constexpr std::size_t max_piece_blocks = 256;  // longest piece fitted at once [blocks]

// A plane through o spanned by the unit vectors e1, e2 (e1 ⟂ e2, normal nrm).
struct Frame {
  Vec3 o = Vec3::Zero(), e1 = Vec3::Zero(), e2 = Vec3::Zero(), nrm = Vec3::Zero();
  V2 to2(const Vec3& p) const { return V2((p - o).dot(e1), (p - o).dot(e2)); }
  Vec3 to3(const V2& p) const { return o + p.x() * e1 + p.y() * e2; }
};

// The plane through o holding the direction d and the point q, or false when q − o is (nearly) along d.
bool frame_through(const Vec3& o, const Vec3& d, const Vec3& q, Frame& f) {
  const Vec3 w = q - o;
  Vec3 n = d.cross(w);
  const double nn = n.norm();
  if (!(nn > 1e-9 * std::max(1.0, w.norm()))) return false;
  n /= nn;
  f.o = o;
  f.e1 = d.normalized();
  f.e2 = n.cross(f.e1);
  f.nrm = n;
  return true;
}

// The longest piece [a, b) starting at o (on block a) (b ≤ end, at most max_blocks) whose vertices lie
// within h_max of the plane through o holding the direction d and the piece's last vertex; its frame
// and largest distance h. b == a when no piece of two blocks or more fits.
std::size_t grow_piece(const ProgramView& v, std::size_t a, const Vec3& o, std::size_t end, const Vec3& d,
                       double h_max, std::size_t max_blocks, Frame& best, double& h_best) {
  std::size_t b_best = a;
  h_best = 0;
  for (std::size_t b = a + 2; b <= end && b - a <= max_blocks; ++b) {
    Frame f;
    if (!frame_through(o, d, v.program[b - 1].end, f)) continue;
    double h = 0;
    for (std::size_t k = a; k + 1 < b && h <= h_max; ++k)
      h = std::max(h, std::abs(f.nrm.dot(v.program[k].end - o)));
    if (h > h_max) {
      if (b - a > b_best - a + 8) break;  // flatness is lost for good (not one odd vertex)
      continue;
    }
    b_best = b;
    best = f;
    h_best = h;
  }
  return b_best;
}

// The largest curvature of the cubic Bézier p0..p3 at 17 parameters [1/mm].
double cubic_peak_curvature(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  double k = 0;
  for (int i = 0; i <= 16; ++i) {
    const double u = i / 16.0, w = 1.0 - u;
    const Vec3 d1 = 3.0 * (w * w * (p1 - p0) + 2.0 * w * u * (p2 - p1) + u * u * (p3 - p2));
    const Vec3 d2 = 6.0 * (w * (p2 - 2.0 * p1 + p0) + u * (p3 - 2.0 * p2 + p1));
    const double n = d1.norm();
    if (n > 0) k = std::max(k, d1.cross(d2).norm() / (n * n * n));
  }
  return k;
}

// The curvature at the middle of the blend `blend` plans at vertex c between two program lines with
// the whole ε (planner/blend.cpp: control points P0, the vertex twice, P3, each end d = min(0.45 of
// the shorter line, 4ε / sin(θ/2)) from the vertex): (8/3)·sin(θ/2) / (d·cos²(θ/2)); 0 where blend
// does not blend (θ ≤ 10⁻⁶ rad).
double blend_curvature(const ProgramView& v, std::size_t c) {
  const double th = v.vertex_turn(c);
  if (!(th > 1e-6)) return 0.0;
  const double sh = std::sin(0.5 * th), ch = std::cos(0.5 * th);
  const double d = std::min(0.45 * std::min(v.program[c - 1].length(), v.program[c].length()),
                            4.0 * v.opt.tolerance / sh);
  return 8.0 / 3.0 * sh / (d * ch * ch);
}

// Whether no cubic of new blocks [from, end of out) curves more than the largest of blend's corner
// blends at the program vertices it replaces: its curvature-limited speed √(a/κ) is then no lower
// than blend's at its corners there.
bool curves_as_blend(const ProgramView& v, const StageOutput& out, std::size_t from) {
  const auto& res = out.res;
  for (std::size_t k = from; k < res.blocks.size(); ++k) {
    if (!res.controls[k].cubic) continue;
    const auto& b = res.blocks[k];
    double kb = 0;
    for (auto c = static_cast<std::size_t>(res.source_first[k]);
         c <= static_cast<std::size_t>(res.source_last[k]) + 1 && c < v.nb; ++c)
      kb = std::max(kb, blend_curvature(v, c));
    if (cubic_peak_curvature(b.start, res.controls[k].c1, res.controls[k].c2, b.end) > kb) return false;
  }
  return true;
}

// Fit the piece [a, b) from p0 (on block a) to p1 (on block b − 1) in its frame, its end tangents t_in,
// t_end where given; its cubic blocks appended to out, the unit tangent at its end in t_out. False
// (nothing appended) when the fit fails its check.
bool fit_piece(const ProgramView& v, std::size_t a, std::size_t b, const Vec3& p0, const Vec3& p1,
               const Frame& f, double h, const Vec3* t_in, const Vec3* t_end, StageOutput& out, Vec3& t_out) {
  const auto& program = v.program;
  SmoothOptions o2 = v.opt;
  o2.tolerance = (v.opt.fit_tolerance() - h) / v.opt.fit_share;  // fit_tolerance() of o2: ε_fit − h
  std::vector<V2> pts;
  std::vector<long> src;
  pts.push_back(f.to2(p0));
  for (std::size_t q = a; q < b; ++q) {
    pts.push_back(f.to2(q + 1 == b ? p1 : program[q].end));
    src.push_back(static_cast<long>(q));
  }
  double len = 0;
  for (std::size_t q = 1; q < pts.size(); ++q) len += (pts[q] - pts[q - 1]).norm();
  RunEnds ends;
  if (t_in) {
    ends.fix0 = true;
    ends.d0 = (f.to2(f.o + *t_in) - f.to2(f.o)).normalized();
  }
  if (t_end) {
    ends.fix1 = true;
    ends.d1 = (f.to2(f.o + *t_end) - f.to2(f.o)).normalized();
  }
  RunFit rf;
  if (!fit_run(pts, ends, len / static_cast<double>(b - a), o2, rf)) return false;
  auto& res = out.res;
  const std::size_t n0 = res.blocks.size();
  const long corners0 = res.corners_kept;
  const double dev0 = res.max_fit_deviation;
  ++res.runs_smoothed;
  res.max_fit_deviation = std::max(res.max_fit_deviation, rf.bound + h);
  for (std::size_t q = a + 1; q < b; ++q)
    if (v.turn_at(q) > v.opt.max_turn) --res.corners_kept;
  append_pieces(out, program[a], rf, pts, src, p0, p1, [&f](const V2& p) { return f.to3(p); });
  if (!curves_as_blend(v, out, n0)) {  // slower than blending its vertices: a failed fit
    while (res.blocks.size() > n0) out.pop_back();
    --res.runs_smoothed;
    res.corners_kept = corners0;
    res.max_fit_deviation = dev0;
    return false;
  }
  const Piece& last = rf.pieces.back();
  V2 tail = last.b3 - last.b2;
  if (!(tail.norm() > 0)) tail = last.b3 - last.b1;
  t_out = (tail.x() * f.e1 + tail.y() * f.e2).normalized();
  return true;
}

// The unit tangent of the feed move across the vertex at the start of block c (before: the block
// c − 1 ending there, else block c starting there) when it joins the run's block there turning at most
// max_turn: the curve may start / end with it, so the joint needs no blend.
bool joined_tangent(const ProgramView& v, std::size_t c, bool before, Vec3& t) {
  if (c == 0 || c >= v.nb) return false;
  const auto &b0 = v.program[c - 1], &b1 = v.program[c];
  if (v.vertex_turn(c) > v.opt.max_turn || b0.kind == toolpath::MotionKind::rapid ||
      b1.kind == toolpath::MotionKind::rapid || b0.length() <= 1e-9 || b1.length() <= 1e-9 ||
      (b1.start - b0.end).norm() > 1e-9)
    return false;
  t = before ? b0.tangent_at(1.0) : b1.tangent_at(0.0);
  return true;
}

// The frame of the last piece [a, last) from p0 to q through q holding the tangent t_end there and p0,
// when its vertices lie within h_max of it.
bool end_frame(const ProgramView& v, std::size_t a, const Vec3& p0, std::size_t last, const Vec3& q,
               const Vec3& t_end, double h_max, Frame& f, double& h) {
  if (!frame_through(q, t_end, p0, f)) return false;
  h = 0;
  for (std::size_t k = a; k + 1 < last && h <= h_max; ++k)
    h = std::max(h, std::abs(f.nrm.dot(v.program[k].end - q)));
  return h <= h_max;
}

}  // namespace

std::size_t find_space_run(const ProgramView& view, std::size_t i) {
  const auto mb = static_cast<std::size_t>(view.opt.min_blocks);
  std::size_t j = i;
  while (j < view.nb && static_cast<long>(j - i) < view.opt.window && view.micro(j)) {
    if (j > i && (!view.continues(i, j) || find_run(view, j).last - j >= mb)) break;  // (or planar)
    ++j;
  }
  return j;
}

void smooth_space_run(const ProgramView& view, std::size_t first, std::size_t last, StageOutput& out) {
  const auto& program = view.program;
  const auto mb = static_cast<std::size_t>(view.opt.min_blocks);
  const double h_max = view.opt.space_flatness * view.opt.fit_tolerance();
  Vec3 t_in = Vec3::Zero(), t_end = Vec3::Zero();
  bool have_t = joined_tangent(view, first, true, t_in);
  bool have_end = joined_tangent(view, last, false, t_end);
  // At a corner (a feed move across the run's end vertex that lends no tangent) the run's end block
  // keeps its corner-side half as a line and the curve joins its other half tangentially, so the
  // corner lies between two program lines (rounded or blended with the whole ε, not next to a curve).
  const Vec3 mid0 = 0.5 * (program[first].start + program[first].end);
  const Vec3 mid1 = 0.5 * (program[last - 1].start + program[last - 1].end);
  const bool split_start = !have_t && view.vertex_turn(first) >= 1e-3;
  const bool split_end = !have_end && view.vertex_turn(last) >= 1e-3 && last - first > 1;
  if (split_start) {
    out.keep(program, first);
    out.res.blocks.back().end = mid0;
    out.tangent_join.back() |= 2;
    have_t = true;
    t_in = view.dir(first);
  }
  if (split_end) {
    have_end = true;
    t_end = view.dir(last - 1);
  }
  std::size_t a = first;
  std::size_t limit = max_piece_blocks;
  while (a < last) {
    const Vec3 p0 = a == first && split_start ? mid0 : program[a].start;
    Frame f;
    double h = 0;
    const Vec3 d = have_t ? t_in : view.dir(a);
    const std::size_t b = last - a >= mb ? grow_piece(view, a, p0, last, d, h_max, limit, f, h) : a;
    Vec3 t_out;
    // the last piece ends with the tangent of the block after the run, or of the run's end block at
    // its middle (its plane then holds that one, and the tangent it starts with is free)
    Frame fe;
    double he = 0;
    const Vec3 q = split_end ? mid1 : program[last - 1].end;
    if (b == last && b - a >= mb && have_end && end_frame(view, a, p0, last, q, t_end, h_max, fe, he) &&
        fit_piece(view, a, b, p0, q, fe, he, nullptr, &t_end, out, t_out)) {
      if (split_end) {
        out.keep(program, last - 1);
        out.res.blocks.back().start = mid1;
        out.tangent_join.back() |= 1;
      }
      break;
    }
    const Vec3* t0 = have_t ? &t_in : nullptr;
    // a piece that the next one continues ends with the polyline's direction at their joint vertex
    // (the mean of its two blocks' directions, projected into the piece's plane), which the next
    // piece's polyline suits too: a free end tangent hands the next piece a direction up to the tube
    // off its polyline, which it must turn away from within its first block (curvature peaks of
    // 3.5× the path's on a helix, slower than blending the vertices).
    Vec3 t_joint = Vec3::Zero();
    const bool joint = b < last && b - a >= mb;
    if (joint) t_joint = (view.dir(b - 1) + view.dir(b)).normalized();
    if (b - a >= mb &&
        fit_piece(view, a, b, p0, program[b - 1].end, f, h, t0, joint ? &t_joint : nullptr, out, t_out)) {
      t_in = t_out;
      have_t = true;
      a = b;
      limit = max_piece_blocks;
      continue;
    }
    if (b - a >= 2 * mb) {  // a piece that fails is halved
      limit = (b - a) / 2;
      continue;
    }
    if (b - a >= mb) ++out.res.runs_kept;
    out.keep(program, a);  // no piece from here: the block as programmed, the next piece along it
    if (a == first && split_start) out.res.blocks.back().start = mid0;
    t_in = view.dir(a);
    ++a;
    have_t = true;
    limit = max_piece_blocks;
  }
}

}  // namespace netshape::motion::detail
