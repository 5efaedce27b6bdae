// antcd demo: the main job. Generates the paper's production-line scene in a temporary folder,
// runs the exact method (ground truth) and the improved ant colony on it, and compares them.
#include <antcd/scene.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_util.hpp"
#include "production_line.hpp"
#include "run_result.hpp"

namespace antcd::cli {

namespace {

struct DemoOptions {
  std::size_t objects = 90;
  std::size_t frames = 300;
  std::uint64_t seed = 1;
  int threads = 1;
  bool keep = false;
};

// Removes the temporary folder on every exit path unless asked to keep it.
struct TempDir {
  std::filesystem::path path;
  bool keep = false;
  ~TempDir() {
    if (!keep && !path.empty()) {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  }
};

void print_row(const char* name, const experiments::RunResult& r, const experiments::Metrics& m) {
  std::printf("%-12s %10.3f %10.3f %9.4f %9.4f %9.4f", name, m.mean_ms, m.p99_ms, m.recall,
              m.precision, m.accuracy);
  if (m.feature_recall) {
    std::printf(" %9.4f", *m.feature_recall);
  } else {
    std::printf(" %9s", "-");
  }
  std::printf("   (%s)\n", r.method.c_str());
}

int run_demo(const DemoOptions& o) {
  TempDir dir;
  dir.keep = o.keep;
  dir.path = std::filesystem::temp_directory_path() /
             ("antcd-demo-" + std::to_string(getpid()) + "-" +
              std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  experiments::ProductionLineOptions options;
  options.objects = o.objects;
  options.frames = o.frames;
  options.seed = o.seed;
  const auto generated = experiments::generate_production_line(options);
  const auto scene_path = experiments::write_scene(generated, dir.path);
  const Scene scene(load_scene(scene_path));
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < scene.object_count(); ++i) {
    triangles += scene.model_of(i).stats().triangles;
  }
  std::printf(
      "antcd demo: veneer production line, %zu objects (%zu distinct meshes, %zu triangles "
      "in all), %zu frames%s\n",
      scene.object_count(), scene.model_count(), triangles, scene.description().frames,
      o.keep ? "" : " (scene in a temporary folder, removed at exit)");
  if (o.keep) std::printf("scene kept at %s\n", scene_path.string().c_str());
  std::printf("loading and building: %.1f ms\n\n", scene.build_ms());

  SceneQuery exact;
  exact.threads = o.threads;
  const auto truth = experiments::run_scene(scene, exact, scene_path.string());
  SceneQuery maco = exact;
  maco.method = Method::Maco;
  maco.seed = o.seed;
  maco.count_feature_truth = true;
  const auto result = experiments::run_scene(scene, maco, scene_path.string());
  SceneQuery box = exact;
  box.method = Method::SphereObb;
  const auto boxes = experiments::run_scene(scene, box, scene_path.string());

  std::size_t colliding = 0;
  std::size_t candidates = 0;
  for (const auto& f : truth.frames) {
    colliding += f.pairs.size();
    candidates += f.candidates.size();
  }
  const double frames = static_cast<double>(truth.frames.size());
  std::printf(
      "ground truth (exact): %.2f colliding object pairs per frame, %.2f broad-phase "
      "candidates per frame\n\n",
      static_cast<double>(colliding) / frames, static_cast<double>(candidates) / frames);
  std::printf("%-12s %10s %10s %9s %9s %9s %9s\n", "method", "mean ms", "p99 ms", "recall",
              "precision", "accuracy", "A/B");
  print_row("exact", truth, experiments::compare_runs(truth, truth));
  print_row("sphere-obb", boxes, experiments::compare_runs(truth, boxes));
  print_row("maco", result, experiments::compare_runs(truth, result));
  std::printf(
      "\nrecall/precision/accuracy: object pairs against exact; A/B: share of each searched "
      "feature space's colliding centroid pairs that MACO found.\n");
  return 0;
}

}  // namespace

void add_demo_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<DemoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "demo",
      "The main job: generate the production-line scene, run exact, sphere-obb and maco, "
      "compare");
  cmd->add_option("--objects", opts->objects, "Objects in the scene")->check(CLI::Range(2, 100000));
  cmd->add_option("--frames", opts->frames, "Frames")->check(CLI::Range(1, 1000000));
  cmd->add_option("--seed", opts->seed, "Seed of the scene and of maco");
  cmd->add_option("--threads", opts->threads, "Worker threads")->check(CLI::Range(1, 256));
  cmd->add_flag("--keep", opts->keep, "Keep the generated scene folder and print its path");
  cmd->callback([opts, &code] { code = run_demo(*opts); });
}

}  // namespace antcd::cli
