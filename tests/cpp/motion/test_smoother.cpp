// netshape::motion::Smoother: the streamed output against the batch smooth(), push patterns, runs
// longer than the buffer, bad input, and Smoother -> Planner against smooth() + Planner.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "netshape/motion.hpp"
#include "netshape/toolpath/gcode_reader.hpp"

using namespace netshape;
using namespace netshape::motion;
using toolpath::Block;
using toolpath::MotionKind;

namespace {

// Builds a connected program from the current point.
struct Builder {
  std::vector<Block> blocks;
  Vec3 p = Vec3::Zero();
  void move(MotionKind kind, const Vec3& q, double feed) {
    Block b;
    b.kind = kind;
    b.start = p;
    b.end = q;
    b.feed = feed;
    b.line = static_cast<long>(blocks.size()) + 1;
    blocks.push_back(b);
    p = q;
  }
  void line(const Vec3& q, double feed = 200) { move(MotionKind::line, q, feed); }
  void rapid(const Vec3& q) { move(MotionKind::rapid, q, 200); }
  void arc(const Vec3& q, const Vec3& c, bool cw, double feed = 200) {
    move(MotionKind::arc, q, feed);
    blocks.back().center = c;
    blocks.back().clockwise = cw;
  }
  // n micro-segments through curve(t), t = 1/n .. 1, with curve(0) = p (the current point)
  void sampled(int n, const std::function<Vec3(double)>& curve, double feed = 200) {
    const Vec3 o = p - curve(0.0);
    for (int k = 1; k <= n; ++k) line(o + curve(static_cast<double>(k) / n), feed);
  }
};

// Several runs sampled from smooth curves with long lines between them (leads), sharp corners between
// micro-segments and between long lines, rapids, a plunge, an arc; the longest stretch of
// micro-segments is 120 blocks.
std::vector<Block> synthetic() {
  Builder b;
  b.rapid({0, 0, 5});
  b.rapid({0, 0, 0});
  b.line({12, 0, 0});
  b.sampled(70, [](double t) { return Vec3(20 * std::sin(1.2 * t), 20 * (1 - std::cos(1.2 * t)), 0); });
  b.line(b.p + 9.0 * Vec3(std::cos(1.2), std::sin(1.2), 0));  // tangent lead-out, 9 mm
  b.line(b.p + Vec3(0, 7, 0));                                  // corner between two long lines
  b.line(b.p + Vec3(-6, 2, 0));
  b.sampled(90, [](double t) { return Vec3(-30 * t, 2.5 * std::sin(6 * t), 0); });   // after a corner
  b.sampled(30, [](double t) { return Vec3(-2 * t, -9 * t + 0.4 * std::sin(4 * t), 0); });  // sharp corner inside
  b.line(b.p + Vec3(0, -5, 0));                                 // a 4..6 mm line: short lead
  const Vec3 c = b.p + Vec3(5, 0, 0);
  b.arc(b.p + Vec3(10, 0, 0), c, true);
  b.line(b.p + Vec3(0, -10, 0));
  b.rapid(b.p + Vec3(0, 0, 4));
  b.rapid(b.p + Vec3(15, 3, 4));
  b.line(b.p + Vec3(0, 0, -4));  // plunge
  b.line(b.p + Vec3(6, 0, 0));
  b.sampled(80, [](double t) {
    const double r = 8 + 4 * t, a = 5.0 * t;
    return Vec3(r * std::sin(a), 8 - r * std::cos(a), 0);
  });
  b.sampled(40, [](double t) { return Vec3(6 * t, -12 * t, 0.1 * t); }, 150);  // a 3-D stretch, other feed
  b.line(b.p + Vec3(0, 0, 5));
  b.sampled(60, [](double t) { return Vec3(0, 15 * t, 0); });  // a straight run in the YZ plane
  b.line(b.p + Vec3(0, 8, 0));
  return b.blocks;
}

// A random program: runs of 3-150 micro-segments along curves with wobble (0.05-1.55 mm steps), long
// lines (some just over max_segment, some turning), 5 um blocks, quarter arcs, rapid lifts and
// plunges, and sharp turns inside runs.
std::vector<Block> random_program(std::mt19937& g) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Builder b;
  b.rapid({0, 0, 5});
  b.rapid({0, 0, 0});
  double a = 0;
  auto heading = [&a] { return Vec3(std::cos(a), std::sin(a), 0); };
  const int stretches = 20 + static_cast<int>(g() % 40);
  for (int k = 0; k < stretches; ++k) {
    const double r = u(g);
    if (r < 0.45) {
      const int n = 3 + static_cast<int>(g() % 150);
      const double step = 0.05 + 1.5 * u(g), bend = (u(g) - 0.5) * 0.6, wobble = 0.3 * u(g);
      for (int q = 0; q < n; ++q) {
        a += bend * step + wobble * (u(g) - 0.5);
        b.line(b.p + step * heading());
      }
    } else if (r < 0.75) {
      if (u(g) < 0.5) a += 3.0 * (u(g) - 0.5);
      const double len = u(g) < 0.3 ? 4.001 + 0.5 * u(g) : 4.0 + 20.0 * u(g) * u(g);
      b.line(b.p + len * heading());
    } else if (r < 0.83) {
      b.line(b.p + 0.005 * Vec3(std::cos(a + 1), std::sin(a + 1), 0));
    } else if (r < 0.9) {
      const Vec3 c = b.p + 5.0 * Vec3(-std::sin(a), std::cos(a), 0), rel = b.p - c;
      b.arc(c + Vec3(-rel.y(), rel.x(), 0), c, false);
      a += 0.5 * pi;
    } else if (r < 0.95) {
      b.rapid(b.p + Vec3(0, 0, 3));
      b.rapid(b.p + Vec3(5 * u(g), 5 * u(g), 0));
      b.line(b.p + Vec3(0, 0, -3));
    } else {
      a += 2.5 * (u(g) - 0.5);
    }
  }
  return b.blocks;
}

struct Streamed {
  std::vector<SmoothedBlock> out;
  SmoothCounts counts;
};

// fill_then_drain: push until the buffer is full, then take all out; one_then_pull: push one, take all
// out; bursts: push seven, take all out; pull_driven: next() first, push one when it needs blocks
enum class Pattern { fill_then_drain, one_then_pull, bursts, pull_driven };

Streamed stream(const std::vector<Block>& prog, const SmoothOptions& o, Pattern pat,
                int min_chunk = Smoother::default_min_chunk) {
  Smoother s(o, min_chunk);
  Streamed r;
  SmoothedBlock sb;
  std::size_t i = 0;
  auto drain = [&] {
    Status st;
    while ((st = s.next(sb)) == Status::ok) r.out.push_back(sb);
    return st;
  };
  if (pat == Pattern::pull_driven) {
    for (;;) {
      const Status st = s.next(sb);
      if (st == Status::ok) {
        r.out.push_back(sb);
      } else if (st == Status::need_blocks) {
        if (i < prog.size()) REQUIRE(s.push(prog[i++]) == Status::ok);
        else s.finish();
      } else {
        REQUIRE(st == Status::finished);
        break;
      }
    }
  } else {
    while (i < prog.size()) {
      const Status st = s.push(prog[i]);
      if (st == Status::ok) {
        ++i;
        if (pat == Pattern::one_then_pull || (pat == Pattern::bursts && i % 7 == 0))
          REQUIRE(drain() == Status::need_blocks);
      } else {
        REQUIRE(st == Status::buffer_full);
        REQUIRE(s.free_blocks() == 0);
        REQUIRE(drain() == Status::need_blocks);
      }
    }
    s.finish();
    REQUIRE(drain() == Status::finished);
  }
  CHECK(s.blocks_pushed() == static_cast<long>(prog.size()));
  r.counts = s.counts();
  return r;
}

void check_equal(const SmoothResult& batch, const Streamed& st) {
  REQUIRE(st.out.size() == batch.blocks.size());
  double worst = 0;
  int kinds = 0, sources = 0;
  for (std::size_t k = 0; k < batch.blocks.size(); ++k) {
    const Block &a = batch.blocks[k], &b = st.out[k].block;
    const CubicControls &ca = batch.controls[k], &cb = st.out[k].controls;
    kinds += a.kind != b.kind || a.clockwise != b.clockwise || a.plane != b.plane || ca.cubic != cb.cubic;
    if (ca.cubic) worst = std::max({worst, (ca.c1 - cb.c1).norm(), (ca.c2 - cb.c2).norm()});
    sources += batch.source_first[k] != st.out[k].source_first || batch.source_last[k] != st.out[k].source_last;
    worst = std::max({worst, (a.start - b.start).norm(), (a.end - b.end).norm()});
    if (a.kind == MotionKind::arc) worst = std::max(worst, (a.center - b.center).norm());
  }
  CHECK(kinds == 0);
  CHECK(sources == 0);
  CHECK(worst == 0.0);  // bit for bit
  CHECK(st.counts.runs_smoothed == batch.runs_smoothed);
  CHECK(st.counts.runs_kept == batch.runs_kept);
  CHECK(st.counts.corners_kept == batch.corners_kept);
  CHECK(st.counts.corners_rounded == batch.corners_rounded);
  CHECK(st.counts.max_fit_deviation == batch.max_fit_deviation);
  CHECK(st.counts.forced_cuts == 0);
}

// Points along every output block (ends and interior), with its sources, against the program.
double deviation(const std::vector<Block>& prog, const std::vector<SmoothedBlock>& out) {
  const int per = 8;
  Points3 pts(static_cast<Eigen::Index>(out.size() * (per + 1)), 3);
  std::vector<long> first, last;
  Eigen::Index row = 0;
  for (const auto& sb : out)
    for (int q = 0; q <= per; ++q) {
      pts.row(row++) = (sb.controls.cubic
                            ? bezier_point({sb.block.start, sb.controls.c1, sb.controls.c2, sb.block.end},
                                           static_cast<double>(q) / per)
                            : sb.block.point_at(static_cast<double>(q) / per))
                           .transpose();
      first.push_back(sb.source_first);
      last.push_back(sb.source_last);
    }
  return deviation_to_program(prog, pts, first, last);
}

double max_gap(const std::vector<SmoothedBlock>& out) {
  double g = 0;
  for (std::size_t k = 1; k < out.size(); ++k) g = std::max(g, (out[k].block.start - out[k - 1].block.end).norm());
  return g;
}

// 3D_Chips.ngc from $NETSHAPE_SHARED_DATA (or the shared folder next to the repository); empty if absent.
std::vector<Block> chips() {
  const char* env = std::getenv("NETSHAPE_SHARED_DATA");
  const std::string path = (env ? std::string(env) : std::string(NETSHAPE_SHARED_DIR) + "/data") + "/gcode/3D_Chips.ngc";
  if (!std::ifstream(path)) return {};
  return toolpath::read_gcode(path).blocks;
}

}  // namespace

TEST_CASE("smoother: streamed output equals smooth() on a synthetic program, every push pattern") {
  const auto prog = synthetic();
  for (const int window : {64, 100, 4096}) {
    SmoothOptions o;
    o.window = window;
    const SmoothResult batch = smooth(prog, o);
    CHECK(batch.runs_smoothed >= 4);
    CHECK(batch.corners_rounded >= 1);
    // min_chunk 1: a cut at every cut block; 1 << 20: only when the buffer is full
    for (const int min_chunk : {1, 20, Smoother::default_min_chunk, 1 << 20})
      for (const Pattern pat :
           {Pattern::fill_then_drain, Pattern::one_then_pull, Pattern::bursts, Pattern::pull_driven}) {
        CAPTURE(window);
        CAPTURE(min_chunk);
        CAPTURE(static_cast<int>(pat));
        const Streamed st = stream(prog, o, pat, min_chunk);
        check_equal(batch, st);
        if (window == 64) CHECK(st.counts.chunks >= 4);  // the program really went through in pieces
        if (min_chunk == 1 && pat == Pattern::pull_driven) CHECK(st.counts.chunks >= 10);
      }
  }
}

TEST_CASE("smoother: random programs, cut at every cut block or in bursts, equal smooth() bit for bit") {
  int compared = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    std::mt19937 g(seed);
    const auto prog = random_program(g);
    SmoothOptions o;
    o.window = seed % 3 == 0 ? 200 : 4096;
    o.tolerance = seed % 2 ? 0.01 : 0.05;
    const int min_chunk = seed % 4 == 0 ? 1 : seed % 4 == 1 ? 5 : seed % 4 == 2 ? 64 : 1000;
    CAPTURE(seed);
    const SmoothResult batch = smooth(prog, o);
    const Streamed st = stream(prog, o, seed % 2 ? Pattern::pull_driven : Pattern::bursts, min_chunk);
    if (st.counts.forced_cuts > 0) {  // a stretch longer than the buffer: within tolerance, not batch
      CHECK(deviation(prog, st.out) <= o.fit_tolerance() + 1e-9);
      CHECK(max_gap(st.out) <= 1e-9);
      continue;
    }
    check_equal(batch, st);
    ++compared;
  }
  CHECK(compared >= 30);
}

TEST_CASE("smoother: runs longer than the buffer are cut at a vertex and stay within tolerance") {
  const auto prog = synthetic();
  SmoothOptions o;
  o.window = 8;  // 18 blocks held: every run of the program is longer
  const Streamed st = stream(prog, o, Pattern::fill_then_drain);
  CHECK(st.counts.forced_cuts > 0);
  CHECK(st.counts.runs_smoothed > 0);
  CHECK(deviation(prog, st.out) <= o.fit_tolerance() + 1e-9);
  CHECK(max_gap(st.out) <= 1e-9);
  for (std::size_t k = 1; k < st.out.size(); ++k) {
    CHECK(st.out[k].source_first >= st.out[k - 1].source_first);
    CHECK(st.out[k].source_last < static_cast<long>(prog.size()));
  }
}

TEST_CASE("smoother: bad blocks are refused with the field named, nothing added; bad options throw") {
  SmoothOptions o;
  o.window = 8;
  Smoother s(o);
  const auto prog = synthetic();
  REQUIRE(s.push(prog[0]) == Status::ok);
  Block bad = prog[1];
  bad.end.y() = std::nan("");
  const int room = s.free_blocks();
  CHECK(s.push(bad) == Status::invalid_input);
  CHECK(std::string(s.last_error()).find("block 1") != std::string::npos);
  CHECK(std::string(s.last_error()).find("block.end") != std::string::npos);
  CHECK(s.free_blocks() == room);
  CHECK(s.blocks_pushed() == 1);
  bad = prog[1];
  bad.feed = -1;
  CHECK(s.push(bad) == Status::invalid_input);
  CHECK(std::string(s.last_error()).find("block.feed") != std::string::npos);
  CHECK(s.push(prog[1]) == Status::ok);
  s.finish();
  CHECK(s.push(prog[2]) == Status::invalid_input);
  SmoothedBlock sb;
  int n = 0;
  while (s.next(sb) == Status::ok) ++n;
  CHECK(n == 2);
  CHECK(s.next(sb) == Status::finished);
  s.reset();
  CHECK(s.free_blocks() == s.capacity());
  CHECK(s.next(sb) == Status::need_blocks);
  o.window = 4;
  CHECK_THROWS_WITH_AS(Smoother{o}, doctest::Contains("window"), std::invalid_argument);
  o.window = 8;
  CHECK_THROWS_WITH_AS(Smoother(o, 0), doctest::Contains("min_chunk"), std::invalid_argument);
  // a moved first start needs a first block that is a line no run takes in, and a point on it
  CHECK_THROWS_WITH_AS(smooth(prog, o, prog[0].start), doctest::Contains("blocks[0].kind"), std::invalid_argument);
  const std::vector<Block> from_line(prog.begin() + 2, prog.end());  // starts with the 12 mm line
  REQUIRE(from_line[0].length() > o.max_segment);
  const std::vector<Block> from_micro(prog.begin() + 3, prog.end());  // a micro-segment first
  CHECK_THROWS_WITH_AS(smooth(from_micro, o, from_micro[0].start), doctest::Contains("longer than max_segment"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(smooth(from_line, o, from_line[0].start + Vec3(0, 0.001, 0)),
                       doctest::Contains("first_start"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(smooth(from_line, o, from_line[0].end), doctest::Contains("first_start"), std::invalid_argument);
  const SmoothResult later = smooth(from_line, o, from_line[0].start + Vec3(3, 0, 0));
  CHECK((later.blocks[0].start - Vec3(3, 0, 0)).norm() == 0.0);
  CHECK(later.blocks[0].end == smooth(from_line, o).blocks[0].end);
}

TEST_CASE("smoother: output starts at the first cut block after min_chunk blocks, not at a full buffer") {
  const auto prog = synthetic();
  // the cut blocks: non-zero length and no micro-segment (SmoothOptions defaults: lines up to 4 mm are)
  std::vector<std::size_t> cuts;
  for (std::size_t c = 1; c < prog.size(); ++c)
    if (prog[c].length() > 1e-9 && !(prog[c].kind == MotionKind::line && prog[c].length() <= 4.0)) cuts.push_back(c);
  SmoothOptions o;  // window 4096: the buffer holds the whole program
  for (const int min_chunk : {1, 20, 100}) {
    CAPTURE(min_chunk);
    Smoother s(o, min_chunk);
    SmoothedBlock sb;
    std::size_t pushed = 0;
    Status st;
    while ((st = s.next(sb)) == Status::need_blocks) {
      REQUIRE(pushed < prog.size());
      REQUIRE(s.push(prog[pushed++]) == Status::ok);
    }
    REQUIRE(st == Status::ok);
    // the first chunk ended at a cut block c >= min_chunk, pushed last: the first such one unless
    // its cut was refused (then a later one)
    std::size_t first = 0;
    for (const std::size_t c : cuts)
      if (c >= static_cast<std::size_t>(min_chunk)) {
        first = c;
        break;
      }
    REQUIRE(first > 0);
    CHECK(pushed >= first + 1);
    CHECK(std::find(cuts.begin(), cuts.end(), pushed - 1) != cuts.end());
    CHECK(pushed <= first + 60);
    CHECK(sb.source_first == 0);
    CHECK(s.counts().chunks == 1);
  }
}

TEST_CASE("smoother: 3D_Chips streamed equals batch; tiny window stays within tolerance") {
  const auto prog = chips();
  if (prog.empty()) {
    MESSAGE("shared data absent (NETSHAPE_SHARED_DATA): skipped");
    return;
  }
  for (const int window : {160, 1000, 4096}) {
    SmoothOptions o;
    o.window = window;
    const SmoothResult batch = smooth(prog, o);
    for (const int min_chunk : {1, Smoother::default_min_chunk})
      for (const Pattern pat : {Pattern::fill_then_drain, Pattern::pull_driven}) {
        CAPTURE(window);
        CAPTURE(min_chunk);
        const Streamed st = stream(prog, o, pat, min_chunk);
        check_equal(batch, st);
        // pulled block by block, the default window too goes through in chunks (3D_Chips has a long
        // line every 20-140 blocks)
        if (window == 160 || pat == Pattern::pull_driven) CHECK(st.counts.chunks > 10);
      }
  }
  SmoothOptions o;
  o.window = 16;
  const Streamed st = stream(prog, o, Pattern::one_then_pull);
  CHECK(st.counts.forced_cuts > 0);
  CHECK(deviation(prog, st.out) <= o.fit_tolerance() + 1e-9);
  CHECK(max_gap(st.out) <= 1e-9);
}

TEST_CASE("smoother -> planner on 3D_Chips: the cycle time of smooth() + planner") {
  const auto prog = chips();
  if (prog.empty()) {
    MESSAGE("shared data absent (NETSHAPE_SHARED_DATA): skipped");
    return;
  }
  SmoothOptions so;
  so.window = 160;
  PlanOptions po;
  po.rule = CornerRule::blend;
  po.tolerance = so.blend_tolerance();
  const AxisLimits lim = AxisLimits::uniform(250, 3000);
  // batch: smooth the whole program, then stream its blocks into the planner
  const SmoothResult batch = smooth(prog, so);
  Planner pb(lim, po);
  Sample s;
  std::size_t i = 0;
  long nb = 0;
  double tb = 0;
  for (Status st; (st = pb.next(s)) != Status::finished;) {
    if (st == Status::ok) {
      tb = s.t;
      ++nb;
    } else if (i < batch.blocks.size()) {
      pb.push(batch.blocks[i], batch.controls[i]);
      ++i;
    } else {
      pb.finish();
    }
  }
  // streaming: program -> smoother -> planner, one block at a time
  Smoother sm(so);
  Planner ps(lim, po);
  SmoothedBlock sb;
  i = 0;
  long ns = 0;
  double ts = 0;
  for (Status st; (st = ps.next(s)) != Status::finished;) {
    if (st == Status::ok) {
      ts = s.t;
      ++ns;
      continue;
    }
    const Status ss = sm.next(sb);
    if (ss == Status::ok) REQUIRE(ps.push(sb.block, sb.controls) == Status::ok);
    else if (ss == Status::finished) ps.finish();
    else if (i < prog.size()) REQUIRE(sm.push(prog[i++]) == Status::ok);
    else sm.finish();
  }
  MESSAGE("3D_Chips cycle: batch " << tb << " s, streamed " << ts << " s, " << sm.counts().chunks << " chunks");
  CHECK(tb > 30.0);
  CHECK(std::abs(ts - tb) <= 1e-9);
  CHECK(ns == nb);
}

TEST_CASE("smoother: a line behind a rounded vertex is no cut, even when it moved as far as a lead") {
  // Two collinear 4 mm micro-segments (too few for a run, kept) before a 10 mm line turning 0.5°: the
  // rounded vertex moves the line's start by half a micro-segment, 2 mm = lead_length, as a lead
  // would. The next (20 mm) line turns 0.5° again; its corner arc is capped by half of the line before,
  // so a chunk starting at the moved line would round it differently from the whole program.
  Builder b;
  b.rapid({0, 0, 5});
  b.rapid({0, 0, 0});
  b.line({6, 0, 0});
  b.line({10, 0, 0});
  b.line({14, 0, 0});
  const double th = 0.5 * pi / 180;
  b.line(b.p + 10.0 * Vec3(std::cos(th), std::sin(th), 0));
  b.line(b.p + 20.0 * Vec3(std::cos(2 * th), std::sin(2 * th), 0));
  b.sampled(12, [](double t) { return Vec3(8 * std::sin(t), 8 * (1 - std::cos(t)), 0); });
  b.line(b.p + Vec3(0, 8, 0));
  // With 18 blocks held the buffer is full in the run after those lines, and the moved 10 mm line is
  // the last cut block left to try: the contract is that a stream without a forced cut is the batch.
  SmoothOptions o;
  o.window = 8;
  SmoothResult batch = smooth(b.blocks, o);
  CHECK(batch.corners_rounded >= 2);
  for (const Pattern pat : {Pattern::fill_then_drain, Pattern::pull_driven}) {
    const Streamed st = stream(b.blocks, o, pat);
    if (st.counts.forced_cuts == 0) check_equal(batch, st);
    CHECK(deviation(b.blocks, st.out) <= o.fit_tolerance() + 1e-9);
    CHECK(max_gap(st.out) <= 1e-9);
  }
  o.window = 64;  // everything in one buffer: the batch
  check_equal(batch = smooth(b.blocks, o), stream(b.blocks, o, Pattern::one_then_pull));
}

TEST_CASE("smoother -> planner on 3D_Chips with jerk limits: every profile covers exactly its segment") {
  // With jerk limits a cubic block is planned as a whole until the block after it arrives and then cut
  // into pieces; S-curve ramps do not add up over pieces, so the whole block must not promise the block
  // before it a slow-down its first piece cannot do (that showed as profiles longer than their piece:
  // the samples stood still, then jumped back).
  const auto prog = chips();
  if (prog.empty()) {
    MESSAGE("shared data absent (NETSHAPE_SHARED_DATA): skipped");
    return;
  }
  SmoothOptions so;
  const SmoothResult sr = smooth(prog, so);
  PlanOptions po;
  po.rule = CornerRule::blend;
  po.tolerance = so.blend_tolerance();
  AxisLimits lim = AxisLimits::uniform(250, 3000);
  lim.jerk = Vec3::Constant(1e5);
  Planner p(lim, po);
  PlannedSegment seg;
  std::size_t i = 0;
  long segments = 0, bad = 0;
  double worst = 0;
  for (Status st; (st = p.next_segment(seg)) != Status::finished;) {
    if (st == Status::ok) {
      ++segments;
      double d = 0;
      for (const double x : seg.profile.d) d += x;
      const double err = std::abs(d - seg.segment.length());
      worst = std::max(worst, err);
      if (err > 1e-9 * std::max(1.0, seg.segment.length())) ++bad;
    } else if (i < sr.blocks.size()) {
      p.push(sr.blocks[i], sr.controls[i]);
      ++i;
    } else {
      p.finish();
    }
  }
  MESSAGE(segments << " segments, largest |profile distance - length| " << worst << " mm");
  CHECK(segments > 10000);
  CHECK(bad == 0);
}
