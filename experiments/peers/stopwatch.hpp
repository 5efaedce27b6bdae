// experiments/peers/stopwatch.hpp — wall time, the calling thread's CPU time and the whole
// process's CPU time of one measured piece of work.
#pragma once

#include <chrono>
#include <ctime>

namespace antcd::experiments::peers_bench {

struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  timespec cpu{};
  timespec process{};
  Stopwatch() {
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &process);
  }
  /// CPU time of every thread of the process (the oneTBB workers included).
  [[nodiscard]] double process_ms() const {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec - process.tv_sec) * 1e3 +
           static_cast<double>(now.tv_nsec - process.tv_nsec) * 1e-6;
  }
  [[nodiscard]] double wall_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall)
        .count();
  }
  [[nodiscard]] double cpu_ms() const {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec - cpu.tv_sec) * 1e3 +
           static_cast<double>(now.tv_nsec - cpu.tv_nsec) * 1e-6;
  }
};

}  // namespace antcd::experiments::peers_bench
