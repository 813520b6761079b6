// The smoothing stage's runs as curves (stage.hpp): a run's leads, its samples, its fit (fit.hpp,
// checked both ways by check.hpp) and its cubic pieces; a run that fails is cut and its parts tried.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "motion/smoothing/fit.hpp"
#include "motion/smoothing/stage.hpp"

namespace netshape::motion::detail {

namespace {

using toolpath::MotionKind;

// A lead: block q (a line longer than a micro-segment, same feed, joined to the run, turning at most
// max_turn against the run's end block e, in the run's plane) lends the run up to lead_length (at most
// half of itself) next to the joint, so the curve starts / ends tangent to it. A corner a curve runs
// into (the run's end block turns against its neighbour) is passed too.
bool lead_block(const ProgramView& v, const RunPlane& pl, long q, std::size_t e) {
  const auto& program = v.program;
  const auto& opt = v.opt;
  if (q < 0 || q >= static_cast<long>(v.nb)) return false;
  const auto& b = program[static_cast<std::size_t>(q)];
  if (b.kind != MotionKind::line || b.length() <= opt.max_segment || b.feed != program[e].feed) return false;
  const int n = pl.ax.n;
  const double tol = opt.plane_tolerance;
  if (std::abs(b.start[n] - pl.nval) > tol || std::abs(b.end[n] - pl.nval) > tol) return false;
  const bool before = static_cast<std::size_t>(q) < e;
  const Vec3 joint = before ? program[e].start : program[e].end;
  if ((joint - (before ? b.end : b.start)).norm() > 1e-9) return false;
  const Vec3 u1 = before ? v.dir(static_cast<std::size_t>(q)) : v.dir(e);
  const Vec3 u2 = before ? v.dir(e) : v.dir(static_cast<std::size_t>(q));
  const double th = turn_between(u1, u2);
  return th <= opt.max_turn ||
         (th <= opt.max_fit_turn && !v.straight_side(static_cast<long>(e), before ? 1 : -1));
}

// The lines that lend the run [i, j) their parts next to its ends. lin / lout: the lending block or −1;
// *_inner: it is the run's own end block (or the block behind up to three tiny ones, *_skip of them,
// kept as programmed between it and the corner), whose corner-side part is emitted as a line.
//
// A run that ends at a vertex with no lead (a corner turning more than max_turn, a change of plane or
// feed, a cut of a run that failed its check) would meet the next block at an angle, left to the
// planner's blend tolerance. Instead the run's end block q lends the run its inner part and its
// corner-side part stays a line, so the corner lies between two lines and is rounded within the fit
// tolerance (round.hpp): when q is long enough for its direction to be sure (≥ 2·ε and ≥ 0.02 mm) and
// turns at most max_turn / 2 against its neighbour r in the run. When q and up to two more blocks next
// to the corner are shorter (tiny blocks around corners are common in CAM output), they are kept as
// programmed and the first longer block r behind them lends instead (corner_skip); the corner then
// spans the tiny blocks and is rounded as one (compound corners).
struct Leads {
  long lin = -1, lout = -1;
  bool lin_inner = false, lout_inner = false;
  std::size_t lin_skip = 0, lout_skip = 0;
};

Leads choose_leads(const ProgramView& v, const RunPlane& pl, const StageOutput& out, std::size_t i,
                   std::size_t j) {
  const auto& res = out.res;
  const auto mb = static_cast<std::size_t>(v.opt.min_blocks);
  Leads l;
  // the kept long line i − 1 (the block just emitted, shortened) or the run's own first block
  if (lead_block(v, pl, static_cast<long>(i) - 1, i) && !res.blocks.empty() &&
      res.source_first.back() == static_cast<long>(i) - 1 && res.blocks.back().kind == MotionKind::line) {
    l.lin = static_cast<long>(i) - 1;
  } else if (j - i > mb && v.corner_lead(i, i + 1)) {
    l.lin = static_cast<long>(i);
    l.lin_inner = true;
  } else if (const std::size_t k = v.corner_skip(i, 1, j - i - mb); k > 0) {
    l.lin = static_cast<long>(i + k);
    l.lin_inner = true;
    l.lin_skip = k;
  }
  if (lead_block(v, pl, static_cast<long>(j), j - 1)) {
    l.lout = static_cast<long>(j);
  } else {
    const std::size_t left = j - i - (l.lin_inner ? 1 + l.lin_skip : 0);  // blocks before lout's
    if (left > mb && v.corner_lead(j - 1, j - 2)) {
      l.lout = static_cast<long>(j) - 1;
      l.lout_inner = true;
    } else if (const std::size_t k = left > mb ? v.corner_skip(j - 1, -1, left - mb) : 0; k > 0) {
      l.lout = static_cast<long>(j - 1 - k);
      l.lout_inner = true;
      l.lout_skip = k;
    }
  }
  return l;
}

// The polyline a run's curve is fitted to: the lead parts, the blocks wholly in the run [r0, r1), and
// per segment its program block (src); the curve's end points first3, last3 and end tangents.
struct RunSamples {
  std::size_t r0 = 0, r1 = 0;
  double mean = 0;  // mean length of the blocks wholly in the run [mm]
  std::vector<V2> pts;
  std::vector<long> src;
  RunEnds ends;
  Vec3 first3, last3;
};

RunSamples sample_run(const ProgramView& v, const RunPlane& pl, const StageOutput& out, std::size_t i,
                      std::size_t j, const Leads& l) {
  const auto& program = v.program;
  const auto& opt = v.opt;
  RunSamples s;
  s.r0 = i + (l.lin_inner ? 1 + l.lin_skip : 0);
  s.r1 = j - (l.lout_inner ? 1 + l.lout_skip : 0);
  const std::size_t r0 = s.r0, r1 = s.r1;
  double run_len = 0;
  for (std::size_t q = r0; q < r1; ++q) run_len += program[q].length();
  const double mean = s.mean = run_len / static_cast<double>(r1 - r0);
  s.first3 = program[r0].start;
  s.last3 = program[r1 - 1].end;
  if (l.lin >= 0) {
    const auto& b = program[static_cast<std::size_t>(l.lin)];
    double beside = 0;  // the tiny blocks kept between the corner and this line
    for (std::size_t q = i; q < i + l.lin_skip; ++q) beside += program[q].length();
    // (not inner: the line is the last new block, already shortened by what came before it)
    const auto& blocks = out.res.blocks;
    const double a = l.lin_inner ? v.lead_part(static_cast<std::size_t>(l.lin), beside, v.corner_need(i))
                                 : std::min({opt.lead_length, 0.5 * b.length(),
                                             (blocks.back().end - blocks.back().start).norm()});
    const Vec3 d = v.dir(static_cast<std::size_t>(l.lin));
    s.first3 = b.end - a * d;
    const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
    for (int q = 0; q < k; ++q) {
      s.pts.push_back(pl.to2(s.first3 + (a * q / k) * d));
      s.src.push_back(l.lin);
    }
    s.ends.fix0 = true;
    s.ends.d0 = pl.to2(d).normalized();
  }
  s.pts.push_back(pl.to2(program[r0].start));
  for (std::size_t q = r0; q < r1; ++q) {
    s.pts.push_back(pl.to2(program[q].end));
    s.src.push_back(static_cast<long>(q));
  }
  if (l.lout >= 0) {
    const auto& b = program[static_cast<std::size_t>(l.lout)];
    double beside = 0;
    for (std::size_t q = j - l.lout_skip; q < j; ++q) beside += program[q].length();
    const double a = l.lout_inner ? v.lead_part(static_cast<std::size_t>(l.lout), beside, v.corner_need(j))
                                  : std::min(opt.lead_length, 0.5 * b.length());
    const Vec3 d = v.dir(static_cast<std::size_t>(l.lout));
    s.last3 = b.start + a * d;
    const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
    for (int q = 1; q <= k; ++q) {
      s.pts.push_back(pl.to2(q == k ? s.last3 : Vec3(b.start + (a * q / k) * d)));
      s.src.push_back(l.lout);
    }
    s.ends.fix1 = true;
    s.ends.d1 = pl.to2(d).normalized();
  }
  // Without a lead, at a straight joint (turning less than 1e-3 rad: a change of feed, a block that is
  // no micro-segment and lends nothing) the curve takes the tangent of the block across the joint when
  // it lies in the run's plane, so the path stays tangent-continuous there.
  auto across = [&](long q, bool before, Vec3& t) {
    if (q < 0 || q >= static_cast<long>(v.nb)) return false;
    const auto& b = program[static_cast<std::size_t>(q)];
    if (b.kind == MotionKind::rapid || b.length() <= 1e-9) return false;
    const Vec3 joint = before ? program[r0].start : program[r1 - 1].end;
    if ((joint - (before ? b.end : b.start)).norm() > 1e-9) return false;
    t = b.tangent_at(before ? 1.0 : 0.0);
    if (std::abs(t[pl.ax.n]) > 1e-9) return false;
    return turn_between(t, before ? v.dir(r0) : v.dir(r1 - 1)) < 1e-3;
  };
  Vec3 tj;
  if (l.lin < 0 && across(static_cast<long>(r0) - 1, true, tj)) {
    s.ends.fix0 = true;
    s.ends.d0 = pl.to2(tj).normalized();
  }
  if (l.lout < 0 && across(static_cast<long>(r1), false, tj)) {
    s.ends.fix1 = true;
    s.ends.d1 = pl.to2(tj).normalized();
  }
  return s;
}

// Append a fitted run: the counts, the shortened lead lines, the corner-side parts of its own end
// blocks (with the tiny blocks kept at the corners) and one cubic block per piece.
void emit_run(const ProgramView& v, const RunPlane& pl, StageOutput& out, std::size_t i, std::size_t j,
              const Leads& l, const RunSamples& s, const RunFit& rf) {
  const auto& program = v.program;
  auto& res = out.res;
  const std::size_t r0 = s.r0, r1 = s.r1;
  const bool lead_in = l.lin >= 0 && !l.lin_inner, lead_out = l.lout >= 0 && !l.lout_inner;
  ++res.runs_smoothed;
  res.max_fit_deviation = std::max(res.max_fit_deviation, rf.bound);
  // creases the curve passes, inside the run or at a lead line, are no kept corners (count_feed_corners
  // took every corner)
  for (std::size_t q = r0 + 1; q < r1; ++q)
    if (v.turn_at(q) > v.opt.max_turn) --res.corners_kept;
  if (lead_in && turn_between(v.dir(static_cast<std::size_t>(l.lin)), v.dir(r0)) > v.opt.max_turn)
    --res.corners_kept;
  if (lead_out && turn_between(v.dir(r1 - 1), v.dir(static_cast<std::size_t>(l.lout))) > v.opt.max_turn)
    --res.corners_kept;
  if (lead_in) {  // the line before now ends where the curve starts
    res.blocks.back().end = s.first3;
    if ((res.blocks.back().end - res.blocks.back().start).norm() <= 1e-12) out.pop_back();
  }
  if (lead_out) {  // the line after starts where the curve ends
    out.start_override_block = static_cast<long>(j);
    out.start_override = s.last3;
  }
  if (l.lin_inner) {  // the tiny blocks kept at the corner, then block lin's first part up to the curve
    for (std::size_t q = i; q <= static_cast<std::size_t>(l.lin); ++q) out.keep(program, q);
    res.blocks.back().end = s.first3;
    out.tangent_join.back() |= 2;
  }
  append_pieces(out, program[i], rf, s.pts, s.src, s.first3, s.last3,
                [&pl](const V2& p) { return pl.to3(p); });
  if (l.lout_inner) {  // block lout's last part from the curve, then the tiny blocks kept at the corner
    out.keep(program, static_cast<std::size_t>(l.lout));
    res.blocks.back().start = s.last3;
    out.tangent_join.back() |= 1;
    for (std::size_t q = static_cast<std::size_t>(l.lout) + 1; q < j; ++q) out.keep(program, q);
  }
}

// Fit the run [i, j) with its leads; false (nothing appended) when the fit fails its check.
bool fit_emit(const ProgramView& v, const RunPlane& pl, StageOutput& out, std::size_t i, std::size_t j) {
  const Leads l = choose_leads(v, pl, out, i, j);
  const RunSamples s = sample_run(v, pl, out, i, j, l);
  RunFit rf;
  if (!fit_run(s.pts, s.ends, s.mean, v.opt, rf)) return false;
  emit_run(v, pl, out, i, j, l, s, rf);
  return true;
}

}  // namespace

void smooth_run(const ProgramView& v, const RunSpan& run, StageOutput& out) {
  const RunPlane pl = run_plane(v, run);
  std::vector<std::pair<std::size_t, std::size_t>> parts{{run.first, run.last}};
  const auto mb = static_cast<std::size_t>(v.opt.min_blocks);
  while (!parts.empty()) {
    const auto [i0, j0] = parts.back();
    parts.pop_back();
    // a straight run (every vertex turning less than 1e-3 rad) next to a corner stays as programmed:
    // its lines are the curve already, and the corner is rounded between them
    bool straight = v.corner_end(i0, true) || v.corner_end(j0 - 1, false);
    for (std::size_t q = i0 + 1; q < j0 && straight; ++q) straight = v.turn_at(q) < 1e-3;
    if (straight) {
      for (std::size_t q = i0; q < j0; ++q) out.keep(v.program, q);
      continue;
    }
    if (j0 - i0 >= mb && fit_emit(v, pl, out, i0, j0)) continue;
    if (j0 - i0 >= 2 * mb) {  // cut at the sharpest interior vertex that leaves min_blocks each side
      std::size_t cut = i0 + mb;
      double worst = -1;
      for (std::size_t q = i0 + mb; q + mb <= j0; ++q) {
        const double th = v.turn_at(q);
        if (th > worst) {
          worst = th;
          cut = q;
        }
      }
      parts.push_back({cut, j0});
      parts.push_back({i0, cut});
      continue;
    }
    if (j0 - i0 >= mb) ++out.res.runs_kept;
    for (std::size_t q = i0; q < j0; ++q) out.keep(v.program, q);
  }
}

}  // namespace netshape::motion::detail
