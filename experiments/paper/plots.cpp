#include "paper/plots.hpp"

#include "paper/format.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace antcd::experiments::paper {

namespace {

/// A gnuplot datablock $name holding the rows (NaN where a value is missing).
std::string datablock(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::ostringstream s;
  s << '$' << name << " << EOD\n";
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (k) s << ' ';
      if (std::isfinite(row[k])) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6g", row[k]);
        s << buf;
      } else {
        s << "NaN";
      }
    }
    s << '\n';
  }
  s << "EOD\n";
  return s.str();
}

const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                         "#9467bd", "#8c564b", "#e377c2", "#17becf"};

constexpr const char* kCentroid = " (paper centroid)";

/// "maco (paper centroid)" → "maco": a search keeps its colour in both verdict modes.
std::string base_name(const std::string& method) {
  const std::size_t at = method.find(kCentroid);
  return at == std::string::npos ? method : method.substr(0, at);
}

}  // namespace

std::string table_plot(const Results& r, bool times) {
  std::ostringstream s;
  std::ostringstream plot;
  for (std::size_t k = 0; k < r.plan.features.size(); ++k) {
    const std::uint32_t n = r.plan.features[k];
    std::vector<std::vector<double>> ours, paper;
    for (std::size_t q = 0; q < 4; ++q) {
      const TableCell c = table_cell(r, 0, n, q);
      ours.push_back({100 * kRates[q], times ? c.ms : 100 * c.ab});
      paper.push_back({100 * kRates[q], times ? paper_table1(n, q) : 100 * paper_table2(n, q)});
    }
    s << datablock("ours" + std::to_string(n), ours)
      << datablock("paper" + std::to_string(n), paper);
    const std::string color = kColors[k % std::size(kColors)];
    plot << (k ? ", \\\n     " : "plot ") << "$ours" << n
         << " using 1:2 with linespoints lw 2 pt 7 lc rgb '" << color << "' title 'ours " << n
         << "^2', $paper" << n << " using 1:2 with linespoints dt 2 pt 6 lc rgb '" << color
         << "' title 'paper " << n << "^2'";
  }
  s << "set key outside right\nset grid\nset xlabel 'detection rate (% of colliding feature pairs "
       "found)'\nset xrange [15:85]\nset xtics 20,20,80\n";
  if (times) {
    s << "set title 'Table 1: time for MACO to reach each detection rate (solid: ours, dashed: "
         "paper)'\nset ylabel 'time (ms)'\nset logscale y\n";
  } else {
    s << "set title 'Table 2: A/B at each detection rate (solid: ours, dashed: paper)'\nset ylabel "
         "'A/B (%)'\nset yrange [0:100]\n";
  }
  s << plot.str() << '\n';
  return s.str();
}

std::string fig3_plot(const Results& r) {
  std::ostringstream s;
  std::ostringstream plot;
  for (std::size_t k = 0; k < r.plan.features.size(); ++k) {
    const std::uint32_t n = r.plan.features[k];
    std::vector<std::vector<double>> rows;
    for (const std::uint32_t m : r.plan.colony_sizes)
      rows.push_back({double(m), fig3_mean(r, n, m)});
    std::string name = "f";
    name += std::to_string(n);
    s << datablock(name, rows);
    plot << (k ? ", \\\n     " : "plot ") << "$f" << n
         << " using 1:2 with linespoints lw 2 pt 7 lc rgb '" << kColors[k % std::size(kColors)]
         << "' title '" << n << "^2'";
  }
  s << "set title 'Figure 3: MACO detection rate against ant colony size (N = 100 iterations)'\n"
       "set xlabel 'ant colony size m'\nset ylabel 'share of colliding feature pairs found'\n"
       "set yrange [0:*]\nset grid\nset key outside right title 'feature pairs'\n";
  s << plot.str() << '\n';
  return s.str();
}

/// Figures 4-5: recall and accuracy against mean time per candidate pair, with the paper's
/// plateaus as dotted lines.
std::string scene_plot(const Results& r, const std::string& title,
                       const std::vector<std::string>& methods,
                       const std::vector<std::pair<std::string, double>>& paper) {
  std::ostringstream s;
  std::map<std::string, std::string> color;
  for (std::size_t k = 0; k < methods.size(); ++k) {
    const std::string base = base_name(methods[k]);
    if (color.count(base) == 0) {
      const std::size_t next = color.size();
      color[base] = kColors[next % std::size(kColors)];
    }
    color[methods[k]] = color[base];
    std::vector<std::vector<double>> rows;
    for (const SceneSeries& x : scene_series(r, {methods[k]})) {
      rows.push_back({x.tally.pair_ms(), x.tally.recall(), x.tally.accuracy()});
    }
    std::string name = "m";  // not "m" + to_string: GCC 12 warns falsely (-Wrestrict) there
    name += std::to_string(k);
    s << datablock(name, rows);
  }
  s << "set multiplot layout 1,2 title '" << title << "'\n";
  s << "set logscale x\nset grid\nset xlabel 'mean time per candidate pair (ms, log scale)'\n"
       "set yrange [0:1.05]\nset key bottom right\n";
  for (int panel = 0; panel < 2; ++panel) {
    s << "set title '"
      << (panel == 0 ? "recall: colliding object pairs detected"
                     : "accuracy: candidate pairs decided as exact does (vs the paper)")
      << "'\n";
    s << "set ylabel '" << (panel == 0 ? "recall" : "accuracy") << "'\n";
    s << "plot ";
    for (std::size_t k = 0; k < methods.size(); ++k) {
      const bool single =
          methods[k] == "exact" || methods[k] == "sphere-obb" || r.learned.count(methods[k]) != 0;
      s << (k ? ", \\\n     " : "") << "$m" << k << " using 1:" << (panel == 0 ? 2 : 3) << " with "
        << (single                                ? "points pt 7 ps 2"
            : methods[k] != base_name(methods[k]) ? "linespoints lw 2 dt 2 pt 6"
                                                  : "linespoints lw 2 pt 7")
        << " lc rgb '" << color[methods[k]] << "' title '" << methods[k] << "'";
    }
    if (panel == 1) {
      for (const auto& [m, v] : paper) {
        s << ", \\\n     " << v << " with lines dt 3 lw 1.5 lc rgb '"
          << (color.count(m) ? color[m] : std::string("#7f7f7f")) << "' title 'paper " << m << " "
          << v << "'";
      }
    }
    s << '\n';
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace antcd::experiments::paper
