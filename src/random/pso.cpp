// Particle swarm baseline (the paper's BOX-PSO and the PSO random collision detection of its
// references [8–10]): a global-best swarm flying over the continuous rectangle [0, na) x [0, nb)
// of the feature grid; a particle's cell is its position rounded down. Synchronous updates: the
// whole swarm is evaluated, then every velocity and position is updated.
#include "random/engines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace antcd::detail {

void run_pso(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
             Recorder& rec) {
  const PsoParams& p = request.pso;
  const double na = space.a.size();
  const double nb = space.b.size();
  const double vmax_a = std::max(1.0, p.max_velocity * na);
  const double vmax_b = std::max(1.0, p.max_velocity * nb);
  constexpr double kInf = std::numeric_limits<double>::infinity();

  struct Particle {
    double x = 0, y = 0;    // position (i, j), continuous
    double vx = 0, vy = 0;  // velocity, cells per iteration
    double best_x = 0, best_y = 0;
    double best_f = kInf;
    std::uint32_t stall = 0;
  };
  std::vector<Particle> swarm(p.particles);
  Rng rng(seed ^ 0x9507ULL);
  auto reseed = [&](Particle& q) {
    q.x = rng.uniform(0, na);
    q.y = rng.uniform(0, nb);
    q.vx = rng.uniform(-vmax_a, vmax_a);
    q.vy = rng.uniform(-vmax_b, vmax_b);
    q.best_f = kInf;
    q.stall = 0;
  };
  for (Particle& q : swarm) reseed(q);
  double g_x = 0, g_y = 0, g_f = kInf;

  auto cell = [](double x, double n) {
    return static_cast<std::uint32_t>(std::clamp(std::floor(x), 0.0, n - 1));
  };

  for (std::uint32_t it = 1; it <= request.iterations; ++it) {
    if (!rec.begin_iteration(it)) return;
    for (Particle& q : swarm) {
      const double f = rec.evaluate(cell(q.x, na), cell(q.y, nb));
      if (rec.stopped()) return;
      if (f < q.best_f) {
        q.best_f = f;
        q.best_x = q.x;
        q.best_y = q.y;
        q.stall = 0;
      } else {
        ++q.stall;
      }
      if (f < g_f) {
        g_f = f;
        g_x = q.x;
        g_y = q.y;
      }
    }
    for (Particle& q : swarm) {
      if (p.stall_restart != 0 && q.stall >= p.stall_restart) {
        // A particle stuck on its own best restarts elsewhere (the swarm keeps its global best);
        // without this a converged swarm re-evaluates the same cells and finds nothing new.
        reseed(q);
        continue;
      }
      const double r1 = rng.unit(), r2 = rng.unit(), r3 = rng.unit(), r4 = rng.unit();
      q.vx = p.inertia * q.vx + p.cognitive * r1 * (q.best_x - q.x) + p.social * r2 * (g_x - q.x);
      q.vy = p.inertia * q.vy + p.cognitive * r3 * (q.best_y - q.y) + p.social * r4 * (g_y - q.y);
      q.vx = std::clamp(q.vx, -vmax_a, vmax_a);
      q.vy = std::clamp(q.vy, -vmax_b, vmax_b);
      q.x += q.vx;
      q.y += q.vy;
      // Absorbing walls: a particle leaving the grid stops on its border.
      if (q.x < 0 || q.x >= na) {
        q.x = std::clamp(q.x, 0.0, std::nextafter(na, 0.0));
        q.vx = 0;
      }
      if (q.y < 0 || q.y >= nb) {
        q.y = std::clamp(q.y, 0.0, std::nextafter(nb, 0.0));
        q.vy = 0;
      }
    }
  }
}

}  // namespace antcd::detail
