// Volumetric compensation of a whole program: block ends compensated in batches, lines and arc chords
// halved until the actual path follows the nominal one, arcs kept as moved arcs where they follow it.
#include "netshape/compensation/program_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/machine/synthesis.hpp"
#include "program_state.hpp"

namespace netshape::compensation {

using machine::Machine;
using machine::MachineData;
using toolpath::Block;
using toolpath::MotionKind;

void ProgramOptions::validate() const {
  NETSHAPE_CHECK(std::isfinite(chord_tolerance) && chord_tolerance > 0.0, "chord_tolerance", chord_tolerance,
                 "must be a positive number [mm]");
  NETSHAPE_CHECK(max_halvings >= 0, "max_halvings", max_halvings, "must be ≥ 0");
  NETSHAPE_CHECK(std::isfinite(rapid_feed) && rapid_feed > 0.0, "rapid_feed", rapid_feed,
                 "must be a positive number [mm/s]");
  for (int k = 0; k < 3; ++k)
    NETSHAPE_CHECK(std::abs(initial_direction[k]) <= 1.0, "initial_direction", initial_direction[k],
                   "must be −1, 0 or +1 per axis");
  point.validate();
}

namespace {

std::string where(const std::string& source, long line) {
  return line > 0 ? source + ":" + std::to_string(line) : source;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Compensates batches of nominal points, keeps the largest correction and residual, and turns the first
// failure of a batch into an exception naming the source line of the point.
class Compensator {
 public:
  Compensator(const Machine& machine, const VolumetricOptions& options, std::string source)
      : machine_(machine), options_(options), source_(std::move(source)), data_(machine) {}

  // (n, 3) commanded points for (n, 3) nominal points whose tip is moved by the state offsets (n, 3)
  // (P + e(P) = nominal − offset); lines[i] is the source line of point i.
  Points3 operator()(const Points3& nominal, const Points3& offset, const std::vector<long>& lines) {
    if (nominal.rows() == 0) return nominal;
    VolumetricResult res = compensate_points_status(machine_, nominal - offset, options_);
    const long i = res.first_failure();
    if (i >= 0) fail(res, i, nominal, lines[static_cast<std::size_t>(i)]);
    max_residual = std::max(max_residual, res.residual.maxCoeff());
    max_correction = std::max(max_correction, (res.commanded - nominal).rowwise().norm().maxCoeff());
    return std::move(res.commanded);
  }

  double max_residual = 0.0;
  double max_correction = 0.0;

 private:
  [[noreturn]] void fail(const VolumetricResult& res, long i, const Points3& nominal, long line) {
    const std::string at = where(source_, line);
    char pt[160];
    std::snprintf(pt, sizeof pt, "(%.6g, %.6g, %.6g) mm", nominal(i, 0), nominal(i, 1), nominal(i, 2));
    switch (res.status[static_cast<std::size_t>(i)]) {
      case VolumetricStatus::outside_travel: {
        const int k = res.axis[i];
        const auto& a = machine_.axes[static_cast<std::size_t>(k)];
        char buf[200];
        std::snprintf(buf, sizeof buf, "compensated axis %c = %.6f mm is outside its travel [%g, %g] mm", "XYZ"[k],
                      res.commanded(i, k), a.travel_min, a.travel_max);
        throw std::invalid_argument(at + ": " + buf + " (nominal point " + pt + ")");
      }
      case VolumetricStatus::outside_table: {
        std::string why = "an error table was left";
        try {
          machine::tip_error(machine_, data_, Vec3(res.commanded.row(i).transpose()));
        } catch (const std::invalid_argument& e) {
          why = e.what();
        }
        throw std::invalid_argument(at + ": nominal point " + pt + ": " + why);
      }
      default:
        throw Error(at + ": volumetric compensation of " + pt + " did not converge (residual " +
                    fmt("%.3g", res.residual[i]) + " mm > " + fmt("%g", options_.tolerance) + " mm)");
    }
  }

  const Machine& machine_;
  VolumetricOptions options_;
  std::string source_;
  MachineData data_;
};

// In-plane distance [mm] of p from the centre c (the plane's two axes).
double in_plane_radius(const Vec3& p, const Vec3& c, const toolpath::PlaneAxes& ax) {
  return std::hypot(p[ax.a] - c[ax.a], p[ax.b] - c[ax.b]);
}

Points3 rows(const std::vector<Vec3>& v) {
  Points3 out(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  return out;
}

// Fraction i/m of an even split of [0, 1] (the same bits as numpy.linspace: i·(1/m), the last exactly 1).
double fraction(int i, int m) { return i == m ? 1.0 : static_cast<double>(i) * (1.0 / m); }

// Segments to follow: nominal end points A → B, commanded end points AC → BC, state offsets at the
// ends OA → OB (linear along the segment), source line.
struct Segments {
  std::vector<Vec3> a, b, ac, bc, oa, ob;
  std::vector<long> line;
  void push(const Vec3& a_, const Vec3& b_, const Vec3& ac_, const Vec3& bc_, const Vec3& oa_, const Vec3& ob_,
            long l) {
    a.push_back(a_);
    b.push_back(b_);
    ac.push_back(ac_);
    bc.push_back(bc_);
    oa.push_back(oa_);
    ob.push_back(ob_);
    line.push_back(l);
  }
};

// Adaptive halving: every segment whose actual path (commanded points interpolated, moved by e) leaves
// the nominal segment by more than tol at t = ¼, ½ or ¾, or that is longer than max_length (a quarter
// of the shortest cyclic period: three checks cannot see a sine longer segments span), is split at its
// nominal midpoint, whose
// commanded point is compensated; all pending pieces are handled together, left halves then right
// halves. Returns per segment the interior commanded points in path order; `worst` gets the largest
// accepted deviation.
std::vector<std::vector<Vec3>> subdivide(const Machine& machine, MachineData& data, Compensator& comp,
                                         const Segments& s, double tol, double max_length, int max_depth,
                                         const std::string& source, double& worst) {
  const std::size_t n = s.a.size();
  std::vector<std::vector<std::pair<double, Vec3>>> interior(n);
  std::vector<std::size_t> seg(n);
  for (std::size_t i = 0; i < n; ++i) seg[i] = i;
  std::vector<double> t0(n, 0.0), t1(n, 1.0);
  std::vector<Vec3> A = s.a, B = s.b, AC = s.ac, BC = s.bc, OA = s.oa, OB = s.ob;
  worst = 0.0;
  static constexpr double ts[3] = {0.25, 0.5, 0.75};
  for (int depth = 0; depth <= max_depth && !seg.empty(); ++depth) {
    std::vector<std::size_t> bad;
    for (std::size_t k = 0; k < seg.size(); ++k) {
      double dev = 0.0;
      for (double t : ts) {
        const Vec3 c = AC[k] + t * (BC[k] - AC[k]);
        const Vec3 act = c + machine::tip_error(machine, data, c) + (OA[k] + t * (OB[k] - OA[k]));
        dev = std::max(dev, point_segment_distance(act, A[k], B[k]));
      }
      if (dev > tol || (B[k] - A[k]).norm() > max_length)
        bad.push_back(k);
      else
        worst = std::max(worst, dev);
    }
    if (bad.empty()) break;
    if (depth == max_depth)
      throw std::invalid_argument(where(source, s.line[seg[bad[0]]]) +
                                  ": could not follow the line within chord_tolerance = " + fmt("%g", tol) +
                                  " mm after " + std::to_string(max_depth) + " halvings");
    const std::size_t m = bad.size();
    std::vector<Vec3> mid(m), mid_off(m);
    std::vector<long> mid_line(m);
    for (std::size_t j = 0; j < m; ++j) {
      mid[j] = 0.5 * (A[bad[j]] + B[bad[j]]);
      mid_off[j] = 0.5 * (OA[bad[j]] + OB[bad[j]]);
      mid_line[j] = s.line[seg[bad[j]]];
    }
    const Points3 mc = comp(rows(mid), rows(mid_off), mid_line);
    std::vector<std::size_t> seg2(2 * m);
    std::vector<double> t02(2 * m), t12(2 * m);
    std::vector<Vec3> A2(2 * m), B2(2 * m), AC2(2 * m), BC2(2 * m), OA2(2 * m), OB2(2 * m);
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t k = bad[j];
      const double tm = 0.5 * (t0[k] + t1[k]);
      const Vec3 c = mc.row(static_cast<Eigen::Index>(j)).transpose();
      interior[seg[k]].emplace_back(tm, c);
      seg2[j] = seg2[m + j] = seg[k];
      t02[j] = t0[k], t12[j] = tm, t02[m + j] = tm, t12[m + j] = t1[k];
      A2[j] = A[k], B2[j] = mid[j], A2[m + j] = mid[j], B2[m + j] = B[k];
      AC2[j] = AC[k], BC2[j] = c, AC2[m + j] = c, BC2[m + j] = BC[k];
      OA2[j] = OA[k], OB2[j] = mid_off[j], OA2[m + j] = mid_off[j], OB2[m + j] = OB[k];
    }
    seg.swap(seg2);
    t0.swap(t02);
    t1.swap(t12);
    A.swap(A2);
    B.swap(B2);
    AC.swap(AC2);
    BC.swap(BC2);
    OA.swap(OA2);
    OB.swap(OB2);
  }
  std::vector<std::vector<Vec3>> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    auto& lst = interior[i];
    std::stable_sort(lst.begin(), lst.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    out[i].reserve(lst.size());
    for (const auto& p : lst) out[i].push_back(p.second);
  }
  return out;
}

}  // namespace

ProgramResult compensate_program(const Machine& machine, const toolpath::Toolpath& program,
                                 const ProgramOptions& options) {
  options.validate();
  const double tol = options.chord_tolerance;
  const std::string source = program.source.empty() ? std::string("<program>") : program.source;
  ProgramResult result;
  ProgramReport& report = result.report;
  report.source = source;
  report.blocks_in = static_cast<long>(program.blocks.size());
  report.commands = static_cast<long>(program.commands.size());
  if (program.blocks.empty()) {
    result.toolpath = program.with_blocks({}, {});
    return result;
  }
  for (const Block& b : program.blocks) b.validate();
  // the blocks compensated (arcs as chords on a machine with backlash) and their state offsets
  const detail::StatefulProgram sp = detail::stateful_program(machine, program, options);
  const std::vector<Block>& blocks = sp.blocks;
  const std::size_t n = blocks.size();
  Compensator comp(machine, options.point, source);
  MachineData data(machine);

  std::vector<long> lines(n);
  std::vector<Vec3> ends(n);
  for (std::size_t i = 0; i < n; ++i) {
    lines[i] = blocks[i].line;
    ends[i] = blocks[i].end;
  }
  const Points3 e_cmd_rows = comp(rows(ends), rows(sp.off_end), lines);
  std::vector<Vec3> e_cmd(n), s_cmd(n);
  for (std::size_t i = 0; i < n; ++i) e_cmd[i] = e_cmd_rows.row(static_cast<Eigen::Index>(i)).transpose();
  // a block starts where the previous one ended; the first block's start (the reader's initial
  // position) is not a programmed point and stays as it is; a block that jumps, or reverses an axis
  // with backlash, gets its own compensated start
  s_cmd[0] = blocks[0].start;
  std::vector<std::size_t> jump;
  for (std::size_t i = 1; i < n; ++i) {
    s_cmd[i] = e_cmd[i - 1];
    if (blocks[i].start != blocks[i - 1].end || sp.reversal[i]) jump.push_back(i);
  }
  if (!jump.empty()) {
    std::vector<Vec3> p, o;
    std::vector<long> l;
    for (std::size_t i : jump) p.push_back(blocks[i].start), o.push_back(sp.off_start[i]), l.push_back(lines[i]);
    const Points3 c = comp(rows(p), rows(o), l);
    for (std::size_t j = 0; j < jump.size(); ++j) s_cmd[jump[j]] = c.row(static_cast<Eigen::Index>(j)).transpose();
  }

  std::vector<std::vector<Block>> out_of(n);  // output blocks of each block
  for (std::size_t i = 1; i < n; ++i) {
    if (!sp.reversal[i]) continue;
    Block nb = blocks[i];  // take-up: the lost motion is taken up, the tip stays at the block's start
    nb.kind = MotionKind::line;
    nb.start = e_cmd[i - 1];
    nb.end = s_cmd[i];
    out_of[i].push_back(nb);
    ++report.takeup_moves;
  }
  // arcs: kept as moved arcs where the moved arc follows the nominal one, else compensated chords
  // (nominal chord error ≤ tol/2, the other half left for the compensation)
  std::vector<std::size_t> split_arc;
  std::vector<std::vector<Vec3>> arc_nom, arc_cmd, arc_off;
  for (std::size_t i = 0; i < n; ++i) {
    const Block& b = blocks[i];
    if (b.kind != MotionKind::arc) continue;
    const Vec3 o0 = sp.off_start[i], o1 = sp.off_end[i];
    const toolpath::PlaneAxes ax = toolpath::plane_axes(b.plane);
    Block nb = b;
    nb.start = s_cmd[i];
    nb.end = e_cmd[i];
    Vec3 center = b.center + 0.5 * ((s_cmd[i] - b.start) + (e_cmd[i] - b.end));
    center[ax.n] = s_cmd[i][ax.n];
    nb.center = center;
    const int count = toolpath::chord_count(b.radius(), b.sweep(), 0.5 * tol);
    // in-plane radii (a helix' normal-axis travel is not a radius): the moved arc may spiral as much
    // as the nominal one does, plus half the tolerance
    const double dr_nom = in_plane_radius(b.start, b.center, ax) - in_plane_radius(b.end, b.center, ax);
    const double dr_cmd = in_plane_radius(nb.start, center, ax) - in_plane_radius(nb.end, center, ax);
    double dev = std::numeric_limits<double>::infinity();
    if (std::abs(dr_cmd - dr_nom) < 0.5 * tol) {
      const int m = std::max(8, count);
      dev = 0.0;
      for (int k = 1; k < m; ++k) {
        const double f = fraction(k, m);
        const Vec3 p = nb.point_at(f);
        const Vec3 act = p + machine::tip_error(machine, data, p) + (o0 + f * (o1 - o0));
        dev = std::max(dev, (act - b.point_at(f)).norm());
      }
    }
    if (dev <= tol) {
      out_of[i].push_back(nb);
      ++report.arcs_kept;
      report.max_path_deviation = std::max(report.max_path_deviation, dev);
    } else {
      const int k = std::max(2, count);
      std::vector<Vec3> nom(static_cast<std::size_t>(k) + 1), off(nom.size());
      for (int j = 0; j <= k; ++j) {
        nom[static_cast<std::size_t>(j)] = b.point_at(fraction(j, k));
        off[static_cast<std::size_t>(j)] = o0 + fraction(j, k) * (o1 - o0);
      }
      nom.front() = b.start;
      nom.back() = b.end;
      off.front() = o0;
      off.back() = o1;
      const Points3 inner = comp(rows(std::vector<Vec3>(nom.begin() + 1, nom.end() - 1)),
                                 rows(std::vector<Vec3>(off.begin() + 1, off.end() - 1)),
                                 std::vector<long>(k - 1, b.line));
      std::vector<Vec3> cmd(nom.size());
      cmd.front() = s_cmd[i];
      cmd.back() = e_cmd[i];
      for (int j = 1; j < k; ++j) cmd[static_cast<std::size_t>(j)] = inner.row(j - 1).transpose();
      split_arc.push_back(i);
      arc_nom.push_back(std::move(nom));
      arc_cmd.push_back(std::move(cmd));
      arc_off.push_back(std::move(off));
      ++report.arcs_split;
    }
  }

  // lines and arc chords: adaptive halving, all segments of the program together
  Segments segs;
  std::vector<std::size_t> owner;
  for (std::size_t i = 0; i < n; ++i) {
    if (blocks[i].kind != MotionKind::line) continue;
    segs.push(blocks[i].start, blocks[i].end, s_cmd[i], e_cmd[i], sp.off_start[i], sp.off_end[i], lines[i]);
    owner.push_back(i);
  }
  for (std::size_t a = 0; a < split_arc.size(); ++a) {
    const std::size_t i = split_arc[a];
    for (std::size_t j = 0; j + 1 < arc_nom[a].size(); ++j) {
      segs.push(arc_nom[a][j], arc_nom[a][j + 1], arc_cmd[a][j], arc_cmd[a][j + 1], arc_off[a][j],
                arc_off[a][j + 1], lines[i]);
      owner.push_back(i);
    }
  }
  if (!owner.empty()) {
    double worst = 0.0;
    double max_length = std::numeric_limits<double>::infinity();
    for (const machine::Axis& ax : machine.axes)
      for (const machine::CyclicTerm& c : ax.cyclic) max_length = std::min(max_length, 0.25 * c.period);
    const auto interior =
        subdivide(machine, data, comp, segs, tol, max_length, options.max_halvings, source, worst);
    report.max_path_deviation = std::max(report.max_path_deviation, worst);
    for (std::size_t k = 0; k < owner.size(); ++k) {
      const std::size_t i = owner[k];
      std::vector<Block>& lst = out_of[i];
      auto add = [&](const Vec3& p) {
        Block nb = blocks[i];
        nb.kind = MotionKind::line;
        nb.start = lst.empty() ? s_cmd[i] : lst.back().end;
        nb.end = p;
        lst.push_back(nb);
      };
      for (const Vec3& p : interior[k]) add(p);
      add(segs.bc[k]);
    }
  }
  // per source block: output pieces (take-up moves not counted), arcs written as chords up front
  std::vector<long> pieces(program.blocks.size(), 0);
  std::vector<char> chorded(program.blocks.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto j = static_cast<std::size_t>(sp.source[i]);
    pieces[j] += static_cast<long>(out_of[i].size()) - (sp.reversal[i] ? 1 : 0);
    chorded[j] = chorded[j] || (blocks[i].kind == MotionKind::line && program.blocks[j].kind == MotionKind::arc);
  }
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    if (program.blocks[i].kind == MotionKind::line && pieces[i] > 1) ++report.lines_split;
    if (chorded[i]) ++report.arcs_split;
  }

  std::vector<Block> out;
  std::vector<long> origin;
  out.reserve(n);
  origin.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (blocks[i].kind == MotionKind::rapid) {
      Block nb = blocks[i];
      nb.start = s_cmd[i];
      nb.end = e_cmd[i];
      out.push_back(nb);
      origin.push_back(sp.source[i]);
    } else {
      for (Block& nb : out_of[i]) {
        out.push_back(std::move(nb));
        origin.push_back(sp.source[i]);
      }
    }
  }
  report.blocks_out = static_cast<long>(out.size());
  report.max_correction = comp.max_correction;
  report.max_residual = comp.max_residual;
  result.toolpath = program.with_blocks(std::move(out), origin);
  return result;
}

}  // namespace netshape::compensation
