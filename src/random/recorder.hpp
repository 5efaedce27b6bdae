// Private: bookkeeping shared by every random search — fitness evaluation, the verdict (witness
// test or centroid threshold), distinct hits, best, stop criteria.
#pragma once

#include <antcd/random.hpp>

#include "random/cell_set.hpp"

#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace antcd::detail {

/// The verdict of one cell, shared by the recorder and count_colliding: the exact triangle test
/// at delta (Witness) on the world vertices. Call only when the cell is within reach.
bool witness_test(const FeatureSpace& space, std::uint32_t i, std::uint32_t j);

/// The resolved thresholds of a search.
struct Thresholds {
  Verdict verdict = Verdict::Witness;
  float delta = 0;      ///< collide()'s delta, as float, rounded up (reach filter)
  float centroid2 = 0;  ///< PaperCentroid: squared centroid threshold
  float centroid = 0;   ///< PaperCentroid: centroid threshold
};
/// Unset centroid_delta: the space's. A set one must be finite and >= 0, else ArgumentError naming
/// `caller`.
Thresholds thresholds(const FeatureSpace& space, Verdict verdict,
                      std::optional<Scalar> centroid_delta, const char* caller);

/// Throws ArgumentError naming `caller` and the field for an invalid SearchRequest (search.cpp).
void validate_search(const SearchRequest& request, const char* caller = "antcd::search");

/// Evaluates feature pairs for a search and applies the stop criteria. One per search call.
class Recorder {
 public:
  struct Lanes;

 private:
  /// The lane arithmetic of evaluate_lanes (aco.cpp): from the 16 lanes' centroids (and radii for
  /// the witness verdict), gathered by the caller, their distances and reaches, in fixed-length,
  /// branch-free loops that vectorise. Returns, over the lanes of `mask`, whether any is
  /// within reach and the bits of the smallest squared distance (non-negative floats order like
  /// their bits).
  struct LaneSummary {
    std::uint32_t any_within = 0;
    std::uint32_t min_d2_bits = 0;
  };
  static LaneSummary compute_lanes(Lanes& lanes, std::uint32_t mask, bool witness, float delta,
                                   float centroid);

 public:
  /// `target_hits` is the absolute hit count of StopCriteria::target_share (0 = off).
  Recorder(const FeatureSpace& space, const SearchRequest& request, const Thresholds& thresholds,
           std::uint64_t target_hits, SearchResult& out)
      : space_(space),
        out_(out),
        t_(thresholds),
        first_hit_(request.stop.first_hit),
        target_hits_(target_hits),
        max_evaluations_(request.stop.max_evaluations),
        max_seconds_(request.stop.max_seconds),
        start_(std::chrono::steady_clock::now()) {
    out_.verdict = t_.verdict;
    out_.centroid_delta = t_.centroid;
  }

  [[nodiscard]] const Thresholds& thresholds() const { return t_; }
  [[nodiscard]] bool stopped() const { return stopped_; }
  [[nodiscard]] bool has_best() const { return best2_ < std::numeric_limits<float>::infinity(); }
  [[nodiscard]] std::uint32_t best_i() const { return best_i_; }
  [[nodiscard]] std::uint32_t best_j() const { return best_j_; }

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

  /// Progress marks: mark k needs ceil(shares[k] x truth) distinct hits.
  void set_marks(const std::vector<double>& shares, std::uint64_t truth) {
    out_.progress.clear();
    for (const double share : shares) {
      ProgressMark mark;
      mark.share = share;
      mark.hits = static_cast<std::uint64_t>(std::ceil(share * static_cast<double>(truth)));
      out_.progress.push_back(mark);
    }
  }

  /// How far cell (i, j) may be from colliding and still collide: r_i + r_j + delta (Witness) or
  /// the centroid threshold (PaperCentroid).
  [[nodiscard]] float reach(std::uint32_t i, std::uint32_t j) const {
    return t_.verdict == Verdict::Witness ? space_.a.radius[i] + space_.b.radius[j] + t_.delta
                                          : t_.centroid;
  }

  /// Fitness f(i, j) (Eq. 6) of one cell; records a hit (verdict) and checks every stop
  /// criterion.
  float evaluate(std::uint32_t i, std::uint32_t j) {
    const float dx = space_.a.x[i] - space_.b.x[j];
    const float dy = space_.a.y[i] - space_.b.y[j];
    const float dz = space_.a.z[i] - space_.b.z[j];
    const float d2 = dx * dx + dy * dy + dz * dz;
    ++out_.evaluations;
    if (d2 < best2_) offer_best(i, j, d2);
    const float r = reach(i, j);
    if (d2 <= r * r) consider(i, j, d2);
    if (!stopped_) check_budget();
    return std::sqrt(d2);
  }

  /// The 16 lanes of a colony step: the candidates' centroids (gathered once, also used by the
  /// caller for Eq. 12's step lengths), distances and reaches.
  static constexpr std::uint32_t kLanes = 16;
  struct Lanes {
    alignas(64) float ax[kLanes], ay[kLanes], az[kLanes];
    alignas(64) float bx[kLanes], by[kLanes], bz[kLanes];
    alignas(64) float ra[kLanes], rb[kLanes];
    alignas(64) float d2[kLanes];
    alignas(64) float d[kLanes];      ///< f(i, j), Eq. 6
    alignas(64) float reach[kLanes];  ///< r_i + r_j + delta (Witness) or delta_c
    alignas(64) std::uint32_t within[kLanes];
  };

  /// Evaluates up to 16 cells at once (the colony's candidates): lane k is cell (ci[k], cj[k]),
  /// and the lanes of `mask` are the candidates, in lane order; the others are computed in the
  /// same fixed-length loops (so that they vectorise) and then ignored. The caller has gathered
  /// the 16 cells' centroids into `lanes` (and their radii for the witness verdict); `ci` and `cj`
  /// hold valid cells in every lane. Stops exactly at max_evaluations (the candidates past the
  /// limit are not evaluated) and at the first hit with first_hit (the cells after it are not
  /// counted); returns how many were evaluated.
  std::uint32_t evaluate_lanes(const std::uint32_t* ci, const std::uint32_t* cj, std::uint32_t mask,
                               Lanes& lanes) {
    auto count = static_cast<std::uint32_t>(std::popcount(mask));
    if (max_evaluations_ != 0) {
      const std::uint64_t left = max_evaluations_ - out_.evaluations;
      while (left < count) {  // drop the last candidates
        const auto last = static_cast<std::uint32_t>(31 - std::countl_zero(mask));
        mask &= ~(std::uint32_t{1} << last);
        --count;
      }
    }
    const bool witness = t_.verdict == Verdict::Witness;
    const LaneSummary sum = compute_lanes(lanes, mask, witness, t_.delta, t_.centroid);
    std::uint32_t counted_in_batch = 0;
    if (std::bit_cast<float>(sum.min_d2_bits) < best2_ || sum.any_within != 0) {
      std::uint32_t evaluated = 0;
      for (std::uint32_t left = mask; left != 0; left &= left - 1) {
        const auto k = static_cast<std::uint32_t>(std::countr_zero(left));
        ++evaluated;
        const float d2 = lanes.d2[k];
        if (d2 < best2_) offer_best(ci[k], cj[k], d2);
        if (lanes.within[k] != 0) {
          out_.evaluations += evaluated - counted_in_batch;
          counted_in_batch = evaluated;
          consider(ci[k], cj[k], d2);
          if (stopped_) return evaluated;
        }
      }
    }
    out_.evaluations += count - counted_in_batch;
    if (!stopped_) check_budget();
    return count;
  }

  /// For the exhaustive and grid scans: a cell known to be within reach (evaluation counted by
  /// the caller).
  void consider_cell(std::uint32_t i, std::uint32_t j, float d2) { consider(i, j, d2); }
  void add_evaluations(std::uint64_t count) { out_.evaluations += count; }
  void offer_best(std::uint32_t i, std::uint32_t j, float d2) {
    if (d2 < best2_) {
      best2_ = d2;
      best_i_ = i;
      best_j_ = j;
    }
  }
  void check_budget() {
    if (max_evaluations_ != 0 && out_.evaluations >= max_evaluations_) {
      stop(StopReason::Evaluations);
    } else if (max_seconds_ > 0 && (out_.evaluations - last_clock_) >= 1024) {
      last_clock_ = out_.evaluations;
      if (elapsed_seconds() >= max_seconds_) stop(StopReason::Time);
    }
  }
  [[nodiscard]] std::uint64_t evaluations() const { return out_.evaluations; }
  [[nodiscard]] std::uint64_t max_evaluations() const { return max_evaluations_; }
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
    if (has_best()) {
      out_.best_distance = std::sqrt(static_cast<Scalar>(best2_));
      out_.best = pair(best_i_, best_j_, out_.best_distance);
    }
  }

 private:
  [[nodiscard]] FeaturePair pair(std::uint32_t i, std::uint32_t j, Scalar d) const {
    return {i, j, space_.a.triangle[i], space_.b.triangle[j], d};
  }

  /// A cell within reach: the verdict decides (once per distinct cell).
  void consider(std::uint32_t i, std::uint32_t j, float d2) {
    if (!seen_.insert(std::uint64_t{i} * space_.b.size() + j)) return;
    if (t_.verdict == Verdict::Witness) {
      ++out_.witness_tests;
      if (!witness_test(space_, i, j)) return;
    }
    add_hit(i, j, std::sqrt(static_cast<Scalar>(d2)));
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
  Thresholds t_;
  bool first_hit_;
  std::uint64_t target_hits_;
  std::uint64_t max_evaluations_;
  double max_seconds_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
  std::uint32_t iteration_offset_ = 0;
  std::uint64_t last_clock_ = 0;
  float best2_ = std::numeric_limits<float>::infinity();
  std::uint32_t best_i_ = 0;
  std::uint32_t best_j_ = 0;
  CellSet seen_;  ///< cells whose verdict is known (tested or hit)
};

}  // namespace antcd::detail
