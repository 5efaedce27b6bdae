// python/src/bind_batch.cpp — antcd.collide_batch and antcd.distance_batch: one pair of models
// under N pose pairs, answered by C++ threads with the GIL released.
//
// Each pose pair is an independent, exact query (the same as antcd.collide / antcd.distance with
// default options): the answers do not depend on the thread count or on the order the threads take
// the pairs in. Poses are validated (rigid, finite) before any thread starts.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "convert.hpp"
#include "model_guard.hpp"

namespace antcd::python {

namespace {

/// Pose pairs handed to one thread at a time: small enough to balance uneven queries, large
/// enough that the shared counter is not contended and that two threads rarely write the same
/// cache line of the output (64 one-byte verdicts fill one).
constexpr std::size_t kChunk = 64;

struct PoseBatch {
  std::vector<Transform> a;  // size n, or 1 (the same pose for every pair)
  std::vector<Transform> b;
  std::size_t n = 0;

  [[nodiscard]] const Transform& pose_a(std::size_t i) const { return a.size() == 1 ? a[0] : a[i]; }
  [[nodiscard]] const Transform& pose_b(std::size_t i) const { return b.size() == 1 ? b[0] : b[i]; }
};

PoseBatch to_batch(py::handle poses_a, py::handle poses_b) {
  PoseBatch batch;
  std::size_t count = kAnyCount;
  batch.a = to_transforms(poses_a, "poses_a", count);
  batch.b = to_transforms(poses_b, "poses_b", count);
  if (count == kAnyCount) {
    throw py::value_error(
        "poses_a and poses_b are both single poses: give at least one (n, 4, 4) batch");
  }
  batch.n = count;
  return batch;
}

unsigned thread_count(const py::handle threads, std::size_t n) {
  const auto requested = to_count(threads, "threads", 0, 1024);
  const unsigned hardware = std::max(1U, std::thread::hardware_concurrency());
  const std::size_t wanted = requested == 0 ? hardware : static_cast<std::size_t>(requested);
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min(wanted, chunks)));
}

/// Runs query(i) for i in [0, n) on `threads` threads (the caller's included), chunk by chunk.
/// The first exception any query throws is rethrown here after every thread has stopped.
template <typename Query>
void run_parallel(std::size_t n, unsigned threads, const Query& query) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    try {
      for (;;) {
        const std::size_t begin = next.fetch_add(kChunk, std::memory_order_relaxed);
        if (begin >= n) return;
        const std::size_t end = std::min(n, begin + kChunk);
        for (std::size_t i = begin; i < end; ++i) query(i);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(n, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace

void bind_batch(py::module_& m) {
  m.def(
      "collide_batch",
      [](const Model& a, const Model& b, const py::handle poses_a, const py::handle poses_b,
         double delta, const py::handle threads) {
        const PoseBatch batch = to_batch(poses_a, poses_b);
        CollisionRequest request;
        request.delta = to_non_negative(delta, "delta");
        const unsigned workers = thread_count(threads, batch.n);
        py::array_t<bool> out(static_cast<py::ssize_t>(batch.n));
        bool* verdicts = out.mutable_data();
        {
          py::gil_scoped_release release;
          const ModelReadLock lock(a, b);
          run_parallel(batch.n, workers, [&](std::size_t i) {
            thread_local CollisionResult result;  // storage reused across queries of a thread
            verdicts[i] = collide(a, batch.pose_a(i), b, batch.pose_b(i), request, result);
          });
        }
        return out;
      },
      py::arg("a"), py::arg("b"), py::arg("poses_a"), py::arg("poses_b"), py::kw_only(),
      py::arg("delta") = 0.0, py::arg("threads") = 0,
      "Boolean collide() of models a and b under n pose pairs: bool[n], entry i is "
      "collide(a, poses_a[i], b, poses_b[i], delta=delta).colliding.\n\n"
      "poses_a, poses_b: float (n, 4, 4) homogeneous matrices (rigid motions); either may be one "
      "(4, 4) matrix or None (identity) used for every pair.\n"
      "threads: C++ threads answering the queries (0: one per hardware thread). The GIL is "
      "released while they run; the answers do not depend on the thread count.");

  m.def(
      "distance_batch",
      [](const Model& a, const Model& b, const py::handle poses_a, const py::handle poses_b,
         const py::handle threads) {
        const PoseBatch batch = to_batch(poses_a, poses_b);
        const unsigned workers = thread_count(threads, batch.n);
        py::array_t<double> out(static_cast<py::ssize_t>(batch.n));
        double* distances = out.mutable_data();
        {
          py::gil_scoped_release release;
          const ModelReadLock lock(a, b);
          run_parallel(batch.n, workers, [&](std::size_t i) {
            distances[i] = distance(a, batch.pose_a(i), b, batch.pose_b(i)).distance;
          });
        }
        return out;
      },
      py::arg("a"), py::arg("b"), py::arg("poses_a"), py::arg("poses_b"), py::kw_only(),
      py::arg("threads") = 0,
      "Exact minimum surface distance of models a and b under n pose pairs: float64[n], entry i "
      "is distance(a, poses_a[i], b, poses_b[i]).distance (0 where the surfaces meet).\n\n"
      "poses_a, poses_b and threads as in collide_batch.");
}

}  // namespace antcd::python
