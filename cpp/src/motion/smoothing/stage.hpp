#pragma once
// The tolerance-band smoothing stage (netshape/motion/smoothing.hpp) by concept (private):
//   runs.cpp     the program's runs and corners (ProgramView, find_run, run_plane, count_feed_corners);
//   run_fit.cpp  a run's leads, its samples, its fit (fit.hpp, checked by check.hpp) and its cubic
//                pieces, and the cut of a run that fails (smooth_run);
//   smoothing.cpp  smooth(): the walk over the program, then the corners between lines (round.hpp);
//   smoother.cpp   the streaming stage (netshape/motion/smoother.hpp).
// Everything reads the program as given; StageOutput collects the new blocks in order.
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "netshape/core/types.hpp"
#include "netshape/motion/smoothing.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

using V2 = Eigen::Vector2d;

/// The angle between two unit directions [rad].
inline double turn_between(const Vec3& u1, const Vec3& u2) {
  return std::atan2(u1.cross(u2).norm(), u1.dot(u2));
}

namespace detail {

/// Queries on a program's blocks for the run search and the leads (each vertex's turn computed once).
/// Block indices are positions in `program`; "the vertex q" is the vertex at the start of block q.
struct ProgramView {
  ProgramView(const std::vector<toolpath::Block>& program, const SmoothOptions& opt);

  const std::vector<toolpath::Block>& program;
  const SmoothOptions& opt;
  std::size_t nb;   ///< number of blocks
  /// shortest block whose direction is sure enough to lend a corner its line (corner_lead); shorter
  /// lines between two corners' lines are parts of one compound corner (round.hpp) [mm]
  double lead_min;

  /// Block i is a micro-segment: a line longer than 1e-9 mm and at most max_segment.
  bool micro(std::size_t i) const;
  /// Unit direction of line block i.
  Vec3 dir(std::size_t i) const;
  /// turn_between(dir(q − 1), dir(q)) [rad].
  double turn_at(std::size_t q) const;
  /// Line blocks a and a + 1 continue each other (joined, turning less than 1e-3 rad).
  bool straight_pair(long a) const;
  /// The side of a vertex that begins with block q and goes on with step ±1 is straight: past up to
  /// three blocks shorter than lead_min (tiny CAM blocks at a corner), a block continues the next one.
  bool straight_side(long q, long step) const;
  /// The vertex q (after micro-segment q − 1) is a corner that ends a run: it turns more than
  /// max_turn, and more than max_fit_turn or with straight sides. A vertex turning between the two
  /// where a curve meets it (a crease of a free-form surface, or a curve running into a straight side)
  /// stays inside the run, whose curve passes it within the fit tolerance.
  bool kept_corner(std::size_t q) const;
  /// The turn at the vertex c between two feed moves joined end to end, else 0 [rad].
  double vertex_turn(std::size_t c) const;
  /// The length the corner arc needs on each line at the vertex c (the arc within the fit tolerance
  /// of the vertex touches the lines R·tan(θ/2) from it, corner_arc_radius) [mm].
  double corner_need(std::size_t c) const;
  /// The part of block q a run uses as its lead: up to lead_length, at most half of q; when q is the
  /// run's end block next to a corner (beside: the length of the tiny blocks kept between them, need:
  /// corner_need), less, down to a tenth of q, so that the corner's line holds the length its arc
  /// needs [mm].
  double lead_part(std::size_t q, double beside, double need) const;
  /// The vertex at q's outer end (its start when at_start) turns at least 1e-3 rad.
  bool corner_at(std::size_t q, bool at_start) const;
  /// Block q, a run's end block beside block r of the run, may lend the run its inner part: at least
  /// lead_min long and turning at most max_turn / 2 against r.
  bool lends(std::size_t q, std::size_t r) const;
  /// corner_at(q, towards the corner) and lends(q, r).
  bool corner_lead(std::size_t q, std::size_t r) const;
  /// The number of tiny blocks (1 to 3) from q inward (step ±1) before a block that lends at the
  /// corner at q's outer end, or 0; room: the most blocks that may be passed.
  std::size_t corner_skip(std::size_t q, int step, std::size_t room) const;
  /// The vertex at q's start (at_start) or end joins another feed move turning more than max_turn.
  bool corner_end(std::size_t q, bool at_start) const;
  /// Block j (> i) continues a run that starts at block i: the same feed, joined to block j − 1, no
  /// kept corner between them.
  bool continues(std::size_t i, std::size_t j) const;

 private:
  mutable std::vector<double> turn_memo_;  // turn_at per vertex, −1 until asked
};

/// Number of vertices between feed moves (rapids and zero-length blocks skipped) turning more than
/// max_turn: every corner, before the runs' curves pass some of them.
long count_feed_corners(const ProgramView& view);

/// A run of micro-segments [first, last): one feed, joined end to end, no kept corner inside, at most
/// `window` blocks, all points in a coordinate plane; planes: bit a set when coordinate a is constant.
struct RunSpan {
  std::size_t first = 0, last = 0;
  int planes = 0;
};
/// The longest run from micro-segment i (last == i when block i is in no coordinate plane by itself).
RunSpan find_run(const ProgramView& view, std::size_t i);

/// A run's coordinate plane: its in-plane axes a, b, normal axis n and the normal coordinate nval [mm].
struct RunPlane {
  toolpath::PlaneAxes ax{};
  double nval = 0;
  Vec3 to3(const V2& p) const {
    Vec3 v;
    v[ax.a] = p.x();
    v[ax.b] = p.y();
    v[ax.n] = nval;
    return v;
  }
  V2 to2(const Vec3& p) const { return V2(p[ax.a], p[ax.b]); }
};
/// The plane of a run: a constant coordinate, preferring one that also holds the lines joined to the
/// run (so that they can lend it leads), then Z, then Y, then X.
RunPlane run_plane(const ProgramView& view, const RunSpan& run);

/// The new program as it is built.
struct StageOutput {
  SmoothResult res;
  std::vector<bool> program_line;  ///< per new block: a program line block or a part of one
  /// per new block: bit 0 its start, bit 1 its end joins a run's curve with the same tangent (set for
  /// the corner lines of runs only: a long line's length may differ between the chunks of a stream)
  std::vector<unsigned char> tangent_join;
  /// a line whose first part became the lead-out of the run before it starts later, at start_override
  long start_override_block = -1;
  Vec3 start_override = Vec3::Zero();

  /// Append program block i as it is (from start_override when it is that block).
  void keep(const std::vector<toolpath::Block>& program, std::size_t i);
  /// Remove the last new block.
  void pop_back();
};

/// Smooth the run: fitted with leads and checked (fit.hpp), its cubic pieces appended to out; a run
/// that fails is cut at its sharpest interior vertex and both parts tried again; a straight run next
/// to a corner and a part shorter than min_blocks that fails are kept as programmed.
void smooth_run(const ProgramView& view, const RunSpan& run, StageOutput& out);

/// The end of a run of micro-segments in space from micro-segment i: one feed, joined end to end, no
/// kept corner inside, at most `window` blocks, ending before a block where a planar run (find_run) of
/// at least min_blocks starts, so planar runs stay as they are.
std::size_t find_space_run(const ProgramView& view, std::size_t i);

/// Smooth a run in space [first, last): cut into pieces each within `space_flatness` of a plane through
/// its end points that holds the incoming tangent; each piece fitted in its plane within
/// fit_tolerance() − (its largest distance from the plane) and checked both ways there (fit.hpp), so
/// it is within fit_tolerance() of the polyline in space; consecutive pieces join with one tangent.
/// A piece that fails is halved; blocks no piece of min_blocks takes are kept as programmed.
void smooth_space_run(const ProgramView& view, std::size_t first, std::size_t last, StageOutput& out);

}  // namespace detail
}  // namespace netshape::motion
