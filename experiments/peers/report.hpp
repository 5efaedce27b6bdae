// experiments/peers/report.hpp — the Markdown report and CSV files of `antcd bench peers`, written
// section by section from the measured runs; each section adds the targets it checks.
#pragma once

#include "peers/build.hpp"
#include "peers/pairs.hpp"
#include "peers/peers_bench.hpp"
#include "peers/scale.hpp"
#include "peers/scenes.hpp"

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace antcd::experiments::peers_bench {

/// One line of the targets table.
struct Target {
  std::string what;
  std::string measured;
  std::string verdict;  ///< "met", "MISSED", "not measured"
};

/// Title, run options, machine, peer versions and how times are taken.
void write_header(std::ostream& md, const PeersBenchOptions& options, std::size_t frames_wanted);
/// Per scene: the engines' times and ratios, agreement with antcd, the disagreements. Sets
/// result.antcd_fcl_agree and result.bullet_disagreements.
void write_scenes(std::ostream& md, const std::vector<SceneRun>& scene_runs,
                  std::vector<Target>& targets, PeersBenchResult& result);
/// The pair protocol's table; clears result.antcd_fcl_agree on any disagreement.
void write_pairs(std::ostream& md, const std::vector<PairCell>& cells, std::size_t poses,
                 std::vector<Target>& targets, PeersBenchResult& result);
/// Build time and memory per triangle.
void write_build(std::ostream& md, const std::vector<BuildRow>& builds, bool quick,
                 std::vector<Target>& targets);
/// pairs.csv and build.csv.
void write_pair_csvs(const std::vector<PairCell>& cells, const std::vector<BuildRow>& builds,
                     PeersBenchResult& result);
/// The scale table and scale.csv.
void write_scale(std::ostream& md, const std::vector<ScaleRow>& rows, std::size_t frames,
                 PeersBenchResult& result);
/// The targets table, the overall agreement, run time and load.
void write_footer(std::ostream& md, const std::vector<Target>& targets,
                  const PeersBenchResult& result, double total_s, const std::string& load_start);
/// scenes.csv and disagreements.csv.
void write_scene_csvs(const std::vector<SceneRun>& scene_runs, PeersBenchResult& result);

}  // namespace antcd::experiments::peers_bench
