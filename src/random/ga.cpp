// Genetic algorithm baseline (the paper's references [8–10]). An individual is a cell (i, j)
// coded as one bit string: ceil(log2 na) bits for i, then ceil(log2 nb) bits for j. A field value
// g of k bits decodes to floor(g * n / 2^k), which covers [0, n) evenly and keeps close codes on
// close indices. Generational replacement with elitism, tournament selection, one-point
// crossover, per-bit mutation. Fitness: the centroid distance, minimised.
#include "random/engines.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace antcd::detail {
namespace {

std::uint32_t bits_for(std::uint32_t n) {
  std::uint32_t bits = 1;
  while (bits < 32 && (std::uint64_t{1} << bits) < n) ++bits;
  return bits;
}

}  // namespace

void run_ga(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
            Recorder& rec) {
  const GaParams& p = request.ga;
  const std::uint32_t na = space.a.size();
  const std::uint32_t nb = space.b.size();
  const std::uint32_t bits_a = bits_for(na);
  const std::uint32_t bits_b = bits_for(nb);
  const std::uint32_t bits = bits_a + bits_b;  // <= 64
  const std::uint64_t mask_a = (std::uint64_t{1} << bits_a) - 1;
  const std::uint64_t mask_b = (std::uint64_t{1} << bits_b) - 1;
  const double mutation = p.mutation < 0 ? 1.0 / bits : p.mutation;
  const std::uint32_t elites = std::min(p.elites, p.population - 1);

  struct Individual {
    std::uint64_t genome = 0;
    double fitness = 0;
  };
  std::vector<Individual> pop(p.population), next(p.population);
  std::vector<std::uint32_t> order(p.population);
  Rng rng(seed ^ 0x6A6A6AULL);

  auto evaluate = [&](Individual& ind) {
    const std::uint64_t ga = ind.genome & mask_a;
    const std::uint64_t gb = (ind.genome >> bits_a) & mask_b;
    const auto i = static_cast<std::uint32_t>((ga * na) >> bits_a);
    const auto j = static_cast<std::uint32_t>((gb * nb) >> bits_b);
    ind.fitness = rec.evaluate(i, j);
  };
  auto random_genome = [&] {
    const std::uint64_t ga = rng.below(mask_a + 1);
    const std::uint64_t gb = rng.below(mask_b + 1);
    return ga | (gb << bits_a);
  };
  auto tournament = [&]() -> const Individual& {
    const Individual* best = &pop[rng.below(p.population)];
    for (std::uint32_t t = 1; t < p.tournament; ++t) {
      const Individual* other = &pop[rng.below(p.population)];
      if (other->fitness < best->fitness) best = other;
    }
    return *best;
  };
  // Each bit flips independently with probability `mutation`. Instead of one draw per bit, the
  // gap to the next flipped bit is drawn from the geometric distribution (same law, one draw per
  // flip plus one).
  const double log_keep = mutation < 1 ? std::log1p(-mutation) : 0;
  auto mutate = [&](std::uint64_t genome) {
    if (mutation <= 0) return genome;
    if (mutation >= 1)
      return genome ^ (bits == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1);
    double bit = -1;
    for (;;) {
      const double u = 1.0 - rng.unit();  // (0, 1]
      bit += 1 + std::floor(std::log(u) / log_keep);
      if (bit >= bits) return genome;
      genome ^= std::uint64_t{1} << static_cast<std::uint32_t>(bit);
    }
  };

  // Generation 1: random population.
  if (!rec.begin_iteration(1)) return;
  for (Individual& ind : pop) {
    ind.genome = random_genome();
    evaluate(ind);
    if (rec.stopped()) return;
  }
  for (std::uint32_t gen = 2; gen <= request.iterations; ++gen) {
    if (!rec.begin_iteration(gen)) return;
    // Elites survive unchanged (and are not evaluated again).
    for (std::uint32_t k = 0; k < p.population; ++k) order[k] = k;
    std::partial_sort(
        order.begin(), order.begin() + elites, order.end(), [&](std::uint32_t x, std::uint32_t y) {
          return pop[x].fitness < pop[y].fitness || (pop[x].fitness == pop[y].fitness && x < y);
        });
    std::uint32_t filled = 0;
    for (; filled < elites; ++filled) next[filled] = pop[order[filled]];
    while (filled < p.population) {
      std::uint64_t c1 = tournament().genome;
      std::uint64_t c2 = tournament().genome;
      if (bits > 1 && rng.unit() < p.crossover) {
        const std::uint32_t cut = 1 + static_cast<std::uint32_t>(rng.below(bits - 1));
        const std::uint64_t low = (std::uint64_t{1} << cut) - 1;
        const std::uint64_t x1 = (c1 & low) | (c2 & ~low);
        const std::uint64_t x2 = (c2 & low) | (c1 & ~low);
        c1 = x1;
        c2 = x2;
      }
      for (const std::uint64_t child : {c1, c2}) {
        if (filled == p.population) break;
        next[filled].genome = mutate(child);
        evaluate(next[filled]);
        if (rec.stopped()) return;
        ++filled;
      }
    }
    pop.swap(next);
  }
}

}  // namespace antcd::detail
