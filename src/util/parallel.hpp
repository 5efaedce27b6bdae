// Private: the library's only door to threads. With ANTCD_WITH_TBB (the CMake option ANTCD_USE_TBB,
// on by default when oneTBB is found) each helper maps to the oneTBB algorithm it is named after;
// without it each runs its work serially on the calling thread, in index order.
//
// Same answers either way: every caller writes disjoint outputs per index or range and combines
// them in a fixed order (or with an associative, commutative join such as min), so its result does
// not depend on how the range is split or how many threads run it. The serial fallback is the case
// of one range on one thread. Checked by the consumer_core_serial test (tests/CMakeLists.txt): a
// build without oneTBB must reproduce the digest of answers a oneTBB build gives.
#pragma once

#include <cstddef>
#include <utility>

#if defined(ANTCD_WITH_TBB)
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <memory>
#include <vector>
#else
#include <array>
#endif

namespace antcd::parallel {

#if defined(ANTCD_WITH_TBB)
/// The calling thread's arena has one slot (an arena of one thread, as `--threads 1` and the TSan
/// tests make): the helpers below then run the serial path without making oneTBB tasks at all.
/// Same answers (every caller is split-independent, see the top of this file), less overhead, and
/// oneTBB's uninstrumented task pool stays out of a ThreadSanitizer run.
inline bool single_slot() { return tbb::this_task_arena::max_concurrency() == 1; }
#endif

/// body(first, last) over subranges that together cover [begin, end) once, none shorter than
/// `grain` unless the whole range is (tbb::blocked_range's grain size).
template <class Body>
void for_ranges(std::size_t begin, std::size_t end, std::size_t grain, const Body& body) {
#if defined(ANTCD_WITH_TBB)
  if (single_slot()) {
    if (begin < end) body(begin, end);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
#else
  (void)grain;
  if (begin < end) body(begin, end);
#endif
}

/// body(k) for every k in [begin, end).
template <class Body>
void for_each_index(std::size_t begin, std::size_t end, const Body& body) {
#if defined(ANTCD_WITH_TBB)
  if (single_slot()) {
    for (std::size_t k = begin; k < end; ++k) body(k);
    return;
  }
  tbb::parallel_for(begin, end, [&](std::size_t k) { body(k); });
#else
  for (std::size_t k = begin; k < end; ++k) body(k);
#endif
}

/// f() and g(), possibly at once.
template <class F, class G>
void invoke(const F& f, const G& g) {
#if defined(ANTCD_WITH_TBB)
  if (single_slot()) {
    f();
    g();
    return;
  }
  tbb::parallel_invoke(f, g);
#else
  f();
  g();
#endif
}

/// join over body(first, last, identity) of subranges covering [begin, end) (tbb::parallel_reduce
/// with a grain of 1); `join` must be associative and commutative for the answer to be fixed.
template <class T, class Body, class Join>
T reduce(std::size_t begin, std::size_t end, T identity, const Body& body, const Join& join) {
#if defined(ANTCD_WITH_TBB)
  if (single_slot()) return begin < end ? body(begin, end, identity) : identity;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(begin, end), identity,
      [&](const tbb::blocked_range<std::size_t>& r, T acc) {
        return body(r.begin(), r.end(), acc);
      },
      join);
#else
  (void)join;
  return begin < end ? body(begin, end, identity) : identity;
#endif
}

/// f() with at most `threads` workers (tbb::task_arena's max_concurrency); returns f()'s value.
template <class F>
decltype(auto) with_threads(int threads, F&& f) {
#if defined(ANTCD_WITH_TBB)
  tbb::task_arena arena(threads);
  return arena.execute(std::forward<F>(f));
#else
  (void)threads;
  return std::forward<F>(f)();
#endif
}

#if defined(ANTCD_WITH_TBB)
namespace detail {
/// The calling thread's task arena of `threads` slots, made once per thread and thread count:
/// making and initialising an arena (oneTBB reads the thread's stack bounds, through
/// /proc/self/maps) cost about three quarters of the instructions of a two-object scene's frame
/// (callgrind), more than its collide() calls.
inline tbb::task_arena& thread_arena(int threads) {
  thread_local std::vector<std::pair<int, std::unique_ptr<tbb::task_arena>>> arenas;
  for (auto& [n, arena] : arenas) {
    if (n == threads) return *arena;
  }
  arenas.emplace_back(threads, std::make_unique<tbb::task_arena>(threads));
  return *arenas.back().second;
}
}  // namespace detail
#endif

/// f() with at most `threads` workers, in an arena the calling thread keeps for later calls with
/// the same count (with_threads makes a new one each call); returns nothing.
template <class F>
void in_thread_arena(int threads, const F& f) {
#if defined(ANTCD_WITH_TBB)
  detail::thread_arena(threads).execute(f);
#else
  (void)threads;
  f();
#endif
}

/// Workers the calling thread's arena may use (1: the calling thread alone, or no oneTBB).
inline int max_concurrency() {
#if defined(ANTCD_WITH_TBB)
  return tbb::this_task_arena::max_concurrency();
#else
  return 1;
#endif
}

/// Sets up the calling thread's arena of `threads` slots now (oneTBB's one-time set-up: its
/// allocator library, the thread's stack bounds), so that a later in_thread_arena call does not
/// pay it.
inline void prepare_thread_arena(int threads) {
#if defined(ANTCD_WITH_TBB)
  detail::thread_arena(threads).initialize();
#else
  (void)threads;
#endif
}

#if defined(ANTCD_WITH_TBB)
/// One T per worker thread, created on first local(); iterate to combine them.
template <class T>
using PerThread = tbb::enumerable_thread_specific<T>;
#else
/// One T per worker thread: the calling thread's only.
template <class T>
class PerThread {
 public:
  T& local() { return one_[0]; }
  auto begin() const { return one_.begin(); }
  auto end() const { return one_.end(); }

 private:
  std::array<T, 1> one_{};
};
#endif

}  // namespace antcd::parallel
