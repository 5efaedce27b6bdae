// MACO as a scene detector against the exact method, frame by frame, single thread.
//
// Scenes: the generated veneer production line of the paper (90 objects, 300 frames, seed 1) and
// the same layout and motion with real third-party meshes from Debian's assimp-testmodels in
// place of the generated equipment (skipped when /usr/share/assimp/models is absent).
//
// Each benchmark iteration runs every frame of the scene three times, interleaved: the exact
// method on one copy of the scene, then MACO (witness verdict, the library defaults, one
// SceneMemory carried from frame to frame) on another copy, then MACO with
// scan_covered_spaces = false (the colony searches even where its budget covers every cell of the
// overlapping leaf pairs) on a third (separate copies, so that none finds another's poses already
// in its world). Interleaving puts all under the same machine load, so the ratios mean something
// on a shared machine; the absolute times do not.
//
// Counters (medians over the iterations):
//   exact_ms, maco_ms   mean time per frame (pose update, broad phase, narrow phase)
//   ratio               maco_ms / exact_ms (target: <= 2)
//   recall, precision   MACO's colliding object pairs against exact's, over all frames
//   undecided           pair-frames MACO left without a witness when its budget ran out
//   evals_per_frame     fitness evaluations per frame
//   colony_ratio, colony_recall, colony_undecided   the same for MACO without the leaf-pair scan
#include <antcd/scene.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shared/production_line.hpp"

namespace {

using namespace antcd;

shared::GeneratedScene production_line(std::vector<std::filesystem::path> meshes) {
  shared::ProductionLineOptions options;
  options.objects = 90;
  options.frames = 300;
  options.seed = 1;
  options.mesh_files = std::move(meshes);
  return shared::generate_production_line(options);
}

std::vector<std::filesystem::path> assimp_meshes() {
  const std::filesystem::path root = "/usr/share/assimp/models";
  std::vector<std::filesystem::path> out;
  for (const char* f : {"OBJ/spider.obj", "PLY/Wuson.ply", "STL/sphereWithHole.stl",
                        "STL/Spider_binary.stl", "OBJ/box.obj"}) {
    if (std::filesystem::exists(root / f)) out.push_back(root / f);
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void bm_scene(benchmark::State& state, bool real_meshes) {
  std::vector<std::filesystem::path> meshes;
  if (real_meshes) {
    meshes = assimp_meshes();
    if (meshes.empty()) {
      state.SkipWithError("no assimp test models in /usr/share/assimp/models");
      return;
    }
  }
  const shared::GeneratedScene generated = production_line(meshes);
  const Scene exact_scene = shared::make_scene(generated);
  const Scene maco_scene = shared::make_scene(generated);
  const Scene colony_scene = shared::make_scene(generated);
  const std::size_t frames = exact_scene.description().frames;
  SceneQuery exact;
  SceneQuery maco;
  maco.method = Method::Maco;
  SceneQuery colony = maco;
  colony.random.search.ant.scan_covered_spaces = false;

  std::vector<double> exact_ms, maco_ms, ratios, colony_ratios;
  double recall = 1, precision = 1, undecided = 0, evals = 0, colony_recall = 1,
         colony_precision = 1, colony_undecided = 0;
  for (auto _ : state) {
    SceneMemory memory, colony_memory;
    double te = 0, tm = 0, tc = 0;
    std::uint64_t truth = 0, reported = 0, agreed = 0, left = 0, evaluations = 0;
    std::uint64_t c_reported = 0, c_agreed = 0, c_left = 0;
    for (std::size_t f = 0; f < frames; ++f) {
      const FrameResult e = exact_scene.run_frame(f, exact);
      const FrameResult m = maco_scene.run_frame(f, maco, &memory);
      const FrameResult c = colony_scene.run_frame(f, colony, &colony_memory);
      te += e.time_ms;
      tm += m.time_ms;
      tc += c.time_ms;
      const std::set<std::pair<std::uint32_t, std::uint32_t>> t(e.pairs.begin(), e.pairs.end());
      truth += t.size();
      reported += m.pairs.size();
      for (const auto& p : m.pairs) agreed += t.count(p);
      left += m.undecided.size();
      c_reported += c.pairs.size();
      for (const auto& p : c.pairs) c_agreed += t.count(p);
      c_left += c.undecided.size();
      evaluations += m.evaluations;
    }
    exact_ms.push_back(te / static_cast<double>(frames));
    maco_ms.push_back(tm / static_cast<double>(frames));
    ratios.push_back(tm / te);
    colony_ratios.push_back(tc / te);
    colony_recall = truth == 0 ? 1 : static_cast<double>(c_agreed) / static_cast<double>(truth);
    colony_precision =
        c_reported == 0 ? 1 : static_cast<double>(c_agreed) / static_cast<double>(c_reported);
    colony_undecided = static_cast<double>(c_left);
    recall = truth == 0 ? 1 : static_cast<double>(agreed) / static_cast<double>(truth);
    precision = reported == 0 ? 1 : static_cast<double>(agreed) / static_cast<double>(reported);
    undecided = static_cast<double>(left);
    evals = static_cast<double>(evaluations) / static_cast<double>(frames);
  }
  state.counters["exact_ms"] = median(exact_ms);
  state.counters["maco_ms"] = median(maco_ms);
  state.counters["ratio"] = median(ratios);
  state.counters["recall"] = recall;
  state.counters["precision"] = precision;
  state.counters["undecided"] = undecided;
  state.counters["evals_per_frame"] = evals;
  state.counters["colony_ratio"] = median(colony_ratios);
  state.counters["colony_recall"] = colony_recall;
  state.counters["colony_precision"] = colony_precision;
  state.counters["colony_undecided"] = colony_undecided;
}

}  // namespace

BENCHMARK_CAPTURE(bm_scene, production_line, false)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(bm_scene, assimp_meshes, true)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
