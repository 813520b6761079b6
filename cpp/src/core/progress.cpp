// The process-wide progress hook and the throttled report of netshape::core::Progress.
#include "netshape/core/progress.hpp"

#include <atomic>

namespace netshape::core {

namespace {
std::atomic<ProgressHook> g_hook{nullptr};
constexpr std::chrono::milliseconds kInterval{50};
}  // namespace

ProgressHook set_progress_hook(ProgressHook hook) noexcept { return g_hook.exchange(hook); }

Progress::Progress(const char* what, std::size_t total) noexcept
    : what_(what), total_(total), hook_(g_hook.load()), next_(std::chrono::steady_clock::now() + kInterval) {}

void Progress::report(std::size_t done) {
  if (hook_ == nullptr) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_) return;
  next_ = now + kInterval;
  if (!hook_(what_, done, total_)) throw Interrupted{};
}

}  // namespace netshape::core
