// Bindings of the `toolpath` area (netshape._core.toolpath). Thin: lambdas only turn out-parameters
// into returns and move C++ vectors into NumPy arrays without copies.
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "default_types.hpp"
#include "netshape/toolpath/block_arrays.hpp"
#include "netshape/toolpath/frames.hpp"
#include "netshape/toolpath/gcode_reader.hpp"
#include "netshape/toolpath/gcode_writer.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::toolpath;

namespace {

std::string vec_str(const Vec3& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", v[0], v[1], v[2]);
  return buf;
}

const char* kind_name(MotionKind k) {
  switch (k) {
    case MotionKind::rapid: return "rapid";
    case MotionKind::line: return "line";
    case MotionKind::arc: return "arc";
  }
  return "?";
}

std::string block_repr(const Block& b) {
  std::ostringstream os;
  os << "Block(" << kind_name(b.kind) << ", start=" << vec_str(b.start) << ", end=" << vec_str(b.end);
  if (b.kind == MotionKind::arc) {
    os << ", center=" << vec_str(b.center) << (b.clockwise ? ", G2" : ", G3")
       << (b.plane == Plane::xy ? " G17" : b.plane == Plane::zx ? " G18" : " G19");
    if (b.turns != 1) os << ", turns=" << b.turns;
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, ", feed=%.6g mm/s, line=%ld)", b.feed, b.line);
  os << buf;
  return os.str();
}

py::dict summary_dict(const Summary& s) {
  py::dict d;
  d["blocks"] = s.blocks();
  d["rapids"] = s.rapids;
  d["lines"] = s.lines;
  d["arcs"] = s.arcs;
  d["rapid_length_mm"] = s.rapid_length;
  d["feed_length_mm"] = s.feed_length;
  d["bbox_min_mm"] = py::make_tuple(s.bbox_min[0], s.bbox_min[1], s.bbox_min[2]);
  d["bbox_max_mm"] = py::make_tuple(s.bbox_max[0], s.bbox_max[1], s.bbox_max[2]);
  d["feed_time_s"] = s.feed_time;
  d["dwell_time_s"] = s.dwell_time;
  d["dwells"] = s.dwells;
  d["source_lines"] = s.source_lines;
  d["total_time_s"] = s.total_time();
  d["warnings"] = s.warnings;
  return d;
}

// Read every block into column arrays (no per-block Python objects).
BlockArrays read_arrays(GcodeReader& reader, bool split, double tol) {
  BlockArrays a;
  Block b;
  std::vector<Block> pieces;
  double dwelled = 0.0;  // dwell time read before the current block [s]
  while (reader.next(b)) {
    const double before = reader.dwell_time() - dwelled;
    dwelled = reader.dwell_time();
    if (split && b.kind == MotionKind::arc) {
      pieces.clear();
      split_block(b, tol, pieces);
      for (std::size_t k = 0; k < pieces.size(); ++k) a.push_back(pieces[k], k == 0 ? before : 0.0);
    } else {
      a.push_back(b, before);
    }
  }
  // dwells after the last move: in `dwell_after` of the last block (zeros elsewhere)
  if (!a.dwell_after.empty()) a.dwell_after.back() = reader.dwell_time() - dwelled;
  a.warnings = reader.warnings();
  return a;
}

// A NumPy view of one column of `self` (a bound BlockArrays), kept alive by it.
template <class T>
py::array column(py::handle self, std::vector<T>& v, std::vector<py::ssize_t> shape, const char* dtype = nullptr) {
  py::array a = dtype ? py::array(py::dtype(dtype), shape, {}, v.data(), self)
                      : py::array(py::dtype::of<T>(), shape, {}, v.data(), self);
  return a;
}

py::dict arrays_dict(py::object self) {
  BlockArrays& a = self.cast<BlockArrays&>();
  const auto n = static_cast<py::ssize_t>(a.size());
  py::dict d;
  d["kind"] = column(self, a.kind, {n});
  d["start"] = column(self, a.start, {n, 3});
  d["end"] = column(self, a.end, {n, 3});
  d["center"] = column(self, a.center, {n, 3});
  d["clockwise"] = column(self, a.clockwise, {n}, "bool");
  d["plane"] = column(self, a.plane, {n});
  d["turns"] = column(self, a.turns, {n});
  d["feed"] = column(self, a.feed, {n});
  d["spindle_rpm"] = column(self, a.spindle_rpm, {n});
  d["tool"] = column(self, a.tool, {n});
  d["line"] = column(self, a.line, {n});
  d["dwell"] = column(self, a.dwell, {n});
  d["dwell_after"] = column(self, a.dwell_after, {n});
  return d;
}

}  // namespace

void bind_toolpath(py::module_& m) {
  m.doc() = "Motion blocks, the RS274/NGC reader and writer (C++ netshape::toolpath).";

  py::enum_<MotionKind>(m, "MotionKind", "Kind of motion block (values are the `kind` array codes).")
      .value("rapid", MotionKind::rapid)
      .value("line", MotionKind::line)
      .value("arc", MotionKind::arc);
  py::enum_<Plane>(m, "Plane", "Arc plane: xy (G17), zx (G18), yz (G19).")
      .value("xy", Plane::xy)
      .value("zx", Plane::zx)
      .value("yz", Plane::yz);

  py::class_<Block>(m, "Block", "One motion block in program coordinates [mm]; feed in mm/s.")
      .def(py::init<>())
      .def_readwrite("kind", &Block::kind)
      .def_readwrite("start", &Block::start, "start point [mm], shape (3,)")
      .def_readwrite("end", &Block::end, "end point [mm], shape (3,)")
      .def_readwrite("center", &Block::center, "arc centre [mm], shape (3,)")
      .def_readwrite("clockwise", &Block::clockwise, "arcs: G2 (True) or G3 (False)")
      .def_readwrite("plane", &Block::plane)
      .def_readwrite("turns", &Block::turns, "arcs: number of turns (P word)")
      .def_readwrite("feed", &Block::feed, "programmed feed [mm/s]")
      .def_readwrite("spindle_rpm", &Block::spindle_rpm, "spindle speed [rev/min]; negative for M4, 0 off")
      .def_readwrite("tool", &Block::tool)
      .def_readwrite("line", &Block::line, "1-based source line (0 = not from a file)")
      .def("validate", &Block::validate)
      .def("length", &Block::length, "path length [mm]")
      .def("sweep", &Block::sweep, "signed sweep angle [rad] (negative clockwise)")
      .def("radius", &Block::radius, "arc radius at the start [mm]")
      .def("point_at", &Block::point_at, py::arg("s"), "point at fraction s in [0, 1] [mm]")
      .def("tangent_at", &Block::tangent_at, py::arg("s"), "unit tangent at fraction s")
      .def("curvature", &Block::curvature, "curvature [1/mm]")
      .def("__repr__", &block_repr);

  py::enum_<CommandKind>(m, "CommandKind", "What a non-motion record is (values are stable).")
      .value("comment", CommandKind::comment)
      .value("word", CommandKind::word)
      .value("dwell", CommandKind::dwell)
      .value("work_offset", CommandKind::work_offset)
      .value("tool_length", CommandKind::tool_length)
      .value("program_end", CommandKind::program_end);

  py::class_<Command>(m, "Command",
                      "A non-motion record (comment, M/S/T word, dwell, offset …) placed before block `before`.")
      .def(py::init<>())
      .def(py::init([](std::size_t before, CommandKind kind, std::string text, double value, long line) {
             Command c;
             c.before = before;
             c.kind = kind;
             c.text = std::move(text);
             c.value = value;
             c.line = line;
             return c;
           }),
           py::arg("before"), py::arg("kind"), py::arg("text"), py::arg("value") = 0.0, py::arg("line") = 0)
      .def_readwrite("before", &Command::before, "index of the motion block it precedes (len(blocks): at the end)")
      .def_readwrite("kind", &Command::kind)
      .def_readwrite("text", &Command::text, "as written out, e.g. 'M8', 'G64 P0.1', 'G4 P0.5', '(finish)'")
      .def_readwrite("value", &Command::value, "dwell [s], work offset index 0-8, or tool length [mm]")
      .def_readwrite("line", &Command::line, "1-based source line (0 = not from a file)")
      .def("__repr__", [](const Command& c) {
        return "Command(before=" + std::to_string(c.before) + ", '" + c.text + "', line=" + std::to_string(c.line) + ")";
      });

  py::class_<ReaderOptions>(m, "ReaderOptions", "Options of the G-code reader (offsets [mm]).")
      .def(py::init<>())
      .def_readwrite("initial_position", &ReaderOptions::initial_position, "[mm], program coordinates")
      .def_readwrite("max_line_length", &ReaderOptions::max_line_length)
      .def_readwrite("keep_commands", &ReaderOptions::keep_commands)
      .def_readwrite("keep_line_numbers", &ReaderOptions::keep_line_numbers)
      .def_readwrite("has_work_offsets", &ReaderOptions::has_work_offsets)
      .def_readwrite("work_offsets", &ReaderOptions::work_offsets, "(9, 3) G54 … G59.3 [mm]")
      .def_readwrite("has_tool_table", &ReaderOptions::has_tool_table)
      .def_readwrite("tool_lengths", &ReaderOptions::tool_lengths, "{tool: length along Z [mm]}")
      .def("validate", &ReaderOptions::validate);

  py::class_<Summary>(m, "Summary", "Whole-program figures: counts, lengths [mm], bounding box [mm], times [s].")
      .def(py::init<>())
      .def_readonly("rapids", &Summary::rapids)
      .def_readonly("lines", &Summary::lines)
      .def_readonly("arcs", &Summary::arcs)
      .def_readonly("rapid_length", &Summary::rapid_length, "[mm]")
      .def_readonly("feed_length", &Summary::feed_length, "[mm]")
      .def_readonly("bbox_min", &Summary::bbox_min, "[mm], shape (3,)")
      .def_readonly("bbox_max", &Summary::bbox_max, "[mm], shape (3,)")
      .def_readonly("feed_time", &Summary::feed_time, "time of feed moves at programmed feed [s]")
      .def_readonly("dwell_time", &Summary::dwell_time, "G4 dwell time [s]")
      .def_readonly("dwells", &Summary::dwells)
      .def_readonly("source_lines", &Summary::source_lines)
      .def_readonly("warnings", &Summary::warnings)
      .def_property_readonly("total_time", &Summary::total_time, "feed time + dwell time [s]")
      .def_property_readonly("blocks", &Summary::blocks)
      .def("to_dict", &summary_dict, "Plain dict with unit-suffixed keys (JSON-ready).")
      .def("__repr__", [](const Summary& s) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "Summary(rapids=%ld, lines=%ld, arcs=%ld, rapid_length=%.6g mm, feed_length=%.6g mm, "
                      "bbox_min=%s, bbox_max=%s, feed_time=%.6g s)",
                      s.rapids, s.lines, s.arcs, s.rapid_length, s.feed_length, vec_str(s.bbox_min).c_str(),
                      vec_str(s.bbox_max).c_str(), s.feed_time);
        return std::string(buf);
      });

  py::class_<Toolpath>(m, "Toolpath", "A program: its motion blocks in order and the name of its source.")
      .def(py::init<>())
      .def_readwrite("blocks", &Toolpath::blocks, "list of Block (a copy on each access)")
      .def_readwrite("source", &Toolpath::source)
      .def_readwrite("dwell_time", &Toolpath::dwell_time, "G4 dwell time [s]")
      .def_readwrite("dwells", &Toolpath::dwells)
      .def_readwrite("commands", &Toolpath::commands, "list of Command (a copy on each access)")
      .def_readwrite("work_offsets", &Toolpath::work_offsets, "(9, 3) offsets the blocks include [mm]")
      .def_readwrite("warnings", &Toolpath::warnings)
      .def("with_blocks", &Toolpath::with_blocks, py::arg("blocks"), py::arg("origin"),
           "A copy with new blocks; origin[i] = index of the block new block i came from (commands follow).")
      .def("summary", &Toolpath::summary)
      .def("split_arcs", &Toolpath::split_arcs, py::arg("chord_tolerance"),
           "A copy with every arc replaced by chords within chord_tolerance [mm].")
      .def("work_offset_index", &work_offset_index,
           "(n,) index 0…8 (G54…G59.3) of the work offset in force at each block (0 before any G54…).")
      .def("block_offsets", &block_offsets,
           "(n, 3) float64 offset program → machine at each block [mm]: work_offsets row in force + tool length.")
      .def("to_machine", &to_machine, py::arg("offsets"),
           "A copy in machine coordinates: each block moved by the work offset (rows of offsets, (9, 3) [mm]) "
           "and tool length in force; carries offsets as work_offsets.")
      .def("to_program", &to_program,
           "A copy in program coordinates: each block moved back by the offset in force (work_offsets zero).")
      .def("sample", [](const Toolpath& t, double spacing, bool feeds_only, double chord_tolerance) {
        Samples smp = sample(t, spacing, feeds_only, chord_tolerance);
        return py::make_tuple(std::move(smp.points), std::move(smp.s));
      }, py::arg("spacing"), py::arg("feeds_only") = true, py::arg("chord_tolerance") = 1e-4,
           "(points (m, 3) [mm], s (m,) [mm]): points every <= spacing along the moves (feed moves only when "
           "feeds_only; arcs as chords within chord_tolerance), s the distance along them.")
      .def("__len__", [](const Toolpath& t) { return t.blocks.size(); })
      .def("__getitem__", [](const Toolpath& t, py::ssize_t i) {
        const auto n = static_cast<py::ssize_t>(t.blocks.size());
        if (i < 0) i += n;
        if (i < 0 || i >= n) throw py::index_error("block index out of range");
        return t.blocks[static_cast<std::size_t>(i)];
      })
      .def("__repr__", [](const Toolpath& t) {
        return "Toolpath(" + std::to_string(t.blocks.size()) + " blocks, source='" + t.source + "')";
      });

  py::class_<BlockArrays>(m, "BlockArrays",
                          "A tool path as a structure of arrays (row i = block i); columns are NumPy views.")
      .def(py::init<>())
      .def_static("from_blocks", &BlockArrays::from_blocks, py::arg("blocks"))
      .def("to_blocks", &BlockArrays::to_blocks, "list of Block")
      .def("to_dict", &arrays_dict,
           "dict of n-row NumPy views: kind uint8, start/end/center (n, 3) [mm], clockwise bool, plane uint8, "
           "turns int32, feed [mm/s], spindle_rpm [rev/min], tool int32, line int64, dwell/dwell_after [s]")
      .def_readonly("warnings", &BlockArrays::warnings)
      .def("__len__", &BlockArrays::size)
      .def("__repr__", [](const BlockArrays& a) { return "BlockArrays(" + std::to_string(a.size()) + " blocks)"; });

  py::class_<GcodeReader>(m, "GcodeReader", "Streaming reader: iterate to get Blocks one at a time.")
      .def_static("open", [](const std::string& path) { return GcodeReader::open(path); }, py::arg("path"))
      .def_static("from_string", [](const std::string& text, const std::string& source) {
        return GcodeReader::from_string(text, source);
      }, py::arg("text"), py::arg("source") = "<string>")
      .def("__iter__", [](GcodeReader& r) -> GcodeReader& { return r; })
      .def("__next__", [](GcodeReader& r) {
        Block b;
        if (!r.next(b)) throw py::stop_iteration();
        return b;
      })
      .def("take_commands", [](GcodeReader& r) {
        std::vector<Command> v;
        r.take_commands(v);
        return v;
      }, "The comments and non-motion commands read so far, and forget them (bounded memory when streaming).")
      .def_property_readonly("warnings", &GcodeReader::warnings)
      .def_property_readonly("lines_read", &GcodeReader::lines_read)
      .def_property_readonly("source", &GcodeReader::source);

  py::class_<WriterOptions>(m, "WriterOptions", "Options of the G-code writer.")
      .def(py::init<>())
      .def_readwrite("split_arcs", &WriterOptions::split_arcs)
      .def_readwrite("chord_tolerance", &WriterOptions::chord_tolerance, "[mm]")
      .def_readwrite("decimals", &WriterOptions::decimals, "-1: shortest exact form; else fixed decimals")
      .def_readwrite("absolute_arc_centers", &WriterOptions::absolute_arc_centers)
      .def_readwrite("header_comment", &WriterOptions::header_comment)
      .def_readwrite("work_offset_word", &WriterOptions::work_offset_word,
                     "write G54 after the header when no work offset is selected before the first block");

  const auto dflt = py::arg_v("options", ReaderOptions{}, "ReaderOptions()");
  m.def("read_gcode", [](const std::string& path, const ReaderOptions& o) {
    py::gil_scoped_release nogil;
    return read_gcode(path, o);
  }, py::arg("path"), dflt);
  m.def("parse_gcode", [](const std::string& text, const std::string& source, const ReaderOptions& o) {
    py::gil_scoped_release nogil;
    return parse_gcode(text, source, o);
  }, py::arg("text"), py::arg("source") = "<string>", dflt);
  m.def("summarize_gcode", [](const std::string& path, const ReaderOptions& o) {
    py::gil_scoped_release nogil;
    return summarize_gcode(path, o);
  }, py::arg("path"), dflt);
  m.def("summarize_gcode_text", [](const std::string& text, const std::string& source, const ReaderOptions& o) {
    py::gil_scoped_release nogil;
    return summarize_gcode_text(text, source, o);
  }, py::arg("text"), py::arg("source") = "<string>", dflt);
  m.def("read_gcode_arrays", [](const std::string& path, bool split, double tol, ReaderOptions o) {
    o.keep_commands = false;
    py::gil_scoped_release nogil;
    GcodeReader r = GcodeReader::open(path, o);
    return read_arrays(r, split, tol);
  }, py::arg("path"), py::arg("split_arcs") = false, py::arg("chord_tolerance") = 0.002, dflt);
  m.def("parse_gcode_arrays", [](const std::string& text, const std::string& source, bool split, double tol,
                                 ReaderOptions o) {
    o.keep_commands = false;
    py::gil_scoped_release nogil;
    GcodeReader r = GcodeReader::from_string(text, source, o);
    return read_arrays(r, split, tol);
  }, py::arg("text"), py::arg("source") = "<string>", py::arg("split_arcs") = false,
     py::arg("chord_tolerance") = 0.002, dflt);
  m.def("format_gcode", [](const Toolpath& t, const WriterOptions& o) {
    std::ostringstream os;
    write_gcode(t, os, o);
    return os.str();
  }, py::arg("toolpath"), py::arg_v("options", WriterOptions{}, "WriterOptions()"));
  m.def("chord_count", &chord_count, py::arg("radius"), py::arg("sweep"), py::arg("tol"));
  m.attr("max_feed_mm_per_min") = max_feed_mm_per_min;
  m.def("block_bounds", [](const Block& b) {
    Vec3 lo, hi;
    block_bounds(b, lo, hi);
    return py::make_tuple(lo, hi);
  }, py::arg("block"));
}
