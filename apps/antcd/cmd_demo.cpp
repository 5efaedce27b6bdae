// antcd demo: the main job. Generates the paper's production-line scene in a temporary folder,
// runs the exact method (ground truth) and the improved ant colony on it, and compares them.
#include <antcd/scene.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "cli_util.hpp"
#include "shared/production_line.hpp"
#include "shared/run_result.hpp"
#include "view_page.hpp"

namespace antcd::cli {

namespace {

struct DemoOptions {
  std::size_t objects = 90;
  std::size_t frames = 300;
  std::uint64_t seed = 1;
  int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::size_t maco_step = 1;
  std::size_t ab_frames = 3;
  bool keep = false;
  std::string view = "demo-view.html";
  bool no_view = false;
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

void print_row(const char* name, const shared::Metrics& m) {
  std::printf("%-12s %10.3f %10.3f %9.4f %9.4f %9.4f\n", name, m.mean_ms, m.p99_ms, m.recall,
              m.precision, m.accuracy);
}

void print_progress(const char* label, std::size_t done, std::size_t total) {
  const int width = 30;
  const int filled = static_cast<int>(width * done / total);
  std::fprintf(stderr, "\r%-12s [%.*s%*s] %zu/%zu frames", label, filled,
               "##############################", width - filled, "", done, total);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

shared::RunResult run(const Scene& scene, const SceneQuery& query, const std::string& name,
                      const char* label, std::size_t frame_step = 1) {
  std::function<void(std::size_t, std::size_t)> progress;
  if (isatty(STDERR_FILENO) != 0) {
    progress = [label](std::size_t done, std::size_t total) { print_progress(label, done, total); };
  }
  return shared::run_scene(scene, query, name, progress, frame_step);
}

// The scene with exact and maco in the browser viewer, next to the table. Where the viewer is not
// built the table still stands: say why there is no page instead of failing the demo.
void write_demo_view(const DemoOptions& o, const std::filesystem::path& scene_path,
                     const shared::RunResult& truth, const shared::RunResult& maco) {
  ViewInputs inputs;
  inputs.scene = scene_path;
  inputs.results = {{"exact", truth}, {"maco", maco}};
  try {
    write_view_file(inputs, o.view);
    std::printf(
        "\nview: wrote %s (the scene with exact's pairs, maco's false alarms and misses, frame "
        "by frame;\nopen it in a browser, e.g. chromium %s#frame=140)\n",
        o.view.c_str(), o.view.c_str());
  } catch (const std::exception& e) {  // viewer not built, or the page could not be written
    std::printf("\nview: no %s: %s\n", o.view.c_str(), e.what());
  }
  // The live page beside it (antcd view --live): needs the WebAssembly build (Emscripten).
  std::filesystem::path live = o.view;
  live.replace_filename(live.stem().string() + "-live.html");
  ViewInputs live_inputs;
  live_inputs.scene = scene_path;
  live_inputs.live = true;
  try {
    write_view_file(live_inputs, live);
    std::printf(
        "live: wrote %s (drag objects with the mouse or a VR controller; antcd compiled "
        "to WebAssembly answers every frame)\n",
        live.string().c_str());
  } catch (const std::exception& e) {
    std::printf("live: no %s: %s\n", live.string().c_str(), e.what());
  }
}

int run_demo(const DemoOptions& o) {
  TempDir dir;
  dir.keep = o.keep;
  dir.path = std::filesystem::temp_directory_path() /
             ("antcd-demo-" + std::to_string(getpid()) + "-" +
              std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  shared::ProductionLineOptions options;
  options.objects = o.objects;
  options.frames = o.frames;
  options.seed = o.seed;
  const auto generated = shared::generate_production_line(options);
  const auto scene_path = shared::write_scene(generated, dir.path);
  const Scene scene(load_scene(scene_path));
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < scene.object_count(); ++i) {
    triangles += scene.model_of(i).stats().triangles;
  }
  std::printf(
      "antcd demo: veneer production line, %zu objects (%zu distinct meshes, %zu triangles "
      "in all), %zu frames, %d thread%s%s\n",
      scene.object_count(), scene.model_count(), triangles, scene.description().frames, o.threads,
      o.threads == 1 ? "" : "s", o.keep ? "" : " (scene in a temporary folder, removed at exit)");
  if (o.keep) std::printf("scene kept at %s\n", scene_path.string().c_str());
  std::printf("loading and building: %.1f ms\n", scene.build_ms());
  std::fflush(stdout);

  const std::string name = scene_path.string();
  SceneQuery exact;
  exact.threads = o.threads;
  const auto truth = run(scene, exact, name, "exact");
  SceneQuery box = exact;
  box.method = Method::SphereObb;
  const auto boxes = run(scene, box, name, "sphere-obb");
  SceneQuery maco = exact;
  maco.method = Method::Maco;
  maco.seed = o.seed;
  const auto result = run(scene, maco, name, "maco", o.maco_step);
  // The ground truth on the frames maco ran.
  shared::RunResult truth_at_maco = truth;
  std::erase_if(truth_at_maco.frames,
                [&](const shared::FrameRecord& f) { return f.frame % o.maco_step != 0; });

  // The paper's A/B needs every search run for its full N iterations and each feature space
  // enumerated: far dearer than a verdict, so it is measured on evenly spaced frames only.
  const std::size_t frames = scene.description().frames;
  const std::size_t ab_frames = std::min(o.ab_frames, frames);
  std::uint64_t hits = 0;
  std::uint64_t truth_features = 0;
  if (ab_frames > 0) {
    SceneQuery ab = maco;
    ab.random.count_truth = true;
    for (std::size_t k = 0; k < ab_frames; ++k) {
      const FrameResult fr = scene.run_frame(k * frames / ab_frames, ab);
      hits += fr.feature_hits;
      truth_features += fr.feature_truth;
      if (isatty(STDERR_FILENO) != 0) print_progress("maco A/B", k + 1, ab_frames);
    }
  }

  std::uint64_t evaluations = 0;
  for (const auto& f : result.frames) evaluations += f.evaluations.value_or(0);
  std::size_t colliding = 0;
  std::size_t candidates = 0;
  for (const auto& f : truth.frames) {
    colliding += f.pairs.size();
    candidates += f.candidates.size();
  }
  const double nframes = static_cast<double>(truth.frames.size());
  std::printf(
      "ground truth (exact): %.2f colliding object pairs per frame, %.2f broad-phase "
      "candidates per frame\n\n",
      static_cast<double>(colliding) / nframes, static_cast<double>(candidates) / nframes);
  std::printf("%-12s %10s %10s %9s %9s %9s\n", "method", "mean ms", "p99 ms", "recall", "precision",
              "accuracy");
  print_row("exact", shared::compare_runs(truth, truth));
  print_row("sphere-obb", shared::compare_runs(truth, boxes));
  print_row("maco", shared::compare_runs(truth_at_maco, result));
  std::printf(
      "\nmean/p99 ms: query time per frame (poses, broad phase, narrow phase). recall, precision,\n"
      "accuracy: colliding object pairs against exact, over the broad phase's candidate pairs.\n"
      "maco: the paper's improved ant colony (m = %u ants, N = %u iterations, %zu features per\n"
      "side) on %zu of the %zu frames%s, stopping at the first colliding feature pair, which the\n"
      "exact triangle test at delta then confirms (the witness verdict): every pair it reports is\n"
      "a real contact, misses are its only error. Where a pair's budget covers every cell of its\n"
      "overlapping leaf pairs, those cells are scanned instead of searched (complete: no witness\n"
      "there proves the pair separate). The colonies' pheromone and last witnesses are carried\n"
      "from frame to frame (docs/random-detection.md); %llu fitness evaluations in all.\n",
      maco.random.search.ant.ants, maco.random.search.iterations,
      static_cast<std::size_t>(maco.random.samples_per_side), result.frames.size(), frames,
      o.maco_step == 1 ? "" : " (every --maco-step-th)",
      static_cast<unsigned long long>(evaluations));
  if (ab_frames > 0) {
    std::printf(
        "maco A/B (share of the sampled feature spaces' colliding feature pairs, each confirmed "
        "by\n"
        "the exact test, found in N iterations, %zu evenly spaced frames): %.4f (%llu of %llu)\n",
        ab_frames,
        truth_features > 0 ? static_cast<double>(hits) / static_cast<double>(truth_features) : 1.0,
        static_cast<unsigned long long>(hits), static_cast<unsigned long long>(truth_features));
  }
  if (!o.no_view) write_demo_view(o, scene_path, truth, result);
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
  cmd->add_option("--seed", opts->seed, "Seed of the scene and of maco")->check(unsigned_integer());
  cmd->add_option("--threads", opts->threads, "Worker threads (default: every core)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--maco-step", opts->maco_step,
                  "Run maco on every k-th frame only; 1 = all (its colonies' memory then spans\n"
                  "consecutive frames)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--ab-frames", opts->ab_frames,
                  "Frames on which maco's A/B (feature-pair recall) is measured; 0 skips it")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd->add_option("--view", opts->view,
                  "Write the scene with the exact and maco results as a browser page here")
      ->check(writable_file())
      ->capture_default_str();
  cmd->add_flag("--no-view", opts->no_view, "Do not write the browser page");
  cmd->add_flag("--keep", opts->keep, "Keep the generated scene folder and print its path");
  cmd->callback([opts, &code] { code = run_demo(*opts); });
}

}  // namespace antcd::cli
