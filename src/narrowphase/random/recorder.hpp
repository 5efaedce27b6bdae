// Private: bookkeeping shared by every random search — fitness evaluation, distinct hits, best,
// stop criteria — and the seeding of the searches' random streams.
#pragma once

#include <antcd/random.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace antcd::detail {

/// SplitMix64 finaliser: turns related seeds (0, 1, 2, ...) into unrelated 64-bit states.
constexpr std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// The searches' random stream: std::mt19937_64 (its output sequence is fixed by the standard)
/// with our own mappings to ranges, so a seed gives the same result with any standard library
/// (the std:: distributions are implementation-defined).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(mix_seed(seed)) {}

  /// Uniform integer in [0, n), n >= 1 (rejection sampling, unbiased).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = engine_();
      if (r >= threshold) return r % n;
    }
  }
  /// Uniform double in [0, 1).
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  std::mt19937_64 engine_;
};

/// Set of 64-bit keys (open addressing, linear probing, power-of-two capacity). Memory grows
/// with the number of distinct hits only; growth is amortised (doubling).
class CellSet {
 public:
  CellSet() { table_.assign(1024, kEmpty); }

  /// Inserts `key`; true when it was not present.
  bool insert(std::uint64_t key) {
    if (2 * (size_ + 1) > table_.size()) grow();
    return insert_unchecked(key);
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  bool insert_unchecked(std::uint64_t key) {
    const std::size_t mask = table_.size() - 1;
    std::size_t slot = static_cast<std::size_t>(mix_seed(key)) & mask;
    while (table_[slot] != kEmpty) {
      if (table_[slot] == key) return false;
      slot = (slot + 1) & mask;
    }
    table_[slot] = key;
    ++size_;
    return true;
  }

  void grow() {
    std::vector<std::uint64_t> old(table_.size() * 2, kEmpty);
    old.swap(table_);
    size_ = 0;
    for (const std::uint64_t key : old) {
      if (key != kEmpty) insert_unchecked(key);
    }
  }

  std::vector<std::uint64_t> table_;
  std::size_t size_ = 0;
};

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

/// The engines, one per file. Each runs one run of request.iterations iterations with its own
/// random stream seeded from `seed`, or less if `rec` stops.
void run_colony(const FeatureSpace& space, const SearchRequest& request, bool improved,
                std::uint64_t seed, Recorder& rec);
void run_pso(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
             Recorder& rec);
void run_ga(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
            Recorder& rec);
void run_exhaustive(const FeatureSpace& space, Recorder& rec);

}  // namespace antcd::detail
