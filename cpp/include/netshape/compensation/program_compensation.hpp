#pragma once
/// \file program_compensation.hpp
/// Volumetric compensation of a whole program (Yang & Kweon §4.2, post-processor): a Toolpath whose
/// actual tool tip, on a machine with geometric errors, follows the nominal program within a chord
/// tolerance.
///
/// What happens to each block (the input is in the frame the machine model is indexed by: machine
/// axis positions when the program was read with work offsets / tool lengths):
/// - every block end point is compensated to `point.tolerance` (compensate_points_status); a block
///   starts where the previous one ended, except where the program jumps (start ≠ previous end: that
///   start is compensated too); the first block's start is the reader's initial position, which is
///   not a programmed point, and is left as it is;
/// - rapids move to their compensated ends;
/// - a line becomes one or more lines: each output segment is halved until the actual path between
///   compensated points, checked at ¼, ½ and ¾ of it, stays within `chord_tolerance` of the nominal
///   line and, on a machine with cyclic terms, it is no longer than a quarter of the shortest period
///   (at most `max_halvings` times);
/// - an arc stays a (moved) arc when the moved arc's actual path, checked at max(8, n) points with
///   n = toolpath::chord_count(r, sweep, chord_tolerance / 2), stays within `chord_tolerance` of the
///   nominal arc and the moved arc does not change the difference of its end radii by more than
///   chord_tolerance / 2; its centre moves by the mean of the start and end corrections (normal-axis
///   coordinate: the start's). Otherwise it becomes max(2, n) compensated chords, each halved like a line;
/// - every output block carries the modal state (feed, spindle, tool, line) of its source block, and
///   every command keeps its order and place (Toolpath::with_blocks).
/// Failures name the source line: a compensated point outside an axis' travel or outside an error
/// table, or a segment still off the path after `max_halvings` (std::invalid_argument); a point that
/// does not converge (netshape::Error).
///
/// State-dependent errors (machine/state_error.hpp): every point is compensated for the tip offset
/// s(d, t) of its block: d the axes' approach directions (the sign of each axis' last motion, from
/// `initial_direction`), t the program time (`block_times`, linear within a block). On a machine
/// with backlash every arc is written as chords (an arc may reverse an axis inside it), and a feed
/// block that reverses an axis with backlash starts with a take-up move: from the previous commanded
/// end to this block's commanded start, over which the lost motion is taken up and the tip stays.
///
/// All units mm.

#include <string>
#include <vector>

#include "netshape/compensation/volumetric_compensation.hpp"
#include "netshape/machine/machine.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::compensation {

/// Options of compensate_program.
struct ProgramOptions {
  double chord_tolerance = 0.002;  ///< largest deviation of the actual path from the nominal one [mm], > 0
  VolumetricOptions point{};       ///< per-point compensation (tolerance [mm], iterations, travel check)
  int max_halvings = 30;           ///< halvings of one segment before giving up, ≥ 0
  /// Program time at each block's end [s] (a feed plan's time stamps; one per block, non-decreasing),
  /// for a machine with thermal drift. Empty: the programmed feeds (block length / feed, rapids at
  /// `rapid_feed`), see block_end_times.
  std::vector<double> block_times;
  double rapid_feed = 250.0;             ///< rapid speed for the default block times [mm/s], > 0
  Vec3 initial_direction = Vec3(1, 1, 1);  ///< approach direction of each axis before it first moves
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// What compensate_program did.
struct ProgramReport {
  std::string source;                 ///< the program's source name
  long blocks_in = 0;                 ///< motion blocks read
  long blocks_out = 0;                ///< motion blocks written
  long lines_split = 0;               ///< lines written as more than one line
  long arcs_kept = 0;                 ///< arcs written as (moved) arcs
  long arcs_split = 0;                ///< arcs written as compensated chords
  double max_correction = 0.0;        ///< largest |P_cmd − P_nom| of the compensated points [mm]
  double max_residual = 0.0;          ///< largest |P_cmd + e(P_cmd) − P_nom| [mm]
  double max_path_deviation = 0.0;    ///< largest checked deviation of the actual path [mm]
  long commands = 0;                  ///< comments and non-motion words carried over
  long takeup_moves = 0;              ///< take-up moves written at axis reversals (backlash)
};

/// The compensated program and its report.
struct ProgramResult {
  toolpath::Toolpath toolpath;
  ProgramReport report;
};

/// Program time at each block's end from the programmed feeds [s]: cumulative length / feed, rapids
/// (and blocks without a feed) at `rapid_feed` [mm/s].
std::vector<double> block_end_times(const toolpath::Toolpath& program, double rapid_feed = 250.0);

/// Compensate `program` (block coordinates in the machine model's frame) on `machine`; see the file
/// comment for what happens to each block. Messages name `program.source` ("<program>" when empty)
/// and the source line.
ProgramResult compensate_program(const machine::Machine& machine, const toolpath::Toolpath& program,
                                 const ProgramOptions& options = {});

}  // namespace netshape::compensation
