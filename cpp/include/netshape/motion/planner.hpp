#pragma once
/// \file planner.hpp
/// Streaming look-ahead planner and 2-step interpolator for controllers (Lee & Lee §2–3).
///
/// Push blocks, pull samples. All memory (the ring buffer of segments) is allocated in the
/// constructor; push(), next() and next_segment() never allocate and never throw: they return a
/// Status (like ruckig's non-throwing update with throw_error = false).
///
///     netshape::motion::Planner planner(limits, options);
///     netshape::motion::Sample sample;
///     for (;;) {
///       auto st = planner.next(sample);               // one fine period (ts2)
///       if (st == Status::need_blocks) {              // look-ahead buffer wants more
///         if (have_block) planner.push(block); else planner.finish();
///       } else if (st == Status::finished) break;
///       else drive(sample.position, sample.velocity);
///     }
///
/// Look-ahead (Lee & Lee §3.2): each new segment gets the largest entry speed it can stop from
/// (eq. 3 with the end speed 0), the corner speed of the junction (eq. 4 or another rule) and the
/// previous block's reachable end speed (eq. 5); the smallest wins, and the backward pass carries the
/// change back through the buffer until nothing changes. A segment's profile is frozen when the
/// rough loop (period ts1) reaches it; the fine loop (period ts2) evaluates the frozen profiles on
/// the path geometry, so every sample lies on the (blended) path.

#include <cstdint>
#include <vector>

#include "netshape/motion/limits.hpp"
#include "netshape/motion/options.hpp"
#include "netshape/motion/profile.hpp"
#include "netshape/motion/segment.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

/// Result of a non-throwing planner call.
enum class Status : std::int8_t {
  ok = 0,            ///< done; for next(): `sample` holds the next fine sample
  buffer_full = 1,   ///< push(): no room; pull samples first
  need_blocks = 2,   ///< next(): the look-ahead buffer must be refilled (push or finish)
  finished = 3,      ///< next(): the program has ended (the last sample was the end point)
  invalid_input = -1 ///< push(): the block is not valid (see last_error()); nothing was added
};

/// One fine-loop sample.
struct Sample {
  double t = 0;                     ///< time since start [s]
  Vec3 position = Vec3::Zero();     ///< [mm]
  Vec3 velocity = Vec3::Zero();     ///< per-axis velocity [mm/s]
  double feed = 0;                  ///< path speed [mm/s]
  double path_acceleration = 0;     ///< tangential acceleration [mm/s^2]
  long block = -1;                  ///< index of the program block being run (blend: the one before)
};

/// A frozen segment with its speed profile (for controllers that interpolate themselves).
struct PlannedSegment {
  Segment segment;
  Profile profile;
  double t0 = 0;  ///< start time [s]
};

namespace detail {
struct LineBlendKernels;
struct LineBlendTables;

/// The pieces of a corner blend between two lines, kept once per blend by the Planner (internal).
/// Per piece: trims of the whole blend, length, speed cap, squared junction limit (piece 0: with the
/// cap before the blend), the reach w = min_i alpha_i·w0 + beta_i in squared speeds, the coefficients
/// of the peak squared speed min_i p1_i·(vs² + ve²) + p0_i and of the tangential budget
/// min_i (A_i − K_i·w)·iu_i (so that neither pass divides), the backward squared speed at its start,
/// and once frozen its trapezoid (speeds, acceleration, phase times and distances) and start time.
/// Every field is an array over the pieces (plain doubles: the kernels that fill it are compiled
/// once per instruction set, see src/motion/line_blend.hpp).
struct LineBlendRecord {
  static constexpr int pieces = 4;
  int np = 0, cursor = 0;  // pieces; next piece to hand out / sample
  double trim_s[pieces] = {}, trim_e[pieces] = {}, len[pieces] = {}, vmax[pieces] = {};
  double w_lim[pieces] = {}, wb[pieces] = {};
  // per axis i and piece k: [i][k]
  double alpha[3][pieces] = {}, beta[3][pieces] = {};
  double p1[3][pieces] = {}, p0[3][pieces] = {}, iu[3][pieces] = {}, K[3][pieces] = {};
  // frozen: speed-up, cruise, slow-down
  double vs[pieces] = {}, ve[pieces] = {}, vp[pieces] = {}, acc[pieces] = {};
  double t1[pieces] = {}, t2[pieces] = {}, t3[pieces] = {};
  double d1[pieces] = {}, d2[pieces] = {}, d3[pieces] = {};
  double dur[pieces] = {}, t0[pieces] = {};
  /// The frozen profile of piece k (a trapezoid without windows).
  void profile(int k, Profile& p) const noexcept;
};
}  // namespace detail

class Planner {
 public:
  /// Validates limits and options (throws std::invalid_argument) and allocates the ring buffer.
  Planner(const AxisLimits& limits, const PlanOptions& options);

  /// Append a block (rapids run at the axis limits; zero-length blocks are skipped).
  Status push(const toolpath::Block& block) noexcept;
  /// No more blocks will come: the last block stops at its end.
  void finish() noexcept;
  /// Next fine sample (period ts2).
  Status next(Sample& out) noexcept;
  /// Alternative to next(): freeze and hand out the next segment with its profile.
  Status next_segment(PlannedSegment& out) noexcept;

  /// Back to the empty state (limits, options and memory kept).
  void reset() noexcept;
  /// Free slots in the ring buffer, counted in blocks that can still be pushed now.
  int free_blocks() const noexcept;
  /// Program end time once known (after finish() and the last segment is frozen), else −1 [s].
  double end_time() const noexcept;
  /// Number of blocks accepted so far.
  long blocks_pushed() const noexcept { return pushed_; }
  /// Message of the last invalid_input.
  const char* last_error() const noexcept { return error_; }
  const AxisLimits& limits() const noexcept { return limits_; }
  const PlanOptions& options() const noexcept { return opt_; }

 private:
  struct Node {
    Segment seg;
    double vmax = 0, a = 1, j = 0;  // cruise cap [mm/s], path acceleration (lines, jerk mode), path jerk
    // curved pieces (arcs, blends) without jerk limits: per-axis bounds over the piece of |u_i| (U)
    // and of the curvature vector |κ n_i| [1/mm] (K); the axis box |u_i·s̈ + κ n_i·ṡ²| ≤ A_i then
    // holds for |s̈| ≤ min_i (A_i − K_i·ṡ²)/U_i
    Vec3 U = Vec3::Zero(), K = Vec3::Zero();
    bool curved = false;
    double v_lim = 0;               // junction limit at the start [mm/s]
    double v_corner = 0;            // corner speed before this node's own cap [mm/s]
    double fcap = 0;                // programmed feed cap [mm/s] (+inf for rapids)
    double res_s = 0, res_e = 0;    // distance reserved for constant-speed windows [mm]
    bool jump_s = false, jump_e = false;
    bool spike_s = false, spike_e = false;  // jerk mode: curvature jump at the start / end (j halved)
    bool tail_trim = false;         // blend mode: end trim is still the tentative maximum
    bool provisional = false;       // last block: not yet cut into pieces (arcs)
    long blk = 0;                   // index of the program block that brought this node in
    // blend pieces: seg holds kind, trims, lengths, curvature and source only; the Bézier (ctrl,
    // table) stays once per blend in blends_[blk % size] until seg_of() copies it in (sampling)
    bool slim = false;
    // a blend between two lines without jerk limits (push_line_blend) is one node whose pieces are
    // kept in recs_[blk % size]: the passes and the freeze loop over them, next() and next_segment()
    // hand them out one by one
    bool multi = false;
    Profile prof;
    double t0 = 0;
  };
  // compact copy of what the backward pass reads and writes, so it walks small records, not Nodes
  // (the reach of a trapezoidal node is w = min_i alpha_i·w0 + beta_i in squared speeds w = v²:
  // lines alpha = 1, beta = 2·a·L; curved pieces the axis box, alpha_i = U_i/(U_i + 2·L·K_i),
  // beta_i = 2·L·A_i/(U_i + 2·L·K_i); precomputed by sync() so the passes need no division)
  struct Quick {
    double w_lim = 0, wb = 0, len = 0, a = 1, j = 0;  // squared junction limit and backward speed [mm²/s²]
    double alpha[3] = {1, 0, 0}, beta[3] = {0, 0, 0};
    int rec = -1;  // multi node: its BlendRec in recs_, else −1
    bool straight = false;  // a line: alpha = (1, 0, 0), beta = (2·a·L, inf, inf), so w = w0 + beta[0]
  };
  static constexpr int rec_pieces = detail::LineBlendRecord::pieces;
  using BlendRec = detail::LineBlendRecord;
  // ring slot of segment k / record slot of block k: the sizes are powers of two, so a mask (an
  // integer division per lookup costs tens of cycles)
  std::size_t slot(long k) const noexcept { return static_cast<std::size_t>(k) & mask_; }
  std::size_t rec_slot(long blk) const noexcept { return static_cast<std::size_t>(blk) & rec_mask_; }
  Quick& q(long k) noexcept { return quick_[slot(k)]; }
  void sync(long k) noexcept;
  void set_reach(Quick& x, bool curved, const Vec3& U, const Vec3& K) const noexcept;
  Node& at(long k) noexcept { return ring_[slot(k)]; }
  const Node& at(long k) const noexcept { return ring_[slot(k)]; }
  double plan_length(const Node& n) const noexcept;
  void set_params(Node& n, const Vec3* line_dir = nullptr) const noexcept;
  double reach_sq(const Quick& n, double w0) const noexcept;
  void split_tail() noexcept;
  void init_blend_piece(Node& bn, const Segment& whole, int i0, int i1, long source, double vfeed, bool slim) noexcept;
  void push_line_blend(long source, long psource, const Vec3& p0, const Vec3& vtx, const Vec3& p3, const Vec3& u1, const Vec3& u2,
                       double d, double vfeed, double& v_prev) noexcept;
  void append(const Node& n) noexcept;
  long blocks_in_buffer() const noexcept;
  void back_pass(long dirty_from) noexcept;
  bool buffer_ready() const noexcept;
  bool freeze_next() noexcept;
  Status ensure_frozen_until(double t) noexcept;
  Status fail(const char* msg) noexcept;
  /// Fine periods of constant speed on each side of a velocity jump: 2 (second differences see the
  /// jump alone), 3 with jerk limits (third differences too).
  double window_periods() const noexcept { return jerk_ ? 3.0 : 2.0; }
  /// Jerk mode: largest speed at a tangent junction where the curvature vector steps by dk [1/mm]:
  /// v²·|dk_i| ≤ J_i·ts2/2 (the acceleration step's third difference gets half of the jerk limit).
  double curvature_step_speed(const Vec3& dk) const noexcept;
  /// Jerk mode: a curvature step at the start (or end) of n; its S-curve jerk is halved once.
  static void mark_spike(Node& n, bool at_start) noexcept;

  AxisLimits limits_;
  PlanOptions opt_;
  std::vector<Node> ring_;
  Node scratch_;  // a new node push() cannot build in place (see push)
  std::vector<Quick> quick_;
  std::vector<Segment> blends_;  // whole blend of each block in the buffer, by blk % size
  std::vector<BlendRec> recs_;   // pieces of the multi node of each block in the buffer, by blk % size
  void freeze_multi(Node& n, BlendRec& r, double vs, double wt) noexcept;
  void put_blend(const Segment& whole, Segment& out) const noexcept;
  Segment& blend_of(long blk) noexcept { return blends_[rec_slot(blk)]; }
  /// The node's segment with its geometry (blend pieces: copied in from blends_ on first use).
  const Segment& seg_of(Node& n) noexcept;
  /// Copy of the node's full segment (blend pieces: the blend with the piece's trims).
  void copy_segment(const Node& n, Segment& out) noexcept;
  bool jerk_ = false;  // limits_.jerk_limited()
  Vec3 inv_acc_ = Vec3::Zero();  // 1/A_i
  long cap_ = 0;
  std::size_t mask_ = 0, rec_mask_ = 0;  // cap_ − 1, blends_.size() − 1
  long head_ = 0;      // first segment in the buffer
  long frozen_ = 0;    // segments [head_, frozen_) are frozen
  long tail_ = 0;      // one past the last
  bool finished_ = false;
  bool done_ = false;
  long pushed_ = 0;
  long sample_ = 0;    // index of the next fine sample
  double t_frozen_end_ = 0;  // end time of the frozen prefix [s]
  double v_frozen_end_ = 0;  // speed at the end of the frozen prefix [mm/s]
  Vec3 last_point_ = Vec3::Zero();
  bool have_last_ = false;
  Vec3 last_dir_ = Vec3::Zero();  // unit direction of the last block pushed (lines)
  const char* error_ = "";
  // the array work of blends between two lines, for the best instruction set the CPU has
  const detail::LineBlendKernels* lb_ = nullptr;
  const detail::LineBlendTables* lb_tables_ = nullptr;
};

}  // namespace netshape::motion
