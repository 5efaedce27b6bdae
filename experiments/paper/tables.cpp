#include "paper/tables.hpp"

#include "paper/format.hpp"
#include "shared/maco_ablation.hpp"
#include "shared/statistics.hpp"

#include <sstream>

namespace antcd::experiments::paper {

using shared::mean;
using shared::median;

std::string table1_csv(const Results& r) {
  std::ostringstream s;
  s << "method,features,candidates_a,candidates_b,space_a,space_b,target_rate,runs,reached,"
       "median_ms,median_evaluations,median_build_ms,paper_ms\n";
  for (std::size_t g = 0; g < std::size(kTableMethods); ++g) {
    for (const std::uint32_t n : r.plan.features) {
      for (std::size_t k = 0; k < 4; ++k) {
        const TableCell c = table_cell(r, g, n, k);
        s << method_key(kTableMethods[g]) << ',' << n << ',' << num(c.candidates_a, 0) << ','
          << num(c.candidates_b, 0) << ',' << num(c.space_a, 0) << ',' << num(c.space_b, 0) << ','
          << num(kRates[k], 1) << ',' << c.runs << ',' << c.reached << ',' << num(c.ms, 3) << ','
          << num(c.evaluations, 0) << ',' << num(c.build_ms, 3) << ','
          << (g == 0 ? num(paper_table1(n, k), 1) : "") << '\n';
      }
    }
  }
  return s.str();
}

std::string table2_csv(const Results& r) {
  std::ostringstream s;
  s << "method,features,target_rate,runs,reached,median_a,median_b,median_ab,median_coverage,"
       "paper_ab\n";
  for (std::size_t g = 0; g < std::size(kTableMethods); ++g) {
    for (const std::uint32_t n : r.plan.features) {
      for (std::size_t k = 0; k < 4; ++k) {
        const TableCell c = table_cell(r, g, n, k);
        s << method_key(kTableMethods[g]) << ',' << n << ',' << num(kRates[k], 1) << ',' << c.runs
          << ',' << c.reached << ',' << num(c.a, 1) << ',' << num(c.b, 1) << ',' << num(c.ab, 4)
          << ',' << num(c.coverage, 4) << ',' << (g == 0 ? num(paper_table2(n, k), 3) : "") << '\n';
      }
    }
  }
  return s.str();
}

std::string space_label(const TableCell& c, std::uint32_t n) {
  if (c.space_a == n && c.space_b == n) return std::to_string(n) + " × " + std::to_string(n);
  return squared(n) + " asked: " + cell(c.space_a, 0) + " × " + cell(c.space_b, 0);
}

std::string table1_md(const Results& r) {
  std::ostringstream s;
  s << "### Table 1 — time for Sphere-OBB-MACO to find 20/40/60/80 % of the colliding feature "
       "pairs (ms, evaluations in brackets)\n\n";
  s << "Ours: median over " << r.plan.pair_frames * r.plan.pair_seeds << " runs ("
    << r.plan.pair_frames << " frames × " << r.plan.pair_seeds
    << " seeds) of the search's wall time when it had found the share, and of the fitness "
       "evaluations it had spent; sampling is excluded (its median is the last column). n/r: the "
       "median run did not get there within "
    << r.plan.table_cap
    << " evaluations. Space: the median sampled feature space, a × b features (it reads n × n "
       "when both sides had at least n candidate triangles). Paper: its Table 1.\n\n";
  s << "| feature pairs (space) | 20 %: ours | paper | 40 %: ours | paper | 60 %: ours | paper | "
       "80 %: ours | paper | reached 80 % | sampling ms |\n";
  s << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const std::uint32_t n : r.plan.features) {
    const TableCell first = table_cell(r, 0, n, 0);
    s << "| " << space_label(first, n);
    TableCell last;
    for (std::size_t k = 0; k < 4; ++k) {
      const TableCell c = table_cell(r, 0, n, k);
      s << " | " << cell(c.ms, 1) << " (" << cell(c.evaluations, 0) << ") | "
        << cell(paper_table1(n, k), 1);
      last = c;
    }
    s << " | " << ratio_text(last.reached, last.runs) << " | " << cell(last.build_ms, 1) << " |\n";
  }
  s << "\nEvery search of the library on the same spaces (median ms to find 80 %; median "
       "evaluations in brackets). Exhaustive is the row-by-row scan of the whole space, the "
       "reference every heuristic search must beat:\n\n";
  s << "| feature pairs |";
  for (const Method a : kTableMethods) s << ' ' << method_key(a) << " |";
  s << "\n| --- |";
  for (std::size_t g = 0; g < std::size(kTableMethods); ++g) s << " ---: |";
  s << '\n';
  for (const std::uint32_t n : r.plan.features) {
    s << "| " << space_label(table_cell(r, 0, n, 0), n) << " |";
    for (std::size_t g = 0; g < std::size(kTableMethods); ++g) {
      const TableCell c = table_cell(r, g, n, 3);
      s << ' ' << cell(c.ms, 1) << " (" << cell(c.evaluations, 0) << ") |";
    }
    s << '\n';
  }
  return s.str();
}

std::string maco_aco_md(const Results& r) {
  std::ostringstream s;
  s << "| feature pairs |";
  for (std::size_t k = 0; k < 4; ++k) {
    s << ' ' << num(100 * kRates[k], 0) << " %: maco | aco | aco / maco |";
  }
  s << "\n| --- |";
  for (std::size_t k = 0; k < 4; ++k) s << " ---: | ---: | ---: |";
  s << '\n';
  for (const std::uint32_t n : r.plan.features) {
    s << "| " << space_label(table_cell(r, 0, n, 0), n) << " |";
    for (std::size_t k = 0; k < 4; ++k) {
      const TableCell m = table_cell(r, 0, n, k);
      const TableCell a = table_cell(r, 1, n, k);
      s << ' ' << cell(m.evaluations, 0) << " | " << cell(a.evaluations, 0) << " | "
        << cell(a.evaluations / m.evaluations, 2) << " |";
    }
    s << '\n';
  }
  return s.str();
}

std::string ablation_csv(const Results& r) {
  std::ostringstream s;
  s << "variant,features,target_rate,runs,reached,median_ms,median_evaluations,"
       "evaluations_vs_maco\n";
  const std::uint32_t n = r.plan.ablation_features;
  const auto variants = shared::maco_ablation();
  for (std::size_t v = 0; v <= variants.size(); ++v) {
    const std::size_t g = v == 0 ? 0 : std::size(kTableMethods) + v - 1;
    for (std::size_t k = 0; k < 4; ++k) {
      const TableCell c = table_cell(r, g, n, k);
      const TableCell base = table_cell(r, 0, n, k);
      s << (v == 0 ? std::string("MACO") : std::string(variants[v - 1].label)) << ',' << n << ','
        << num(kRates[k], 1) << ',' << c.runs << ',' << c.reached << ',' << num(c.ms, 3) << ','
        << num(c.evaluations, 0) << ',' << num(c.evaluations / base.evaluations, 3) << '\n';
    }
  }
  return s.str();
}

std::string ablation_md(const Results& r) {
  std::ostringstream s;
  const std::uint32_t n = r.plan.ablation_features;
  s << "| variant at " << squared(n)
    << " | 20 % | 40 % | 60 % | 80 % | 80 %: ms | 80 %: evaluations / MACO's | reached 80 % |\n"
       "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  const auto variants = shared::maco_ablation();
  const TableCell base = table_cell(r, 0, n, 3);
  for (std::size_t v = 0; v <= variants.size(); ++v) {
    const std::size_t g = v == 0 ? 0 : std::size(kTableMethods) + v - 1;
    s << "| "
      << (v == 0 ? std::string("MACO (all four, defaults)") : std::string(variants[v - 1].what));
    for (std::size_t k = 0; k < 4; ++k) s << " | " << cell(table_cell(r, g, n, k).evaluations, 0);
    const TableCell c = table_cell(r, g, n, 3);
    s << " | " << cell(c.ms, 1) << " | " << cell(c.evaluations / base.evaluations, 2) << " | "
      << ratio_text(c.reached, c.runs) << " |\n";
  }
  // The classic colony (all four off) for reference.
  s << "| ACO (all four off, fixed ρ)";
  for (std::size_t k = 0; k < 4; ++k) s << " | " << cell(table_cell(r, 1, n, k).evaluations, 0);
  const TableCell aco = table_cell(r, 1, n, 3);
  s << " | " << cell(aco.ms, 1) << " | " << cell(aco.evaluations / base.evaluations, 2) << " | "
    << ratio_text(aco.reached, aco.runs) << " |\n";
  return s.str();
}

std::string cost_md(const Results& r) {
  std::ostringstream s;
  s << "| search | ns / evaluation |\n| --- | ---: |\n";
  for (std::size_t g = 0; g < std::size(kTableMethods); ++g) {
    s << "| " << method_key(kTableMethods[g]) << " | " << cell(ns_per_evaluation(r, g), 1)
      << " |\n";
  }
  return s.str();
}

std::string table2_md(const Results& r) {
  std::ostringstream s;
  s << "### Table 2 — A/B (%) of Sphere-OBB-MACO at each detection rate\n\n";
  s << "A: distinct triangle pairs among the feature pairs found when the rate is reached that "
       "the exact triangle test confirms (they touch at the same pose); B: every colliding "
       "triangle pair of the two objects (collide() with all contacts). Median over the runs "
       "that reached the rate. Coverage: the share of B whose two triangles are both in the "
       "sample, i.e. the highest A/B any search of that space can reach.\n\n";
  s << "| feature pairs | B | coverage % | 20 %: ours | paper | 40 %: ours | paper | 60 %: ours "
       "| paper | 80 %: ours | paper |\n";
  s << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const std::uint32_t n : r.plan.features) {
    const TableCell first = table_cell(r, 0, n, 0);
    s << "| " << squared(n) << " | " << cell(first.b, 0) << " | " << pct(first.coverage);
    for (std::size_t k = 0; k < 4; ++k) {
      const TableCell c = table_cell(r, 0, n, k);
      s << " | " << pct(c.ab) << " | " << pct(paper_table2(n, k));
    }
    s << " |\n";
  }
  return s.str();
}

std::string fig3_csv(const Results& r) {
  std::ostringstream s;
  s << "features,ants,runs,mean_rate,median_rate,mean_ms,mean_evaluations\n";
  for (const std::uint32_t n : r.plan.features) {
    for (const std::uint32_t m : r.plan.colony_sizes) {
      std::vector<double> rate, ms, ev;
      for (const Fig3Run& f : r.fig3) {
        if (f.features != n || f.ants != m) continue;
        rate.push_back(f.rate);
        ms.push_back(f.ms);
        ev.push_back(f.evaluations);
      }
      s << n << ',' << m << ',' << rate.size() << ',' << num(mean(rate), 4) << ','
        << num(median(rate), 4) << ',' << num(mean(ms), 3) << ',' << num(mean(ev), 0) << '\n';
    }
  }
  return s.str();
}

std::string scene_csv(const Results& r, const std::vector<std::string>& methods) {
  std::ostringstream s;
  s << "method,budget_evaluations,frames,candidate_pairs,colliding_pairs,mean_pair_ms,"
       "mean_frame_ms,time_vs_exact,mean_pair_evaluations,recall,precision,accuracy\n";
  const double frames = static_cast<double>(r.scene_frames.size());
  for (const SceneSeries& x : scene_series(r, methods)) {
    const Tally& t = x.tally;
    s << x.method << ',' << x.budget << ',' << r.scene_frames.size() << ',' << t.total() << ','
      << (t.tp + t.fn) << ',' << num(t.pair_ms(), 4) << ',' << num(t.ms / frames, 3) << ','
      << num(t.ms / r.exact.ms, 3) << ',' << num(t.pair_evaluations(), 1) << ','
      << num(t.recall(), 4) << ',' << num(t.precision(), 4) << ',' << num(t.accuracy(), 4) << '\n';
  }
  return s.str();
}

std::string scene_md(const Results& r, const std::vector<std::string>& methods) {
  std::ostringstream s;
  s << "| method | budget (evaluations / pair) | mean ms / pair | × exact's time | mean "
       "evaluations / pair | recall | precision | accuracy |\n"
       "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SceneSeries& x : scene_series(r, methods)) {
    const Tally& t = x.tally;
    const bool random = x.budget != 0;
    s << "| " << x.method << " | " << (random ? std::to_string(x.budget) : std::string("-"))
      << " | " << num(t.pair_ms(), 4) << " | " << num(t.ms / r.exact.ms, 2) << " | "
      << (random ? num(t.pair_evaluations(), 0) : std::string("-")) << " | " << num(t.recall(), 3)
      << " | " << num(t.precision(), 3) << " | " << num(t.accuracy(), 3) << " |\n";
  }
  return s.str();
}

std::uint32_t best_colony_size(const Results& r, std::uint32_t n) {
  double best = -1;
  std::uint32_t best_m = 0;
  for (const std::uint32_t m : r.plan.colony_sizes) {
    const double v = fig3_mean(r, n, m);
    if (v > best) {
      best = v;
      best_m = m;
    }
  }
  return best_m;
}

std::string fig3_md(const Results& r) {
  const Plan& p = r.plan;
  std::ostringstream s;
  s << "| feature pairs |";
  for (const std::uint32_t m : p.colony_sizes) s << " m = " << m << " |";
  s << " best m: ours | best m: paper |\n| --- |";
  for (std::size_t k = 0; k < p.colony_sizes.size(); ++k) s << " ---: |";
  s << " ---: | ---: |\n";
  for (const std::uint32_t n : p.features) {
    s << "| " << squared(n) << " |";
    for (const std::uint32_t m : p.colony_sizes) s << ' ' << pct(fig3_mean(r, n, m)) << " % |";
    const int row = feature_row(n);
    s << ' ' << best_colony_size(r, n) << " | "
      << (row < 0 ? std::string("-") : std::to_string(kPaperBestAnts[row])) << " |\n";
  }
  return s.str();
}

std::string delta_sensitivity_csv(const Results& r) {
  const Plan& p = r.plan;
  std::ostringstream s;
  s << "method,delta_scale,budget_evaluations,mean_pair_ms,recall,precision,accuracy\n";
  const Tally& base = r.random.at({"maco (paper centroid)", p.budgets.back()});
  s << "maco,1," << p.budgets.back() << ',' << num(base.pair_ms(), 4) << ','
    << num(base.recall(), 4) << ',' << num(base.precision(), 4) << ',' << num(base.accuracy(), 4)
    << '\n';
  for (const auto& [scale, t] : r.sensitivity) {
    s << "maco," << num(scale, 2) << ',' << p.budgets.back() << ',' << num(t.pair_ms(), 4) << ','
      << num(t.recall(), 4) << ',' << num(t.precision(), 4) << ',' << num(t.accuracy(), 4) << '\n';
  }
  return s.str();
}

std::string delta_sensitivity_md(const Results& r) {
  const Tally& top = r.random.at({"maco (paper centroid)", r.plan.budgets.back()});
  std::ostringstream s;
  s << "| δc scale | mean ms / pair | recall | precision | accuracy |\n"
       "| ---: | ---: | ---: | ---: | ---: |\n";
  s << "| 1 | " << num(top.pair_ms(), 3) << " | " << num(top.recall(), 3) << " | "
    << num(top.precision(), 3) << " | " << num(top.accuracy(), 3) << " |\n";
  for (auto it = r.sensitivity.rbegin(); it != r.sensitivity.rend(); ++it) {
    const Tally& t = it->second;
    s << "| " << num(it->first, 2) << " | " << num(t.pair_ms(), 3) << " | " << num(t.recall(), 3)
      << " | " << num(t.precision(), 3) << " | " << num(t.accuracy(), 3) << " |\n";
  }
  return s.str();
}

}  // namespace antcd::experiments::paper
