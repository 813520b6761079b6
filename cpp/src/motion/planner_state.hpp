#pragma once
/// \file planner_state.hpp
/// Internal: the state of a motion::Planner, which holds one through a pointer. The ring of nodes
/// (segments with their limits and, once frozen, their profiles), the pass records the look-ahead
/// walks, the blend stores, and the operations on them; each planner_*.cpp file implements one
/// concept of it (see the comment at the top of each).
///
/// Invariants: segments [head_, frozen_) are frozen (their profiles fixed, times increasing from
/// t0 = 0), [frozen_, tail_) are planned and may still change; node k lives in ring slot
/// k & ring_mask_ and its pass record in the same slot of passes_; the blend of program block b lives
/// in slot b & block_mask_ of the blend stores, a cubic block b (and its cubic record) in that slot of
/// the cubic stores. The buffer always ends at rest.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "blend_bounds.hpp"
#include "cubic_record.hpp"
#include "line_blend.hpp"
#include "planner_geometry.hpp"
#include "netshape/motion/cubic.hpp"
#include "netshape/motion/planner.hpp"

namespace netshape::motion::detail {

constexpr double inf = std::numeric_limits<double>::infinity();
/// An arc is cut into at most this many pieces ...
constexpr int max_arc_pieces = 64;
/// ... of at most this sweep [rad] (when it can).
constexpr double arc_piece_angle = pi / 32;
/// Most pieces (ring nodes) of a corner blend.
constexpr int max_blend_pieces = 8;
/// Ring nodes one push() may add: the previous arc's pieces, the blend pieces, the new block.
constexpr long nodes_per_push = max_arc_pieces + max_blend_pieces + 2;

/// std::min(a, b) by value, (b < a) ? b : a: the same result, but GCC keeps it in registers (one
/// minsd) where std::min's reference result sometimes goes through the stack.
inline double min_of(double a, double b) noexcept { return b < a ? b : a; }

/// Smallest of `per_axis` over the axes that move (moving[i] > 0); all axes if none moves.
inline double min_over_moving(const Vec3& per_axis, const Vec3& moving) {
  double m = inf;
  for (int i = 0; i < 3; ++i)
    if (moving[i] > 0) m = std::min(m, per_axis[i]);
  return std::isfinite(m) ? m : per_axis.minCoeff();
}

/// Smallest num[i]/den[i] over the i with den[i] > 0, +inf if none; one division (the fractions are
/// compared by cross-multiplication).
inline double min_ratio(const double* num, const double* den) noexcept {
  if (den[0] > 0 && den[1] > 0 && den[2] > 0) {
    // the loop below with every denominator > 0 (the common case), on values instead of an index
    double nb = num[0], db = den[0];
    if (num[1] * db < nb * den[1]) {
      nb = num[1];
      db = den[1];
    }
    if (num[2] * db < nb * den[2]) {
      nb = num[2];
      db = den[2];
    }
    return nb / db;
  }
  int best = -1;
  for (int i = 0; i < 3; ++i)
    if (den[i] > 0 && (best < 0 || num[i] * den[best] < num[best] * den[i])) best = i;
  return best < 0 ? inf : num[best] / den[best];
}

/// How a node's speed is bounded.
enum class SpeedBound : std::uint8_t {
  /// Along the path: cruise cap, path acceleration and path jerk (lines; in jerk mode also curves).
  path,
  /// A curved piece without jerk limits, per axis: |u_i|·v ≤ V_i and |u_i·s̈ + κ n_i·v²| ≤ A_i, which
  /// holds for K_i·v² ≤ A_i (K_i bounds |κ n_i| on the piece) and |s̈| ≤ min_i (A_i − K'_i·v²)/U'_i with
  /// the terms U', K' of the direction of the speed change (Node::ramp_tangent, ramp_curvature: from
  /// signed bounds of u_i and κ n_i, so a centripetal part that eases an axis while it slows down or
  /// speeds up is not charged to it).
  axis_box,
};

/// Where a node's path geometry is kept.
enum class Geometry : std::uint8_t {
  /// `Node::segment` is complete.
  in_node,
  /// A blend piece: `segment` holds kind, trims, length, curvature and source only; the control points
  /// and table stay once per blend in the blend store until segment_of() copies them in (sampling).
  in_blend_store,
  /// A piece of a cubic block: as in_blend_store, the whole cubic (its Bézier, table and chord) kept
  /// once per block in the cubic store (split_cubic_block()).
  in_cubic_store,
  /// One node for a whole blend between two lines: its pieces are in the line-blend record of its
  /// block (the passes and the freeze loop over them, next() and next_segment() hand them out one by
  /// one), its geometry in the blend store.
  line_blend_record,
  /// One node for a whole cubic block cut into pieces (without jerk limits and velocity-jump windows):
  /// its pieces are in the cubic record of its block (CubicRecord; handled as line_blend_record), the
  /// node's segment is the whole cubic with its trims and its untrimmed copy is in the cubic store.
  cubic_record,
};

/// Whether a node's extent is final.
enum class Extent : std::uint8_t {
  /// Trims and bounds are final.
  settled,
  /// The last block pushed: one node with bounds over the whole block until its end is known; then
  /// split_last_block() cuts arcs into pieces.
  whole_block,
  /// As whole_block, and the blend rule has not placed the blend at its end yet: the node is planned
  /// with the largest end trim a blend may take (0.45 of its length).
  whole_block_blend_pending,
};

/// What happens at one end of a node.
struct NodeEnd {
  double window = 0;            ///< distance reserved for a constant-speed window [mm]
  bool velocity_jump = false;   ///< the velocity jumps here (vector, per-axis rules): constant-speed window
  bool curvature_step = false;  ///< jerk mode: the curvature vector steps here; the node's jerk is halved once
};

/// One segment of the ring with its limits and, once frozen, its profile.
struct Node {
  Segment segment;
  double v_max = 0;       ///< cruise cap [mm/s] (on entry to set_limits(): the programmed feed cap)
  double path_accel = 1;  ///< path acceleration [mm/s²] (lines; jerk mode)
  double path_jerk = 0;   ///< path jerk [mm/s³] (+inf without jerk limits)
  /// SpeedBound::axis_box: per-axis bounds over the piece of |u_i| (U) and of the curvature vector
  /// |κ n_i| [1/mm] (K)
  Vec3 tangent_bound = Vec3::Zero(), curvature_bound = Vec3::Zero();
  /// SpeedBound::axis_box, per direction of a speed change ([0] speeding up, [1] slowing down along
  /// the path): per-axis terms U_i, K_i such that U_i·|a| + K_i·v² ≤ A_i, with the speed cap
  /// (curvature_bound), keeps every axis within A_i on the piece (BlendBounds::ramps, arc_bounds); each
  /// at most tangent_bound, curvature_bound. Read only for SpeedBound::axis_box nodes (never lines)
  Vec3 ramp_tangent[2] = {Vec3::Zero(), Vec3::Zero()}, ramp_curvature[2] = {Vec3::Zero(), Vec3::Zero()};
  SpeedBound bound = SpeedBound::path;
  double v_junction = 0;  ///< junction limit at the start [mm/s]
  double v_corner = 0;    ///< corner speed before this node's own cap [mm/s]
  double feed_cap = 0;    ///< programmed feed cap [mm/s] (+inf for rapids)
  NodeEnd start, end;
  Extent extent = Extent::settled;
  Geometry geometry = Geometry::in_node;
  long block = 0;  ///< index of the program block that brought this node in
  Profile profile;
  double t0 = 0;  ///< start time once frozen [s]
};

/// What the pieces of a block take from its whole-block node (finish_piece).
struct PieceBase {
  double feed_cap = 0, v_corner = 0;
  NodeEnd start, end;
  explicit PieceBase(const Node& n) noexcept : feed_cap(n.feed_cap), v_corner(n.v_corner), start(n.start), end(n.end) {}
};

/// The smallest velocity, acceleration and jerk limit of the axes that move on a segment
/// (Segment::moving_axes; of all axes if none moves). Every piece of a block or blend has the same.
struct AxisMinima {
  double velocity = 0, acceleration = 0, jerk = 0;
};

/// Compact copy of what the backward pass reads and writes, so it walks small records, not Nodes.
/// The reach of a trapezoidal node is w = min_i alpha_i·w0 + beta_i in squared speeds w = v²: lines
/// alpha = (1, 0, 0), beta = (2·a·L, inf, inf); curved pieces the axis box, alpha_i = U_i/(U_i + 2·L·K_i),
/// beta_i = 2·L·A_i/(U_i + 2·L·K_i) with the speeding-up terms of the node (Node::ramp_tangent[0], ...);
/// alpha_down, beta_down the same with its slowing-down terms (on lines equal to alpha, beta), for the
/// backward pass; set by update_pass() so the passes need no division. What the backward pass reads
/// without jerk limits comes first (w_junction to line_blend).
struct PassRecord {
  double w_junction = 0;  ///< squared junction limit [mm²/s²]
  double w_backward = 0;  ///< squared speed the backward pass allows at the start [mm²/s²]
  double alpha_down[3] = {1, 0, 0}, beta_down[3] = {0, 0, 0};
  int line_blend = -1;                  ///< Geometry::line_blend_record: its slot in line_blends_, else −1
  int cubic = -1;                       ///< Geometry::cubic_record: its slot in cubic_records_, else −1
  SpeedBound bound = SpeedBound::path;  ///< SpeedBound::path: w = w0 + beta[0]
  double length = 0;                    ///< planned length (see planned_length) [mm]
  double path_accel = 1, path_jerk = 0;
  double alpha[3] = {1, 0, 0}, beta[3] = {0, 0, 0};
};

/// What init_cubic_node() finds on a cubic block's arc-length table and split_cubic_block() cuts it
/// with: the per-interval bounds and the curvature |κ| at the 17 table nodes.
struct CubicTable {
  BlendBounds bounds;
  double curvature[17] = {};
  AxisMinima minima;  ///< axis_minima() of the cubic (its pieces have the same)
};

/// The planner's state and operations. Planner's streaming calls run the operations of the same
/// name here; its queries read the state directly.
class PlannerState {
 public:
  /// Validates limits and options (throws std::invalid_argument) and allocates every buffer.
  PlannerState(const AxisLimits& limits, const PlanOptions& options);
  /// Back to the empty state (limits, options and memory kept).
  void reset() noexcept;

  // planner_push.cpp
  /// Append a block; `cubic` non-null: a cubic block (the Bézier b.start, c1, c2, b.end).
  Status push(const toolpath::Block& block, const CubicControls* cubic = nullptr) noexcept;
  void finish() noexcept;
  // planner_output.cpp
  Status next(Sample& out) noexcept;
  Status next_segment(PlannedSegment& out) noexcept;

 private:
  friend class motion::Planner;

  // --- addressing (sizes are powers of two: a mask, not a division, per lookup) ---
  std::size_t ring_slot(long k) const noexcept { return static_cast<std::size_t>(k) & ring_mask_; }
  std::size_t block_slot(long block) const noexcept { return static_cast<std::size_t>(block) & block_mask_; }
  Node& node(long k) noexcept { return nodes_[ring_slot(k)]; }
  const Node& node(long k) const noexcept { return nodes_[ring_slot(k)]; }
  PassRecord& pass(long k) noexcept { return passes_[ring_slot(k)]; }
  Segment& blend_geometry(long block) noexcept { return blends_[block_slot(block)]; }
  long blocks_in_buffer() const noexcept;
  Status fail(const char* msg) noexcept;

  // --- nodes and their pass records (planner_push.cpp, inline below) ---
  /// Length the passes plan with: the node's length minus its windows (and, while the blend at its
  /// end is pending, minus the largest end trim a blend may take) [mm].
  double planned_length(const Node& n) const noexcept;
  /// The limit minima over the axes that move on s.
  AxisMinima axis_minima(const Segment& s) const noexcept;
  /// Cruise cap, path acceleration and jerk, speed bound of n from its segment and bounds.
  /// n.v_max holds the programmed feed cap on entry; line_dir: a line's unit direction if known;
  /// minima: axis_minima(n.segment) if known.
  void set_limits(Node& n, const Vec3* line_dir = nullptr, const AxisMinima* minima = nullptr) const noexcept;
  /// The reach coefficients of x (see PassRecord) from its length and n's speed bound and terms.
  void set_reach(PassRecord& x, const Node& n) const noexcept;
  /// The same for an axis-box piece with ramp terms U, K (x.bound set to SpeedBound::axis_box).
  void set_box_reach(PassRecord& x, const Vec3 (&U)[2], const Vec3 (&K)[2]) const noexcept;
  /// Pass record of node k from the node (w_backward and line_blend: the caller).
  void update_pass(long k) noexcept;
  /// Largest squared speed at the end of a node that starts at sqrt(w0) [mm²/s²] (the backward pass
  /// has its own step). (Defined inline in planner_lookahead.cpp, its only user.)
  double reach_squared(const PassRecord& n, double w0) const noexcept;
  /// Node n at the tail with its pass record (w_backward = 0).
  void append(const Node& n) noexcept;
  /// The last node holds a whole block whose end is now known: cut arcs into pieces.
  void split_last_block() noexcept;
  /// Piece k of m of a block cut into pieces (its geometry and bounds already set): speed cap and
  /// limits, the block's junction, window and curvature-step marks on its first / last piece, and the
  /// junction speed from the piece before (v_prev, updated to this piece's cap). minima: as set_limits.
  void finish_piece(Node& x, const PieceBase& base, int k, int m, double& v_prev,
                    const AxisMinima* minima = nullptr) noexcept;
  /// Jerk mode: a curvature step at the start (or end) of n; its S-curve jerk is halved once.
  static void mark_curvature_step(Node& n, bool at_start) noexcept;
  /// Jerk mode: largest speed at a tangent junction where the curvature vector steps by dk [1/mm]:
  /// v²·|dk_i| ≤ J_i·ts2/2 (the acceleration step's third difference gets half of the jerk limit).
  double curvature_step_speed(const Vec3& dk) const noexcept;
  /// Fine periods of constant speed on each side of a velocity jump: 2 (second differences see the
  /// jump alone), 3 with jerk limits (third differences too).
  double window_periods() const noexcept { return jerk_limited_ ? 3.0 : 2.0; }

  // --- cubic blocks (planner_cubic.cpp) ---
  /// Why a cubic block is not valid (a static message naming the field), or nullptr.
  static const char* cubic_error(const toolpath::Block& b, const CubicControls& c) noexcept;
  /// n becomes the whole cubic block as one node (Geometry::in_node, kind blend, its table filled)
  /// with bounds over all of it; feed cap, limits, junction and extent: the caller. The interval
  /// bounds of its table stay in cubic_table(source) for split_cubic_block().
  void init_cubic_node(Node& n, const toolpath::Block& b, const CubicControls& c, long source) noexcept;
  /// Pieces split_last_block() cuts a cubic block into (runs of table intervals).
  int cubic_piece_count() const noexcept { return jerk_limited_ ? 4 : 16; }
  /// split_last_block() for a cubic block: its trimmed window cut at table nodes, bounds per piece.
  void split_cubic_block() noexcept;
  /// split_cubic_block() into the cubic record of the block (cubic_records_used()): m pieces between
  /// cuts (arc lengths), table step `step`; intervals(k, i0, i1) gives the table intervals of piece k;
  /// amin: the smallest acceleration of the axes that move. (Defined in planner_cubic.cpp.)
  template <class Intervals>
  void fill_cubic_record(Node& whole, const PieceBase& base, const double* cuts, int m, int step, double amin,
                         const Intervals& intervals) noexcept;
  /// Whether cubic blocks are cut into the pieces of one cubic-record node (no jerk limits, no
  /// velocity-jump windows) rather than into ring nodes.
  bool cubic_records_used() const noexcept {
    return !jerk_limited_ && options_.rule != CornerRule::vector && options_.rule != CornerRule::per_axis;
  }
  /// Jerk mode: whether the curvature vectors k1, k2 [1/mm] at a tangent joint next to a cubic block
  /// agree up to the rounding of the curves that meet there (no curvature step).
  static bool curvature_continuous(const Vec3& k1, const Vec3& k2) noexcept;

  /// The table of the cubic block `source` (see CubicTable).
  CubicTable& cubic_table(long source) noexcept { return cubic_tables_[static_cast<std::size_t>(source) & 1u]; }

  // --- corner blends (planner_blend.cpp) ---
  /// The blend rule's corner between the previous block's node `prev` (ring index) and the new
  /// block's node nn (not yet appended): blend nodes appended, nn's junction speeds set.
  void append_corner_blend(long prev, Node& nn, const Vec3& u1, const Vec3& u2, double sin_half, long source) noexcept;
  void init_blend_piece(Node& bn, const Segment& whole, int i0, int i1, long source, double vfeed,
                        Geometry geometry) noexcept;
  void append_line_blend(long source, long psource, const Vec3& p0, const Vec3& vtx, const Vec3& p3, const Vec3& u1,
                         const Vec3& u2, double d, double vfeed, double& v_prev) noexcept;

  // --- look-ahead: backward pass and freeze (planner_lookahead.cpp) ---
  void back_pass(long dirty_from) noexcept;
  /// Whether the buffer is deep enough to freeze (inline in planner_lookahead.cpp, its only user).
  bool buffer_ready() const noexcept;
  bool freeze_next() noexcept;
  void freeze_line_blend(Node& n, LineBlendRecord& r, double vs, double wt) noexcept;
  /// The pieces of a cubic-record node one after the other, as freeze_next() for single nodes.
  void freeze_cubic_record(Node& n, CubicRecord& r, double vs, double wt) noexcept;
  /// Node n, whose pieces are in a record, frozen from vs to ve with its last piece ending at t_end.
  void freeze_record_node(Node& n, double vs, double ve, double t_end) noexcept;
  /// The profile of a SpeedBound::axis_box piece without jerk limits over length len from vs to ve
  /// (windows ws, we) with cruise cap v_max and the piece's ramp terms (Node::ramp_tangent,
  /// ramp_curvature). (Defined inline in planner_lookahead.cpp, its only user.)
  Profile axis_box_profile(double len, double vs, double ve, double v_max, const Vec3 (&ramp_tangent)[2],
                           const Vec3 (&ramp_curvature)[2], double ws, double we) const noexcept;

  // --- output (planner_output.cpp) ---
  Status ensure_frozen_until(double t) noexcept;
  void copy_blend_geometry(const Segment& whole, Segment& out) const noexcept;
  /// The node's segment with its geometry (blend pieces: copied in from the blend store on first use).
  const Segment& segment_of(Node& n) noexcept;
  /// Copy of the node's full segment (blend pieces: the blend with the piece's trims).
  void copy_segment(const Node& n, Segment& out) noexcept;

  AxisLimits limits_;
  PlanOptions options_;
  bool jerk_limited_ = false;     // limits_.jerk_limited()
  Vec3 inv_acceleration_ = Vec3::Zero();  // 1/A_i
  Eigen::Array<double, 6, 1> acceleration2_ = Eigen::Array<double, 6, 1>::Zero();  // A_x, A_y, A_z twice
  // the array work of blends between two lines, for the best instruction set the CPU has
  const LineBlendKernels* line_blend_kernels_ = nullptr;
  const LineBlendTables* line_blend_tables_ = nullptr;
  // the array work of cubic records, likewise
  const CubicRecordKernels* cubic_record_kernels_ = nullptr;

  // tables of the last two cubic blocks pushed, by the parity of their source: the block whose end is
  // not known yet (held whole) and the one push() is building
  CubicTable cubic_tables_[2];
  std::vector<Node> nodes_;        // the ring
  std::vector<PassRecord> passes_; // pass record of each node, same slot
  Node scratch_;                   // a new node push() cannot build in its ring slot
  std::vector<Segment> blends_;    // whole blend of each block in the buffer, by block slot
  std::vector<LineBlendRecord> line_blends_;  // pieces of the line-blend node of each block, by block slot
  std::vector<Segment> cubics_;    // whole cubic block, by block slot (in_cubic_store pieces; cubic_record: untrimmed)
  std::vector<CubicRecord> cubic_records_;  // pieces of the cubic-record node of each block, by block slot
  long capacity_ = 0;              // ring size
  std::size_t ring_mask_ = 0, block_mask_ = 0;  // capacity_ − 1, blends_.size() − 1

  long head_ = 0;    // first segment in the buffer
  long frozen_ = 0;  // segments [head_, frozen_) are frozen
  long tail_ = 0;    // one past the last
  bool finished_ = false;
  bool done_ = false;
  long pushed_ = 0;
  long next_sample_ = 0;     // index of the next fine sample
  double t_frozen_end_ = 0;  // end time of the frozen prefix [s]
  double v_frozen_end_ = 0;  // speed at the end of the frozen prefix [mm/s]
  Vec3 last_point_ = Vec3::Zero();
  bool have_last_ = false;
  Vec3 last_dir_ = Vec3::Zero();  // unit direction of the last block pushed (lines)
  bool last_cubic_ = false;       // the last block pushed was a cubic block
  double blend_tolerance_ = 0.0;  // contour tolerance of the corner blend being built [mm] (push)
  const char* error_ = "";
};

// ---------------------------------------------------------------------------------------------------
// Small operations every pass runs per node, inline so each translation unit can inline them.

inline long PlannerState::blocks_in_buffer() const noexcept {
  return tail_ > head_ ? pushed_ - node(head_).block : 0;
}

inline double PlannerState::planned_length(const Node& n) const noexcept {
  const Segment& s = n.segment;
  const double te = n.extent == Extent::whole_block_blend_pending ? 0.45 * s.full_length : s.trim_end;
  double len = s.full_length - s.trim_start - te;
  if (jerk_limited_ && n.extent != Extent::settled && s.kind != SegmentKind::line) {
    // a cubic or arc block not cut into its pieces yet: S-curve ramps do not add up over pieces (each
    // starts and ends without acceleration), so the whole block may promise a slow-down its pieces
    // cannot do; its first piece's length alone never does (the pieces after it only add reach)
    len = std::min(len, s.full_length / (s.kind == SegmentKind::arc ? arc_piece_count(s) : cubic_piece_count()));
  }
  return std::max(0.0, len - n.start.window - n.end.window);
}

inline void PlannerState::update_pass(long k) noexcept {
  const Node& n = node(k);
  if (n.geometry == Geometry::cubic_record) return;  // its pieces' records are final (split_cubic_block)
  PassRecord& x = pass(k);
  x.w_junction = n.v_junction * n.v_junction;
  x.length = planned_length(n);
  x.path_accel = n.path_accel;
  x.path_jerk = n.path_jerk;
  x.line_blend = x.cubic = -1;
  set_reach(x, n);
}

inline void PlannerState::append(const Node& n) noexcept {
  if (&n != &node(tail_)) node(tail_) = n;  // (push builds most lines in place)
  update_pass(tail_);
  pass(tail_).w_backward = 0.0;
  ++tail_;
}

}  // namespace netshape::motion::detail
