// antcd bench: benchmark suites. `bench paper` reproduces the experiments of the paper's section 5
// (experiments/paper/paper_bench.hpp). Each suite registers itself on the `bench` command through
// an add_bench_*_command(CLI::App& bench, int& code) function; add new suites in
// add_bench_commands.
#include <iostream>
#include <memory>
#include <string>

#include "cli_util.hpp"
#include "paper/paper_bench.hpp"

namespace antcd::cli {

void add_bench_peers_command(CLI::App& bench, int& code);  // cmd_bench_peers.cpp

namespace {

void add_bench_paper_command(CLI::App& bench, int& code) {
  auto opts = std::make_shared<experiments::PaperBenchOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = bench.add_subcommand(
      "paper",
      "Reproduce the paper's section 5 (Tables 1-2, Figures 3-5) on the generated production "
      "line: CSV and Markdown tables, PNG plots (gnuplot) and report.md");
  cmd->add_flag("--quick", opts->quick,
                "Fewer feature counts, frames, seeds and budgets (under 2 minutes; for CI)");
  cmd->add_option("--out", *out, "Output folder (created if missing)")
      ->required()
      ->check(writable_folder())
      ->type_name("DIR");
  cmd->add_option("--seed", opts->seed, "Seed of the scene, the sampling and the searches")
      ->capture_default_str()
      ->check(unsigned_integer());
  cmd->add_option("--threads", opts->threads,
                  "Worker threads for independent runs (times to quote: 1, on an idle machine)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->callback([opts, out, &code] {
    opts->out = *out;
    experiments::run_paper_bench(*opts, std::cerr);
    std::cout << "wrote " << (opts->out / "report.md").string() << '\n';
    code = 0;
  });
}

}  // namespace

void add_bench_commands(CLI::App& app, int& code) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmark suites");
  bench->require_subcommand(1);
  add_bench_paper_command(*bench, code);
  add_bench_peers_command(*bench, code);
}

}  // namespace antcd::cli
