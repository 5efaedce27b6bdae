// antcd run / scene generate / compare: scenes in motion and their metrics.
#include <antcd/file.hpp>
#include <antcd/scene.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_util.hpp"
#include "shared/production_line.hpp"
#include "shared/run_result.hpp"
#include "shared/statistics.hpp"

namespace antcd::cli {

namespace {

struct RunOptions {
  std::string scene;
  std::string method = "exact";
  double delta = 0;
  std::optional<double> feature_delta;
  std::uint64_t seed = 1;
  int threads = 1;
  std::uint32_t samples = 1000;
  std::uint32_t iterations = 100;
  std::uint32_t agents = 60;
  bool feature_truth = false;
  bool search_all = false;
  std::string verdict = "witness";
  std::uint64_t frame_evaluations = 0;
  double frame_seconds = 0;
  bool no_memory = false;
  bool colony_only = false;
  bool report_distance = false;
  bool volume = false;
  bool continuous = false;
  std::string out;
  std::string model;
};

void print_progress(std::size_t done, std::size_t total) {
  const int width = 40;
  const int filled = static_cast<int>(width * done / total);
  std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu frames", filled,
               "########################################", width - filled, "", done, total);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

int run_run(const RunOptions& o) {
  const bool tty = isatty(STDERR_FILENO) != 0;
  const std::function<void(std::size_t, std::size_t)> progress =
      tty ? std::function<void(std::size_t, std::size_t)>(print_progress)
          : std::function<void(std::size_t, std::size_t)>();
  const bool learned = is_learned_method(o.method);
  if (!learned && !o.model.empty()) {
    throw UsageError("--model is for --method box-dnn or box-lstm, not " + o.method);
  }
  if (o.volume && o.method != "exact") {
    throw UsageError("--volume is for --method exact, not " + o.method);
  }
  if (o.continuous && o.method != "exact") {
    throw UsageError("--continuous is for --method exact, not " + o.method);
  }
  if (o.continuous && (o.volume || o.report_distance)) {
    throw UsageError(std::string("--continuous cannot be combined with ") +
                     (o.volume ? "--volume (sweeps test surfaces)"
                               : "--report-distance (its distances are at the frame poses)"));
  }
  SceneQuery query;
  if (!learned) query.method = parse_method(o.method);
  if (o.colony_only && (learned || (query.method != Method::Aco && query.method != Method::Maco))) {
    throw UsageError("--colony-only is for --method aco or maco, not " + o.method);
  }
  query.delta = o.delta;
  query.random.search.centroid_delta = o.feature_delta;
  query.seed = o.seed;
  query.threads = o.threads;
  query.random.samples_per_side = o.samples;
  query.random.search.iterations = o.iterations;
  query.random.search.set_agents(o.agents);
  query.random.count_truth = o.feature_truth;
  query.random.all_witnesses = o.search_all;
  try {
    query.random.search.verdict = parse_verdict(o.verdict);
  } catch (const ArgumentError& e) {
    throw UsageError(std::string("--verdict: ") + e.what());
  }
  query.frame_evaluations = o.frame_evaluations;
  query.random.search.ant.scan_covered_spaces = !o.colony_only;
  query.frame_seconds = o.frame_seconds;
  query.volume = o.volume;
  query.continuous = o.continuous;
  const Scene scene = [&] {
    const QuietStderr quiet;  // the scene's mesh loads
    return Scene(load_scene(o.scene));
  }();
  if (learned) {
    // The learned baselines read bounding-volume features of Scene::model_of, the rest shape.
    for (const SceneObject& obj : scene.description().objects) {
      if (obj.deforming()) {
        throw UsageError("--method " + o.method + " does not handle deforming objects ('" +
                         obj.name + "' deforms); use exact, sphere-obb or a random method");
      }
    }
  }
  shared::RunResult result =
      learned ? run_learned(scene, o.scene, o.method, o.model, o.delta, progress)
              : shared::run_scene(scene, query, o.scene, progress, 1, !o.no_memory);
  if (o.report_distance) shared::add_distances(scene, result);
  if (!o.out.empty()) {
    write_file_atomic(o.out, shared::to_json(result));
    return 0;
  }
  std::size_t colliding = 0;
  std::size_t candidates = 0;
  std::vector<double> times;
  for (const auto& f : result.frames) {
    colliding += f.pairs.size();
    candidates += f.candidates.size();
    times.push_back(f.time_ms);
  }
  std::printf("scene: %s (%zu objects, %zu models, %zu frames)\n", o.scene.c_str(),
              scene.object_count(), scene.model_count(), result.frames.size());
  std::printf("method: %s, delta %g, seed %llu, threads %d\n", result.method.c_str(), o.delta,
              static_cast<unsigned long long>(o.seed), o.threads);
  if (!result.verdict.empty()) {
    std::uint64_t evaluations = 0;
    std::size_t undecided = 0;
    for (const auto& f : result.frames) {
      evaluations += f.evaluations.value_or(0);
      undecided += f.undecided.size();
    }
    std::printf("random search: verdict %s, memory %s, %llu evaluations, %zu undecided pairs\n",
                result.verdict.c_str(), result.memory ? "on" : "off",
                static_cast<unsigned long long>(evaluations), undecided);
  }
  std::printf("build: %.1f ms\n", result.build_ms);
  std::printf("frames: total %.1f ms, mean %.3f ms, p99 %.3f ms\n", result.total_ms,
              result.total_ms / static_cast<double>(result.frames.size()),
              shared::quantile(times, 0.99));
  std::printf(
      "colliding pairs: %zu over all frames (%.2f per frame), broad-phase candidates %.2f per "
      "frame\n",
      colliding, static_cast<double>(colliding) / static_cast<double>(result.frames.size()),
      static_cast<double>(candidates) / static_cast<double>(result.frames.size()));
  if (o.continuous) {
    double earliest = 1;
    for (const auto& f : result.frames) {
      for (const double t : *f.toi) earliest = std::min(earliest, t);
    }
    std::printf(
        "continuous: pairs touching between frames, earliest time of impact %.6g of a step "
        "(--out writes each pair's toi and contact point)\n",
        colliding == 0 ? 1.0 : earliest);
  }
  if (o.report_distance) {
    double largest = 0;
    for (const auto& f : result.frames) {
      for (const double d : *f.distances) largest = std::max(largest, d);
    }
    std::printf("surface distance of the colliding pairs: at most %.6g (--out writes each)\n",
                largest);
  }
  return 0;
}

struct GenerateOptions {
  std::string out;
  std::size_t objects = 90;
  std::size_t vertices = 750;
  std::size_t frames = 300;
  std::uint64_t seed = 1;
  std::vector<std::string> meshes;
  bool flexible = false;
};

int run_generate(const GenerateOptions& o) {
  shared::ProductionLineOptions options;
  options.objects = o.objects;
  options.vertices = o.vertices;
  options.frames = o.frames;
  options.seed = o.seed;
  options.flexible = o.flexible;
  if (o.flexible && !o.meshes.empty()) {
    throw UsageError("--flexible makes the generated veneer sheets flexible: not with --mesh");
  }
  for (const auto& m : o.meshes) {
    // Refuse a mesh no scene could use (e.g. only zero-area triangles) before writing anything.
    (void)load_model(m, {});
    options.mesh_files.emplace_back(m);
  }
  const auto generated = shared::generate_production_line(options);
  const auto path = shared::write_scene(generated, o.out);
  std::size_t deforming = 0;
  for (const SceneObject& obj : generated.scene.objects) deforming += obj.deforming() ? 1 : 0;
  std::printf("wrote %s (%zu objects, %zu meshes, %zu frames", path.string().c_str(),
              generated.scene.objects.size(), generated.meshes.size(), generated.scene.frames);
  if (o.flexible) std::printf(", %zu flexible sheets with their vertex frames", deforming);
  std::printf(")\n");
  return 0;
}

struct CompareOptions {
  std::string truth, result;
};

int run_compare(const CompareOptions& o) {
  const auto truth = shared::parse_run_result(read_file(o.truth), o.truth);
  const auto result = shared::parse_run_result(read_file(o.result), o.result);
  const shared::Metrics m = shared::compare_runs(truth, result);
  std::printf("truth:  %s (%s)\nresult: %s (%s)\nframes: %zu\n", o.truth.c_str(),
              truth.method.c_str(), o.result.c_str(), result.method.c_str(), m.frames);
  std::printf("object-pair recall:    %.4f  (%llu of %llu colliding pairs)\n", m.recall,
              static_cast<unsigned long long>(m.true_positives),
              static_cast<unsigned long long>(m.true_pairs));
  std::printf("object-pair precision: %.4f  (%llu of %llu reported pairs)\n", m.precision,
              static_cast<unsigned long long>(m.true_positives),
              static_cast<unsigned long long>(m.reported_pairs));
  std::printf("accuracy (candidates): %.4f  (%llu of %llu broad-phase pairs)\n", m.accuracy,
              static_cast<unsigned long long>(m.correct_candidates),
              static_cast<unsigned long long>(m.candidate_pairs));
  if (m.feature_recall) {
    std::printf("feature-pair recall:   %.4f  (A/B)\n", *m.feature_recall);
  } else {
    std::printf("feature-pair recall:   n/a (run with a random method and --feature-truth)\n");
  }
  std::printf(
      "time per frame:        mean %.3f ms, p99 %.3f ms (truth: mean %.3f ms, p99 %.3f ms)\n",
      m.mean_ms, m.p99_ms, m.truth_mean_ms, m.truth_p99_ms);
  return 0;
}

}  // namespace

void add_scene_commands(CLI::App& app, int& code) {
  auto run = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scene's frames with a collision method");
  cmd->add_option("SCENE", run->scene, "Scene file (antcd-scene/1 JSON)")->required();
  cmd->add_option("--method", run->method,
                  "exact | sphere-obb | aco | maco | pso | ga | box-dnn | box-lstm (the last two "
                  "need --model)")
      ->check(CLI::IsMember(
          {"exact", "sphere-obb", "aco", "maco", "pso", "ga", "box-dnn", "box-lstm"}));
  cmd->add_option("--delta", run->delta, "Collision threshold δ in mesh units")
      ->check(non_negative_finite());
  cmd->add_option("--feature-delta", run->feature_delta,
                  "Random methods: centroid threshold, > 0 (default: from triangle sizes)")
      ->check(positive_finite());
  cmd->add_option("--seed", run->seed, "Seed of the random methods")->check(unsigned_integer());
  cmd->add_option("--threads", run->threads, "Worker threads")->check(CLI::Range(1, 256));
  cmd->add_option("--samples", run->samples, "Random methods: features sampled per side")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--iterations", run->iterations, "Random methods: iterations N")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--ants", run->agents, "Random methods: ants / particles / population m")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--feature-truth", run->feature_truth,
                "Random methods: also count each space's colliding feature pairs (for A/B)");
  cmd->add_flag("--search-all", run->search_all,
                "Random methods: run every search for its N iterations instead of stopping at "
                "the first colliding feature pair (same verdicts; feature_hits counts them all)");
  cmd->add_option(
      "--verdict", run->verdict,
      "Random methods: witness (the exact triangle test confirms each reported pair) or "
      "paper-centroid (the paper's centroid threshold, a proximity test)");
  cmd->add_option(
         "--frame-evaluations", run->frame_evaluations,
         "Random methods: fitness evaluations shared by a frame's candidate pairs (anytime "
         "query; pairs left without a witness are listed as undecided); 0 = off")
      ->check(unsigned_integer());
  cmd->add_option(
         "--frame-seconds", run->frame_seconds,
         "Random methods: wall-time budget of a frame's searches (not deterministic); 0 = off")
      ->check(non_negative_finite());
  cmd->add_flag("--no-memory", run->no_memory,
                "Random methods: search each frame afresh instead of carrying the colonies' "
                "pheromone and witnesses from frame to frame");
  cmd->add_flag("--colony-only", run->colony_only,
                "aco / maco: let the colony search even when its budget covers every cell of the "
                "overlapping leaf pairs (by default those cells are scanned instead: complete and "
                "cheaper)");
  cmd->add_flag("--report-distance", run->report_distance,
                "Also write each colliding pair's exact surface distance (\"distances\", in the "
                "order of \"pairs\")");
  cmd->add_flag("--volume", run->volume,
                "Exact method: closed objects also collide when one lies wholly inside another");
  cmd->add_flag("--continuous", run->continuous,
                "Exact method: report the pairs that touch anywhere between each frame and the "
                "next, with the first time of impact and contact point (\"toi\", "
                "\"contact_points\")");
  cmd->add_option("--model", run->model,
                  "box-dnn / box-lstm: the model file written by antcd learn train")
      ->type_name("MODEL.pt");
  cmd->add_option("--out", run->out, "Write the result JSON here (atomically)")
      ->check(writable_file());
  cmd->callback([run, &code] { code = run_run(*run); });

  auto gen = std::make_shared<GenerateOptions>();
  CLI::App* scene = app.add_subcommand("scene", "Scene tools");
  scene->require_subcommand(1);
  CLI::App* g = scene->add_subcommand("generate", "Write the paper's production-line scene");
  g->add_option("--out", gen->out, "Output folder (scene.json and meshes/)")
      ->required()
      ->check(writable_folder());
  g->add_option("--objects", gen->objects, "Number of objects")->check(CLI::Range(2, 100000));
  g->add_option("--vertices", gen->vertices, "Average vertices per mesh")
      ->check(CLI::Range(8, 1000000));
  g->add_option("--frames", gen->frames, "Frames of motion")->check(CLI::Range(1, 1000000));
  g->add_option("--seed", gen->seed, "Seed of the layout and motions")->check(unsigned_integer());
  g->add_option("--mesh", gen->meshes, "Place these mesh files instead of generated equipment")
      ->check(CLI::ExistingFile);
  g->add_flag("--flexible", gen->flexible,
              "Flexible veneer sheets: deforming grids (vertex frames in frames/*.avf, "
              "self_collision on) that sag between the rollers, droop past the conveyor's ends, "
              "and one of which folds onto itself");
  g->callback([gen, &code] { code = run_generate(*gen); });

  auto cmp = std::make_shared<CompareOptions>();
  CLI::App* c = app.add_subcommand("compare", "Metrics of a run against a ground-truth run");
  c->add_option("TRUTH", cmp->truth, "Result of an exact run")->required();
  c->add_option("RESULT", cmp->result, "Result to evaluate")->required();
  c->callback([cmp, &code] { code = run_compare(*cmp); });
}

}  // namespace antcd::cli
