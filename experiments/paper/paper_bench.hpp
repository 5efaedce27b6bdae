// experiments/paper/paper_bench.hpp — `antcd bench paper`: the experiments of the paper's
// section 5.
//
// run_paper_bench generates the veneer production line (shared/production_line.hpp), runs the
// exact method over it as ground truth, and measures:
// - Table 1: time and evaluations for the improved ant colony (MACO) and every other search to
//   find 20/40/60/80 % of the colliding feature pairs of one object pair, for n x n feature pairs,
//   n = 1000 … 5000 (the pair is re-tessellated until each side has n candidate triangles at
//   delta = 0); MACO against ACO in evaluations; the ablation of MACO's switches
//   (shared/maco_ablation.hpp); the cost per evaluation of each search;
// - Table 2: at those rates, A/B = colliding triangle pairs found (each confirmed by the exact
//   triangle test) over the object pair's actual colliding triangle pairs;
// - Figure 3: share of colliding feature pairs found against the ant colony's size;
// - Figures 4-5: object-pair recall, precision and accuracy against time per candidate pair for
//   the section 4 flow (random_detect at delta = 0) with the witness and the paper-centroid
//   verdicts: sphere-obb, aco, maco and exact (Figure 4); maco, pso, ga, exact, plus box-dnn and
//   box-lstm (our learned baselines, trained here on generated scenes, never this one) when antcd
//   was built with libtorch (experiments/paper/learned.hpp) (Figure 5).
// It writes, into `out`: table1.md/.csv/.png, table2.md/.csv/.png, ablation.csv, fig3.csv/.png,
// fig4.csv/.png, fig5.csv/.png, delta_sensitivity.csv, report.md (our figures beside the
// paper's, with the differences computed from this run), the gnuplot scripts (*.gp) and the
// generated scene (scene/). Every file is written atomically.
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
  /// Worker threads (>= 1) for independent runs. Times are per search, but runs sharing the
  /// cores slow each other: quote times only from --threads 1 on an idle machine.
  int threads = 1;
  /// The gnuplot program (a name looked up on PATH, or a path).
  std::string gnuplot = "gnuplot";
};

/// Runs the experiments and writes the files listed above; progress goes to `log`. Throws
/// antcd::ArgumentError for bad options (empty `out`, threads < 1) and antcd::Error when gnuplot
/// is missing or fails, or a file cannot be written.
void run_paper_bench(const PaperBenchOptions& options, std::ostream& log);

}  // namespace antcd::experiments
