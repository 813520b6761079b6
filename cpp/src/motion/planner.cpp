#include "netshape/motion/planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "line_blend.hpp"
#include "netshape/motion/corner.hpp"

namespace netshape::motion {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double tangent_angle = 1e-6;  // [rad] below this a junction counts as tangent
// the blend rule blends turns with tangent_angle < θ < π − 1e-3, told apart by sin(θ/2)
const double sin_half_tangent = std::sin(0.5 * tangent_angle), sin_half_reversal = std::cos(0.5e-3);
constexpr int max_arc_pieces = 64;      // an arc is cut into at most this many pieces ...
constexpr double arc_piece_angle = pi / 32;  // ... of at most this sweep [rad] (when it can)
constexpr int blend_pieces = 8;         // most pieces of a corner blend
// pieces of a corner blend, as runs of its 16 arc-length table intervals (node indices)
const int cuts_general[9] = {0, 2, 4, 6, 8, 10, 12, 14, 16};
constexpr int n_cuts_general = 8;
const int cuts_jerk[5] = {0, 4, 8, 12, 16};
constexpr int n_cuts_jerk = 4;
// between two lines: detail::cuts_lines (line_blend.hpp)
const int cuts_one[2] = {0, 16};
// nodes one push may add: the previous arc's pieces, the blend pieces, the new block
constexpr long per_block = max_arc_pieces + blend_pieces + 2;

bool finite3(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

double min_over(const Vec3& per_axis, const Vec3& moving) {
  double m = inf;
  for (int i = 0; i < 3; ++i)
    if (moving[i] > 0) m = std::min(m, per_axis[i]);
  return std::isfinite(m) ? m : per_axis.minCoeff();
}

Vec3 end_tangent(const Segment& s) {
  return s.kind == SegmentKind::blend ? Vec3((s.ctrl[3] - s.ctrl[2]).normalized()) : s.block.tangent_at(1.0);
}
// point and tangent at arc length s along the untrimmed programmed piece
Vec3 piece_point(const Segment& s, double at) {
  if (s.kind == SegmentKind::line)
    return s.block.start + (at / s.full_length) * (s.block.end - s.block.start);
  return s.block.point_at(std::clamp(at / s.full_length, 0.0, 1.0));
}
Vec3 piece_tangent(const Segment& s, double at) { return s.block.tangent_at(std::clamp(at / s.full_length, 0.0, 1.0)); }

// largest |cos| and |sin| over the angles between p0 and p1 [rad]
void trig_max(double p0, double p1, double& mc, double& ms) {
  if (p0 > p1) std::swap(p0, p1);
  if (p1 - p0 >= pi) {
    mc = ms = 1.0;
    return;
  }
  mc = std::max(std::abs(std::cos(p0)), std::abs(std::cos(p1)));
  ms = std::max(std::abs(std::sin(p0)), std::abs(std::sin(p1)));
  if (std::floor(p1 / pi) >= std::ceil(p0 / pi)) mc = 1.0;                          // k·π inside
  if (std::floor((p1 - 0.5 * pi) / pi) >= std::ceil((p0 - 0.5 * pi) / pi)) ms = 1.0;  // π/2 + k·π inside
}

int arc_piece_count(const Segment& s) {
  const double sweep = std::abs(s.block.sweep()) * s.length() / s.full_length;
  return std::clamp(static_cast<int>(std::ceil(sweep / arc_piece_angle - 1e-9)), 1, max_arc_pieces);
}

// Per-axis bounds over the arc window [s0, s1] (arc length from the block start) of |u_i| (U) and of
// the curvature vector |κ n_i| (K) [1/mm]; a helix's curvature vector points to its axis.
void arc_bounds(const Segment& s, double s0, double s1, Vec3& U, Vec3& K) {
  const toolpath::Block& b = s.block;
  const auto ax = toolpath::plane_axes(b.plane);
  const double r0 = std::hypot(b.start[ax.a] - b.center[ax.a], b.start[ax.b] - b.center[ax.b]);
  const double r1 = std::hypot(b.end[ax.a] - b.center[ax.a], b.end[ax.b] - b.center[ax.b]);
  const double sw = b.sweep(), dn = b.end[ax.n] - b.start[ax.n];
  const double ang0 = std::atan2(b.start[ax.b] - b.center[ax.b], b.start[ax.a] - b.center[ax.a]);
  double mc, ms;
  trig_max(ang0 + sw * s0 / s.full_length, ang0 + sw * s1 / s.full_length, mc, ms);
  const double rmin = std::min(r0, r1), rmax = std::max(r0, r1), dr = rmax - rmin;
  const double rho = std::hypot(rmin * sw, dn);  // |dp/df| (lower bound when the radius varies)
  U[ax.a] = std::min(1.0, (rmax * std::abs(sw) * ms + dr) / rho);
  U[ax.b] = std::min(1.0, (rmax * std::abs(sw) * mc + dr) / rho);
  U[ax.n] = std::min(1.0, std::abs(dn) / rho);
  const double c = sw != 0.0 ? dn / sw : 0.0;
  const double kappa = std::max(r0 / (r0 * r0 + c * c), r1 / (r1 * r1 + c * c)) * (1.0 + 1e-9);
  K[ax.a] = kappa * mc;
  K[ax.b] = kappa * ms;
  K[ax.n] = 0.0;
}

// Per-axis bounds of a blend's unit tangent |u_i| (U) and curvature vector |κ n_i| (K) over runs of
// its 17 table nodes, with a margin for what lies between the nodes (a quarter of the largest second
// difference of the node values, twice the parabolic estimate). The raw maxima are taken once per
// run of `step` intervals; a longer run is the max over its runs (max is exact, so the bounds of the
// whole blend equal those computed over all nodes at once).
struct BlendBounds {
  double mu[16][3], mk[16][3], du[16][3], dk[16][3];  // raw maxima per table interval
  void fill(const std::array<Vec3, 17>& T, const std::array<Vec3, 17>& Kv) noexcept {
    double t[17][3], k[17][3], dt[17][3], dkk[17][3];
    for (int i = 0; i < 17; ++i)
      for (int c = 0; c < 3; ++c) {
        t[i][c] = std::abs(T[static_cast<std::size_t>(i)][c]);
        k[i][c] = std::abs(Kv[static_cast<std::size_t>(i)][c]);
      }
    for (int c = 0; c < 3; ++c) dt[0][c] = dkk[0][c] = dt[16][c] = dkk[16][c] = 0.0;  // ends: none
    for (int i = 1; i <= 15; ++i)
      for (int c = 0; c < 3; ++c) {
        dt[i][c] = std::abs(t[i - 1][c] - 2 * t[i][c] + t[i + 1][c]);
        dkk[i][c] = std::abs(k[i - 1][c] - 2 * k[i][c] + k[i + 1][c]);
      }
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 3; ++c) {
        mu[r][c] = std::max(t[r][c], t[r + 1][c]);
        mk[r][c] = std::max(k[r][c], k[r + 1][c]);
        du[r][c] = std::max(dt[r][c], dt[r + 1][c]);
        dk[r][c] = std::max(dkk[r][c], dkk[r + 1][c]);
      }
  }
  // bounds over the table nodes i0..i1 (intervals [i0, i1))
  void bounds(int r0, int r1, Vec3& U, Vec3& K) const noexcept {
    for (int c = 0; c < 3; ++c) {
      double a = mu[r0][c], b = mk[r0][c], e = du[r0][c], f = dk[r0][c];
      for (int r = r0 + 1; r < r1; ++r) {
        a = std::max(a, mu[r][c]);
        b = std::max(b, mk[r][c]);
        e = std::max(e, du[r][c]);
        f = std::max(f, dk[r][c]);
      }
      U[c] = std::min(1.0, std::max(0.0, a) + 0.25 * std::max(0.0, e) + 1e-12);
      K[c] = std::max(0.0, b) * (1.0 + 1e-9) + 0.25 * std::max(0.0, f);
    }
  }
};

// curvature vector κ·n [1/mm] at the start or the end of a segment (0 on lines)
Vec3 curvature_vector(const Segment& s, bool at_end) {
  if (s.kind == SegmentKind::line) return Vec3::Zero();
  if (s.kind == SegmentKind::blend) {
    const double u = at_end ? 1.0 : 0.0;
    const Vec3 d1 = bezier_d1(s.ctrl, u), d2 = bezier_d2(s.ctrl, u);
    const double n2 = d1.squaredNorm();
    return n2 > 0 ? Vec3((d2 - d1 * (d1.dot(d2) / n2)) / n2) : Vec3::Zero();
  }
  const Vec3 p = s.point_at(at_end ? s.length() : 0.0);
  const auto ax = toolpath::plane_axes(s.block.plane);
  Vec3 r = Vec3::Zero();
  r[ax.a] = s.block.center[ax.a] - p[ax.a];
  r[ax.b] = s.block.center[ax.b] - p[ax.b];
  const double rn = r.norm();
  return rn > 0 ? Vec3(r * (s.block.curvature() / rn)) : Vec3::Zero();
}

// smallest num[i]/den[i] over the i with den[i] > 0, +inf if none; one division (the fractions are
// compared by cross-multiplication)
double min_ratio(const double* num, const double* den) noexcept {
  int best = -1;
  for (int i = 0; i < 3; ++i)
    if (den[i] > 0 && (best < 0 || num[i] * den[best] < num[best] * den[i])) best = i;
  return best < 0 ? inf : num[best] / den[best];
}

// quadratic corner bound next to curves: v·d/ts + κ·v² ≤ A
double jump_speed(double acc, double d, double ts, double kappa) {
  const double b = d / ts;
  if (kappa <= 0) return b > 0 ? acc / b : inf;
  return 2.0 * acc / (b + std::sqrt(b * b + 4.0 * kappa * acc));
}
}  // namespace

Planner::Planner(const AxisLimits& limits, const PlanOptions& options) : limits_(limits), opt_(options) {
  limits_.validate();
  opt_.validate();
  jerk_ = limits_.jerk_limited();
  inv_acc_ = limits_.acceleration.cwiseInverse();
  lb_ = &detail::line_blend_kernels();
  lb_tables_ = &detail::line_blend_tables();
  // power-of-two sizes (see slot()): the ring holds at least one push's nodes plus 12 per block of
  // look-ahead (rounded up: 14 for look-ahead 64)
  const auto pow2 = [](long n) {
    long p = 1;
    while (p < n) p *= 2;
    return p;
  };
  cap_ = pow2(per_block + 12 * (opt_.lookahead + 2) + 3);
  mask_ = static_cast<std::size_t>(cap_ - 1);
  ring_.resize(static_cast<std::size_t>(cap_));
  quick_.resize(static_cast<std::size_t>(cap_));
  // blocks from the head's to the newest: at most lookahead + 2 (push refuses beyond)
  blends_.resize(static_cast<std::size_t>(pow2(opt_.lookahead + 4)));
  rec_mask_ = blends_.size() - 1;
  recs_.resize(blends_.size());
}

void Planner::put_blend(const Segment& g, Segment& out) const noexcept {
  // the pieces of a blend come one after the other: the caller's segment often holds this blend's
  // geometry already (same control points bit for bit, length and source); then only the trims change
  static_assert(sizeof(g.ctrl) == 12 * sizeof(double), "control points are 12 packed doubles");
  using C = Eigen::Array<double, 12, 1>;
  if (out.kind == SegmentKind::blend && out.source == g.source && out.full_length == g.full_length) {
    // equal control points: the sum of the absolute differences is 0 (NaN is never equal)
    const double diff = (Eigen::Map<const C>(out.ctrl[0].data()) - Eigen::Map<const C>(g.ctrl[0].data())).abs().sum();
    if (diff == 0.0) return;
  }
  out = g;
}

void Planner::copy_segment(const Node& n, Segment& out) noexcept {
  if (n.seg.kind == SegmentKind::line) {
    // the fields of a line (push writes only these into the ring); its control points and table are 0
    const Segment& s = n.seg;
    out.kind = SegmentKind::line;
    out.block = s.block;
    out.ctrl = {};
    out.table = {};
    out.full_length = s.full_length;
    out.trim_start = s.trim_start;
    out.trim_end = s.trim_end;
    out.curvature = s.curvature;
    out.curvature_rate = s.curvature_rate;
    out.source = s.source;
    return;
  }
  if (!n.slim) {
    out = n.seg;
    return;
  }
  put_blend(blends_[rec_slot(n.blk)], out);
  out.trim_start = n.seg.trim_start;
  out.trim_end = n.seg.trim_end;
  out.curvature = n.seg.curvature;
  out.curvature_rate = n.seg.curvature_rate;
}

const Segment& Planner::seg_of(Node& n) noexcept {
  if (n.slim) {
    Segment full;
    copy_segment(n, full);
    n.seg = full;
    n.slim = false;
  }
  return n.seg;
}

void Planner::sync(long k) noexcept {
  const Node& n = at(k);
  Quick& x = q(k);
  x.w_lim = n.v_lim * n.v_lim;
  x.len = plan_length(n);
  x.a = n.a;
  x.j = n.j;
  x.rec = -1;
  set_reach(x, n.curved, n.U, n.K);
}

void Planner::set_reach(Quick& x, bool curved, const Vec3& U, const Vec3& K) const noexcept {
  x.straight = !curved;
  if (!curved) {
    x.alpha[0] = 1.0;
    x.beta[0] = 2.0 * x.a * x.len;
    for (int i = 1; i < 3; ++i) {
      x.alpha[i] = 0.0;
      x.beta[i] = inf;
    }
    return;
  }
  // per axis: w·(U_i + 2·L·K_i) ≤ U_i·w0 + 2·L·A_i (exact for constant bounds)
  double den[3];
  for (int i = 0; i < 3; ++i) den[i] = U[i] + 2.0 * x.len * K[i];
  const bool any = den[0] > 0 || den[1] > 0 || den[2] > 0;
  if (den[0] > 0 && den[1] > 0 && den[2] > 0) {
    // the three reciprocals from one division: 1/d0 = d1·d2/(d0·d1·d2), ...
    const double d01 = den[0] * den[1], r = 1.0 / (d01 * den[2]);
    const double rd[3] = {den[1] * den[2] * r, den[0] * den[2] * r, d01 * r};
    for (int i = 0; i < 3; ++i) {
      x.alpha[i] = U[i] * rd[i];
      x.beta[i] = 2.0 * x.len * limits_.acceleration[i] * rd[i];
    }
  } else {
    for (int i = 0; i < 3; ++i) {
      if (den[i] > 0) {
        const double r = 1.0 / den[i];
        x.alpha[i] = U[i] * r;
        x.beta[i] = 2.0 * x.len * limits_.acceleration[i] * r;
      } else {
        x.alpha[i] = 0.0;
        x.beta[i] = inf;
      }
    }
  }
  if (!any) {  // no bound at all: the speed carries over
    x.alpha[0] = 1.0;
    x.beta[0] = 0.0;
  }
}

void Planner::reset() noexcept {
  head_ = frozen_ = tail_ = 0;
  finished_ = done_ = false;
  pushed_ = 0;
  sample_ = 0;
  t_frozen_end_ = v_frozen_end_ = 0;
  have_last_ = false;
  last_point_ = Vec3::Zero();
  error_ = "";
}

long Planner::blocks_in_buffer() const noexcept { return tail_ > head_ ? pushed_ - at(head_).blk : 0; }

int Planner::free_blocks() const noexcept {
  const long by_nodes = (cap_ - (tail_ - head_)) / per_block;
  const long by_blocks = opt_.lookahead + 1 - blocks_in_buffer();
  return static_cast<int>(std::max(0L, std::min(by_nodes, by_blocks)));
}

double Planner::end_time() const noexcept {
  return (finished_ && frozen_ == tail_) ? t_frozen_end_ : -1.0;
}

Status Planner::fail(const char* msg) noexcept {
  error_ = msg;
  return Status::invalid_input;
}

bool Planner::buffer_ready() const noexcept {
  // free_blocks() == 0 without its division
  return finished_ || cap_ - (tail_ - head_) < per_block || blocks_in_buffer() >= opt_.lookahead + 1;
}

double Planner::plan_length(const Node& n) const noexcept {
  const Segment& s = n.seg;
  const double te = n.tail_trim ? 0.45 * s.full_length : s.trim_end;
  return std::max(0.0, s.full_length - s.trim_start - te - n.res_s - n.res_e);
}

void Planner::set_params(Node& n, const Vec3* line_dir) const noexcept {
  // n.vmax holds the programmed feed cap on entry
  const Segment& s = n.seg;
  if (s.kind == SegmentKind::line && !jerk_ && opt_.rule != CornerRule::paper) {
    // the common case below without the moving-axes minima it does not use
    const Vec3 u = line_dir ? *line_dir : s.block.tangent_at(0.0);
    n.curved = false;
    n.vmax = std::min(n.vmax, along(limits_.velocity, u));
    n.a = along(limits_.acceleration, u);
    n.j = inf;
    return;
  }
  const Vec3 moving = s.moving_axes();
  const double amin = min_over(limits_.acceleration, moving);
  const double vmin = min_over(limits_.velocity, moving);
  const double jmin = min_over(limits_.jerk, moving);
  const bool jerk = std::isfinite(jmin);
  n.curved = false;
  if (s.kind == SegmentKind::line) {
    const Vec3 u = s.block.tangent_at(0.0);
    n.vmax = std::min(n.vmax, along(limits_.velocity, u));
    n.a = opt_.rule == CornerRule::paper ? amin : along(limits_.acceleration, u);
    n.j = jerk ? along(limits_.jerk, u) : inf;
    return;
  }
  if (!jerk) {
    // the per-axis box: |u_i|·v ≤ V_i and K_i·v² ≤ A_i (the tangential share is set per speed)
    n.curved = true;
    n.j = inf;
    for (int i = 0; i < 3; ++i) {
      if (n.U[i] > 0) n.vmax = std::min(n.vmax, limits_.velocity[i] / n.U[i]);
      if (n.K[i] > 0) n.vmax = std::min(n.vmax, std::sqrt(limits_.acceleration[i] / n.K[i]));
    }
    n.a = amin;
    return;
  }
  // with jerk limits: centripetal share c·A, tangential share sqrt(1 − c²)·A (vector bound)
  const double c = opt_.centripetal_fraction;
  const double k = std::max(s.curvature, 1e-300);
  n.a = std::sqrt(1.0 - c * c) * amin;
  n.vmax = std::min({n.vmax, vmin, std::sqrt(c * amin / k)});
  // jerk vector = (j_t − v³κ²) t + (3 v a_t κ + v³ dκ/ds) n: give j_t 0.4 J and the rest 0.3 J each
  n.j = 0.4 * jmin;
  n.vmax = std::min(n.vmax, 0.3 * jmin / (k * (c * amin + 3.0 * n.a)));
  if (s.curvature_rate > 0) n.vmax = std::min(n.vmax, std::cbrt(0.3 * jmin / s.curvature_rate));
}

// largest squared speed at one end of a node when the other end runs at sqrt(w0) [mm²/s²]
double Planner::reach_sq(const Quick& n, double w0) const noexcept {
  if (std::isfinite(n.j)) {
    const double r = reach_speed(std::sqrt(w0), n.len, n.a, n.j);
    return r * r;
  }
  return std::min({n.alpha[0] * w0 + n.beta[0], n.alpha[1] * w0 + n.beta[1], n.alpha[2] * w0 + n.beta[2]});
}

void Planner::append(const Node& n) noexcept {
  if (&n != &at(tail_)) at(tail_) = n;  // (push builds most lines in place)
  sync(tail_);
  q(tail_).wb = 0.0;
  ++tail_;
}

// The last node holds a whole block whose end is now known: cut arcs into pieces of at most
// arc_piece_angle, each with its own bounds (the axis box is much tighter on a short piece).
void Planner::split_tail() noexcept {
  Node& p = at(tail_ - 1);
  if (!p.provisional) return;
  p.provisional = false;
  p.tail_trim = false;
  if (p.seg.kind != SegmentKind::arc) {
    sync(tail_ - 1);
    return;
  }
  const Node base = p;
  const double s0 = base.seg.trim_start, s1 = base.seg.full_length - base.seg.trim_end;
  const int m = arc_piece_count(base.seg);
  double v_prev = 0;
  for (int k = 0; k < m; ++k) {
    Node x = base;
    const double a = s0 + (s1 - s0) * k / m, b = k + 1 == m ? s1 : s0 + (s1 - s0) * (k + 1) / m;
    x.seg.trim_start = a;
    x.seg.trim_end = base.seg.full_length - b;
    arc_bounds(x.seg, a, b, x.U, x.K);
    x.vmax = base.fcap;
    set_params(x);
    x.spike_s = x.spike_e = false;  // set_params gave the piece its full jerk again
    if (k == 0 && base.spike_s) mark_spike(x, true);
    if (k + 1 == m && base.spike_e) mark_spike(x, false);
    x.res_s = k == 0 ? base.res_s : 0.0;
    x.jump_s = k == 0 && base.jump_s;
    x.res_e = k + 1 == m ? base.res_e : 0.0;
    x.jump_e = k + 1 == m && base.jump_e;
    x.v_lim = k == 0 ? std::min(base.v_corner, x.vmax) : std::min(v_prev, x.vmax);
    v_prev = x.vmax;
    if (k == 0) {
      p = x;
      sync(tail_ - 1);
    } else {
      append(x);
    }
  }
}

void Planner::mark_spike(Node& n, bool at_start) noexcept {
  if (!n.spike_s && !n.spike_e) n.j *= 0.5;
  (at_start ? n.spike_s : n.spike_e) = true;
}

double Planner::curvature_step_speed(const Vec3& dk) const noexcept {
  double v = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(dk[i]) > 1e-12) v = std::min(v, std::sqrt(0.5 * limits_.jerk[i] * opt_.ts2 / std::abs(dk[i])));
  return v;
}

// A blend piece over the table nodes i0..i1 of `whole`, written in place (a Node is large: no
// temporary and copy). slim: the node keeps kind, trims, length, curvature and source only and the
// geometry stays in blends_; else it holds the whole segment. Bounds, speeds and reach: the caller.
void Planner::init_blend_piece(Node& bn, const Segment& whole, int i0, int i1, long source, double vfeed,
                               bool slim) noexcept {
  if (slim) {
    bn.seg.kind = SegmentKind::blend;
    bn.seg.full_length = whole.full_length;
    bn.seg.curvature = whole.curvature;
    bn.seg.curvature_rate = whole.curvature_rate;
    bn.seg.source = whole.source;
  } else {
    bn.seg = whole;
  }
  bn.slim = slim;
  bn.multi = false;
  bn.seg.trim_start = whole.table[static_cast<std::size_t>(i0)];
  bn.seg.trim_end = whole.full_length - whole.table[static_cast<std::size_t>(i1)];
  bn.blk = source;
  bn.fcap = vfeed;
  bn.res_s = bn.res_e = 0.0;
  bn.jump_s = bn.jump_e = bn.spike_s = bn.spike_e = bn.tail_trim = bn.provisional = false;
}

// The blend of a corner between two lines without jerk limits, cut into pieces at the table nodes
// detail::cuts_lines (one piece for a gentle turn) and written as ONE node of the ring: the kernel
// (line_blend.hpp) fills the whole blend into blends_ and the pieces' trims, lengths, speed caps,
// reach coefficients (back_pass) and the coefficients of their peak speed and tangential budget
// (freeze_multi) into the record recs_[source % size], so neither pass divides. v_prev: the speed cap
// before the blend on entry, the cap of its last piece on return [mm/s].
void Planner::push_line_blend(long source, long psource, const Vec3& p0, const Vec3& vtx, const Vec3& p3, const Vec3& u1,
                              const Vec3& u2, double d, double vfeed, double& v_prev) noexcept {
  const Vec3& A = limits_.acceleration;
  const std::size_t slot = this->slot(tail_);
  const std::size_t ri = rec_slot(source);
  BlendRec& r = recs_[ri];
  Segment& whole = blends_[ri];
  const int np = lb_->build(*lb_tables_, whole, p0, vtx, p3, u1, u2, d, psource, A, limits_.velocity, inv_acc_, vfeed,
                            v_prev, r);
  // the axes that move on the blend (Segment::moving_axes) and the smallest of their accelerations
  double amin_blend = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(d * u1[i]) > 1e-12 || std::abs(d * u2[i]) > 1e-12) amin_blend = std::min(amin_blend, A[i]);
  if (!std::isfinite(amin_blend)) amin_blend = A.minCoeff();
  // one node for the whole blend, its pieces in the record
  Node& bn = ring_[slot];
  init_blend_piece(bn, whole, 0, 16, source, vfeed, true);
  bn.multi = true;
  bn.curved = true;
  bn.j = inf;
  bn.a = amin_blend;
  bn.v_lim = bn.v_corner = std::min(v_prev, r.vmax[0]);  // (its square is r.w_lim[0])
  v_prev = r.vmax[np - 1];
  bn.vmax = v_prev;
  Quick& x = quick_[slot];
  x.w_lim = r.w_lim[0];
  x.len = whole.full_length;
  x.a = bn.a;
  x.j = inf;
  x.wb = 0.0;
  x.straight = false;
  x.rec = static_cast<int>(ri);
  ++tail_;
}

Status Planner::push(const toolpath::Block& b) noexcept {
  if (finished_) return fail("push() after finish()");
  // a full buffer first: a streaming caller pushes until buffer_full, so every block meets this
  // test once more than the others (a bad block is reported when there is room for it)
  if (cap_ - (tail_ - head_) < per_block || blocks_in_buffer() > opt_.lookahead) return Status::buffer_full;
  if (!finite3(b.start) || !finite3(b.end) || !finite3(b.center) || !std::isfinite(b.feed) || b.feed < 0)
    return fail("block has a non-finite coordinate or a negative feed");
  const bool arc = b.kind == toolpath::MotionKind::arc;
  if (arc && !(b.radius() > 0)) return fail("arc radius must be positive");
  if (arc && b.turns < 1) return fail("arc turns must be at least 1");
  const double len = b.length();
  if (!(len > 1e-9)) return Status::ok;  // nothing to move
  if (have_last_ && (b.start - last_point_).norm() > 1e-6 * (1.0 + last_point_.norm()))
    return fail("block does not start where the previous one ended");
  const long source = pushed_++;
  last_point_ = b.end;
  have_last_ = true;
  const bool rapid = b.kind == toolpath::MotionKind::rapid;
  const bool jerk_mode = limits_.jerk_limited();

  const bool has_prev = tail_ > head_ && tail_ - 1 >= frozen_;
  const long first = tail_ - 1;  // the previous block's node (it is cut into pieces below)
  const double ts2 = opt_.ts2;
  const bool jump_rule = opt_.rule == CornerRule::vector || opt_.rule == CornerRule::per_axis;
  const double wf = window_periods();  // constant-speed window on each side of a velocity jump [ts2]

  // a line's unit direction (Block::tangent_at's arithmetic), found once: set_params, the corner
  // here and the next block's corner read it
  const Vec3 dir = arc ? Vec3::Zero() : Vec3((b.end - b.start) / len);
  const Vec3 prev_dir = last_dir_;
  last_dir_ = dir;
  // the junction with the previous block (its node is final up to its end trim)
  Vec3 u1 = Vec3::Zero(), u2 = Vec3::Zero();
  double sin_half = 0.0;
  bool blend_here = false;
  const bool prev_line = has_prev && at(first).seg.kind == SegmentKind::line;
  if (has_prev) {
    u1 = prev_line ? prev_dir : end_tangent(at(first).seg);
    u2 = arc ? b.tangent_at(0.0) : dir;
    // sin(θ/2) = |u2 − u1|/2 for unit tangents: the blend rule needs no angle (no atan2 per block)
    sin_half = 0.5 * (u2 - u1).norm();
    blend_here = opt_.rule == CornerRule::blend && sin_half > sin_half_tangent && sin_half < sin_half_reversal;
  }
  // The new node: the whole block, bounds over all of it, until its end is known. A Node is large
  // (~700 bytes): a line is built in the ring slot where it will stay when what goes in before it is
  // known now: nothing, or the one node of a blend between two lines (push_line_blend). Else (arcs,
  // an arc before, blends in jerk mode) it is built in scratch_ and copied in by append().
  const bool in_place = !arc && (!has_prev || (prev_line && (!blend_here || !jerk_mode)));
  Node& nn = in_place ? ring_[slot(tail_ + (blend_here ? 1 : 0))] : scratch_;
  if (arc) {
    nn = Node{};
    nn.seg = Segment::arc(b, source);
    arc_bounds(nn.seg, 0.0, nn.seg.full_length, nn.U, nn.K);
  } else {
    // Segment::line field by field (a line's ctrl and table are never read: copy_segment hands
    // them out as zeros); then every field of the Node the planner reads before the freeze
    if (!in_place) nn = Node{};
    nn.seg.kind = SegmentKind::line;
    nn.seg.block = b;
    nn.seg.full_length = len;
    nn.seg.trim_start = nn.seg.trim_end = 0.0;
    nn.seg.curvature = nn.seg.curvature_rate = 0.0;
    nn.seg.source = source;
    nn.U.setZero();
    nn.K.setZero();
    nn.res_s = nn.res_e = 0.0;
    nn.jump_s = nn.jump_e = nn.spike_s = nn.spike_e = false;
    nn.slim = nn.multi = false;
  }
  nn.blk = source;
  nn.fcap = (rapid || b.feed <= 0) ? inf : b.feed;
  nn.vmax = nn.fcap;
  set_params(nn, arc ? nullptr : &dir);
  nn.provisional = true;
  const double first_piece = arc ? nn.seg.full_length / arc_piece_count(nn.seg) : nn.seg.full_length;
  if (jump_rule) nn.res_e = wf * ts2 * std::min(nn.vmax, first_piece / (4.0 * wf * ts2));
  nn.tail_trim = opt_.rule == CornerRule::blend;

  if (!has_prev) {
    nn.v_lim = nn.v_corner = 0.0;  // start from rest
    append(nn);
    back_pass(tail_ - 1);
    return Status::ok;
  }
  const double theta = blend_here ? 0.0 : turn_angle(u1, u2);  // (the blend branch below returns)

  if (blend_here) {
    const Segment& pseg = at(first).seg;  // the whole previous block (trim_start already final)
    const long psource = pseg.source;
    const bool lines = pseg.kind == SegmentKind::line && nn.seg.kind == SegmentKind::line;
    // corner blend: P0 on the previous piece, P3 on the next, both at distance d from the vertex
    const double dmax = 0.45 * std::min(pseg.full_length, nn.seg.full_length);
    double d = std::min(dmax, 4.0 * opt_.tolerance / sin_half);
    std::array<Vec3, 4> bl;
    for (int it = 0; it < 40; ++it) {
      const double sp = pseg.full_length - d;
      const Vec3 p0 = piece_point(pseg, sp), p3 = piece_point(nn.seg, d);
      if (lines) {  // the tangents are u1 and u2; the deviation bound is exact
        bl = {p0, p0 + d * u1, p3 - d * u2, p3};
        break;
      }
      const Vec3 t0 = piece_tangent(pseg, sp), t3 = piece_tangent(nn.seg, d);
      bl = {p0, p0 + d * t0, p3 - d * t3, p3};
      double dev = 0;
      for (int i = 1; i < 16; ++i) {
        const Vec3 qp = bezier_point(bl, i / 16.0);
        dev = std::max(dev, std::min(pseg.distance_to_piece(qp, sp, pseg.full_length),
                                     nn.seg.distance_to_piece(qp, 0.0, d)));
      }
      if (dev <= opt_.tolerance) break;
      d *= 0.5;
    }
    at(first).seg.trim_end = d;
    nn.seg.trim_start = d;
    split_tail();
    const double vfeed = std::min(at(first).fcap, nn.fcap);
    double v_prev = at(tail_ - 1).vmax;
    // the blend, cut into pieces at its arc-length table nodes; each piece has its own axis-box
    // bounds, so the speed follows the curvature (the forward and backward passes over the pieces
    // are the phase-plane method on a grid of stations)
    if (lines && !jerk_mode) {  // the common case, built from scalar coefficients
      push_line_blend(source, psource, bl[0], pseg.block.end, bl[3], u1, u2, d, vfeed, v_prev);
      nn.v_corner = v_prev;
      nn.v_lim = std::min(nn.v_corner, nn.vmax);
      append(nn);
      back_pass(first);
      return Status::ok;
    }
    std::array<Vec3, 17> T, Kv;
    Segment& whole = blend_of(source);
    whole = Segment::blend(bl[0], bl[1], bl[2], bl[3], psource, &T, &Kv);
    BlendBounds tab;
    tab.fill(T, Kv);
    // piece boundaries at table nodes
    const int* cut = jerk_mode ? cuts_jerk : cuts_general;
    int np = jerk_mode ? n_cuts_jerk : n_cuts_general;
    if (!jerk_mode) {
      Vec3 U, K;
      tab.bounds(0, 16, U, K);
      double vcap = vfeed;
      for (int i = 0; i < 3; ++i)
        if (U[i] > 0) vcap = std::min(vcap, limits_.velocity[i] / U[i]);
      // a gentle turn: the centripetal part takes little of the budget at full speed; one piece
      if (K.maxCoeff() * vcap * vcap <= 0.02 * limits_.acceleration.minCoeff()) {
        np = 1;
        cut = cuts_one;
      }
    }
    // jerk mode: where the blend meets an arc the curvature jumps (tangent junction); cap the speed
    // so the acceleration step's third difference takes at most half of J_i (see below)
    Vec3 dk0 = Vec3::Zero(), dk1 = Vec3::Zero();
    if (jerk_mode) {
      dk0 = Kv[0] - curvature_vector(at(tail_ - 1).seg, true);
      dk1 = curvature_vector(nn.seg, false) - Kv[16];
      if (dk0.norm() > 1e-12) {
        mark_spike(at(tail_ - 1), false);
        sync(tail_ - 1);
      }
    }
    // what set_params() finds for every piece of this blend (the same axes move on all of them)
    const double amin_blend = min_over(limits_.acceleration, whole.moving_axes());
    for (int k = 0; k < np; ++k) {
      const int i0 = cut[k], i1 = cut[k + 1];
      // built in place in the ring (a Node is large: no temporary and copy)
      const std::size_t slot = this->slot(tail_);
      Node& bn = ring_[slot];
      // jerk mode: the node keeps the whole geometry; else it stays in blends_ (copy_segment / seg_of)
      init_blend_piece(bn, whole, i0, i1, source, vfeed, !jerk_mode);
      tab.bounds(i0, i1, bn.U, bn.K);
      bn.vmax = vfeed;
      if (jerk_mode) {
        double kmax = 0, rate = 0;
        for (int i = i0; i <= i1; ++i) {
          const auto ii = static_cast<std::size_t>(i);
          kmax = std::max(kmax, Kv[ii].norm());
          if (i > i0 && whole.table[ii] > whole.table[ii - 1])
            rate = std::max(rate, std::abs(Kv[ii].norm() - Kv[ii - 1].norm()) / (whole.table[ii] - whole.table[ii - 1]));
        }
        bn.seg.curvature = kmax;
        bn.seg.curvature_rate = rate;
        set_params(bn);
      } else {
        // set_params() on a curved piece without jerk limits: the per-axis box
        bn.curved = true;
        bn.j = inf;
        bn.a = amin_blend;
        // min of the ratios with one division each, min of the roots = root of the min (one root)
        bn.vmax = std::min(bn.vmax, min_ratio(limits_.velocity.data(), bn.U.data()));
        const double wk = min_ratio(limits_.acceleration.data(), bn.K.data());
        if (wk < inf) bn.vmax = std::min(bn.vmax, std::sqrt(wk));
      }
      bn.v_lim = bn.v_corner = std::min(v_prev, bn.vmax);
      if (jerk_mode) {
        if (k == 0 && dk0.norm() > 1e-12) mark_spike(bn, true);
        if (k + 1 == np && dk1.norm() > 1e-12) mark_spike(bn, false);
        if (k == 0) bn.v_lim = bn.v_corner = std::min(bn.v_lim, curvature_step_speed(dk0));
      }
      v_prev = bn.vmax;
      Quick& x = quick_[slot];  // sync(tail_) without its two modulos
      x.w_lim = bn.v_lim * bn.v_lim;
      x.len = plan_length(bn);
      x.a = bn.a;
      x.j = bn.j;
      set_reach(x, bn.curved, bn.U, bn.K);
      x.wb = 0.0;
      x.rec = -1;
      ++tail_;
    }
    nn.v_corner = v_prev;
    if (jerk_mode && dk1.norm() > 1e-12) {
      nn.v_corner = std::min(nn.v_corner, curvature_step_speed(dk1));
      mark_spike(nn, true);
    }
    nn.v_lim = std::min(nn.v_corner, nn.vmax);
    append(nn);
    back_pass(first);
    return Status::ok;
  }

  const double amin = moving_axes_min(limits_.acceleration, u1, u2);
  split_tail();
  Node& p = at(tail_ - 1);  // the previous block's last piece
  const double vcap = std::min(p.vmax, nn.fcap);
  double v = vcap;
  bool jump = false;
  const Vec3 dk = jerk_mode ? Vec3(curvature_vector(nn.seg, false) - curvature_vector(p.seg, true)) : Vec3::Zero();
  if (theta > tangent_angle) {
    // next to arcs the vertex straddling second differences also see the centripetal part
    const double kappa = std::max(p.seg.kind == SegmentKind::arc ? p.seg.block.curvature() : 0.0,
                                  arc ? nn.seg.block.curvature() : 0.0);
    switch (opt_.rule) {
      case CornerRule::paper:
        v = std::max(paper_corner_speed(amin, opt_.ts1, theta), opt_.allowable_speed_difference);
        break;
      case CornerRule::vector:
        v = jump_speed(amin, (u2 - u1).norm(), ts2, kappa);
        if (jerk_mode) {
          // third differences: a velocity step Δv gives |Δv|/ts2², an acceleration step |Δa|/ts2
          const double jmin = moving_axes_min(limits_.jerk, u1, u2);
          v = std::min(v, jump_speed(jmin * ts2, (u2 - u1).norm(), ts2, dk.norm()));
        }
        jump = true;
        break;
      case CornerRule::per_axis:
        v = inf;
        for (int i = 0; i < 3; ++i)
          v = std::min(v, jump_speed(limits_.acceleration[i], std::abs(u2[i] - u1[i]), ts2, kappa));
        if (jerk_mode)
          for (int i = 0; i < 3; ++i)
            v = std::min(v, jump_speed(limits_.jerk[i] * ts2, std::abs(u2[i] - u1[i]), ts2, std::abs(dk[i])));
        jump = true;
        break;
      case CornerRule::junction_deviation: {
        // theta is the turn between the tangents; Klipper's δ maps scv with the moving-axes minimum
        const double dev = opt_.square_corner_velocity > 0
                               ? klipper_junction_deviation(opt_.square_corner_velocity, amin)
                               : opt_.junction_deviation;
        const double aj = opt_.junction_accel == JunctionAccel::along_change
                              ? junction_acceleration(limits_.acceleration, u1, u2, opt_.junction_accel)
                              : amin;
        v = junction_deviation_speed(aj, dev, theta);
        break;
      }
      case CornerRule::blend: v = 0.0; break;  // reversal: stop
    }
    v = std::min(v, vcap);
  } else if (jerk_mode && opt_.rule != CornerRule::paper && opt_.rule != CornerRule::junction_deviation) {
    // tangent junction where the curvature jumps (line ↔ arc, arcs of other radii): the acceleration
    // steps by v²·Δ(κn); its third difference |Δa_i|/ts2 gets half of J_i, the S-curve ramps on both
    // sides the other half
    v = std::min(v, curvature_step_speed(dk));
    if (dk.norm() > 1e-12) {
      mark_spike(p, false);
      mark_spike(nn, true);
      sync(tail_ - 1);
    }
  }
  if (jump_rule) {
    if (jump) {
      v = std::min({v, p.seg.length() / (4.0 * wf * ts2), first_piece / (4.0 * wf * ts2)});
      p.res_e = wf * ts2 * v;
      nn.res_s = wf * ts2 * v;
    } else {
      p.res_e = 0.0;
    }
    p.jump_e = jump;
    nn.jump_s = jump;
    sync(tail_ - 1);
  }
  nn.v_corner = v;
  nn.v_lim = std::min(v, nn.vmax);
  append(nn);
  back_pass(first);
  return Status::ok;
}

void Planner::finish() noexcept {
  if (finished_) return;
  finished_ = true;
  if (tail_ > frozen_) {
    const long first = tail_ - 1;
    Node& t = at(first);
    t.tail_trim = false;
    t.seg.trim_end = 0.0;
    t.res_e = 0.0;
    t.jump_e = false;
    split_tail();
    sync(first);
    back_pass(first);
  }
}

void Planner::back_pass(long dirty_from) noexcept {
  double w_next = 0.0;  // the buffer always ends at rest (squared speeds: no root per node)
  if (tail_ <= frozen_) return;
  for (long k = tail_ - 1; k >= frozen_; --k) {
    Quick& n = quick_[slot(k)];
    double w;
    if (n.rec >= 0) {
      // a multi node: its pieces from the last to the first
      BlendRec& r = recs_[static_cast<std::size_t>(n.rec)];
      w = w_next;
      for (int p = r.np - 1; p >= 0; --p) {
        w = std::min(std::min(r.w_lim[p], r.alpha[0][p] * w + r.beta[0][p]),
                     std::min(r.alpha[1][p] * w + r.beta[1][p], r.alpha[2][p] * w + r.beta[2][p]));
        if (k < dirty_from && w == r.wb[p]) {  // so are the pieces before it (and w == n.wb below)
          w = r.wb[0];
          break;
        }
        r.wb[p] = w;
      }
    } else {
      // Lee & Lee eq. 3 (trapezoid; on curves the axis box), capped by the junction limit (without
      // jerk limits reach_sq is the min of three affine terms, inlined here; on a line only the first
      // is finite: the same value with half the latency in the chain)
      w = jerk_        ? std::min(n.w_lim, reach_sq(n, w_next))
          : n.straight ? std::min(n.w_lim, w_next + n.beta[0])
                       : std::min(std::min(n.w_lim, n.alpha[0] * w_next + n.beta[0]),
                                  std::min(n.alpha[1] * w_next + n.beta[1], n.alpha[2] * w_next + n.beta[2]));
    }
    if (k < dirty_from && w == n.wb) break;  // nothing changes further back
    n.wb = w;
    w_next = w;
  }
}

bool Planner::freeze_next() noexcept {
  if (frozen_ >= tail_) return false;
  const bool is_tail = frozen_ == tail_ - 1;
  if (is_tail && !finished_) return false;
  if (!buffer_ready()) return false;
  const std::size_t slot = this->slot(frozen_);
  Node& n = ring_[slot];
  const Quick& qn = quick_[slot];
  const double vs = v_frozen_end_;
  const double wt = is_tail ? 0.0 : quick_[(slot + 1) & mask_].wb;
  if (qn.rec >= 0) {
    freeze_multi(n, recs_[static_cast<std::size_t>(qn.rec)], vs, wt);
    return true;
  }
  const double ve = std::sqrt(std::min(wt, reach_sq(qn, vs * vs)));
  const double wf = window_periods();
  const double ws = n.jump_s ? wf * opt_.ts2 * vs : 0.0, we = n.jump_e ? wf * opt_.ts2 * ve : 0.0;
  const double len = n.seg.length();
  if (n.curved && !std::isfinite(qn.j)) {
    // peak speed and tangential acceleration from the axis box at that speed:
    // 2·w − vs² − ve² = 2·L·(A_i − K_i·w)/U_i for the binding axis
    const double lr = std::max(0.0, len - std::min(ws, len) - std::min(we, len));
    const double S = vs * vs + ve * ve;
    double num[3], den[3];
    for (int i = 0; i < 3; ++i) {
      num[i] = n.U[i] * S + 2.0 * lr * limits_.acceleration[i];
      den[i] = 2.0 * n.U[i] + 2.0 * lr * n.K[i];
    }
    double wp = std::min(n.vmax * n.vmax, min_ratio(num, den));
    wp = std::max(wp, std::max(vs * vs, ve * ve));
    for (int i = 0; i < 3; ++i) num[i] = limits_.acceleration[i] - n.K[i] * wp;
    double a = min_ratio(num, n.U.data());
    // at the curvature cap the tangential budget is 0: a floor of 1e-6·A keeps the rounding-size speed
    // differences of neighbouring pieces from turning into long ramps
    const double amin = limits_.acceleration.minCoeff();
    if (!(a > 1e-6 * amin)) a = 1e-6 * amin;
    if (!std::isfinite(a)) a = amin;
    n.prof = Profile::make(len, vs, ve, std::sqrt(wp), a, inf, ws, we);
  } else {
    n.prof = Profile::make(len, vs, ve, std::max(n.vmax, std::max(vs, ve)), n.a, n.j, ws, we);
  }
  n.t0 = t_frozen_end_;
  t_frozen_end_ += n.prof.duration;
  v_frozen_end_ = ve;
  ++frozen_;
  return true;
}

// The pieces of a multi node one after the other (the freeze kernel, line_blend.hpp), as
// freeze_next() does for single nodes.
void Planner::freeze_multi(Node& n, BlendRec& r, double vs, double wt) noexcept {
  const double v_end = lb_->freeze(r, vs, wt, limits_.acceleration, t_frozen_end_);
  const double t = r.t0[r.np - 1] + r.dur[r.np - 1];
  // of the node's profile only the end speeds and the duration are read (the pieces have their own)
  n.prof.vs = vs;
  n.prof.ve = v_end;
  n.prof.duration = t - t_frozen_end_;
  n.t0 = t_frozen_end_;
  t_frozen_end_ = t;
  v_frozen_end_ = v_end;
  ++frozen_;
}

void detail::LineBlendRecord::profile(int k, Profile& p) const noexcept {
  p.vs = vs[k];
  p.ve = ve[k];
  p.vp = vp[k];
  p.a = acc[k];
  p.j = inf;
  p.t[0] = 0.0;
  p.t[1] = t1[k];
  p.t[2] = t2[k];
  p.t[3] = t3[k];
  p.t[4] = 0.0;
  p.d[0] = 0.0;
  p.d[1] = d1[k];
  p.d[2] = d2[k];
  p.d[3] = d3[k];
  p.d[4] = 0.0;
  p.duration = dur[k];
}

Status Planner::ensure_frozen_until(double t) noexcept {
  while (t_frozen_end_ <= t && frozen_ < tail_) {
    if (!freeze_next()) return Status::need_blocks;
  }
  if (t_frozen_end_ <= t && !finished_) return Status::need_blocks;
  return Status::ok;
}

Status Planner::next(Sample& out) noexcept {
  if (done_) return Status::finished;
  const double ts2 = opt_.ts2;
  const double t = static_cast<double>(sample_) * ts2;
  if (sample_ % opt_.fine_steps() == 0) {
    // rough loop: freeze the profile for the coming rough period [t, t + ts1] if the buffer allows
    const Status st = ensure_frozen_until(t + opt_.ts1);
    if (st != Status::ok && t_frozen_end_ <= t) return st;
  }
  {
    const Status st = ensure_frozen_until(t);
    if (st != Status::ok) return st;
  }
  out.t = t;
  if (finished_ && frozen_ == tail_ && t >= t_frozen_end_) {
    // past the end: the program's end point at rest
    out.position = last_point_;
    out.velocity.setZero();
    out.feed = 0;
    out.path_acceleration = 0;
    out.block = pushed_ - 1;
    done_ = true;
    head_ = tail_;
    ++sample_;
    return Status::ok;
  }
  while (head_ < frozen_ - 1 && at(head_).t0 + at(head_).prof.duration <= t) ++head_;
  Node& n = at(head_);
  double s, v, acc;
  const Segment* sg;
  if (n.multi) {
    // the piece of the blend that runs at t, on the whole blend (trims 0) at the piece's offset
    BlendRec& r = recs_[rec_slot(n.blk)];
    int k = r.cursor;
    while (k + 1 < r.np && r.t0[k] + r.dur[k] <= t) ++k;
    r.cursor = k;
    Profile pk;
    r.profile(k, pk);
    pk.eval(t - r.t0[k], s, v, acc);
    sg = &blend_of(n.blk);
    s += r.trim_s[k];
  } else {
    sg = &seg_of(n);
    n.prof.eval(t - n.t0, s, v, acc);
  }
  out.position = sg->point_at(s);
  out.velocity = v * sg->tangent_at(s);
  out.feed = v;
  out.path_acceleration = acc;
  out.block = sg->source;
  ++sample_;
  return Status::ok;
}

Status Planner::next_segment(PlannedSegment& out) noexcept {
  if (head_ == frozen_) {
    if (frozen_ == tail_) return finished_ ? Status::finished : Status::need_blocks;
    if (!freeze_next()) return Status::need_blocks;
  }
  const std::size_t slot = this->slot(head_);
  const Node& n = ring_[slot];
  if (n.multi) {
    BlendRec& r = recs_[static_cast<std::size_t>(quick_[slot].rec)];  // recs_ and blends_ by the same index
    const Segment& g = blends_[static_cast<std::size_t>(quick_[slot].rec)];
    const int k = r.cursor;
    put_blend(g, out.segment);
    out.segment.trim_start = r.trim_s[k];
    out.segment.trim_end = r.trim_e[k];
    out.segment.curvature = g.curvature;
    out.segment.curvature_rate = g.curvature_rate;
    r.profile(k, out.profile);
    out.t0 = r.t0[k];
    if (++r.cursor == r.np) {
      r.cursor = 0;
      ++head_;
    }
    return Status::ok;
  }
  copy_segment(n, out.segment);
  out.profile = n.prof;
  out.t0 = n.t0;
  ++head_;
  return Status::ok;
}

}  // namespace netshape::motion
