// Planner's public API: construction (every buffer is allocated here), copy and move, reset and the
// buffer queries; the streaming calls forward to PlannerState (planner_state.hpp).
#include "netshape/motion/planner.hpp"

#include <algorithm>
#include <utility>

#include "planner_state.hpp"

namespace netshape::motion {

Planner::Planner(const AxisLimits& limits, const PlanOptions& options)
    : state_(std::make_unique<detail::PlannerState>(limits, options)) {}

Planner::Planner(const Planner& other)
    : state_(other.state_ ? std::make_unique<detail::PlannerState>(*other.state_) : nullptr) {}

Planner& Planner::operator=(const Planner& other) {
  if (this != &other) state_ = other.state_ ? std::make_unique<detail::PlannerState>(*other.state_) : nullptr;
  return *this;
}

Planner::Planner(Planner&& other) noexcept = default;
Planner& Planner::operator=(Planner&& other) noexcept = default;
Planner::~Planner() = default;

Status Planner::push(const toolpath::Block& block) noexcept { return state_->push(block); }
Status Planner::push(const toolpath::Block& block, const CubicControls& controls) noexcept {
  return state_->push(block, controls.cubic ? &controls : nullptr);
}
void Planner::finish() noexcept { state_->finish(); }
Status Planner::next(Sample& out) noexcept { return state_->next(out); }
Status Planner::next_segment(PlannedSegment& out) noexcept { return state_->next_segment(out); }
void Planner::reset() noexcept { state_->reset(); }

int Planner::free_blocks() const noexcept {
  const detail::PlannerState& s = *state_;
  const long by_nodes = (s.capacity_ - (s.tail_ - s.head_)) / detail::nodes_per_push;
  const long by_blocks = s.options_.lookahead + 1 - s.blocks_in_buffer();
  return static_cast<int>(std::max(0L, std::min(by_nodes, by_blocks)));
}

double Planner::end_time() const noexcept {
  const detail::PlannerState& s = *state_;
  return (s.finished_ && s.frozen_ == s.tail_) ? s.t_frozen_end_ : -1.0;
}

double Planner::frozen_time() const noexcept { return state_->t_frozen_end_; }

long Planner::blocks_pushed() const noexcept { return state_->pushed_; }
const char* Planner::last_error() const noexcept { return state_->error_; }
const AxisLimits& Planner::limits() const noexcept { return state_->limits_; }
const PlanOptions& Planner::options() const noexcept { return state_->options_; }

namespace detail {

PlannerState::PlannerState(const AxisLimits& limits, const PlanOptions& options) : limits_(limits), options_(options) {
  limits_.validate();
  options_.validate();
  jerk_limited_ = limits_.jerk_limited();
  inv_acceleration_ = limits_.acceleration.cwiseInverse();
  acceleration2_ << limits_.acceleration.array(), limits_.acceleration.array();
  line_blend_kernels_ = &line_blend_kernels();
  line_blend_tables_ = &line_blend_tables();
  cubic_record_kernels_ = &cubic_record_kernels();
  // power-of-two sizes (see ring_slot()): the ring holds one push's nodes plus 12 per block of
  // look-ahead, rounded up
  const auto pow2 = [](long n) {
    long p = 1;
    while (p < n) p *= 2;
    return p;
  };
  capacity_ = pow2(nodes_per_push + 12 * (options_.lookahead + 2) + 3);
  ring_mask_ = static_cast<std::size_t>(capacity_ - 1);
  nodes_.resize(static_cast<std::size_t>(capacity_));
  passes_.resize(static_cast<std::size_t>(capacity_));
  // blocks from the head's to the newest: at most lookahead + 2 (push refuses beyond)
  blends_.resize(static_cast<std::size_t>(pow2(options_.lookahead + 4)));
  block_mask_ = blends_.size() - 1;
  line_blends_.resize(blends_.size());
  cubics_.resize(blends_.size());
  cubic_records_.resize(blends_.size());
}

void PlannerState::reset() noexcept {
  head_ = frozen_ = tail_ = 0;
  finished_ = done_ = false;
  pushed_ = 0;
  next_sample_ = 0;
  t_frozen_end_ = v_frozen_end_ = 0;
  have_last_ = false;
  last_cubic_ = false;
  last_point_ = Vec3::Zero();
  error_ = "";
}

Status PlannerState::fail(const char* msg) noexcept {
  error_ = msg;
  return Status::invalid_input;
}

}  // namespace detail
}  // namespace netshape::motion
