// The planner's output side: fine samples (next) and frozen segments with their profiles
// (next_segment), freezing as far as the rough loop needs, and the copies of segment geometry they
// hand out.
#include <cmath>

#include "motion/planner/state.hpp"

namespace netshape::motion::detail {

namespace {
// The piece of a record (LineBlendRecord, CubicRecord) that runs at time t, found from the record's
// cursor forward (samples come in time order) and kept there; its distance s from the piece's start,
// speed v and path acceleration acc at t. Returns the piece.
template <class Record>
int eval_record_at(Record& r, double t, double& s, double& v, double& acc) noexcept {
  int k = r.cursor;
  while (k + 1 < r.np && r.t0[k] + r.dur[k] <= t) ++k;
  r.cursor = k;
  Profile pk;
  r.profile(k, pk);
  pk.eval(t - r.t0[k], s, v, acc);
  return k;
}

// Piece r.cursor of a record handed out: its profile and start time into out, the cursor to the next
// piece. True when that was the last piece (the cursor is back at 0 and the record's node is done).
template <class Record>
bool hand_out_piece(Record& r, PlannedSegment& out) noexcept {
  const int k = r.cursor;
  r.profile(k, out.profile);
  out.t0 = r.t0[k];
  if (++r.cursor < r.np) return false;
  r.cursor = 0;
  return true;
}
}  // namespace

void PlannerState::copy_blend_geometry(const Segment& g, Segment& out) const noexcept {
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

void PlannerState::copy_segment(const Node& n, Segment& out) noexcept {
  if (n.segment.kind == SegmentKind::line) {
    // the fields of a line (push writes only these into the ring); its control points and table are 0
    const Segment& s = n.segment;
    out.kind = SegmentKind::line;
    out.block = s.block;
    out.ctrl.fill(Vec3::Zero());  // (Vec3 value-initialisation leaves its coefficients undefined)
    out.table = {};
    out.full_length = s.full_length;
    out.trim_start = s.trim_start;
    out.trim_end = s.trim_end;
    out.curvature = s.curvature;
    out.curvature_rate = s.curvature_rate;
    out.source = s.source;
    return;
  }
  if (n.geometry == Geometry::in_node) {
    out = n.segment;
    return;
  }
  const auto& store = n.geometry == Geometry::in_cubic_store ? cubics_ : blends_;
  copy_blend_geometry(store[block_slot(n.block)], out);
  out.trim_start = n.segment.trim_start;
  out.trim_end = n.segment.trim_end;
  out.curvature = n.segment.curvature;
  out.curvature_rate = n.segment.curvature_rate;
}

const Segment& PlannerState::segment_of(Node& n) noexcept {
  if (n.geometry == Geometry::in_blend_store || n.geometry == Geometry::in_cubic_store) {
    Segment full;
    copy_segment(n, full);
    n.segment = full;
    n.geometry = Geometry::in_node;
  }
  return n.segment;
}

Status PlannerState::ensure_frozen_until(double t) noexcept {
  while (t_frozen_end_ <= t && frozen_ < tail_) {
    if (!freeze_next()) return Status::need_blocks;
  }
  if (t_frozen_end_ <= t && !finished_) return Status::need_blocks;
  return Status::ok;
}

Status PlannerState::next(Sample& out) noexcept {
  if (done_) return Status::finished;
  const double ts2 = options_.ts2;
  const double t = static_cast<double>(next_sample_) * ts2;
  if (next_sample_ % options_.fine_steps() == 0) {
    // rough loop: freeze the profile for the coming rough period [t, t + ts1] if the buffer allows
    const Status st = ensure_frozen_until(t + options_.ts1);
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
    ++next_sample_;
    return Status::ok;
  }
  while (head_ < frozen_ - 1 && node(head_).t0 + node(head_).profile.duration <= t) ++head_;
  Node& n = node(head_);
  double s, v, acc;
  const Segment* sg;
  if (n.geometry == Geometry::line_blend_record) {
    // the piece of the blend that runs at t, on the whole blend (trims 0) at the piece's offset
    LineBlendRecord& r = line_blends_[block_slot(n.block)];
    const int k = eval_record_at(r, t, s, v, acc);
    sg = &blend_geometry(n.block);
    s += r.trim_s[k];
  } else if (n.geometry == Geometry::cubic_record) {
    // the same for the piece of a cubic block, on the untrimmed cubic in the cubic store
    CubicRecord& r = cubic_records_[block_slot(n.block)];
    const int k = eval_record_at(r, t, s, v, acc);
    sg = &cubics_[block_slot(n.block)];
    s += r.trim_start[k];
  } else {
    sg = &segment_of(n);
    n.profile.eval(t - n.t0, s, v, acc);
  }
  out.position = sg->point_at(s);
  out.velocity = v * sg->tangent_at(s);
  out.feed = v;
  out.path_acceleration = acc;
  out.block = sg->source;
  ++next_sample_;
  return Status::ok;
}

Status PlannerState::next_segment(PlannedSegment& out) noexcept {
  if (head_ == frozen_) {
    if (frozen_ == tail_) return finished_ ? Status::finished : Status::need_blocks;
    if (!freeze_next()) return Status::need_blocks;
  }
  const std::size_t slot = ring_slot(head_);
  const Node& n = nodes_[slot];
  if (n.geometry == Geometry::line_blend_record) {
    // the record and the blend store share the block slot
    LineBlendRecord& r = line_blends_[static_cast<std::size_t>(passes_[slot].line_blend)];
    const Segment& g = blends_[static_cast<std::size_t>(passes_[slot].line_blend)];
    const int k = r.cursor;
    copy_blend_geometry(g, out.segment);
    out.segment.trim_start = r.trim_s[k];
    out.segment.trim_end = r.trim_e[k];
    out.segment.curvature = g.curvature;
    out.segment.curvature_rate = g.curvature_rate;
    if (hand_out_piece(r, out)) ++head_;
    return Status::ok;
  }
  if (n.geometry == Geometry::cubic_record) {
    // the record and the cubic store share the block slot
    const std::size_t bs = static_cast<std::size_t>(passes_[slot].cubic);
    CubicRecord& r = cubic_records_[bs];
    const int k = r.cursor;
    copy_blend_geometry(cubics_[bs], out.segment);
    out.segment.trim_start = r.trim_start[k];
    out.segment.trim_end = r.trim_end[k];
    out.segment.curvature = r.curvature[k];
    out.segment.curvature_rate = r.curvature_rate[k];
    if (hand_out_piece(r, out)) ++head_;
    return Status::ok;
  }
  copy_segment(n, out.segment);
  out.profile = n.profile;
  out.t0 = n.t0;
  ++head_;
  return Status::ok;
}

}  // namespace netshape::motion::detail
