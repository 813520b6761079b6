#pragma once
/// \file smoothing.hpp
/// Tolerance-band smoothing of micro-segment programs, a stage before the planner.
///
/// A run of short line blocks (each at most `max_segment` long, every interior turn at most
/// `max_turn`, one feed, all points in one coordinate plane G17/G18/G19) is replaced by a smoothing
/// spline of the run, handed out as one cubic Bézier block per knot span (cubic.hpp: a line block, the
/// chord, plus its inner control points), so the new path is curvature-continuous along a run: a cubic
/// B-spline that minimises the weighted squared distance to samples of the polyline plus ℓ⁴·∫|s''|²
/// (`smoothing_length` ℓ), then is pulled back into the tube by raising the weights of the samples it
/// leaves, each round solving only the control points near them (knots are added next to samples that
/// stay out for several rounds, samples where the check below fails between two). A long line adjoining a
/// run lends it up to `lead_length`, so the curve joins the line tangentially. The spline is checked
/// against the run's polyline both ways — every point of the spline within `fit_tolerance()` of the
/// polyline and every point of the polyline within it of the spline — with rigorous upper bounds from
/// chord samples (below). A run that still fails after `max_refinements` rounds is cut at its sharpest
/// interior vertex and both parts are tried again; a part shorter than `min_blocks` that fails is left
/// as programmed. A run in space (micro-segments in no coordinate plane, up to where a planar run
/// starts) is cut into pieces, each within space_flatness·fit_tolerance() = h_max of a plane through
/// its end points holding the tangent it starts with; a piece is fitted in its plane as above within
/// fit_tolerance() − h (h: its vertices' largest distance from the plane), so it is within
/// fit_tolerance() of the polyline in space both ways (the projection moves no point by more than h).
/// Consecutive pieces share their tangent; a run's ends take the tangent of the feed move across them,
/// or at a corner the end block's corner-side half stays a line. Vertices turning more than `max_turn`
/// are corners: they end a run, except where a curve
/// meets one turning at most `max_fit_turn` (not straight on both sides): the run's curve passes it. A
/// straight run next to a corner stays as programmed. A vertex between two program lines (a corner
/// between lines, a vertex of a run left as programmed) becomes a tangent arc inside it whose distance
/// from the vertex is at most `fit_tolerance()` (`round_corners`), one arc for a corner turned over
/// several blocks shorter than max(0.02 mm, 2·tolerance); the planner's blend rule blends the rest within
/// the remaining tolerance. Arcs, rapids and other long lines pass through unchanged.
///
/// Error bounds: between two chord points c0 = s(u0), c1 = s(u1) in one knot span the spline deviates
/// from the chord by at most σ = (u1 − u0)²/8 · max|s''| (s'' is linear on a span); dist(c, S) to a
/// polyline segment S is convex along the chord, so every spline point between them is within
/// max(dist(c0, S), dist(c1, S)) + σ of S; likewise a polyline piece [q0, q1] is within
/// max(dist(q0, C), dist(q1, C)) + σ of the spline when C is the chord [c0, c1].
///
/// Units: mm, rad.

#include <vector>

#include "netshape/motion/cubic.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

/// Options of the smoothing stage.
struct SmoothOptions {
  double tolerance = 0.01;    ///< total contour tolerance ε [mm] (fit plus the planner's corner blends)
  double fit_share = 0.98;    ///< share of ε given to the fitted curves; the rest is the blend tolerance
  double max_segment = 4.0;   ///< a line longer than this is not a micro-segment [mm]
  double max_turn = 0.5236;   ///< a vertex turning more than this (30°) is a corner that is kept [rad]
  /// a corner turning at most this (92°) that a curve meets (not straight on both sides) stays inside
  /// the run, passed by its curve within the fit tolerance; 0 keeps every corner [rad]
  double max_fit_turn = 1.6057;
  int min_blocks = 3;         ///< shortest run that is smoothed [blocks]
  int window = 4096;          ///< longest run fitted at once [blocks] (longer runs are cut at a vertex)
  int max_refinements = 60;   ///< pull-back rounds (refit with raised weights) before a run is cut / kept
  double smoothing_length = 1.5;   ///< ℓ: the fit minimises Σ w·dist² + ℓ⁴·∫|s''|² (ℓ in mm)
  double knot_spacing = 1.0;  ///< knot spacing of the spline in mean segment lengths of the run
  double lead_length = 2.0;   ///< longest part of an adjoining line a run's curve may use [mm]
  bool round_corners = true;  ///< replace the vertex between two program lines by an arc within fit_tolerance()
  double plane_tolerance = 1e-9;  ///< a run is planar when its normal coordinate varies less [mm]
  /// runs in space (in no coordinate plane) are smoothed in pieces each within this share of the fit
  /// tolerance of a plane (the rest of it is the fit's); 0 leaves them as programmed
  double space_flatness = 0.5;

  /// Tolerance of the fitted curves (and corner arcs) against the polyline [mm].
  double fit_tolerance() const noexcept { return tolerance * fit_share; }
  /// Tolerance left for the planner's corner blends [mm].
  double blend_tolerance() const noexcept { return tolerance * (1.0 - fit_share); }
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Output of smooth(): the new blocks and, per new block, the range of program blocks it replaces.
struct SmoothResult {
  std::vector<toolpath::Block> blocks;  ///< a cubic piece: its chord (kind line), see `controls`
  std::vector<CubicControls> controls;  ///< per new block: the inner control points of a cubic piece
  std::vector<long> source_first, source_last;  ///< per new block: first / last program block index
  long runs_smoothed = 0;   ///< runs replaced by a spline
  long runs_kept = 0;       ///< runs that failed the check and were left as programmed
  long corners_kept = 0;    ///< vertices between feed moves turning more than max_turn, but for creases a curve passes
  long corners_rounded = 0; ///< vertices between two program lines replaced by an arc
  double max_fit_deviation = 0;  ///< largest checked bound over the smoothed runs, both ways [mm]
};

/// Smooth a program (blocks in order, consecutive blocks joined). Throws std::invalid_argument on
/// bad options or blocks.
SmoothResult smooth(const std::vector<toolpath::Block>& program, const SmoothOptions& options);

/// smooth() of a program whose first block, a line, was partly used by what came before it (the run
/// before it borrowed its first part as a lead, as when the streaming Smoother cuts a program in
/// chunks): that block's output starts at `first_start`, a point on it. Everything else reads the
/// block as programmed, so a chunk cut at such a line gives the bits of smooth() on the whole program.
/// Throws std::invalid_argument also when the first block is no line longer than max_segment (a block
/// no run takes in) or `first_start` is not on it.
SmoothResult smooth(const std::vector<toolpath::Block>& program, const SmoothOptions& options,
                    const Vec3& first_start);

/// Largest distance of the points to the program [mm]: point k is measured against the program
/// blocks [first[k] − 1, last[k] + 1] (its source range widened by one block on each side).
double deviation_to_program(const std::vector<toolpath::Block>& program, const Points3& points,
                            const std::vector<long>& first, const std::vector<long>& last);

}  // namespace netshape::motion
