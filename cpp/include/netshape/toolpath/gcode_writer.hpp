#pragma once
/// \file gcode_writer.hpp
/// RS274/NGC writer: a Toolpath back to G-code (mm, absolute, modal). What it writes reads back
/// (GcodeReader) into the same blocks and the same commands: coordinates exactly (shortest round-trip
/// number form; to rounding of the offsets when work offsets / tool lengths are applied), arc centres
/// and feeds to a few units in the last place, command texts exactly.

#include <ostream>
#include <string>

#include "netshape/toolpath/toolpath.hpp"

namespace netshape::toolpath {

/// Largest feed the writer writes, F [mm/min] (1.67e6 mm/s): far above any machine tool and the rapid
/// feeds programs write as F words (3D_Chips.ngc has F4500000), far below the numbers whose F words stop
/// being a feed. A block feed above it throws std::invalid_argument.
constexpr double max_feed_mm_per_min = 1e8;

/// Options of the writer.
struct WriterOptions {
  bool split_arcs = false;         ///< write arcs as G1 chords instead of G2/G3
  double chord_tolerance = 0.002;  ///< chord error when splitting arcs [mm]
  int decimals = -1;               ///< -1: shortest form that reads back exactly; 0…12: fixed decimals
  bool absolute_arc_centers = false;  ///< G90.1 absolute I/J/K (exact centres) instead of G91.1 offsets
  std::string header_comment;      ///< written as a "( … )" comment on the first line when not empty
  /// When no work_offset command precedes the first block, write "G54" after the "G21 …" line: the
  /// program then names the frame its coordinates are in (G54 is the one in force at the start).
  bool work_offset_word = false;
  void validate() const;
};

/// Write `toolpath` as G-code to `out`: a "G21 G90 G17 G94 G91.1" header; every Command (comment,
/// M/S/T word, G4 dwell, G43/G49, G54…, G64 …) as written in `text`, on its own line, before the block it
/// precedes, in order; one line per block with only the words that change (modal G, F in mm/min rounded
/// to 1e-6, and S/M3/M4/M5, T…M6 where a block's spindle or tool differs from what the commands set).
/// Coordinates are written in program coordinates: the work offset and tool length that the written
/// G54…/G43 commands put in force (from `toolpath.work_offsets` and the commands' values) are
/// subtracted. A block whose start is not where the previous one ended is preceded by a G0 to its start.
/// Ends with the program's M2/M30 command, or M2 when it has none. Throws std::invalid_argument for
/// non-finite blocks, a feed above max_feed_mm_per_min, decreasing `before`, multi-line command text or a block after the program end.
void write_gcode(const Toolpath& toolpath, std::ostream& out, const WriterOptions& options = {});

/// The G-code text of `toolpath` (see write_gcode).
std::string format_gcode(const Toolpath& toolpath, const WriterOptions& options = {});

}  // namespace netshape::toolpath
