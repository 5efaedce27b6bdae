// experiments/paper/plots.hpp — the gnuplot scripts of the PNGs (data inline as datablocks).
#pragma once

#include "paper/results.hpp"

#include <string>
#include <utility>
#include <vector>

namespace antcd::experiments::paper {

/// Tables 1 (times = true) or 2 (A/B) against the detection rate, ours beside the paper's.
std::string table_plot(const Results& r, bool times);
/// Figure 3: MACO's detection rate against the colony size.
std::string fig3_plot(const Results& r);
/// Figures 4-5: recall and accuracy against mean time per candidate pair, with the paper's
/// plateaus (`paper`: method, value) as dotted lines.
std::string scene_plot(const Results& r, const std::string& title,
                       const std::vector<std::string>& methods,
                       const std::vector<std::pair<std::string, double>>& paper);

}  // namespace antcd::experiments::paper
