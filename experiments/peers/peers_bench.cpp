// `antcd bench peers`: antcd against FCL and Bullet (see peers_bench.hpp). This file runs the
// selected protocols in order; scenes.cpp, pairs.cpp, build.cpp and scale.cpp measure, report.cpp
// writes.
#include "peers/peers_bench.hpp"

#include "peers/adapters/peer_mesh.hpp"
#include "peers/build.hpp"
#include "peers/generated_scenes.hpp"
#include "peers/machine.hpp"
#include "peers/pairs.hpp"
#include "peers/report.hpp"
#include "peers/scale.hpp"
#include "peers/scenes.hpp"
#include "shared/production_line.hpp"

#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd::experiments {

using namespace peers_bench;

PeersBenchResult run_peers_bench(const PeersBenchOptions& options, std::ostream& log) {
  if (options.threads < 1) throw antcd::ArgumentError("--threads must be at least 1");
  const auto total_start = std::chrono::steady_clock::now();
  const std::size_t frames_default = options.quick ? 30 : 300;
  const std::size_t frames_wanted = options.frames > 0 ? options.frames : frames_default;
  const std::string load_start = load_average();

  PeersBenchResult result;
  std::ostringstream md;
  std::vector<Target> targets;

  write_header(md, options, frames_wanted);

  // ---- Scenes ----
  std::vector<SceneRun> scene_runs;
  if (options.run_scenes) {
    const WorkDir work(options.work_dir);
    std::vector<std::pair<std::string, std::unique_ptr<Scene>>> scenes;
    std::vector<std::string> descriptions;
    if (!options.scene_file.empty()) {
      auto scene = std::make_unique<Scene>(load_scene(options.scene_file));
      descriptions.push_back("scene file " + options.scene_file.string());
      scenes.emplace_back(options.scene_file.filename().string(), std::move(scene));
    } else {
      shared::ProductionLineOptions paper;
      paper.frames = frames_wanted;
      log << "generating the paper scene (90 objects, 750 vertices, " << frames_wanted
          << " frames)\n";
      const shared::GeneratedScene g = shared::generate_production_line(paper);
      scenes.emplace_back("paper", load_generated(g, work.path() / "paper"));
      descriptions.push_back(
          "the paper's production line: shared/production_line.hpp with default options "
          "(90 objects, ~750 vertices per mesh, seed 1)");
      shared::ProductionLineOptions dense = paper;
      dense.objects = 180;
      shared::GeneratedScene gd = shared::generate_production_line(dense);
      pack_along_line(gd, 0.5);
      scenes.emplace_back("dense", load_generated(gd, work.path() / "dense"));
      descriptions.push_back(
          "dense: the same generator with 180 objects, then every translation's x (the line's "
          "direction) multiplied by 0.5, so neighbouring stations overlap");
    }
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const Scene& scene = *scenes[s].second;
      const std::size_t frames = std::min(frames_wanted, scene.description().frames);
      log << "scene " << scenes[s].first << ": " << scene.object_count() << " objects, " << frames
          << " frames\n";
      SceneRun run =
          run_scene(scene, scenes[s].first, frames, options.threads, SceneEngines{}, &log);
      run.description = descriptions[s];
      scene_runs.push_back(std::move(run));
    }
  }

  if (!scene_runs.empty()) write_scenes(md, scene_runs, targets, result);

  // ---- Pairs, build, memory ----
  if (options.run_pairs) {
    const std::vector<std::size_t> sizes =
        options.quick ? std::vector<std::size_t>{1'000, 10'000}
                      : std::vector<std::size_t>{1'000, 10'000, 100'000, 1'000'000};
    const std::size_t poses = options.quick ? 100 : 1000;
    std::vector<PairCell> cells;
    std::vector<BuildRow> builds;
    for (const std::size_t size : sizes) {
      log << "pairs: nominal " << size << " triangles, " << poses << " poses\n";
      auto c = run_pairs_at(size, poses, log);
      cells.insert(cells.end(), c.begin(), c.end());
      const Mesh mesh = peers::benchmark_torus(size);
      const int reps = options.quick ? 3 : (size >= 1'000'000 ? 3 : 5);
      builds.push_back(measure_build(size, mesh, reps));
      log << "  build: " << size << " done\n";
    }
    write_pairs(md, cells, poses, targets, result);
    write_build(md, builds, options.quick, targets);
    write_pair_csvs(cells, builds, result);
  }

  // ---- Scale ----
  if (options.run_scale) {
    const WorkDir work(options.work_dir.empty() ? std::filesystem::path()
                                                : options.work_dir / "scale");
    struct Spec {
      std::size_t objects;
      std::size_t vertices;
    };
    const std::vector<Spec> specs =
        options.quick ? std::vector<Spec>{{90, 750}, {1000, 200}}
                      : std::vector<Spec>{{90, 750}, {1000, 1000}, {3000, 333}, {10000, 100}};
    const std::size_t frames = options.quick ? 5 : 30;
    std::vector<ScaleRow> rows;
    for (const Spec& s : specs) {
      log << "scale: " << s.objects << " objects, " << s.vertices << " vertices per mesh\n";
      rows.push_back(run_scale_row(s.objects, s.vertices, frames,
                                   work.path() / ("line_" + std::to_string(s.objects)), log));
    }
    write_scale(md, rows, frames, result);
  }

  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - total_start).count();
  write_footer(md, targets, result, total_s, load_start);
  if (!scene_runs.empty()) write_scene_csvs(scene_runs, result);
  result.report_markdown = md.str();
  return result;
}

}  // namespace antcd::experiments
