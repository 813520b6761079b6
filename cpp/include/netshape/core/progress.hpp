#pragma once
/// \file progress.hpp
/// Progress reports and cancellation for long computations.
///
/// A long loop of the core (a Z-map sweep over a program, a volumetric compensation, a feed plan, a
/// posture plan) holds a `Progress` and calls `tick(done)` once per unit of work. At most every 50 ms
/// (checked every 256 ticks, so a tick costs an increment) the host's hook is called with the stage
/// name, the units done and the total. When the hook answers false the tick throws `Interrupted`,
/// which unwinds the computation (RAII: nothing is half-written by the core's own writers).
///
/// The Python extension installs a hook that handles Ctrl-C (pending signals) and forwards the
/// report to an optional Python callable; a C++ host may install its own. Without a hook a tick
/// never calls anything. `Interrupted` is deliberately not a `std::exception`, so the places that
/// turn a `std::exception` into a status code let it pass. Never tick inside a `noexcept` function.
#include <chrono>
#include <cstddef>

namespace netshape::core {

/// Thrown by `Progress::tick` when the host's hook asks the computation to stop.
struct Interrupted {};

/// The host's hook: `what` names the stage, `done` of `total` units are finished (`total` 0: unknown).
/// Returns false to stop the computation. Called only from the thread that runs the computation.
using ProgressHook = bool (*)(const char* what, std::size_t done, std::size_t total);

/// Installs the hook (nullptr removes it) for every later `Progress`; returns the previous one.
ProgressHook set_progress_hook(ProgressHook hook) noexcept;

/// The progress of one long loop.
class Progress {
 public:
  Progress(const char* what, std::size_t total) noexcept;
  /// One more unit of work is done; `done` counts units so far. Throws `Interrupted`.
  void tick(std::size_t done) {
    if ((++calls_ & 255u) != 0 || hook_ == nullptr) return;
    report(done);
  }
  /// Calls the hook if 50 ms have passed since the last call (for loops with few, long units).
  /// Throws `Interrupted`.
  void report(std::size_t done);

 private:
  const char* what_;
  std::size_t total_;
  std::size_t calls_ = 0;
  ProgressHook hook_;
  std::chrono::steady_clock::time_point next_;
};

}  // namespace netshape::core
