// The tolerance-band smoothing stage (netshape/motion/smoothing.hpp): runs and corners of a program,
// and the smoothed program. The fit of a run: smoothing_fit.hpp (its check smoothing_check.hpp, the
// spline smoothing_spline.hpp); arcs at corners between lines: smoothing_round.hpp.
#include "netshape/motion/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/motion/segment.hpp"
#include "smoothing_corner.hpp"
#include "smoothing_fit.hpp"
#include "smoothing_round.hpp"
#include "smoothing_spline.hpp"

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
  using toolpath::MotionKind;
  const std::size_t nb = program.size();
  for (std::size_t i = 0; i < nb; ++i) {
    try {
      program[i].validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("blocks[" + std::to_string(i) + "]: " + e.what());
    }
  }
  SmoothResult res;
  res.blocks.reserve(nb);
  auto micro = [&](std::size_t i) {
    const auto& b = program[i];
    const double l = b.length();
    return b.kind == MotionKind::line && l > 1e-9 && l <= opt.max_segment;
  };
  auto dir = [&](std::size_t i) { return ((program[i].end - program[i].start) / program[i].length()).eval(); };
  // turn_between(dir(q − 1), dir(q)) at the vertex between blocks q − 1 and q, computed once per vertex
  // (the run search, the corner counts and the checks below ask for most vertices several times)
  std::vector<double> turn_memo(nb, -1.0);
  auto turn_at = [&](std::size_t q) {
    double& t = turn_memo[q];
    if (t < 0) t = turn_between(dir(q - 1), dir(q));
    return t;
  };
  // shortest block whose direction is sure enough to lend a corner its line (corner_lead below); shorter
  // lines between two corners' lines are parts of one compound corner (round_corners)
  const double lead_min = std::max(0.02, 2.0 * opt.tolerance);
  // Is the vertex at the start of micro-segment q (after micro-segment q − 1) a corner that ends a run?
  // It turns more than max_turn, and more than max_fit_turn or with straight sides (the block on each
  // side continues the one beyond it within 1e-3 rad). A vertex turning between the two where a curve
  // meets it (a crease of a free-form surface, or a curve running into a straight side) stays inside
  // the run, whose curve passes it within the fit tolerance.
  auto straight_pair = [&](long a) {  // line blocks a and a + 1 continue each other
    if (a < 0 || a + 1 >= static_cast<long>(nb)) return false;
    const auto ua = static_cast<std::size_t>(a);
    const auto &b0 = program[ua], &b1 = program[ua + 1];
    return b0.kind == MotionKind::line && b1.kind == MotionKind::line && b0.length() > 1e-9 && b1.length() > 1e-9 &&
           (b1.start - b0.end).norm() <= 1e-9 && turn_at(ua + 1) < 1e-3;
  };
  // the side of a vertex that begins with block q and goes on with step ±1 is straight: past up to
  // three blocks shorter than lead_min (tiny CAM blocks at a corner), a block continues the next one
  auto straight_side = [&](long q, long step) {
    for (int k = 0; k < 3 && q >= 0 && q < static_cast<long>(nb) && program[static_cast<std::size_t>(q)].length() < lead_min; ++k)
      q += step;
    return straight_pair(step > 0 ? q : q - 1);
  };
  auto kept_corner = [&](std::size_t q) {
    const double th = turn_at(q);
    if (th <= opt.max_turn) return false;
    if (th > opt.max_fit_turn) return true;
    return straight_side(static_cast<long>(q) - 1, -1) && straight_side(static_cast<long>(q), 1);
  };
  // corners between feed moves
  long prev = -1;
  for (std::size_t i = 0; i < nb; ++i) {
    const auto& b = program[i];
    if (b.length() <= 1e-9) continue;
    if (b.kind == MotionKind::rapid) {
      prev = -1;
      continue;
    }
    if (prev >= 0) {
      const Vec3 u1 = program[static_cast<std::size_t>(prev)].tangent_at(1.0), u2 = b.tangent_at(0.0);
      if (turn_between(u1, u2) > opt.max_turn) ++res.corners_kept;
    }
    prev = static_cast<long>(i);
  }
  // a line whose first part became the lead-out of the run before it starts later
  long start_override_block = first_start ? 0 : -1;
  std::vector<bool> program_line;  // per new block: a program line block or a part of one
  // per new block: bit 0 its start, bit 1 its end joins a run's curve with the same tangent (set for
  // the corner lines of runs only: a long line's length may differ between the chunks of a stream)
  std::vector<unsigned char> tangent_join;
  Vec3 start_override = first_start ? *first_start : Vec3::Zero();
  auto keep = [&](std::size_t i) {
    res.blocks.push_back(program[i]);
    res.controls.emplace_back();
    if (static_cast<long>(i) == start_override_block) res.blocks.back().start = start_override;
    res.source_first.push_back(static_cast<long>(i));
    res.source_last.push_back(static_cast<long>(i));
    program_line.push_back(program[i].kind == MotionKind::line);
    tangent_join.push_back(0);
  };
  std::size_t i = 0;
  std::vector<V2> pts;
  while (i < nb) {
    if (!micro(i)) {
      keep(i);
      ++i;
      continue;
    }
    // extend the run [i, j)
    int planes = 7;  // bit a: coordinate a constant
    auto plane_bits = [&](const Vec3& p, const Vec3& q) {
      int m = 0;
      for (int a = 0; a < 3; ++a)
        if (std::abs(p[a] - q[a]) <= opt.plane_tolerance) m |= 1 << a;
      return m;
    };
    const Vec3 origin = program[i].start;
    std::size_t j = i;
    while (j < nb && static_cast<long>(j - i) < opt.window && micro(j)) {
      if (j > i) {
        if (program[j].feed != program[i].feed) break;
        if ((program[j].start - program[j - 1].end).norm() > 1e-9) break;
        if (kept_corner(j)) break;
      }
      const int m = planes & plane_bits(origin, program[j].end);
      if (m == 0) break;
      planes = m;
      ++j;
    }
    if (static_cast<long>(j - i) < opt.min_blocks) {
      // too short to smooth; a micro-segment that is in no coordinate plane by itself (j == i) is
      // kept too, so every pass of this loop moves past at least one block
      j = std::max(j, i + 1);
      for (std::size_t q = i; q < j; ++q) keep(q);
      i = j;
      continue;
    }
    // plane: normal axis = a constant coordinate (prefer one that also holds the lines joined to the
    // run, so that they can lend it leads; then Z, then Y, then X)
    {
      auto joined_line_bits = [&](long q) {
        if (q < 0 || q >= static_cast<long>(nb)) return 7;
        const auto& b = program[static_cast<std::size_t>(q)];
        if (b.kind != MotionKind::line || b.feed != program[i].feed) return 7;
        return plane_bits(origin, b.start) & plane_bits(origin, b.end);
      };
      const int before = joined_line_bits(static_cast<long>(i) - 1), after = joined_line_bits(static_cast<long>(j));
      for (int m : {planes & before & after, planes & before, planes & after})
        if (m != 0) {
          planes = m;
          break;
        }
    }
    toolpath::Plane plane = (planes & 4) ? toolpath::Plane::xy : (planes & 2) ? toolpath::Plane::zx : toolpath::Plane::yz;
    const auto ax = toolpath::plane_axes(plane);
    const double nval = program[i].start[ax.n];
    auto to3 = [&](const V2& p) {
      Vec3 v;
      v[ax.a] = p.x();
      v[ax.b] = p.y();
      v[ax.n] = nval;
      return v;
    };
    auto to2 = [&](const Vec3& p) { return V2(p[ax.a], p[ax.b]); };
    // a lead: block q (a line longer than a micro-segment, same feed, joined to the run, turning at
    // most max_turn against the run's end block e, in the run's plane) lends the run up to
    // lead_length (at most half of itself) next to the joint, so the curve starts / ends tangent to it
    auto lead_block = [&](long q, std::size_t e) {
      if (q < 0 || q >= static_cast<long>(nb)) return false;
      const auto& b = program[static_cast<std::size_t>(q)];
      if (b.kind != MotionKind::line || b.length() <= opt.max_segment || b.feed != program[e].feed) return false;
      if (std::abs(b.start[ax.n] - nval) > opt.plane_tolerance || std::abs(b.end[ax.n] - nval) > opt.plane_tolerance)
        return false;
      const bool before = static_cast<std::size_t>(q) < e;
      const Vec3 joint = before ? program[e].start : program[e].end;
      if ((joint - (before ? b.end : b.start)).norm() > 1e-9) return false;
      const Vec3 u1 = before ? dir(static_cast<std::size_t>(q)) : dir(e);
      const Vec3 u2 = before ? dir(e) : dir(static_cast<std::size_t>(q));
      const double th = turn_between(u1, u2);
      // a corner a curve runs into (the run's end block turns against its neighbour) is passed too
      return th <= opt.max_turn ||
             (th <= opt.max_fit_turn && !straight_side(static_cast<long>(e), before ? 1 : -1));
    };
    // A run that ends at a vertex with no lead (a corner turning more than max_turn, a change of plane
    // or feed, a cut of a run that failed its check) would meet the next block at an angle, left to
    // the planner's blend tolerance. Instead the run's end block q lends the run its inner part and its
    // corner-side part stays a line, so the corner lies between two lines and is rounded within the fit
    // tolerance below: when q is long enough for its direction to be sure (≥ 2·ε and ≥ 0.02 mm) and
    // turns at most max_turn / 2 against its neighbour r in the run. When q and up to two more blocks
    // next to the corner are shorter (tiny blocks around corners are common in CAM output), they are
    // kept as programmed and the first longer block r behind them lends instead (corner_skip); the
    // corner then spans the tiny blocks and is rounded as one (compound corners, below).
    // The turn at the vertex at the start of block c between two feed moves joined end to end, else 0.
    auto vertex_turn = [&](std::size_t c) {
      if (c == 0 || c >= nb) return 0.0;
      const auto &b0 = program[c - 1], &b1 = program[c];
      if (b0.kind == MotionKind::rapid || b1.kind == MotionKind::rapid || b0.length() <= 1e-9 ||
          b1.length() <= 1e-9 || (b1.start - b0.end).norm() > 1e-9)
        return 0.0;
      return turn_between(b0.tangent_at(1.0), b1.tangent_at(0.0));
    };
    // The length the corner arc below needs on each line at the vertex at the start of block c (the arc
    // within the fit tolerance of the vertex touches the lines R·tan(θ/2) from it, corner_arc_radius).
    auto corner_need = [&](std::size_t c) {
      const double th = vertex_turn(c);
      if (!(th > 1e-3) || th > pi - 1e-3) return 0.0;
      return corner_arc_radius(th, opt.fit_tolerance()) * std::tan(0.5 * th);
    };
    // The part of block q a run uses as its lead: up to lead_length, at most half of q; when q is the
    // run's end block next to a corner (beside: the length of the tiny blocks kept between them, need:
    // corner_need), less, down to a tenth of q, so that the corner's line holds the length its arc needs.
    auto lead_part = [&](std::size_t q, double beside, double need) {
      const double len = program[q].length();
      const double a = std::min(opt.lead_length, 0.5 * len);
      return std::min(a, std::max(0.1 * len, len + beside - need));
    };
    // the vertex at q's outer end (its start when at_start) turns at least 1e-3 rad
    auto corner_at = [&](std::size_t q, bool at_start) { return vertex_turn(at_start ? q : q + 1) >= 1e-3; };
    auto lends = [&](std::size_t q, std::size_t r) {
      const std::size_t q0 = std::min(q, r), q1 = std::max(q, r);
      return program[q].length() >= lead_min &&
             (q1 == q0 + 1 ? turn_at(q1) : turn_between(dir(q0), dir(q1))) <= 0.5 * opt.max_turn;
    };
    auto corner_lead = [&](std::size_t q, std::size_t r) { return corner_at(q, r > q) && lends(q, r); };
    // the number of tiny blocks (1 to 3) from q inward (step ±1) before a block that lends at the
    // corner at q's outer end, or 0
    auto corner_skip = [&](std::size_t q, int step, std::size_t room) {
      if (!corner_at(q, step > 0)) return std::size_t{0};
      for (std::size_t k = 1; k <= 3 && k + 1 <= room; ++k) {
        const std::size_t t = q + (step > 0 ? k - 1 : 1 - k);  // the k-th block from the corner
        if (program[t].length() >= lead_min) return std::size_t{0};
        const std::size_t r = step > 0 ? t + 1 : t - 1, r2 = step > 0 ? r + 1 : r - 1;
        if (lends(r, r2)) return k;
      }
      return std::size_t{0};
    };
    auto fit_emit = [&](std::size_t i, std::size_t j) -> bool {
      // Leads: the kept long line i − 1 (the block just emitted, shortened) and the long line j lend the
      // run their parts next to the joints, so the curve starts / ends tangent to them; without such a
      // line, next to a corner the run's own end block (or the block behind up to three tiny ones) lends
      // its run-side part (corner_lead, corner_skip) and its corner-side part is emitted as a line.
      long lin = -1, lout = -1;
      bool lin_inner = false, lout_inner = false;
      std::size_t lin_skip = 0, lout_skip = 0;  // tiny blocks kept between the corner and its line (corner_skip)
      if (lead_block(static_cast<long>(i) - 1, i) && !res.blocks.empty() &&
          res.source_first.back() == static_cast<long>(i) - 1 && res.blocks.back().kind == MotionKind::line) {
        lin = static_cast<long>(i) - 1;
      } else if (j - i > static_cast<std::size_t>(opt.min_blocks) && corner_lead(i, i + 1)) {
        lin = static_cast<long>(i);
        lin_inner = true;
      } else if (const std::size_t k = corner_skip(i, 1, j - i - static_cast<std::size_t>(opt.min_blocks)); k > 0) {
        lin = static_cast<long>(i + k);
        lin_inner = true;
        lin_skip = k;
      }
      if (lead_block(static_cast<long>(j), j - 1)) {
        lout = static_cast<long>(j);
      } else {
        const std::size_t left = j - i - (lin_inner ? 1 + lin_skip : 0);  // blocks before lout's
        if (left > static_cast<std::size_t>(opt.min_blocks) && corner_lead(j - 1, j - 2)) {
          lout = static_cast<long>(j) - 1;
          lout_inner = true;
        } else if (const std::size_t k = left > static_cast<std::size_t>(opt.min_blocks)
                                             ? corner_skip(j - 1, -1, left - static_cast<std::size_t>(opt.min_blocks))
                                             : 0;
                   k > 0) {
          lout = static_cast<long>(j - 1 - k);
          lout_inner = true;
          lout_skip = k;
        }
      }
      // blocks wholly in the run
      const std::size_t r0 = i + (lin_inner ? 1 + lin_skip : 0), r1 = j - (lout_inner ? 1 + lout_skip : 0);
      std::vector<long> src;  // per polyline segment: its program block
      double run_len = 0;
      for (std::size_t q = r0; q < r1; ++q) run_len += program[q].length();
      const double mean = run_len / static_cast<double>(r1 - r0);
      pts.clear();
      RunEnds ends;
      Vec3 first3 = program[r0].start, last3 = program[r1 - 1].end;
      if (lin >= 0) {
        const auto& b = program[static_cast<std::size_t>(lin)];
        double beside = 0;  // the tiny blocks kept between the corner and this line
        for (std::size_t q = i; q < i + lin_skip; ++q) beside += program[q].length();
        double a = lin_inner ? lead_part(static_cast<std::size_t>(lin), beside, corner_need(i))
                             : std::min({opt.lead_length, 0.5 * b.length(), (res.blocks.back().end - res.blocks.back().start).norm()});
        const Vec3 d = dir(static_cast<std::size_t>(lin));
        first3 = b.end - a * d;
        const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
        for (int q = 0; q < k; ++q) {
          pts.push_back(to2(first3 + (a * q / k) * d));
          src.push_back(lin);
        }
        ends.fix0 = true;
        ends.d0 = to2(d).normalized();
      }
      pts.push_back(to2(program[r0].start));
      for (std::size_t q = r0; q < r1; ++q) {
        pts.push_back(to2(program[q].end));
        src.push_back(static_cast<long>(q));
      }
      if (lout >= 0) {
        const auto& b = program[static_cast<std::size_t>(lout)];
        double beside = 0;
        for (std::size_t q = j - lout_skip; q < j; ++q) beside += program[q].length();
        const double a = lout_inner ? lead_part(static_cast<std::size_t>(lout), beside, corner_need(j))
                                    : std::min(opt.lead_length, 0.5 * b.length());
        const Vec3 d = dir(static_cast<std::size_t>(lout));
        last3 = b.start + a * d;
        const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
        for (int q = 1; q <= k; ++q) {
          pts.push_back(to2(q == k ? last3 : Vec3(b.start + (a * q / k) * d)));
          src.push_back(lout);
        }
        ends.fix1 = true;
        ends.d1 = to2(d).normalized();
      }
      // Without a lead, at a straight joint (turning less than 1e-3 rad: a change of feed, a block that
      // is no micro-segment and lends nothing) the curve takes the tangent of the block across the joint
      // when it lies in the run's plane, so the path stays tangent-continuous there.
      auto across = [&](long q, bool before, Vec3& t) {
        if (q < 0 || q >= static_cast<long>(nb)) return false;
        const auto& b = program[static_cast<std::size_t>(q)];
        if (b.kind == MotionKind::rapid || b.length() <= 1e-9) return false;
        const Vec3 joint = before ? program[r0].start : program[r1 - 1].end;
        if ((joint - (before ? b.end : b.start)).norm() > 1e-9) return false;
        t = b.tangent_at(before ? 1.0 : 0.0);
        if (std::abs(t[ax.n]) > 1e-9) return false;
        return turn_between(t, before ? dir(r0) : dir(r1 - 1)) < 1e-3;
      };
      Vec3 tj;
      if (lin < 0 && across(static_cast<long>(r0) - 1, true, tj)) {
        ends.fix0 = true;
        ends.d0 = to2(tj).normalized();
      }
      if (lout < 0 && across(static_cast<long>(r1), false, tj)) {
        ends.fix1 = true;
        ends.d1 = to2(tj).normalized();
      }
      const bool lead_in = lin >= 0 && !lin_inner, lead_out = lout >= 0 && !lout_inner;
      RunFit rf;
      if (!fit_run(pts, ends, mean, opt, rf)) return false;
      ++res.runs_smoothed;
      res.max_fit_deviation = std::max(res.max_fit_deviation, rf.bound);
      // creases the curve passes, inside the run or at a lead line, are no kept corners (the count above
      // took every corner)
      for (std::size_t q = r0 + 1; q < r1; ++q)
        if (turn_at(q) > opt.max_turn) --res.corners_kept;
      if (lead_in && turn_between(dir(static_cast<std::size_t>(lin)), dir(r0)) > opt.max_turn) --res.corners_kept;
      if (lead_out && turn_between(dir(r1 - 1), dir(static_cast<std::size_t>(lout))) > opt.max_turn) --res.corners_kept;
      if (lead_in) {  // the line before now ends where the curve starts
        res.blocks.back().end = first3;
        if ((res.blocks.back().end - res.blocks.back().start).norm() <= 1e-12) {
          res.blocks.pop_back();
          res.controls.pop_back();
          res.source_first.pop_back();
          res.source_last.pop_back();
          program_line.pop_back();
          tangent_join.pop_back();
        }
      }
      if (lead_out) {  // the line after starts where the curve ends
        start_override_block = static_cast<long>(j);
        start_override = last3;
      }
      // parameter -> program block
      std::vector<double> cum(pts.size(), 0.0);
      for (std::size_t q = 1; q < pts.size(); ++q) cum[q] = cum[q - 1] + (pts[q] - pts[q - 1]).norm();
      auto block_at = [&](double u) {
        const long s = static_cast<long>(std::upper_bound(cum.begin(), cum.end(), u) - cum.begin()) - 1;
        return src[static_cast<std::size_t>(std::clamp(s, 0L, static_cast<long>(src.size()) - 1))];
      };
      if (lin_inner) {  // the tiny blocks kept at the corner, then block lin's first part up to the curve
        for (std::size_t q = i; q <= static_cast<std::size_t>(lin); ++q) keep(q);
        res.blocks.back().end = first3;
        tangent_join.back() |= 2;
      }
      Vec3 cur = first3;
      for (std::size_t q = 0; q < rf.pieces.size(); ++q) {
        const Piece& p = rf.pieces[q];
        toolpath::Block b = program[i];  // the chord of the cubic piece
        b.kind = MotionKind::line;
        b.start = cur;
        b.end = q + 1 == rf.pieces.size() ? last3 : to3(p.b3);
        if ((b.end - b.start).norm() <= 1e-12) continue;
        res.blocks.push_back(b);
        CubicControls cc;
        cc.cubic = true;
        cc.c1 = to3(p.b1);
        cc.c2 = to3(p.b2);
        res.controls.push_back(cc);
        res.source_first.push_back(block_at(p.ua));
        res.source_last.push_back(block_at(p.ub));
        program_line.push_back(false);
        tangent_join.push_back(3);
        cur = b.end;
      }
      if (lout_inner) {  // block lout's last part from the curve, then the tiny blocks kept at the corner
        keep(static_cast<std::size_t>(lout));
        res.blocks.back().start = last3;
        tangent_join.back() |= 1;
        for (std::size_t q = static_cast<std::size_t>(lout) + 1; q < j; ++q) keep(q);
      }
      return true;
    };
    // the vertex at q's start (at_start) or end joins another feed move turning more than max_turn
    auto corner_end = [&](std::size_t q, bool at_start) { return vertex_turn(at_start ? q : q + 1) > opt.max_turn; };
    // a run that fails the check is cut at its sharpest interior vertex and both parts are tried
    std::vector<std::pair<std::size_t, std::size_t>> parts{{i, j}};
    const auto mb = static_cast<std::size_t>(opt.min_blocks);
    while (!parts.empty()) {
      const auto [i0, j0] = parts.back();
      parts.pop_back();
      // a straight run (every vertex turning less than 1e-3 rad) next to a corner stays as programmed:
      // its lines are the curve already, and the corner is rounded between them
      bool straight = corner_end(i0, true) || corner_end(j0 - 1, false);
      for (std::size_t q = i0 + 1; q < j0 && straight; ++q) straight = turn_at(q) < 1e-3;
      if (straight) {
        for (std::size_t q = i0; q < j0; ++q) keep(q);
        continue;
      }
      if (j0 - i0 >= mb && fit_emit(i0, j0)) continue;
      if (j0 - i0 >= 2 * mb) {
        std::size_t cut = i0 + mb;
        double worst = -1;
        for (std::size_t q = i0 + mb; q + mb <= j0; ++q) {
          const double th = turn_at(q);
          if (th > worst) {
            worst = th;
            cut = q;
          }
        }
        parts.push_back({cut, j0});
        parts.push_back({i0, cut});
        continue;
      }
      if (j0 - i0 >= mb) ++res.runs_kept;
      for (std::size_t q = i0; q < j0; ++q) keep(q);
    }
    i = j;
  }
  // corners between two program lines become arcs within the fit tolerance (smoothing_round.hpp)
  if (opt.round_corners) round_line_corners(res, program_line, tangent_join, lead_min, opt);
  return res;
}
}  // namespace

}  // namespace netshape::motion
