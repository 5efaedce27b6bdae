// Private: bookkeeping shared by every random search — fitness evaluation, distinct hits, best,
// stop criteria.
#pragma once

#include <antcd/random.hpp>

#include "random/cell_set.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

namespace antcd::detail {

/// Evaluates feature pairs for a search and applies the stop criteria. One per search call.
class Recorder {
 public:
  /// `target_hits` is the absolute hit count of StopCriteria::target_share (0 = off).
  Recorder(const FeatureSpace& space, const SearchRequest& request, Scalar delta,
           std::uint64_t target_hits, SearchResult& out)
      : space_(space),
        out_(out),
        delta_(delta),
        delta2_(delta * delta),
        first_hit_(request.stop.first_hit),
        target_hits_(target_hits),
        max_evaluations_(request.stop.max_evaluations),
        max_seconds_(request.stop.max_seconds),
        start_(std::chrono::steady_clock::now()) {
    out_.delta = delta;
  }

  [[nodiscard]] Scalar delta() const { return delta_; }
  [[nodiscard]] Scalar delta_squared() const { return delta2_; }
  [[nodiscard]] bool stopped() const { return stopped_; }
  [[nodiscard]] bool has_best() const { return out_.evaluations > 0; }
  [[nodiscard]] const FeaturePair& best() const { return out_.best; }

  /// Marks the start of iteration `k` (1-based) of the current run. Returns false (and stops)
  /// when the clock ran out.
  bool begin_iteration(std::uint32_t k) {
    if (stopped_) return false;
    if (max_seconds_ > 0 && elapsed_seconds() >= max_seconds_) {
      stop(StopReason::Time);
      return false;
    }
    out_.iterations = iteration_offset_ + k;
    return true;
  }
  /// Starts run number out.runs + 1 (restarts continue the iteration count).
  void begin_run() {
    iteration_offset_ = out_.iterations;
    ++out_.runs;
  }

  /// Progress marks: `needed[k]` distinct hits for mark k (ascending order not required).
  void set_marks(const std::vector<double>& shares, std::uint64_t truth) {
    out_.progress.clear();
    for (const double share : shares) {
      ProgressMark mark;
      mark.share = share;
      mark.hits = static_cast<std::uint64_t>(std::ceil(share * static_cast<double>(truth)));
      out_.progress.push_back(mark);
    }
  }

  /// Fitness f(i, j) (Eq. 6); records a hit (Eq. 5) and checks every stop criterion.
  Scalar evaluate(std::uint32_t i, std::uint32_t j) {
    const FeatureSide& a = space_.a;
    const FeatureSide& b = space_.b;
    const Scalar dx = a.x[i] - b.x[j];
    const Scalar dy = a.y[i] - b.y[j];
    const Scalar dz = a.z[i] - b.z[j];
    const Scalar d2 = dx * dx + dy * dy + dz * dz;
    const Scalar d = std::sqrt(d2);
    ++out_.evaluations;
    if (d < out_.best_distance) {
      out_.best_distance = d;
      out_.best = pair(i, j, d);
    }
    if (d2 <= delta2_ && seen_.insert(std::uint64_t{i} * b.size() + j)) {
      add_hit(i, j, d);
    }
    if (!stopped_) check_budget();
    return d;
  }

  /// For the exhaustive scan, which evaluates each cell once and keeps its own counters: adds a
  /// hit without the duplicate check.
  void add_unique_hit(std::uint32_t i, std::uint32_t j, Scalar d) { add_hit(i, j, d); }
  /// For the exhaustive scan: adds `count` evaluations and offers a row's best.
  void add_evaluations(std::uint64_t count) { out_.evaluations += count; }
  void offer_best(std::uint32_t i, std::uint32_t j, Scalar d) {
    if (d < out_.best_distance) {
      out_.best_distance = d;
      out_.best = pair(i, j, d);
    }
  }
  void check_budget() {
    if (max_evaluations_ != 0 && out_.evaluations >= max_evaluations_) {
      stop(StopReason::Evaluations);
    } else if (max_seconds_ > 0 && (out_.evaluations & 1023) == 0 &&
               elapsed_seconds() >= max_seconds_) {
      stop(StopReason::Time);
    }
  }
  [[nodiscard]] std::uint64_t evaluations() const { return out_.evaluations; }
  [[nodiscard]] std::uint64_t max_evaluations() const { return max_evaluations_; }
  [[nodiscard]] bool time_limited() const { return max_seconds_ > 0; }
  [[nodiscard]] double elapsed_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  void stop(StopReason reason) {
    if (stopped_) return;
    stopped_ = true;
    out_.stop = reason;
  }

  /// Called once the search loop has ended.
  void finish() {
    if (!stopped_) out_.stop = StopReason::Iterations;
    out_.found = !out_.hits.empty();
  }

 private:
  [[nodiscard]] FeaturePair pair(std::uint32_t i, std::uint32_t j, Scalar d) const {
    return {i, j, space_.a.triangle[i], space_.b.triangle[j], d};
  }

  void add_hit(std::uint32_t i, std::uint32_t j, Scalar d) {
    out_.hits.push_back(pair(i, j, d));
    for (ProgressMark& mark : out_.progress) {
      if (!mark.reached && mark.hits != 0 && out_.hits.size() >= mark.hits) {
        mark.reached = true;
        mark.evaluations = out_.evaluations;
        mark.seconds = elapsed_seconds();
      }
    }
    if (first_hit_) {
      stop(StopReason::FirstHit);
    } else if (target_hits_ != 0 && out_.hits.size() >= target_hits_) {
      stop(StopReason::Target);
    }
  }

  const FeatureSpace& space_;
  SearchResult& out_;
  Scalar delta_;
  Scalar delta2_;
  bool first_hit_;
  std::uint64_t target_hits_;
  std::uint64_t max_evaluations_;
  double max_seconds_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
  std::uint32_t iteration_offset_ = 0;
  CellSet seen_;
};

}  // namespace antcd::detail
