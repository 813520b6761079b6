#pragma once
/// \file gcode_reader.hpp
/// Streaming RS274/NGC (LinuxCNC dialect) reader: turns program text into motion blocks one at a
/// time, holding only the current line and the modal state, so programs of any length read in
/// bounded memory.
///
/// Supported subset (docs/toolpath.md has the full list): G0 G1 G2 G3 (I J K and R forms, full
/// circles, P turns, helical), G4 dwell, G17/18/19, G20/21 (inch input converted to mm), G90/G91,
/// G90.1/G91.1, G94, F S T M0 M1 M2 M3 M4 M5 M6 M30, N words, comments, `%` lines, numbered and
/// named parameters and `[...]` expressions, `O1234` program numbers (kept as words), LinuxCNC
/// subroutines `oN sub`/`endsub`/`call`/`return` (a call replays the body; its blocks carry the call's
/// line). Work offsets G54–G59.3 and tool length G43 H / G49 are
/// applied from ReaderOptions when given (otherwise taken as zero, with one warning). Codes that do
/// not move the tool (G40, G61/G61.1/G64 P Q, G80, G92.1/G92.2, G97, G98/G99, M0 M1 M7–M9, M48–M53,
/// M60 …) and comments are kept as Commands in program order. Everything else that would change the
/// path (cutter compensation G41/G42, canned cycles, NURBS, G92 offsets, G93/G95 feed modes, o-word
/// control flow, M98/M99, rotary axes …) is refused with a ParseError naming the line, the
/// column and the word.
///
/// Units of the output: mm, mm/s (the G-code F word is in mm/min or in/min), s (G4 P).

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/toolpath/block.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::toolpath {

/// Options of the reader.
struct ReaderOptions {
  /// Position of the tool before the first block, in program coordinates [mm].
  Vec3 initial_position = Vec3::Zero();
  /// Longest accepted source line [characters]; longer lines are a ParseError (guards memory).
  long max_line_length = 1 << 20;
  /// Keep comments and non-motion words as Commands (off: only blocks, dwell totals and warnings).
  bool keep_commands = true;
  /// Also keep N line numbers as commands ("N10", before the line's other records; written on a line
  /// of their own). Off by default.
  bool keep_line_numbers = false;
  /// Work offsets G54 … G59.3 (rows 0 … 8) [mm], applied when `has_work_offsets`; G54 is in force at
  /// the start. Without them a program that selects a work offset reads with zero offsets and one warning.
  bool has_work_offsets = false;
  WorkOffsets work_offsets = WorkOffsets::Zero();
  /// Tool lengths [mm] by tool number (LinuxCNC tool table Z), applied along +Z by G43 [H] when
  /// `has_tool_table`; G43 H of a tool not in the table is an error. Without a table G43 reads as
  /// zero length with one warning.
  bool has_tool_table = false;
  std::map<int, double> tool_lengths;
  void validate() const;
};

/// Streaming reader. Create with `open(path)` or `from_string(text)`, then call `next(block)` until it
/// returns false. Throws netshape::ParseError (a std::invalid_argument) on bad input, with the
/// source name, the 1-based line and column, and the reason.
class GcodeReader {
 public:
  /// Read the file at `path` (opened now; std::invalid_argument if it cannot be opened).
  static GcodeReader open(const std::string& path, const ReaderOptions& options = {});
  /// Read program text held in memory; `source` names it in error messages.
  static GcodeReader from_string(std::string text, const std::string& source = "<string>",
                                 const ReaderOptions& options = {});

  GcodeReader(GcodeReader&&) noexcept;
  GcodeReader& operator=(GcodeReader&&) noexcept;
  ~GcodeReader();

  /// The next motion block; false at the end of the program (end of text, M2 or M30).
  bool next(Block& block);

  /// Name of the source (file path or the name given to from_string).
  const std::string& source() const noexcept;
  /// Number of source lines read so far.
  long lines_read() const noexcept;
  /// Total time of G4 dwells read so far [s].
  double dwell_time() const noexcept;
  /// Number of G4 dwells read so far.
  long dwells() const noexcept;
  /// Current tool position in program coordinates [mm].
  Vec3 position() const noexcept;
  /// Move the commands read so far (comments, non-motion words, dwells, offsets; `before` counts the
  /// blocks returned by next()) to the end of `out`.
  void take_commands(std::vector<Command>& out);
  /// Warnings so far ("file:line: G55 selects a work offset but none were given; taken as zero").
  const std::vector<std::string>& warnings() const noexcept;

  struct Impl;

 private:
  explicit GcodeReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Read a whole program file into a Toolpath (arcs kept as arcs).
Toolpath read_gcode(const std::string& path, const ReaderOptions& options = {});
/// Parse program text into a Toolpath; `source` names it in error messages.
Toolpath parse_gcode(const std::string& text, const std::string& source = "<string>",
                     const ReaderOptions& options = {});

/// Accumulates a Summary block by block, so a program can be summarised while it streams.
class SummaryBuilder {
 public:
  /// Add one block (its length, time at programmed feed and exact bounding box).
  void add(const Block& block);
  /// Add dwell time [s] (G4).
  void add_dwell(double seconds, long count = 1);
  /// The figures so far.
  const Summary& summary() const noexcept { return s_; }

 private:
  Summary s_;
  bool empty_ = true;
};

/// Summarise a program file while streaming it: memory does not grow with the program's length.
Summary summarize_gcode(const std::string& path, const ReaderOptions& options = {});
/// Summarise program text.
Summary summarize_gcode_text(const std::string& text, const std::string& source = "<string>",
                             const ReaderOptions& options = {});

}  // namespace netshape::toolpath
