// Progress reports and cancellation (core/progress.hpp): without a hook a tick calls nothing; with one
// the hook is called at most every 50 ms with the stage, done and total; false stops the loop with
// core::Interrupted, which a catch of std::exception does not swallow.
#include <doctest/doctest.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "netshape/core/progress.hpp"

using namespace netshape::core;

namespace {
std::vector<std::size_t> g_done;
std::string g_what;
std::size_t g_total = 0;
std::size_t g_stop_after = 0;

bool record(const char* what, std::size_t done, std::size_t total) {
  g_what = what;
  g_total = total;
  g_done.push_back(done);
  return g_done.size() < g_stop_after;
}

struct HookGuard {
  explicit HookGuard(ProgressHook h) : old(set_progress_hook(h)) {}
  ~HookGuard() { set_progress_hook(old); }
  ProgressHook old;
};
}  // namespace

TEST_CASE("progress: no hook, no call; a hook sees the stage and stops the loop when it says so") {
  HookGuard none(nullptr);
  {
    Progress p("idle", 10);
    for (std::size_t i = 0; i < 100000; ++i) p.tick(i);  // nothing to call, nothing thrown
  }
  g_done.clear();
  g_stop_after = 3;
  HookGuard guard(&record);
  Progress p("loop", 1000000);
  std::size_t reached = 0;
  auto run = [&] {
    for (std::size_t i = 0; i < 1000000; ++i) {
      p.tick(i);
      reached = i;
      if (i % 1000 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  };
  bool swallowed = false;
  try {
    try {
      run();
    } catch (const std::exception&) {
      swallowed = true;
    }
  } catch (const Interrupted&) {
  }
  CHECK_FALSE(swallowed);
  REQUIRE(g_done.size() == 3);
  CHECK(g_what == "loop");
  CHECK(g_total == 1000000);
  CHECK(g_done[0] < g_done[1]);
  CHECK(g_done[1] < g_done[2]);
  CHECK(reached < 1000000 - 1);  // stopped part way
}

TEST_CASE("progress: reports are at least 50 ms apart") {
  g_done.clear();
  g_stop_after = 1000;
  HookGuard guard(&record);
  Progress p("timed", 0);
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::milliseconds(300)) p.report(0);
  // 300 ms of reports: at most 6 calls (the first after 50 ms)
  CHECK(g_done.size() >= 1);
  CHECK(g_done.size() <= 6);
}
