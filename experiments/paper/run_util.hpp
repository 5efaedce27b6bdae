// experiments/paper/run_util.hpp — what the measuring steps of `antcd bench paper` share: the
// clock and running independent runs on oneTBB workers.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstddef>

namespace antcd::experiments::paper {

using Clock = std::chrono::steady_clock;

inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Runs f(0) … f(count - 1) on up to `threads` oneTBB workers; rethrows the first exception.
template <typename F>
void parallel_for(std::size_t count, int threads, F&& f) {
  if (threads <= 1 || count <= 1) {
    for (std::size_t k = 0; k < count; ++k) f(k);
    return;
  }
  // One task per index (runs are long and uneven); oneTBB rethrows the first exception.
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t k = range.begin(); k != range.end(); ++k) f(k);
                      });
  });
}

}  // namespace antcd::experiments::paper
