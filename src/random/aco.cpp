// The ant colony engine shared by Sphere-OBB-ACO (section 3.3, Eqs. 7–8) and Sphere-OBB-MACO
// (section 3.4, Eqs. 9–15). docs/random-detection.md explains the reading of the paper on the
// feature grid; in short:
// - a city is a cell (i, j) of the grid, i.e. a feature pair;
// - an ant's tour starts at a cell of a reported leaf pair (or a uniformly random cell) and makes
//   `steps` moves; from cell c the candidates J_k(c) are the 8 neighbours at distance 1 and the 8
//   at distance `hop`, not yet on the ant's path; every candidate is evaluated (and any collision
//   recorded) in one batch;
// - pheromone lives on a grid of at most pheromone_resolution² blocks over the two models' leaf
//   order (pose-independent), tau_ij = tau(block of j), and is kept in a ColonyMemory from one
//   search to the next;
// - L_k, the path length, is the mean centroid distance of the path's cells in units of the
//   space's centroid threshold.
// The inner loop uses floats, the pheromone kept as log2(tau) per block and the fast log2 / exp2
// of fast_math.hpp: no call into the maths library per candidate.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "random/engines.hpp"
#include "random/fast_math.hpp"
#include "random/lane_vectors.hpp"
#include "random/recorder.hpp"

namespace antcd::detail {

// The lane arithmetic of a colony step (Recorder::evaluate_lanes): the 16 lanes' distances and
// reaches, in fixed-length, branch-free loops that vectorise inside run_colony's clones (this file
// is built without trapping maths or errno, so that float selects and sqrt vectorise; neither
// changes a value).
[[gnu::always_inline]] inline Recorder::LaneSummary Recorder::compute_lanes(
    Lanes& lanes, std::uint32_t mask, bool witness, float delta, float centroid) {
  if (witness) {
    for (std::uint32_t k = 0; k < kLanes; ++k) {
      lanes.reach[k] = lanes.ra[k] + lanes.rb[k] + delta;
    }
  } else {
    for (std::uint32_t k = 0; k < kLanes; ++k) lanes.reach[k] = centroid;
  }
  for (std::uint32_t k = 0; k < kLanes; ++k) {
    const float dx = lanes.ax[k] - lanes.bx[k];
    const float dy = lanes.ay[k] - lanes.by[k];
    const float dz = lanes.az[k] - lanes.bz[k];
    const float d2 = dx * dx + dy * dy + dz * dz;
    lanes.d2[k] = d2;
    lanes.d[k] = std::sqrt(d2);
    lanes.within[k] = d2 <= lanes.reach[k] * lanes.reach[k] ? 1U : 0U;
  }
  // Reductions over the candidates' lanes only (lane_vectors.hpp).
  lanes::U8 any{};
  lanes::U8 least = lanes::splat(~0U);
  for (std::uint32_t half = 0; half < 2; ++half) {
    const lanes::U8 ok = lanes::expand(mask, half);
    any |= lanes::load(lanes.within + 8 * half) & ok;
    const auto bits = (lanes::U8)lanes::load(lanes.d2 + 8 * half);
    least = lanes::min(least, bits | ~ok);
  }
  LaneSummary summary;
  summary.any_within = lanes::reduce_or(any);
  summary.min_d2_bits = lanes::reduce_min(least);
  return summary;
}

namespace {

struct Cell {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
};

/// The 16 lanes' centroids (and radii with `witness`) of a cell at least hop_a / hop_b from
/// every border: each side's values from its five rows / columns.
inline void gather_interior(const FeatureSpace& space, std::uint32_t i, std::uint32_t j,
                            std::uint32_t hop_a, std::uint32_t hop_b, bool witness,
                            Recorder::Lanes& l) {
  lanes::spread_rows(space.a.x.data(), i, hop_a, l.ax);
  lanes::spread_rows(space.a.y.data(), i, hop_a, l.ay);
  lanes::spread_rows(space.a.z.data(), i, hop_a, l.az);
  lanes::spread_columns(space.b.x.data(), j, hop_b, l.bx);
  lanes::spread_columns(space.b.y.data(), j, hop_b, l.by);
  lanes::spread_columns(space.b.z.data(), j, hop_b, l.bz);
  if (witness) {
    lanes::spread_rows(space.a.radius.data(), i, hop_a, l.ra);
    lanes::spread_columns(space.b.radius.data(), j, hop_b, l.rb);
  }
}

/// The same for any cell, lane by lane from the (valid) cells ci, cj.
inline void gather_lanes(const FeatureSpace& space, const std::uint32_t* ci,
                         const std::uint32_t* cj, bool witness, Recorder::Lanes& l) {
  for (std::uint32_t k = 0; k < Recorder::kLanes; ++k) {
    l.ax[k] = space.a.x[ci[k]];
    l.ay[k] = space.a.y[ci[k]];
    l.az[k] = space.a.z[ci[k]];
    l.bx[k] = space.b.x[cj[k]];
    l.by[k] = space.b.y[cj[k]];
    l.bz[k] = space.b.z[cj[k]];
  }
  if (witness) {
    for (std::uint32_t k = 0; k < Recorder::kLanes; ++k) {
      l.ra[k] = space.a.radius[ci[k]];
      l.rb[k] = space.b.radius[cj[k]];
    }
  }
}

/// Distance between two features of one side with the L1 norm (a metric; no square root).
inline float feature_step(const FeatureSide& s, std::uint32_t p, std::uint32_t q) {
  return std::abs(s.x[p] - s.x[q]) + std::abs(s.y[p] - s.y[q]) + std::abs(s.z[p] - s.z[q]);
}

/// The cell metric of Eq. 12: how far the pair's two features move in space,
/// |a_i - a_i'|_1 + |b_j - b_j'|_1 (mesh units).
inline float cell_distance(const FeatureSpace& s, Cell p, Cell q) {
  return feature_step(s.a, p.i, q.i) + feature_step(s.b, p.j, q.j);
}

/// Order keys, for the largest of the 16 lanes: floats are mapped to integers of the same order
/// (negative ones have their magnitude bits flipped: bits ^ ((bits >> 31) & 0x7FFFFFFF)), whose
/// maximum vectorises; no lane is NaN. -0 and +0 may come out either way, which no caller can
/// tell apart (l - top and the == test treat them alike). The inverse:
inline float from_order_key(std::int32_t key) {
  return std::bit_cast<float>(key ^ ((key >> 31) & 0x7FFFFFFF));
}

/// Eq. 7 in logarithms with the remaining-distance reading of Eq. 12, for the 16 lanes, in one
/// pass: d_ij (`step`: cell_distance from the current cell, cax..cbz its two centroids, to each
/// candidate, from the centroids the batch gathered; same sums as cell_distance, in the same
/// order), then alpha' log2 tau - beta' log2(d_oj + d_ij + max(0, f - reach)) into `out`.
inline void remaining_log_weights(const Recorder::Lanes& l, float cax, float cay, float caz,
                                  float cbx, float cby, float cbz, const float* log_tau,
                                  float travelled, float alpha, float beta, float denom_floor,
                                  float* step, float* out) {
  for (std::uint32_t k = 0; k < Recorder::kLanes; ++k) {
    const float sa = std::abs(cax - l.ax[k]) + std::abs(cay - l.ay[k]) + std::abs(caz - l.az[k]);
    const float sb = std::abs(cbx - l.bx[k]) + std::abs(cby - l.by[k]) + std::abs(cbz - l.bz[k]);
    step[k] = sa + sb;
    const float missing = l.d[k] > l.reach[k] ? l.d[k] - l.reach[k] : 0.0f;
    float denom = travelled + step[k] + missing;
    denom = denom > denom_floor ? denom : denom_floor;
    out[k] = alpha * log_tau[k] - beta * fast_log2(denom);
  }
}

/// Sets the lanes outside `mask` to -inf and returns the largest of the 16 lanes, i.e. the
/// candidates' largest (order keys: see from_order_key).
inline float masked_max(float* v, std::uint32_t mask) {
  lanes::U8 best = lanes::splat(0x80000000U);
  for (std::uint32_t half = 0; half < 2; ++half) {
    const lanes::F8 x = lanes::select(lanes::expand(mask, half), lanes::load(v + 8 * half),
                                      lanes::splat(-std::numeric_limits<float>::infinity()));
    lanes::store(v + 8 * half, x);
    const auto bits = (lanes::I8)x;
    const lanes::I8 key = bits ^ ((bits >> 31) & 0x7FFFFFFF);
    best = (lanes::U8)lanes::max((lanes::I8)best, key);
  }
  return from_order_key(lanes::reduce_max((lanes::I8)best));
}

/// Roulette weights 2^(l - top) of the lanes of `mask`, 0 for the others.
inline void roulette_weights(const float* log_weight, float top, std::uint32_t mask,
                             float* weight) {
  for (std::uint32_t k = 0; k < Recorder::kLanes; ++k) {
    weight[k] = fast_exp2(log_weight[k] - top);
  }
  for (std::uint32_t half = 0; half < 2; ++half) {
    lanes::store(weight + 8 * half, lanes::select(lanes::expand(mask, half),
                                                  lanes::load(weight + 8 * half), lanes::F8{}));
  }
}

/// The roulette's count (Eq. 7): with the serial running totals c_k of the 16 lanes' weights
/// (c_k = c_{k-1} + w_k in float, from 0) and target = u * c_15, the number of lanes with
/// c_k <= target. The serial totals are a chain of 16 dependent additions; they are first summed
/// as prefix sums in three vector steps per half (another association, hence another rounding:
/// sums of at most 16 non-negative terms, within 15 x 2^-24 of the exact total either way, so the
/// two totals and their targets differ by under 4e-6 of the total). A lane whose total lies
/// further than total / 2^16 from the target compares the same way with both sums; when every
/// lane does (almost always), their count is the answer. Otherwise the serial totals are computed
/// into `cumulative` and counted: the result is always that of the serial sums.
inline std::uint32_t roulette_below(const float* weight, float u, float* cumulative) {
  const lanes::F8 zero{};
  lanes::F8 lo = lanes::load(weight);
  lanes::F8 hi = lanes::load(weight + 8);
  lo += __builtin_shufflevector(lo, zero, 8, 0, 1, 2, 3, 4, 5, 6);
  hi += __builtin_shufflevector(hi, zero, 8, 0, 1, 2, 3, 4, 5, 6);
  lo += __builtin_shufflevector(lo, zero, 8, 8, 0, 1, 2, 3, 4, 5);
  hi += __builtin_shufflevector(hi, zero, 8, 8, 0, 1, 2, 3, 4, 5);
  lo += __builtin_shufflevector(lo, zero, 8, 8, 8, 8, 0, 1, 2, 3);
  hi += __builtin_shufflevector(hi, zero, 8, 8, 8, 8, 0, 1, 2, 3);
  hi += lanes::splat(lo[7]);
  const float approx_total = hi[7];
  const float approx_target = u * approx_total;
  const float margin = approx_total * 0x1p-16f;
  const lanes::F8 low = lanes::splat(approx_target - margin);
  const lanes::F8 high = lanes::splat(approx_target + margin);
  const auto near = ((lanes::U8)(lo > low) & (lanes::U8)(lo <= high)) |
                    ((lanes::U8)(hi > low) & (lanes::U8)(hi <= high));
  if (lanes::reduce_or(near) == 0) {
    return lanes::reduce_add(((lanes::U8)(lo <= low) & 1U) + ((lanes::U8)(hi <= low) & 1U));
  }
  float total = 0;
  for (std::uint32_t k = 0; k < Recorder::kLanes; ++k) {
    total += weight[k];
    cumulative[k] = total;
  }
  const lanes::F8 target = lanes::splat(u * total);
  return lanes::reduce_add(((lanes::U8)(lanes::load(cumulative) <= target) & 1U) +
                           ((lanes::U8)(lanes::load(cumulative + 8) <= target) & 1U));
}

/// Pheromone grid size along one side: at most `resolution` blocks, at most one per triangle.
std::uint32_t grid_size(std::uint32_t resolution, std::uint32_t model_triangles) {
  return std::max<std::uint32_t>(1, std::min(resolution, model_triangles));
}

}  // namespace

// Compiled for the baseline and for AVX2 (fast_math.hpp): the lane helpers above are inlined into
// each clone, so a step makes no call through the clones' dispatch.
ANTCD_VECTOR_CLONES void run_colony(const FeatureSpace& space, const SearchRequest& request,
                                    bool improved, std::uint64_t seed, ColonyMemory& memory,
                                    Recorder& rec) {
  const AntParams& p = request.ant;
  MacoSwitches sw = p.maco;
  if (!improved) {
    sw.adaptive_exponents = sw.adaptive_evaporation = sw.path_heuristic = false;
    sw.reward_punishment = sw.greedy_moves = false;
  }
  const std::uint32_t na = space.a.size();
  const std::uint32_t nb = space.b.size();
  const std::uint32_t big_n = request.iterations;

  // Pheromone grid over the models' leaf order, carried in the memory.
  const std::uint32_t ga = grid_size(p.pheromone_resolution, space.a.model_triangles);
  const std::uint32_t gb = grid_size(p.pheromone_resolution, space.b.model_triangles);
  if (memory.grid_a != ga || memory.grid_b != gb || memory.log_tau.size() != std::size_t{ga} * gb) {
    const auto witnesses = std::move(memory.witnesses);
    memory.clear();
    memory.witnesses = witnesses;
    memory.grid_a = ga;
    memory.grid_b = gb;
    memory.log_tau.assign(std::size_t{ga} * gb, static_cast<float>(std::log2(p.tau0)));
  }
  // The pheromone is kept as log2(tau): a candidate's weight needs alpha' log2 tau (Eq. 7 in
  // logarithms), so no logarithm is taken per candidate, and evaporation is one addition.
  std::vector<float>& log_tau = memory.log_tau;
  std::vector<std::uint32_t> block_row(na), block_col(nb);  // no division in the inner loop
  for (std::uint32_t i = 0; i < na; ++i) {
    block_row[i] = static_cast<std::uint32_t>(std::uint64_t{space.a.position[i]} * ga /
                                              std::max<std::uint32_t>(1, space.a.model_triangles)) *
                   gb;
  }
  for (std::uint32_t j = 0; j < nb; ++j) {
    block_col[j] = static_cast<std::uint32_t>(std::uint64_t{space.b.position[j]} * gb /
                                              std::max<std::uint32_t>(1, space.b.model_triangles));
  }
  auto block_of = [&](std::uint32_t i, std::uint32_t j) {
    return std::size_t{block_row[i]} + block_col[j];
  };
  // Hops: about one 64th of a side, so a tour can leave a patch of the grid.
  const std::uint32_t hop_a = std::max<std::uint32_t>(2, (na + 63) / 64);
  const std::uint32_t hop_b = std::max<std::uint32_t>(2, (nb + 63) / 64);

  // Leaf pairs whose both leaves kept features: the starting cells (section 4 step 3), each as
  // its two leaves' ranges in leaf_features, so that an ant's start reads one entry.
  struct StartRange {
    std::uint32_t a0, a1, b0, b1;
  };
  std::vector<StartRange> starts;
  if (p.start == AntStart::LeafPairs) {
    for (const auto& [la, lb] : space.overlaps) {
      const StartRange r{space.a.leaf_start[la], space.a.leaf_start[la + 1], space.b.leaf_start[lb],
                         space.b.leaf_start[lb + 1]};
      if (r.a0 != r.a1 && r.b0 != r.b1) starts.push_back(r);
    }
  }

  const std::size_t path_capacity = std::size_t{p.steps} + 1;
  std::vector<Cell> paths(std::size_t{p.ants} * path_capacity);
  std::vector<std::uint32_t> path_length(p.ants);
  std::vector<double> tour_length(p.ants);           // L_k
  std::vector<double> pending(log_tau.size(), 0.0);  // deposits of this iteration, per block
  std::vector<std::uint8_t> is_touched(log_tau.size(), 0);
  std::vector<std::uint32_t> touched;  // blocks with a pending deposit, in first-touch order
  touched.reserve(std::size_t{p.ants} * path_capacity);
  constexpr std::uint32_t kCandidates = Recorder::kLanes;
  alignas(64) std::array<std::uint32_t, kCandidates> cand_i{}, cand_j{}, cand_block{};
  Recorder::Lanes lanes;
  alignas(64) std::array<float, kCandidates> cand_step{}, cand_tau{}, cand_log{}, cand_weight{},
      cand_cumulative{};
  const bool witness = rec.thresholds().verdict == Verdict::Witness;

  const auto unit = static_cast<float>(space.centroid_delta);  // > 0: the length unit
  const float denom_floor = 1e-6f * unit;
  const auto log_tau_floor = static_cast<float>(std::log2(1e-9 * p.tau0));
  double bt =
      memory.best_evaluation > 0 ? memory.best_evaluation : std::numeric_limits<double>::infinity();

  // J_k(c): the 8 neighbours at distance 1 (lanes 0–7), then the 8 at distance hop (8–15). The
  // directions are listed so that lane 7 - k (8 + 15 - k) is the opposite move of lane k.
  // Offsets are kept as wrapping 32-bit integers: cur + offset is then below na (nb) exactly when
  // the signed sum lies in [0, na) (na + hop_a < 2^32), so one unsigned compare checks a border.
  static constexpr std::array<std::array<int, 2>, 8> kDirections = {
      {{-1, -1}, {-1, 0}, {-1, 1}, {0, -1}, {0, 1}, {1, -1}, {1, 0}, {1, 1}}};
  constexpr std::uint32_t kNoLane = Recorder::kLanes;
  alignas(64) std::array<std::uint32_t, Recorder::kLanes> lane_di{}, lane_dj{};
  for (std::uint32_t k = 0; k < 8; ++k) {
    lane_di[k] = static_cast<std::uint32_t>(kDirections[k][0]);
    lane_dj[k] = static_cast<std::uint32_t>(kDirections[k][1]);
    lane_di[k + 8] = static_cast<std::uint32_t>(kDirections[k][0]) * hop_a;
    lane_dj[k + 8] = static_cast<std::uint32_t>(kDirections[k][1]) * hop_b;
  }
  auto opposite_lane = [](std::uint32_t k) { return k < 8 ? 7 - k : 23 - k; };
  static constexpr std::array<std::uint32_t, Recorder::kLanes> kLaneIndex = {
      0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  // Same stream for Aco and Maco: Maco with every switch off runs exactly as Aco.
  Rng rng(seed ^ 0xAC0ULL);

  auto pick_start = [&]() -> Cell {
    if (!starts.empty()) {
      const StartRange& r = starts[rng.below32(static_cast<std::uint32_t>(starts.size()))];
      return {space.a.leaf_features[r.a0 + rng.below32(r.a1 - r.a0)],
              space.b.leaf_features[r.b0 + rng.below32(r.b1 - r.b0)]};
    }
    return {rng.below32(na), rng.below32(nb)};
  };

  for (std::uint32_t k = 1; k <= big_n; ++k) {
    if (!rec.begin_iteration(k)) break;
    // N_c counts every iteration this colony has run (memory), capped at N for Eqs. 9–11 so that
    // a long-lived colony stays in its mature stage instead of growing alpha' without bound.
    const std::uint64_t nc_total = ++memory.iterations;
    const double nc = static_cast<double>(std::min<std::uint64_t>(nc_total, big_n));
    const double scale = sw.adaptive_exponents ? nc / p.n : 1.0;
    const auto alpha = static_cast<float>(p.alpha * scale);
    const auto beta = static_cast<float>(p.beta * scale);
    // Eq. 11 (switch 2) or the fixed rho of Eq. 8.
    const double rho = sw.adaptive_evaporation ? big_n / (nc + big_n) : p.rho;

    // The end point s of the corridor reading of Eq. 12: the best cell known so far.
    const bool has_goal = rec.has_best();
    const Cell goal{rec.best_i(), rec.best_j()};
    const bool corridor = sw.path_heuristic && sw.heuristic == PathHeuristic::Corridor;
    const bool remaining = sw.path_heuristic && sw.heuristic == PathHeuristic::Remaining;

    std::uint32_t ants_done = 0;
    for (std::uint32_t ant = 0; ant < p.ants; ++ant) {
      Cell* path = &paths[std::size_t{ant} * path_capacity];
      Cell cur = pick_start();
      float sum_f = rec.evaluate(cur.i, cur.j);
      if (rec.stopped()) break;
      const Cell origin = cur;
      float travelled = 0;  // d_oj of the remaining-distance reading
      std::uint32_t len = 0;
      path[len++] = cur;
      std::uint32_t came_from = kNoLane;  // lane of the cell just left, none at the start

      bool stopped = false;
      for (std::uint32_t step = 0; step < p.steps; ++step) {
        // The 16 lanes' cells and whether each is inside the grid and not the cell just left (the
        // opposite lane of the last move), in vectors of 8 lanes.
        lanes::U8 lane_i[2], lane_j[2], lane_ok[2];
        const lanes::U8 ci = lanes::splat(cur.i), cj = lanes::splat(cur.j);
        const lanes::U8 size_a = lanes::splat(na), size_b = lanes::splat(nb);
        const lanes::U8 last_a = lanes::splat(na - 1), last_b = lanes::splat(nb - 1);
        for (std::uint32_t half = 0; half < 2; ++half) {
          const lanes::U8 ui = ci + lanes::load(lane_di.data() + 8 * half);
          const lanes::U8 uj = cj + lanes::load(lane_dj.data() + 8 * half);
          const auto in_a = (lanes::U8)(ui < size_a);
          const auto in_b = (lanes::U8)(uj < size_b);
          const auto not_back =
              (lanes::U8)(lanes::load(kLaneIndex.data() + 8 * half) != lanes::splat(came_from));
          lane_ok[half] = in_a & in_b & not_back;
          lane_i[half] = ui;
          lane_j[half] = uj;
          // Every lane holds a valid cell for the loads (the ones outside the grid clamped).
          lanes::store(cand_i.data() + 8 * half, (ui & in_a) | (last_a & ~in_a));
          lanes::store(cand_j.data() + 8 * half, (uj & in_b) | (last_b & ~in_b));
        }
        // J_k: cells not yet on this ant's path (the tabu list of Eq. 7): every lane against
        // every path cell, four vector compares per cell, no branch per lane.
        lanes::U8 on_path[2] = {};
        for (std::uint32_t t = 0; t < len; ++t) {
          const lanes::U8 pi = lanes::splat(path[t].i), pj = lanes::splat(path[t].j);
          for (std::uint32_t half = 0; half < 2; ++half) {
            on_path[half] |= (lanes::U8)(lane_i[half] == pi) & (lanes::U8)(lane_j[half] == pj);
          }
        }
        const std::uint32_t ok_mask =
            lanes::to_mask(lane_ok[0] & ~on_path[0], lane_ok[1] & ~on_path[1]);
        if (ok_mask == 0) break;  // boxed in by its own path at a border
        // The candidates stay in their lanes (lane order is candidate order): the lanes of
        // ok_mask. The other lanes are computed and never chosen.
        const bool interior =
            cur.i >= hop_a && cur.i + hop_a < na && cur.j >= hop_b && cur.j + hop_b < nb;
        if (interior) {
          gather_interior(space, cur.i, cur.j, hop_a, hop_b, witness, lanes);
        } else {
          gather_lanes(space, cand_i.data(), cand_j.data(), witness, lanes);
        }
        rec.evaluate_lanes(cand_i.data(), cand_j.data(), ok_mask, lanes);
        if (rec.stopped()) {
          stopped = true;
          break;
        }
        // Eq. 7 in logarithms: log2(tau^alpha' eta^beta') = alpha' log2 tau - beta' log2 denom,
        // with denom = 1/eta: f(j) (classic), or one of the readings of Eq. 12 (switch 3).
        if (interior) {
          std::array<std::uint32_t, kCandidates> row, col;
          lanes::spread_rows(block_row.data(), cur.i, hop_a, row.data());
          lanes::spread_columns(block_col.data(), cur.j, hop_b, col.data());
          for (std::uint32_t half = 0; half < 2; ++half) {
            lanes::store(cand_block.data() + 8 * half,
                         lanes::load(row.data() + 8 * half) + lanes::load(col.data() + 8 * half));
          }
        } else {
          for (std::uint32_t k = 0; k < kCandidates; ++k) {
            cand_block[k] = block_row[cand_i[k]] + block_col[cand_j[k]];
          }
        }
        for (std::uint32_t k = 0; k < kCandidates; ++k) cand_tau[k] = log_tau[cand_block[k]];
        if (remaining) {
          // d_ij: the step from the current cell, from the centroids the batch gathered.
          const float cax = space.a.x[cur.i], cay = space.a.y[cur.i], caz = space.a.z[cur.i];
          const float cbx = space.b.x[cur.j], cby = space.b.y[cur.j], cbz = space.b.z[cur.j];
          remaining_log_weights(lanes, cax, cay, caz, cbx, cby, cbz, cand_tau.data(), travelled,
                                alpha, beta, denom_floor, cand_step.data(), cand_log.data());
        } else {
          for (std::uint32_t k = 0; k < kCandidates; ++k) {
            const Cell to{cand_i[k], cand_j[k]};
            float denom = lanes.d[k];
            if (corridor) {
              denom += cell_distance(space, origin, to);
              if (has_goal) denom += cell_distance(space, to, goal);
            }
            denom = denom > denom_floor ? denom : denom_floor;
            cand_log[k] = alpha * cand_tau[k] - beta * fast_log2(denom);
          }
        }
        // The candidates' largest (the other lanes become -inf).
        const float top = masked_max(cand_log.data(), ok_mask);
        std::uint32_t pick = 0;
        if (sw.greedy_moves) {
          // The first largest (the greedy route).
          const lanes::F8 t = lanes::splat(top);
          const std::uint32_t largest =
              lanes::to_mask((lanes::U8)(lanes::load(cand_log.data()) == t),
                             (lanes::U8)(lanes::load(cand_log.data() + 8) == t));
          pick = static_cast<std::uint32_t>(std::countr_zero(largest & ok_mask));
        } else {
          // Roulette over weights scaled by the largest (2^(l - top) in (0, 1]); the other lanes
          // weigh 0, so the running totals at the candidates are those of the candidates alone.
          roulette_weights(cand_log.data(), top, ok_mask, cand_weight.data());
          // The first candidate whose running total exceeds the target, or the last candidate if
          // none does. The totals never decrease along the 16 lanes (the other lanes add 0), so
          // the lanes at or below the target are the first `below`.
          const std::uint32_t below =
              roulette_below(cand_weight.data(), rng.unit_float(), cand_cumulative.data());
          const std::uint32_t after = ok_mask >> below;  // below <= 16
          pick = after != 0 ? below + static_cast<std::uint32_t>(std::countr_zero(after))
                            : static_cast<std::uint32_t>(31 - std::countl_zero(ok_mask));
        }
        pick &= kCandidates - 1;  // a candidate's lane already (ok_mask is not empty)
        const Cell next{cand_i[pick], cand_j[pick]};
        if (remaining) travelled += cand_step[pick];
        cur = next;
        came_from = opposite_lane(pick);
        sum_f += lanes.d[pick];
        path[len++] = cur;
      }
      if (stopped) break;
      path_length[ant] = len;
      tour_length[ant] = std::max(static_cast<double>(sum_f) / len / unit, 1e-9);
      ++ants_done;
    }
    if (ants_done < p.ants) break;  // stopped inside the iteration: no update

    // Pheromone update once per iteration. Eq. 13: bt follows the best evaluation.
    const double iteration_best = *std::min_element(tour_length.begin(), tour_length.end());
    bt = std::min(bt, iteration_best);
    // Eq. 8 / Eq. 14: evaporation of every block.
    // In log2: evaporation adds log2(1 - rho) to every block (rho = 1 forgets everything: the
    // floor), deposits add in the linear domain (a few per ant, not per candidate).
    const float keep = rho < 1 ? static_cast<float>(std::log2(1.0 - rho)) : -1e30f;
    for (float& t : log_tau) t = std::max(t + keep, log_tau_floor);
    // Deposits are summed per block first (linear domain, double), then each touched block takes
    // its sum in one logarithm: log2(2^tau + sum of Delta tau), the same quantity as one deposit
    // after the other, with one exp2/log2 pair per block instead of per path cell.
    touched.clear();
    for (std::uint32_t ant = 0; ant < p.ants; ++ant) {
      // Delta tau^k = Q / L_k on each cell of the path.
      double deposit = p.q / tour_length[ant];
      // Eqs. 14–15 (switch 4): paths as good as the best evaluation are rewarded (+theta),
      // the others punished (mu < 0).
      if (sw.reward_punishment) deposit *= tour_length[ant] <= bt ? 1.0 + p.theta : 1.0 + p.mu;
      const Cell* path = &paths[std::size_t{ant} * path_capacity];
      for (std::uint32_t t = 0; t < path_length[ant]; ++t) {
        const std::size_t b = block_of(path[t].i, path[t].j);
        if (!is_touched[b]) {
          is_touched[b] = 1;
          touched.push_back(static_cast<std::uint32_t>(b));
        }
        pending[b] += deposit;
      }
    }
    for (const std::uint32_t b : touched) {
      float& lt = log_tau[b];
      // A punishment factor mu < -1 makes deposits negative: a block driven to or below zero
      // pheromone takes the floor.
      const double linear = std::exp2(double{lt}) + pending[b];
      lt = linear > 0 ? std::max(static_cast<float>(std::log2(linear)), log_tau_floor)
                      : log_tau_floor;
      pending[b] = 0;
      is_touched[b] = 0;
    }
  }
  if (std::isfinite(bt)) memory.best_evaluation = bt;
}

}  // namespace antcd::detail
