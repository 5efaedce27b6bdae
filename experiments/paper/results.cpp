#include "paper/results.hpp"

#include "shared/statistics.hpp"

#include <algorithm>

namespace antcd::experiments::paper {

using shared::mean;
using shared::median;

TableCell table_cell(const Results& r, std::size_t method, std::uint32_t features,
                     std::size_t rate) {
  TableCell c;
  std::vector<double> ms, ev, build, sa, sb, ca, cb, a, b, ab, cov;
  for (const PairRun& run : r.runs) {
    if (run.features != features || run.truth == 0 || method >= run.marks.size()) continue;
    const MarkResult& m = run.marks[method][rate];
    ++c.runs;
    ms.push_back(m.ms);
    ev.push_back(m.evaluations);
    build.push_back(run.build_ms);
    sa.push_back(run.space_a);
    sb.push_back(run.space_b);
    ca.push_back(static_cast<double>(run.candidates_a));
    cb.push_back(static_cast<double>(run.candidates_b));
    b.push_back(static_cast<double>(run.contacts));
    const double contacts = std::max<double>(1, static_cast<double>(run.contacts));
    cov.push_back(static_cast<double>(run.contacts_in_space) / contacts);
    if (m.reached) {
      ++c.reached;
      a.push_back(static_cast<double>(m.found_contacts));
      ab.push_back(static_cast<double>(m.found_contacts) / contacts);
    }
  }
  c.ms = median(ms);
  c.evaluations = median(ev);
  c.build_ms = median(build);
  c.space_a = median(sa);
  c.space_b = median(sb);
  c.candidates_a = median(ca);
  c.candidates_b = median(cb);
  c.b = median(b);
  c.coverage = median(cov);
  c.a = median(a);
  c.ab = median(ab);
  return c;
}

double ns_per_evaluation(const Results& r, std::size_t method) {
  std::vector<double> ns;
  for (const PairRun& run : r.runs) {
    if (method >= run.marks.size()) continue;
    for (std::size_t k = run.marks[method].size(); k-- > 0;) {
      const MarkResult& m = run.marks[method][k];
      if (m.reached && m.evaluations > 0) {
        ns.push_back(1e6 * m.ms / m.evaluations);
        break;
      }
    }
  }
  return median(ns);
}

double fig3_mean(const Results& r, std::uint32_t n, std::uint32_t m) {
  std::vector<double> rate;
  for (const Fig3Run& f : r.fig3) {
    if (f.features == n && f.ants == m) rate.push_back(f.rate);
  }
  return mean(rate);
}

std::vector<std::string> fig4_series(const Results&) {
  return {"sphere-obb", "aco", "maco", "aco (paper centroid)", "maco (paper centroid)", "exact"};
}

std::vector<std::string> fig5_series(const Results& r) {
  std::vector<std::string> v = {"maco", "maco (paper centroid)", "pso", "ga"};
  for (const auto& [name, tally] : r.learned) v.push_back(name);
  v.push_back("exact");
  return v;
}

std::vector<SceneSeries> scene_series(const Results& r, const std::vector<std::string>& methods) {
  std::vector<SceneSeries> out;
  for (const std::string& m : methods) {
    if (m == "exact") {
      out.push_back({m, 0, r.exact});
    } else if (m == "sphere-obb") {
      out.push_back({m, 0, r.sphere_obb});
    } else if (r.learned.count(m) != 0) {
      out.push_back({m, 0, r.learned.at(m)});
    } else {
      for (const std::uint64_t b : r.plan.budgets) out.push_back({m, b, r.random.at({m, b})});
    }
  }
  return out;
}

}  // namespace antcd::experiments::paper
