// experiments/paper/tables.hpp — the CSV files and Markdown tables of `antcd bench paper`.
#pragma once

#include "paper/results.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace antcd::experiments::paper {

std::string table1_csv(const Results& r);
std::string table2_csv(const Results& r);
/// table1.md: MACO against the paper, then every search at 80 %.
std::string table1_md(const Results& r);
std::string table2_md(const Results& r);
/// "1000 × 1000", or "1000² asked: 784 × 1000" when a side had fewer candidates than n.
std::string space_label(const TableCell& c, std::uint32_t n);
/// MACO against ACO: median evaluations to each rate, per feature count.
std::string maco_aco_md(const Results& r);
/// ablation.csv / the ablation table: MACO's switches (shared/maco_ablation.hpp) at
/// Plan::ablation_features, evaluations to each rate against MACO with every switch at default.
std::string ablation_csv(const Results& r);
std::string ablation_md(const Results& r);
/// Cost per fitness evaluation of each search (ns_per_evaluation).
std::string cost_md(const Results& r);
std::string fig3_csv(const Results& r);
/// Figure 3 as a table: the mean rate per colony size, our best size and the paper's.
std::string fig3_md(const Results& r);
/// fig4.csv / fig5.csv: one row per method and budget.
std::string scene_csv(const Results& r, const std::vector<std::string>& methods);
std::string scene_md(const Results& r, const std::vector<std::string>& methods);
/// delta_sensitivity.csv: MACO with the paper's centroid verdict at the largest budget, δc scaled.
std::string delta_sensitivity_csv(const Results& r);
/// The same as a Markdown table, the unscaled δc first.
std::string delta_sensitivity_md(const Results& r);

/// The colony size with the highest mean rate at n features (the first of equals).
std::uint32_t best_colony_size(const Results& r, std::uint32_t n);

}  // namespace antcd::experiments::paper
