// shared/maco_ablation.hpp — the ablation of MACO's switches (antcd/random.hpp, MacoSwitches):
// each of the four improvements of section 3.4 off alone and on alone, then the first reading
// of Eq. 12 and section 3.4 (1)'s greedy route. One list for the Google Benchmark
// (bench/random_bench.cpp) and `antcd bench paper`, so both measure the same variants.
#pragma once

#include <antcd/random.hpp>

#include <array>

namespace antcd::shared {

struct MacoVariant {
  const char* label;  ///< "MACO-without-1-exponents", …: stable names for files and benchmarks
  const char* what;   ///< a short description for reports
  MacoSwitches switches;
};

/// The switches with one field changed from the defaults (designated initialisers cannot skip
/// the leading fields here without warnings).
inline MacoSwitches maco_switches(bool exponents, bool evaporation, bool heuristic, bool reward,
                                  PathHeuristic reading = PathHeuristic::Remaining,
                                  bool greedy = false) {
  MacoSwitches s;
  s.adaptive_exponents = exponents;
  s.adaptive_evaporation = evaporation;
  s.path_heuristic = heuristic;
  s.reward_punishment = reward;
  s.heuristic = reading;
  s.greedy_moves = greedy;
  return s;
}

inline std::array<MacoVariant, 10> maco_ablation() {
  return {{
      {"MACO-without-1-exponents", "without (1) adaptive exponents, Eqs. 9-10",
       maco_switches(false, true, true, true)},
      {"MACO-without-2-evaporation", "without (2) adaptive evaporation, Eq. 11",
       maco_switches(true, false, true, true)},
      {"MACO-without-3-heuristic", "without (3) path heuristic, Eq. 12",
       maco_switches(true, true, false, true)},
      {"MACO-without-4-reward", "without (4) reward and punishment, Eqs. 13-15",
       maco_switches(true, true, true, false)},
      {"MACO-only-1-exponents", "only (1) adaptive exponents",
       maco_switches(true, false, false, false)},
      {"MACO-only-2-evaporation", "only (2) adaptive evaporation",
       maco_switches(false, true, false, false)},
      {"MACO-only-3-heuristic", "only (3) path heuristic",
       maco_switches(false, false, true, false)},
      {"MACO-only-4-reward", "only (4) reward and punishment",
       maco_switches(false, false, false, true)},
      {"MACO-corridor-eq12", "Eq. 12 in its first (corridor) reading",
       maco_switches(true, true, true, true, PathHeuristic::Corridor)},
      {"MACO-greedy-route", "section 3.4 (1): the most probable route instead of the roulette",
       maco_switches(true, true, true, true, PathHeuristic::Remaining, true)},
  }};
}

}  // namespace antcd::shared
