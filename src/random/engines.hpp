// Private: the search engines behind search() (aco.cpp, pso.cpp, ga.cpp,
// exhaustive.cpp: the exhaustive scan and the grid).
#pragma once

#include <antcd/random.hpp>

#include <antcd/rng.hpp>
#include "random/recorder.hpp"

#include <cstdint>

namespace antcd::detail {

/// The engines, one per file. Each runs one run of request.iterations iterations with its own
/// random stream seeded from `seed`, or less if `rec` stops.
/// The colonies read and update `memory` (pheromone, N_c, Eq. 13's bt).
void run_colony(const FeatureSpace& space, const SearchRequest& request, bool improved,
                std::uint64_t seed, ColonyMemory& memory, Recorder& rec);
void run_pso(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
             Recorder& rec);
void run_ga(const FeatureSpace& space, const SearchRequest& request, std::uint64_t seed,
            Recorder& rec);
void run_exhaustive(const FeatureSpace& space, Recorder& rec);
void run_grid(const FeatureSpace& space, Recorder& rec);
/// Every cell of every overlapping leaf pair (FeatureSpace::overlaps), one leaf pair an
/// iteration: the complete search of the cells that can collide.
void run_leaf_pair_scan(const FeatureSpace& space, Recorder& rec);

}  // namespace antcd::detail
