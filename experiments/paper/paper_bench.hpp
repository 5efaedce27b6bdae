// experiments/paper/paper_bench.hpp — `antcd bench paper`: the experiments of the paper's section 5.
//
// run_paper_bench generates the veneer production line (shared/production_line.hpp), runs the
// exact method over it as ground truth, and measures:
// - Table 1: time for the improved ant colony (MACO) to find 20/40/60/80 % of the colliding feature
//   pairs of one object pair, for 1000² … 5000² feature pairs;
// - Table 2: at those rates, A/B = colliding triangle pairs found (confirmed by the exact triangle
//   test) over the object pair's actual colliding triangle pairs;
// - Figure 3: share of colliding feature pairs found against the ant colony's size;
// - Figure 4: detection rate against time for sphere-obb, aco and maco;
// - Figure 5: detection rate against time for maco, pso, ga and exact, plus box-dnn and box-lstm
//   (our learned baselines, trained here on generated scenes, never this one) when antcd was built
//   with libtorch (experiments/paper/learned.hpp).
// It writes, into `out`: table1.md/.csv/.png, table2.md/.csv/.png, fig3.csv/.png, fig4.csv/.png,
// fig5.csv/.png, report.md (our figures beside the paper's, with the differences explained), the
// gnuplot scripts (*.gp) and the generated scene (scene/). Every file is written atomically.
//
// The PNGs are drawn by gnuplot (Debian package gnuplot-nox), which must be on PATH: when it cannot
// be run, run_paper_bench throws antcd::Error naming gnuplot before any measurement starts.
//
// Quick mode measures fewer feature counts, frames, seeds, colony sizes and budgets (it finishes in
// well under two minutes on two cores in a Release build) and writes every file all the same.
// Apart from the measured times, the results depend only on the options (not on `threads`).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>

namespace antcd::experiments {

struct PaperBenchOptions {
  bool quick = false;
  /// Output folder, created if missing. Files of an earlier run are replaced.
  std::filesystem::path out;
  /// Seed of the scene generator and of every sampling and search.
  std::uint64_t seed = 1;
  /// Worker threads (>= 1) for independent runs; timings are per search, so they stay comparable.
  int threads = 1;
  /// The gnuplot program (a name looked up on PATH, or a path).
  std::string gnuplot = "gnuplot";
};

/// Runs the experiments and writes the files listed above; progress goes to `log`. Throws
/// antcd::ArgumentError for bad options (empty `out`, threads < 1) and antcd::Error when gnuplot
/// is missing or fails, or a file cannot be written.
void run_paper_bench(const PaperBenchOptions& options, std::ostream& log);

}  // namespace antcd::experiments
