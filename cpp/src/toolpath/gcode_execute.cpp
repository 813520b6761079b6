// G-code reader, executing one line in NGC order (F, S, T, M6, spindle, coolant, dwell, modes,
// offsets, motion, stop): modal state, work offsets and tool lengths, non-motion records, and the
// block the line emits (lines, rapids, arcs in the three planes with their centre, radius and turns).
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "gcode_reader_impl.hpp"

namespace netshape::toolpath {

void GcodeReader::Impl::record_comments() {
  if (!comments.empty() && opt.keep_commands)
    for (const auto& [cb, ce] : comments) record(CommandKind::comment, std::string(line_b + cb, line_b + ce));
}

bool GcodeReader::Impl::execute(Block& out) {
  if (opt.keep_line_numbers && has('n')) {
    const double n = val('n');
    if (n < 0.0 || n > 1e9 || std::round(n) != n) fail_at(wc('n'), "N = " + fmt_num(n) + ": line number must be a non-negative integer");
    record(CommandKind::word, "N" + std::to_string(static_cast<long>(n)));
  }
  record_comments();
  // Unsupported letters first (they change the path or belong to refused codes).
  static const char* const kAxisNames = "abcuvw";
  for (const char* p = kAxisNames; *p; ++p)
    if (has(*p))
      fail_at(wc(*p), std::string("axis word ") + static_cast<char>(*p - 32) +
                          " is not supported (only X, Y, Z axes)");

  // G codes: sort into modal groups, refuse what is not supported.
  int g_motion = -2, g_motion_col = 0, g_plane = -1, g_units = -1, g_dist = -1, g_arcdist = -1;
  bool g_dwell = false;
  int g_dwell_col = 0;
  // codes kept as commands (×10 code, or −1 when absent)
  long g_cutter = -1, g_tlo = -1, g_cs = -1, g_path = -1, g_spindle_mode = -1, g_retract = -1, g_g92 = -1;
  bool g_cancel = false;
  int group_col[16] = {0};
  auto group = [&](int gi, int column, long c10) {
    if (group_col[gi]) fail_at(column, code_name('G', c10) + " conflicts with another G-code of the same modal group on the line");
    group_col[gi] = column;
  };
  bool uses_p = false, uses_q = false, uses_h = false;
  for (int i = 0; i < ng; ++i) {
    const long c = code10(gval[i]);
    const int column = gcol[i];
    if (c < 0) fail_at(column, "unknown G-code G" + fmt_num(gval[i]));
    switch (c) {
      case 0: case 10: case 20: case 30: case 800:
        group(0, column, c);
        g_motion = static_cast<int>(c / 10);
        if (c == 800) {
          g_motion = -1;
          g_cancel = true;
        }
        g_motion_col = column;
        break;
      case 40:
        group(1, column, c);
        g_dwell = true;
        g_dwell_col = column;
        break;
      case 170: case 180: case 190:
        group(2, column, c);
        g_plane = static_cast<int>(c / 10 - 17);
        break;
      case 200: case 210:
        group(3, column, c);
        g_units = c == 200 ? 1 : 0;
        break;
      case 900: case 910:
        group(4, column, c);
        g_dist = c == 910 ? 1 : 0;
        break;
      case 901: case 911:
        group(5, column, c);
        g_arcdist = c == 901 ? 1 : 0;
        break;
      case 400:  // cutter compensation off: nothing to undo
        group(6, column, c);
        g_cutter = c;
        break;
      case 430: case 490:  // tool length offset (applied from the tool table when given)
        group(7, column, c);
        if (c == 430) uses_h = true;
        g_tlo = c;
        break;
      case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
        group(8, column, c);  // work offsets (applied when given)
        g_cs = c;
        break;
      case 610: case 611: case 640:
        group(9, column, c);
        if (c == 640) uses_p = uses_q = true;
        g_path = c;
        break;
      case 940:  // the only feed mode: the writer states it in its header
        group(10, column, c);
        break;
      case 970:
        group(11, column, c);
        g_spindle_mode = c;
        break;
      case 980: case 990:
        group(12, column, c);
        g_retract = c;
        break;
      case 921: case 922:  // cancel G92 offsets: there are none
        group(13, column, c);
        g_g92 = c;
        break;
      case 50: case 51: case 52: case 53: case 62: case 63:
        fail_at(column, "NURBS/spline block " + code_name('G', c) + " is not supported");
      case 410: case 411: case 420: case 421:
        fail_at(column, "cutter radius compensation " + code_name('G', c) + " is not supported");
      case 730: case 760: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
        fail_at(column, "canned cycle " + code_name('G', c) + " is not supported");
      case 920: case 923:
        fail_at(column, "coordinate offset " + code_name('G', c) + " is not supported");
      case 930:
        fail_at(column, "inverse-time feed G93 is not supported (use G94, units per minute)");
      case 950:
        fail_at(column, "feed per revolution G95 is not supported (use G94, units per minute)");
      case 960:
        fail_at(column, "constant surface speed G96 is not supported");
      case 100: case 280: case 281: case 300: case 301: case 330: case 331:
      case 382: case 383: case 384: case 385: case 431: case 432: case 520: case 530: case 171: case 181:
      case 191: case 761: case 742: case 642:
        fail_at(column, code_name('G', c) + " is not supported (it changes the path in a way this reader does not model)");
      default:
        fail_at(column, "unknown G-code " + code_name('G', c));
    }
  }

  // M codes.
  int m_spindle = -1, m_stop = -1, m_override = -1;
  int m_coolant[3] = {-1, -1, -1};  // M7, M8, M9 in the order given
  int n_coolant = 0;
  bool m_change = false;
  int mgroup_col[8] = {0};
  auto mgroup = [&](int gi, int column, long c) {
    if (mgroup_col[gi]) fail_at(column, "M" + std::to_string(c) + " conflicts with another M-code of the same modal group on the line");
    mgroup_col[gi] = column;
  };
  for (int i = 0; i < nm; ++i) {
    const long c10 = code10(mval[i]);
    const int column = mcol[i];
    if (c10 < 0 || c10 % 10) fail_at(column, "unknown M-code M" + fmt_num(mval[i]));
    const long c = c10 / 10;
    switch (c) {
      case 0: case 1: case 2: case 30: case 60:
        mgroup(0, column, c);
        m_stop = static_cast<int>(c);
        break;
      case 3: case 4: case 5:
        mgroup(1, column, c);
        m_spindle = static_cast<int>(c);
        break;
      case 6:
        mgroup(2, column, c);
        m_change = true;
        break;
      case 7: case 8: case 9:  // coolant (M7 and M8 may share a line)
        if (n_coolant == 3) fail_at(column, "too many coolant M-codes on one line");
        m_coolant[n_coolant++] = static_cast<int>(c);
        break;
      case 48: case 49: case 50: case 51: case 52: case 53:
        mgroup(3, column, c);
        m_override = static_cast<int>(c);
        break;  // overrides
      case 98: case 99:
        fail_at(column, "subroutine M" + std::to_string(c) + " is not supported");
      default:
        fail_at(column, (c >= 100 && c <= 199 ? "user M-code M" : "unsupported M-code M") + std::to_string(c));
    }
  }

  // Units first: F and axis words on this line are read in the units in force after it.
  if (g_units >= 0) inch = g_units == 1;
  const double u = inch ? kInch : 1.0;

  if (has('f')) {
    const double f = val('f');
    if (f < 0.0) fail_at(wc('f'), "F = " + fmt_num(f) + ": feed must not be negative");
    feed = f * u / 60.0;
    if (!(feed <= kMaxCoordinate)) fail_at(wc('f'), "F = " + fmt_num(f) + ": feed out of range");
  }
  if (has('s')) {
    const double s = val('s');
    if (s < 0.0 || !(s <= 1e7)) fail_at(wc('s'), "S = " + fmt_num(s) + ": spindle speed must be in 0 … 1e7 [rev/min]");
    speed = s;
    record(CommandKind::word, "S" + fmt_word(s));
  }
  if (has('t')) {
    const double t = val('t');
    if (t < 0.0 || t > 1e9 || std::round(t) != t) fail_at(wc('t'), "T = " + fmt_num(t) + ": tool number must be a non-negative integer");
    selected_tool = static_cast<int>(t);
    record(CommandKind::word, "T" + std::to_string(selected_tool));
  }
  if (m_change) {
    tool = selected_tool;
    record(CommandKind::word, "M6");
  }
  if (m_spindle == 3) spindle_dir = 1;
  if (m_spindle == 4) spindle_dir = -1;
  if (m_spindle == 5) spindle_dir = 0;
  if (m_spindle >= 0) record(CommandKind::word, "M" + std::to_string(m_spindle));
  for (int i = 0; i < n_coolant; ++i) record(CommandKind::word, "M" + std::to_string(m_coolant[i]));
  if (m_override >= 0) record(CommandKind::word, "M" + std::to_string(m_override));

  if (g_dwell) {
    if (!has('p')) fail_at(g_dwell_col, "G4 dwell needs a P word (seconds)");
    const double p = val('p');
    if (p < 0.0 || !(p <= 1e7)) fail_at(wc('p'), "P = " + fmt_num(p) + ": dwell must be in 0 … 1e7 [s]");
    dwell_total += p;
    ++dwell_count;
    uses_p = true;
    record(CommandKind::dwell, "G4 P" + fmt_word(p), p);
  }
  if (g_plane >= 0) plane = static_cast<Plane>(g_plane);
  if (g_cutter >= 0) record(CommandKind::word, code_name('G', g_cutter));
  if (g_tlo >= 0) tool_length(g_tlo);
  if (g_cs >= 0) work_offset(g_cs);
  if (g_path >= 0) {
    std::string t = code_name('G', g_path);
    if (g_path == 640) {  // P (blending tolerance) and Q (naive CAM tolerance) are lengths: in mm
      for (const char l : {'p', 'q'}) {
        if (!has(l)) continue;
        const double v = val(l);
        if (!(v >= 0.0 && v <= kMaxCoordinate))
          fail_at(wc(l), std::string(1, static_cast<char>(l - 32)) + " = " + fmt_num(v) +
                             ": G64 tolerance must be a non-negative length");
        t += ' ';
        t += static_cast<char>(l - 32);
        t += fmt_word(v * u);
      }
    }
    record(CommandKind::word, std::move(t));
  }
  if (g_dist >= 0) incremental = g_dist == 1;
  if (g_arcdist >= 0) arc_absolute = g_arcdist == 1;
  if (g_g92 >= 0) record(CommandKind::word, code_name('G', g_g92));
  if (g_spindle_mode >= 0) record(CommandKind::word, code_name('G', g_spindle_mode));
  if (g_retract >= 0) record(CommandKind::word, code_name('G', g_retract));
  if (g_cancel) record(CommandKind::word, "G80");
  if (g_motion != -2) motion = g_motion;

  const bool axes = has('x') || has('y') || has('z');
  const bool arc_words = has('i') || has('j') || has('k') || has('r');
  bool produced = false;

  if (g_motion != -2 && g_motion_col && motion >= 2 && !axes)
    fail_at(g_motion_col, std::string(motion == 2 ? "G2" : "G3") + " arc without X, Y or Z end point words");
  if (axes) {
    if (motion < 0)
      fail_at(wc(has('x') ? 'x' : has('y') ? 'y' : 'z'),
              "axis words without an active motion mode (program G0, G1, G2 or G3)");
    Vec3 target = position;
    const char letters[3] = {'x', 'y', 'z'};
    for (int a = 0; a < 3; ++a) {
      if (!has(letters[a])) continue;
      const double v = val(letters[a]) * u;
      if (!(std::abs(v) <= kMaxCoordinate))
        fail_at(wc(letters[a]), std::string(1, static_cast<char>(letters[a] - 32)) + " = " + fmt_num(val(letters[a])) +
                                    ": coordinate out of range (|value| ≤ 1e9 mm)");
      target[a] = incremental ? position[a] + v : v;
      if (!(std::abs(target[a]) <= kMaxCoordinate))
        fail_at(wc(letters[a]), "coordinate out of range (|value| ≤ 1e9 mm)");
    }
    const int mcol0 = g_motion_col ? g_motion_col : wc(has('x') ? 'x' : has('y') ? 'y' : 'z');
    if (motion >= 1 && !(feed > 0.0))
      fail_at(mcol0, "feed move with no feed rate: program F (units per minute) before G1/G2/G3");
    out.start = position;
    out.end = target;
    out.feed = feed;
    out.spindle_rpm = spindle_dir * speed;
    out.tool = tool;
    out.line = owner_line();
    out.turns = 1;
    out.clockwise = false;
    out.plane = plane;
    out.center = Vec3::Zero();
    if (motion <= 1) {
      if (arc_words) {
        const char w = has('i') ? 'i' : has('j') ? 'j' : has('k') ? 'k' : 'r';
        fail_at(wc(w), std::string("word ") + static_cast<char>(w - 32) + " is only used with G2/G3 arcs");
      }
      out.kind = motion == 0 ? MotionKind::rapid : MotionKind::line;
    } else {
      make_arc(out, target, u, mcol0);
      uses_p = true;
    }
    if (offset != Vec3::Zero()) {  // to the output frame; the start is exactly where the last block ended
      out.start = mpos;
      out.end = target + offset;
      out.center += offset;
    }
    position = target;
    mpos = out.end;
    produced = true;
    ++blocks_out;
  } else if (arc_words) {
    const char w = has('i') ? 'i' : has('j') ? 'j' : has('k') ? 'k' : 'r';
    fail_at(wc(w), std::string("word ") + static_cast<char>(w - 32) + " without a motion (no X, Y or Z on the line)");
  }
  if (has('p') && !uses_p) fail_at(wc('p'), "word P is not used by any code on the line");
  if (has('q') && !uses_q) fail_at(wc('q'), "word Q is not used by any code on the line");
  if (has('h') && !uses_h) fail_at(wc('h'), "word H is not used by any code on the line");
  static const char* const kUnused = "del";
  for (const char* p = kUnused; *p; ++p)
    if (has(*p)) fail_at(wc(*p), std::string("word ") + static_cast<char>(*p - 32) + " is not supported here");

  if (m_stop >= 0)
    record(m_stop == 2 || m_stop == 30 ? CommandKind::program_end : CommandKind::word, "M" + std::to_string(m_stop));
  if (m_stop == 2 || m_stop == 30) ended = true;
  return produced;
}

void GcodeReader::Impl::tool_length(long c) {
  if (c == 490) {
    tool_offset = 0.0;
    set_offset();
    record(CommandKind::tool_length, "G49", 0.0);
    return;
  }
  std::string text = "G43";
  int t = tool;
  if (has('h')) {
    const double h = val('h');
    if (h < 0.0 || h > 1e9 || std::round(h) != h)
      fail_at(wc('h'), "H = " + fmt_num(h) + ": tool number must be a non-negative integer");
    t = static_cast<int>(h);
    text += " H" + std::to_string(t);
  }
  double len = 0.0;
  if (opt.has_tool_table) {
    if (t != 0) {
      const auto it = opt.tool_lengths.find(t);
      if (it == opt.tool_lengths.end())
        fail_at(has('h') ? wc('h') : 1, "G43: tool " + std::to_string(t) + " is not in the tool table");
      len = it->second;
    }
  } else if (!warned_tools) {
    warned_tools = true;
    warn(text + " applies a tool length but no tool table was given; taken as zero");
  }
  tool_offset = len;
  set_offset();
  record(CommandKind::tool_length, std::move(text), len);
}

void GcodeReader::Impl::work_offset(long c) {
  static const long codes[9] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
  int k = 0;
  while (codes[k] != c) ++k;
  if (!opt.has_work_offsets && !warned_offsets) {
    warned_offsets = true;
    warn(code_name('G', c) + " selects a work offset but no work offsets were given; taken as zero");
  }
  coord_system = k;
  set_offset();
  record(CommandKind::work_offset, code_name('G', c), k);
}

void GcodeReader::Impl::make_arc(Block& out, const Vec3& target, double u, int column) {
  const PlaneAxes ax = plane_axes(plane);
  const char off_letter[3] = {'i', 'j', 'k'};
  const char* plane_name[3] = {"XY plane (G17)", "ZX plane (G18)", "YZ plane (G19)"};
  const int pl = static_cast<int>(plane);
  if (has(off_letter[ax.n]))
    fail_at(wc(off_letter[ax.n]), std::string(1, static_cast<char>(off_letter[ax.n] - 32)) +
                                       " word given for an arc in the " + plane_name[pl]);
  out.kind = MotionKind::arc;
  out.clockwise = motion == 2;
  const Vec3& s = position;
  const Vec3& e = target;
  const double tol = (inch ? 0.0005 * kInch : 0.002);
  Vec3 c = s;
  if (has('r')) {
    if (has(off_letter[ax.a]) || has(off_letter[ax.b]))
      fail_at(wc('r'), "arc given with both R and I/J/K words");
    const double r = val('r') * u;
    if (!(std::abs(r) <= kMaxCoordinate)) fail_at(wc('r'), "R = " + fmt_num(val('r')) + ": radius out of range");
    const double da = e[ax.a] - s[ax.a], db = e[ax.b] - s[ax.b];
    const double chord = std::hypot(da, db);
    if (std::abs(r) < 1e-9) fail_at(wc('r'), "R arc with zero radius");
    if (chord <= 1e-9 * (1.0 + std::abs(r)))
      fail_at(wc('r'), "R arc with coincident end points (program a full circle with I/J/K)");
    double half = 0.5 * chord;
    const double ar = std::abs(r);
    if (half > ar) {
      if (half - ar > tol)
        fail_at(wc('r'), "arc radius too small to reach the end point: R " + fmt_fixed(ar, 4) +
                             " mm, half chord " + fmt_fixed(half, 4) + " mm");
      half = ar;
    }
    const double h = std::sqrt(std::max(0.0, ar * ar - half * half));
    // left normal of the chord; G3 with R > 0 (arc under 180°) has its centre on the left.
    const double na = -db / chord, nb = da / chord;
    double side = out.clockwise ? -1.0 : 1.0;
    if (r < 0.0) side = -side;
    c[ax.a] = 0.5 * (s[ax.a] + e[ax.a]) + side * h * na;
    c[ax.b] = 0.5 * (s[ax.b] + e[ax.b]) + side * h * nb;
  } else {
    if (!has(off_letter[ax.a]) && !has(off_letter[ax.b]))
      fail_at(column, std::string("arc needs R or the centre words ") +
                          static_cast<char>(off_letter[ax.a] - 32) + "/" + static_cast<char>(off_letter[ax.b] - 32) +
                          " in the " + plane_name[pl]);
    for (int k : {ax.a, ax.b}) {
      const char l = off_letter[k];
      if (arc_absolute) {
        if (!has(l))
          fail_at(column, std::string("absolute arc centres (G90.1) need both ") +
                              static_cast<char>(off_letter[ax.a] - 32) + " and " +
                              static_cast<char>(off_letter[ax.b] - 32));
        c[k] = val(l) * u;
      } else {
        c[k] = s[k] + (has(l) ? val(l) * u : 0.0);
      }
      if (!(std::abs(c[k]) <= kMaxCoordinate)) fail_at(wc(l), "arc centre out of range (|value| ≤ 1e9 mm)");
    }
    const double r0 = std::hypot(s[ax.a] - c[ax.a], s[ax.b] - c[ax.b]);
    const double r1 = std::hypot(e[ax.a] - c[ax.a], e[ax.b] - c[ax.b]);
    if (r0 <= 1e-9) fail_at(column, "arc centre coincides with its start point (zero radius)");
    if (std::abs(r1 - r0) > tol + 1e-3 * r0)
      fail_at(column, "arc radius mismatch: start radius " + fmt_fixed(r0, 3) + " mm, end radius " +
                          fmt_fixed(r1, 3) + " mm");
  }
  c[ax.n] = s[ax.n];
  out.center = c;
  out.turns = 1;
  if (has('p')) {
    const double p = val('p');
    if (p < 1.0 || p > 1e4 || std::round(p) != p)
      fail_at(wc('p'), "P = " + fmt_num(p) + ": arc turns must be an integer in 1 … 10000");
    out.turns = static_cast<int>(p);
  }
}

}  // namespace netshape::toolpath
