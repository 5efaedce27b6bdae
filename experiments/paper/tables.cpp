#include "paper/tables.hpp"

#include "paper/format.hpp"
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

std::string table1_md(const Results& r) {
  std::ostringstream s;
  s << "### Table 1 — time for Sphere-OBB-MACO to find 20/40/60/80 % of the colliding feature "
       "pairs (ms)\n\n";
  s << "Ours: median over " << r.plan.pair_frames * r.plan.pair_seeds << " runs ("
    << r.plan.pair_frames << " frames × " << r.plan.pair_seeds
    << " seeds) of the search's wall time when it had found the share; sampling is excluded (its "
       "median is the last column). n/r: the median run did not get there within "
    << r.plan.table_cap
    << " evaluations. Space: median size of the sampled feature space, a × b (a side with fewer "
       "candidate triangles than requested keeps them all). Paper: its Table 1.\n\n";
  s << "| feature pairs | space | 20 %: ours | paper | 40 %: ours | paper | 60 %: ours | paper | "
       "80 %: ours | paper | reached 80 % | sampling ms |\n";
  s << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const std::uint32_t n : r.plan.features) {
    const TableCell first = table_cell(r, 0, n, 0);
    s << "| " << squared(n) << " | " << cell(first.space_a, 0) << " × " << cell(first.space_b, 0);
    TableCell last;
    for (std::size_t k = 0; k < 4; ++k) {
      const TableCell c = table_cell(r, 0, n, k);
      s << " | " << cell(c.ms, 1) << " | " << cell(paper_table1(n, k), 1);
      last = c;
    }
    s << " | " << ratio_text(last.reached, last.runs) << " | " << cell(last.build_ms, 1) << " |\n";
  }
  s << "\nThe same measurement for every search of the library (median ms to find 80 %; median "
       "evaluations in brackets). Exhaustive is the row-by-row scan of the whole space, the "
       "reference every heuristic search must beat:\n\n";
  s << "| feature pairs |";
  for (const Method a : kTableMethods) s << ' ' << method_key(a) << " |";
  s << "\n| --- |";
  for (std::size_t g = 0; g < std::size(kTableMethods); ++g) s << " ---: |";
  s << '\n';
  for (const std::uint32_t n : r.plan.features) {
    s << "| " << squared(n) << " |";
    for (std::size_t g = 0; g < std::size(kTableMethods); ++g) {
      const TableCell c = table_cell(r, g, n, 3);
      s << ' ' << cell(c.ms, 1) << " (" << cell(c.evaluations, 0) << ") |";
    }
    s << '\n';
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
       "mean_frame_ms,recall,precision,accuracy\n";
  const double frames = static_cast<double>(r.scene_frames.size());
  for (const SceneSeries& x : scene_series(r, methods)) {
    const Tally& t = x.tally;
    s << x.method << ',' << x.budget << ',' << r.scene_frames.size() << ',' << t.total() << ','
      << (t.tp + t.fn) << ',' << num(t.pair_ms(), 4) << ',' << num(t.ms / frames, 3) << ','
      << num(t.recall(), 4) << ',' << num(t.precision(), 4) << ',' << num(t.accuracy(), 4) << '\n';
  }
  return s.str();
}

std::string scene_md(const Results& r, const std::vector<std::string>& methods) {
  std::ostringstream s;
  s << "| method | budget (evaluations / pair) | mean ms / pair | recall | precision | accuracy "
       "|\n| --- | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SceneSeries& x : scene_series(r, methods)) {
    const Tally& t = x.tally;
    s << "| " << x.method << " | " << (x.budget == 0 ? std::string("-") : std::to_string(x.budget))
      << " | " << num(t.pair_ms(), 3) << " | " << num(t.recall(), 3) << " | "
      << num(t.precision(), 3) << " | " << num(t.accuracy(), 3) << " |\n";
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
  const Tally& base = r.random.at({"maco", p.budgets.back()});
  s << "maco,1," << p.budgets.back() << ',' << num(base.pair_ms(), 4) << ','
    << num(base.recall(), 4) << ',' << num(base.precision(), 4) << ',' << num(base.accuracy(), 4)
    << '\n';
  for (const auto& [scale, t] : r.sensitivity) {
    s << "maco," << num(scale, 2) << ',' << p.budgets.back() << ',' << num(t.pair_ms(), 4) << ','
      << num(t.recall(), 4) << ',' << num(t.precision(), 4) << ',' << num(t.accuracy(), 4)
      << '\n';
  }
  return s.str();
}

std::string delta_sensitivity_md(const Results& r) {
  const Tally& top = r.random.at({"maco", r.plan.budgets.back()});
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
