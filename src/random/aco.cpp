// The ant colony engine shared by Sphere-OBB-ACO (section 3.3, Eqs. 7–8) and Sphere-OBB-MACO
// (section 3.4, Eqs. 9–15). docs/random-detection.md explains the reading of the paper on the
// feature grid; in short:
// - a city is a cell (i, j) of the grid, i.e. a feature pair;
// - an ant's tour starts at a uniformly random cell and makes `steps` moves; from cell c the
//   candidates J_k(c) are the 8 neighbours at distance 1 and the 8 at distance `hop` (one
//   pheromone block) not yet on the ant's path; every candidate is evaluated (and any collision
//   recorded);
// - pheromone lives on a grid of at most pheromone_resolution² blocks (64² by default),
//   tau_ij = tau(block of j);
// - L_k, the path length, is the mean centroid distance of the path's cells in units of delta.
#include "random/engines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace antcd::detail {
namespace {

struct Cell {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
};

/// The distance between two cells used by the path heuristic of Eq. 12: how far the pair's two
/// features move in space, |a_i - a_i'| + |b_j - b_j'| (mesh units, a metric on the grid). With it
/// f(c') <= f(c) + D(c, c'), so D bounds how much closer to colliding a cell can be than another.
Scalar cell_distance(const FeatureSpace& s, Cell p, Cell q) {
  const Scalar ax = s.a.x[p.i] - s.a.x[q.i];
  const Scalar ay = s.a.y[p.i] - s.a.y[q.i];
  const Scalar az = s.a.z[p.i] - s.a.z[q.i];
  const Scalar bx = s.b.x[p.j] - s.b.x[q.j];
  const Scalar by = s.b.y[p.j] - s.b.y[q.j];
  const Scalar bz = s.b.z[p.j] - s.b.z[q.j];
  return std::sqrt(ax * ax + ay * ay + az * az) + std::sqrt(bx * bx + by * by + bz * bz);
}

/// Index of the first entry of the non-decreasing `cumulative` that exceeds u * total.
std::size_t roulette(const double* cumulative, std::size_t count, double u) {
  const double target = u * cumulative[count - 1];
  const double* it = std::upper_bound(cumulative, cumulative + count, target);
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative), count - 1);
}

}  // namespace

void run_colony(const FeatureSpace& space, const SearchRequest& request, bool improved,
                std::uint64_t seed, Recorder& rec) {
  const AntParams& p = request.ant;
  const MacoSwitches sw = improved ? p.maco : MacoSwitches{false, false, false, false};
  const std::uint32_t na = space.a.size();
  const std::uint32_t nb = space.b.size();
  const std::uint32_t big_n = request.iterations;

  // Pheromone grid: blocks of block_a x block_b cells, ga x gb of them.
  const std::uint32_t block_a = (na + p.pheromone_resolution - 1) / p.pheromone_resolution;
  const std::uint32_t block_b = (nb + p.pheromone_resolution - 1) / p.pheromone_resolution;
  const std::uint32_t ga = (na + block_a - 1) / block_a;
  const std::uint32_t gb = (nb + block_b - 1) / block_b;
  const std::size_t blocks = std::size_t{ga} * gb;
  const std::uint32_t hop_a = std::max<std::uint32_t>(2, block_a);
  const std::uint32_t hop_b = std::max<std::uint32_t>(2, block_b);
  std::vector<std::uint32_t> block_row(na), block_col(nb);  // no division in the inner loop
  for (std::uint32_t i = 0; i < na; ++i) block_row[i] = (i / block_a) * gb;
  for (std::uint32_t j = 0; j < nb; ++j) block_col[j] = j / block_b;
  auto block_of = [&](Cell c) { return std::size_t{block_row[c.i]} + block_col[c.j]; };

  // Everything the loops touch is allocated here, once.
  std::vector<double> tau(blocks, p.tau0);
  std::vector<double> tau_weight(blocks);  // tau^alpha' for this iteration
  const std::size_t path_capacity = std::size_t{p.steps} + 1;
  std::vector<Cell> paths(std::size_t{p.ants} * path_capacity);
  std::vector<std::uint32_t> path_length(p.ants);
  std::vector<double> tour_length(p.ants);  // L_k
  constexpr std::size_t kCandidates = 16;
  std::array<Cell, kCandidates> cand{};
  std::array<double, kCandidates> cand_cumulative{};
  std::array<Scalar, kCandidates> cand_distance{};

  const Scalar delta = rec.delta();
  // L_k is measured in units of delta so that Q / L_k does not depend on the mesh units.
  const Scalar length_unit = delta > 0 ? delta : Scalar{1};
  // Guards a zero denominator in eta (two coincident centroids at the tour's start).
  const Scalar eta_floor = 1e-12 * length_unit;
  // Numerical floor for the pheromone (not in the paper): keeps every block reachable and the
  // values out of denormals after many evaporations.
  const double tau_floor = 1e-9 * p.tau0;
  double bt = std::numeric_limits<double>::infinity();  // Eq. 13's best evaluation

  static constexpr std::array<std::array<int, 2>, 8> kDirections = {
      {{-1, -1}, {-1, 0}, {-1, 1}, {0, -1}, {0, 1}, {1, -1}, {1, 0}, {1, 1}}};

  // Same stream for Aco and Maco: Maco with every switch off runs exactly as Aco.
  Rng rng(seed ^ 0xAC0ULL);

  for (std::uint32_t nc = 1; nc <= big_n; ++nc) {
    if (!rec.begin_iteration(nc)) return;
    // Eqs. 9–10 (switch 1) or the fixed exponents of Eq. 7.
    const double scale = sw.adaptive_exponents ? static_cast<double>(nc) / p.n : 1.0;
    const double alpha = p.alpha * scale;
    const double beta = p.beta * scale;
    // Eq. 11 (switch 2) or the fixed rho of Eq. 8.
    const double rho = sw.adaptive_evaporation ? static_cast<double>(big_n) / (nc + big_n) : p.rho;

    for (std::size_t k = 0; k < blocks; ++k) {
      tau_weight[k] = alpha == 1.0 ? tau[k] : std::pow(tau[k], alpha);
    }
    // The end point s of Eq. 12: the best cell known when the iteration starts.
    const bool has_goal = rec.has_best();
    const Cell goal{rec.best().i, rec.best().j};

    for (std::uint32_t ant = 0; ant < p.ants; ++ant) {
      Cell* path = &paths[std::size_t{ant} * path_capacity];
      // Start cell: uniform over the grid, as ants are placed on random cities in the classic
      // colony; the pheromone then acts on every move.
      Cell cur{static_cast<std::uint32_t>(rng.below(na)),
               static_cast<std::uint32_t>(rng.below(nb))};
      Scalar sum_f = rec.evaluate(cur.i, cur.j);
      if (rec.stopped()) return;
      const Cell origin = cur;
      std::uint32_t len = 0;
      path[len++] = cur;
      // 256-bit filter over the path's cells: most candidates are ruled off the tabu list
      // without scanning the path.
      std::array<std::uint64_t, 4> filter{};
      auto filter_bit = [](Cell c) {
        return static_cast<std::uint32_t>((c.i * 0x9E3779B1U) ^ (c.j * 0x85EBCA77U)) >> 24;
      };
      auto remember = [&](Cell c) {
        const std::uint32_t h = filter_bit(c);
        filter[h >> 6] |= std::uint64_t{1} << (h & 63);
      };
      remember(cur);

      for (std::uint32_t step = 0; step < p.steps; ++step) {
        std::size_t count = 0;
        double total = 0;
        for (int scale_index = 0; scale_index < 2; ++scale_index) {
          const std::int64_t ha = scale_index == 0 ? 1 : hop_a;
          const std::int64_t hb = scale_index == 0 ? 1 : hop_b;
          for (const auto& dir : kDirections) {
            const std::int64_t ci = std::int64_t{cur.i} + dir[0] * ha;
            const std::int64_t cj = std::int64_t{cur.j} + dir[1] * hb;
            if (ci < 0 || cj < 0 || ci >= na || cj >= nb) continue;
            const Cell c{static_cast<std::uint32_t>(ci), static_cast<std::uint32_t>(cj)};
            // J_k: cells not yet on this ant's path (the tabu list of Eq. 7).
            bool visited = false;
            const std::uint32_t h = filter_bit(c);
            const bool maybe = (filter[h >> 6] >> (h & 63)) & 1;
            for (std::uint32_t t = 0; maybe && t < len; ++t) {
              if (path[t].i == c.i && path[t].j == c.j) {
                visited = true;
                break;
              }
            }
            if (visited) continue;
            const Scalar d = rec.evaluate(c.i, c.j);
            if (rec.stopped()) return;
            // eta = 1/d (Eq. 7) or 1/(d_oj + d_ij + d_js) (Eq. 12, switch 3).
            Scalar denom = d;
            if (sw.path_heuristic) {
              denom += cell_distance(space, origin, c);
              if (has_goal) denom += cell_distance(space, c, goal);
            }
            denom = std::max(denom, eta_floor);
            // eta^beta = d^-beta (one log and one exp; skipped when beta is 1).
            const double eta_beta = beta == 1.0 ? 1.0 / denom : std::exp(-beta * std::log(denom));
            const double w = tau_weight[block_of(c)] * eta_beta;
            total += std::isfinite(w) ? w : 0.0;
            cand[count] = c;
            cand_distance[count] = d;
            cand_cumulative[count] = total;
            ++count;
          }
        }
        if (count == 0) break;  // boxed in by its own path at a border
        // Eq. 7: move to a candidate with probability proportional to tau^alpha eta^beta.
        const std::size_t pick = total > 0 && std::isfinite(total)
                                     ? roulette(cand_cumulative.data(), count, rng.unit())
                                     : rng.below(count);
        cur = cand[pick];
        sum_f += cand_distance[pick];
        path[len++] = cur;
        remember(cur);
      }
      path_length[ant] = len;
      tour_length[ant] = std::max(sum_f / len / length_unit, 1e-9);
    }

    // Pheromone update once per iteration. Eq. 13: bt follows the best evaluation.
    const double iteration_best = *std::min_element(tour_length.begin(), tour_length.end());
    bt = std::min(bt, iteration_best);
    // Eq. 8 / Eq. 14: evaporation of every block.
    for (double& t : tau) t *= 1.0 - rho;
    for (std::uint32_t ant = 0; ant < p.ants; ++ant) {
      // Delta tau^k = Q / L_k on each cell of the path.
      double deposit = p.q / tour_length[ant];
      // Eqs. 14–15 (switch 4): paths as good as the best evaluation are rewarded (+theta),
      // the others punished (mu < 0).
      if (sw.reward_punishment) deposit *= tour_length[ant] <= bt ? 1.0 + p.theta : 1.0 + p.mu;
      const Cell* path = &paths[std::size_t{ant} * path_capacity];
      for (std::uint32_t t = 0; t < path_length[ant]; ++t) tau[block_of(path[t])] += deposit;
    }
    for (double& t : tau) t = std::max(t, tau_floor);
  }
}

}  // namespace antcd::detail
