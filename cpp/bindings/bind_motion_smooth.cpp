// Python bindings of motion's smoothing stage: smooth(), the streaming Smoother, smoothing + planning
// loops for the bench, and the deviation of samples from a program (netshape.motion.smooth_path).
#include <pybind11/pybind11.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "default_types.hpp"
#include "motion_arrays.hpp"
#include "netshape/core/error.hpp"
#include "netshape/motion.hpp"
#include "netshape/toolpath/block_arrays.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::motion;

using motion_arrays::block_arrays;
using motion_arrays::drain;
using motion_arrays::program_blocks_from_arrays;

namespace {

SmoothOptions smooth_options(double tolerance, double fit_share, double max_segment, double max_turn, int min_blocks,
                             int window, double smoothing_length, double lead_length, double max_fit_turn,
                             double space_flatness) {
  SmoothOptions o;
  o.space_flatness = space_flatness;
  o.max_fit_turn = max_fit_turn;
  o.tolerance = tolerance;
  o.fit_share = fit_share;
  o.max_segment = max_segment;
  o.max_turn = max_turn;
  o.min_blocks = min_blocks;
  o.window = window;
  o.smoothing_length = smoothing_length;
  o.lead_length = lead_length;
  return o;
}

// The program through a Smoother, pushed in bursts of `chunk` blocks (each burst stops early when the
// buffer is full) with the output drained after each burst.
SmoothResult smooth_streamed(const std::vector<toolpath::Block>& blocks, const SmoothOptions& o, int chunk,
                             int min_chunk, SmoothCounts& counts, long& first_out_after) {
  Smoother sm(o, min_chunk);
  first_out_after = -1;
  SmoothResult r;
  SmoothedBlock sb;
  std::size_t i = 0;
  auto drain = [&] {
    Status st;
    while ((st = sm.next(sb)) == Status::ok) {
      if (r.blocks.empty()) first_out_after = sm.blocks_pushed();
      r.blocks.push_back(sb.block);
      r.controls.push_back(sb.controls);
      r.source_first.push_back(sb.source_first);
      r.source_last.push_back(sb.source_last);
    }
    if (st == Status::invalid_input) throw std::invalid_argument(sm.last_error());
  };
  while (i < blocks.size()) {
    for (int q = 0; q < chunk && i < blocks.size(); ++q, ++i) {
      const Status st = sm.push(blocks[i]);
      if (st == Status::buffer_full) break;
      if (st == Status::invalid_input) throw std::invalid_argument(sm.last_error());
    }
    drain();
  }
  sm.finish();
  drain();
  counts = sm.counts();
  r.runs_smoothed = counts.runs_smoothed;
  r.runs_kept = counts.runs_kept;
  r.corners_kept = counts.corners_kept;
  r.corners_rounded = counts.corners_rounded;
  r.max_fit_deviation = counts.max_fit_deviation;
  return r;
}

py::dict smooth_stats(const SmoothResult& r) {
  py::dict stats;
  stats["runs_smoothed"] = r.runs_smoothed;
  stats["runs_kept"] = r.runs_kept;
  stats["corners_kept"] = r.corners_kept;
  stats["corners_rounded"] = r.corners_rounded;
  stats["max_fit_deviation_mm"] = r.max_fit_deviation;
  return stats;
}

// smooth() of program blocks as (new block arrays, first, last, stats).
py::tuple smooth_tuple(const std::vector<toolpath::Block>& blocks, const SmoothOptions& o) {
  SmoothResult r;
  {
    py::gil_scoped_release release;
    r = smooth(blocks, o);
  }
  py::dict arrays = block_arrays(r.blocks, r.controls);
  py::dict stats = smooth_stats(r);
  return py::make_tuple(arrays, r.source_first, r.source_last, stats);
}
// Program -> Smoother in a second thread, its blocks handed through a bounded single-producer /
// single-consumer ring to the Planner in this one (the two-stage pipeline of a controller, where
// smoothing and planning run in tasks of their own). Planned segments without sampling; returns
// (segments, end time of the last one [s]). An error of the Smoother is rethrown here.
std::pair<long, double> smooth_plan_threaded(const std::vector<toolpath::Block>& blocks, Smoother& sm, Planner& p) {
  constexpr std::size_t cap = 1024;  // ring slots (a power of two)
  // a side that finds the ring full / empty sleeps (not spins), so the CPU time counts work only
  constexpr std::chrono::microseconds pause{20};
  std::vector<SmoothedBlock> ring(cap);
  std::atomic<std::size_t> head{0}, tail{0};  // blocks written / read so far
  std::atomic<bool> done{false};              // the Smoother has handed out its last block
  std::string error;                          // set before done when the Smoother failed
  std::thread producer([&] {
    SmoothedBlock sb;
    std::size_t i = 0;
    for (;;) {
      const Status ss = sm.next(sb);
      if (ss == Status::ok) {
        const std::size_t h = head.load(std::memory_order_relaxed);
        while (h - tail.load(std::memory_order_acquire) == cap) std::this_thread::sleep_for(pause);
        ring[h & (cap - 1)] = sb;
        head.store(h + 1, std::memory_order_release);
      } else if (ss == Status::need_blocks) {
        if (i < blocks.size()) sm.push(blocks[i++]);
        else sm.finish();
      } else {
        if (ss == Status::invalid_input) error = sm.last_error();
        break;
      }
    }
    done.store(true, std::memory_order_release);
  });
  PlannedSegment seg;
  long segments = 0;
  double t_end = 0;
  while (drain(p, seg, segments, t_end) == Status::need_blocks) {
    const std::size_t t = tail.load(std::memory_order_relaxed);
    for (;;) {
      if (head.load(std::memory_order_acquire) != t) {
        const SmoothedBlock& sb = ring[t & (cap - 1)];
        p.push(sb.block, sb.controls);
        tail.store(t + 1, std::memory_order_release);
        break;
      }
      if (done.load(std::memory_order_acquire) && head.load(std::memory_order_acquire) == t) {
        p.finish();
        break;
      }
      std::this_thread::sleep_for(pause);
    }
  }
  producer.join();
  if (!error.empty()) throw std::invalid_argument(error);
  return {segments, t_end};
}

}  // namespace

void bind_motion_smooth(py::module_& m) {
  m.def(
      "_smooth_arrays",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, double tolerance, double fit_share, double max_segment, double max_turn,
         int min_blocks, int window, double smoothing_length, double lead_length, double max_fit_turn,
         double space_flatness) {
        // Tolerance-band smoothing (smoothing.hpp): the new blocks as arrays, per new block the first and
        // last program block it replaces, and the counts.
        const SmoothOptions o = smooth_options(tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                                               smoothing_length, lead_length, max_fit_turn, space_flatness);
        return smooth_tuple(program_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns, feed), o);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("tolerance"), py::arg("fit_share") = 0.98, py::arg("max_segment") = 4.0,
      py::arg("max_turn") = 0.5236, py::arg("min_blocks") = 3, py::arg("window") = 4096,
      py::arg("smoothing_length") = SmoothOptions{}.smoothing_length, py::arg("lead_length") = 2.0,
      py::arg("max_fit_turn") = 1.6057, py::arg("space_flatness") = SmoothOptions{}.space_flatness);
  // _smooth_arrays on a Toolpath or BlockArrays as it is (no columns through Python).
  const auto smooth_program = [](const std::vector<toolpath::Block>& blocks, double tolerance, double fit_share,
                                 double max_segment, double max_turn, int min_blocks, int window,
                                 double smoothing_length, double lead_length, double max_fit_turn,
                                 double space_flatness) {
    const SmoothOptions o = smooth_options(tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                                           smoothing_length, lead_length, max_fit_turn, space_flatness);
    return smooth_tuple(motion_arrays::program_blocks(blocks), o);
  };
  m.def(
      "_smooth_program",
      [smooth_program](const toolpath::Toolpath& program, double tolerance, double fit_share, double max_segment,
                       double max_turn, int min_blocks, int window, double smoothing_length, double lead_length,
                       double max_fit_turn, double space_flatness) {
        return smooth_program(program.blocks, tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                              smoothing_length, lead_length, max_fit_turn, space_flatness);
      },
      py::arg("program"), py::arg("tolerance"), py::arg("fit_share"), py::arg("max_segment"), py::arg("max_turn"),
      py::arg("min_blocks"), py::arg("window"), py::arg("smoothing_length"), py::arg("lead_length"),
      py::arg("max_fit_turn"), py::arg("space_flatness"));
  m.def(
      "_smooth_program",
      [smooth_program](const toolpath::BlockArrays& program, double tolerance, double fit_share, double max_segment,
                       double max_turn, int min_blocks, int window, double smoothing_length, double lead_length,
                       double max_fit_turn, double space_flatness) {
        return smooth_program(program.to_blocks(), tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                              smoothing_length, lead_length, max_fit_turn, space_flatness);
      },
      py::arg("program"), py::arg("tolerance"), py::arg("fit_share"), py::arg("max_segment"), py::arg("max_turn"),
      py::arg("min_blocks"), py::arg("window"), py::arg("smoothing_length"), py::arg("lead_length"),
      py::arg("max_fit_turn"), py::arg("space_flatness"));
  m.def(
      "_smooth_stream_arrays",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, double tolerance, double fit_share, double max_segment, double max_turn,
         int min_blocks, int window, double smoothing_length, double lead_length, int chunk, double max_fit_turn,
         int min_chunk, double space_flatness) {
        // _smooth_arrays through the streaming Smoother (smoother.hpp), blocks pushed `chunk` at a time;
        // stats add the number of chunks smoothed and of forced cuts, and the blocks pushed before the
        // first block came out.
        NETSHAPE_CHECK(chunk >= 1, "chunk", chunk, "must be >= 1 [blocks]");
        const SmoothOptions o = smooth_options(tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                                               smoothing_length, lead_length, max_fit_turn, space_flatness);
        const auto blocks = program_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns, feed);
        SmoothResult r;
        SmoothCounts counts;
        long first_out_after = -1;
        {
          py::gil_scoped_release release;
          r = smooth_streamed(blocks, o, chunk, min_chunk, counts, first_out_after);
        }
        py::dict arrays = block_arrays(r.blocks, r.controls);
        py::dict stats = smooth_stats(r);
        stats["chunks"] = counts.chunks;
        stats["forced_cuts"] = counts.forced_cuts;
        stats["first_output_after_blocks"] = first_out_after;
        return py::make_tuple(arrays, r.source_first, r.source_last, stats);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("tolerance"), py::arg("fit_share") = 0.98, py::arg("max_segment") = 4.0,
      py::arg("max_turn") = 0.5236, py::arg("min_blocks") = 3, py::arg("window") = 4096,
      py::arg("smoothing_length") = SmoothOptions{}.smoothing_length, py::arg("lead_length") = 2.0,
      py::arg("chunk") = 1, py::arg("max_fit_turn") = 1.6057, py::arg("min_chunk") = Smoother::default_min_chunk,
      py::arg("space_flatness") = SmoothOptions{}.space_flatness);
  m.def(
      "_smooth_plan",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, double tolerance, int window, const AxisLimits& limits, const PlanOptions& options,
         bool streamed, int repeat, int threads) {
        // Smoothing and planning without sampling (planned segments): streamed, program -> Smoother ->
        // Planner one block at a time (threads 2: the Smoother in a thread of its own,
        // smooth_plan_threaded); else smooth() on the whole program, then the Planner. Returns
        // (segments, cycle time [s]) of the last repeat.
        NETSHAPE_CHECK(threads == 1 || threads == 2, "threads", threads, "must be 1 or 2");
        SmoothOptions o;
        o.tolerance = tolerance;
        o.window = window;
        const auto blocks = program_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns, feed);
        Planner p(limits, options);
        Smoother sm(o);
        PlannedSegment seg;
        SmoothedBlock sb;
        long segments = 0;
        double t_end = 0;
        py::gil_scoped_release release;
        for (int r = 0; r < repeat; ++r) {
          p.reset();
          sm.reset();
          segments = 0;
          if (streamed && threads == 2) {
            std::tie(segments, t_end) = smooth_plan_threaded(blocks, sm, p);
            continue;
          }
          SmoothResult smoothed;
          if (!streamed) smoothed = smooth(blocks, o);
          std::size_t i = 0, j = 0;
          for (;;) {
            const Status st = drain(p, seg, segments, t_end);
            if (st != Status::need_blocks) break;
            if (!streamed) {
              if (j < smoothed.blocks.size()) {
                p.push(smoothed.blocks[j], smoothed.controls[j]);
                ++j;
              } else {
                p.finish();
              }
              continue;
            }
            const Status ss = sm.next(sb);
            if (ss == Status::ok) p.push(sb.block, sb.controls);
            else if (ss == Status::finished) p.finish();
            else if (ss == Status::invalid_input) throw std::invalid_argument(sm.last_error());
            else if (i < blocks.size()) sm.push(blocks[i++]);
            else sm.finish();
          }
        }
        py::gil_scoped_acquire acquire;
        return py::make_tuple(segments, t_end);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("tolerance"), py::arg("window"), py::arg("limits"),
      py::arg("options"), py::arg("streamed"), py::arg("repeat") = 1, py::arg("threads") = 1);
  m.def(
      "_deviation_to_program",
      [](const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
         py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
         const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
         py_types::RefVector feed, py_types::RefPoints3 points, const std::vector<long>& first,
         const std::vector<long>& last) {
        const auto blocks = program_blocks_from_arrays(kind, start, end, center, clockwise, plane, turns, feed);
        const Points3 p = points;
        py::gil_scoped_release release;
        return deviation_to_program(blocks, p, first, last);
      },
      py::arg("kind"), py::arg("start"), py::arg("end"), py::arg("center"), py::arg("clockwise"), py::arg("plane"),
      py::arg("turns"), py::arg("feed"), py::arg("points"), py::arg("first"), py::arg("last"));
}
