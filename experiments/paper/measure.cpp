// The measurements of `antcd bench paper` (see paper_bench.hpp): the scene and its ground truth,
// the measured pair (Tables 1-2, Figure 3) and the scene's candidate pairs (Figures 4-5), then
// the files. One function, in the order of the steps it runs.
#include "paper/paper_bench.hpp"

#include "paper/format.hpp"
#include "paper/gnuplot.hpp"
#include "paper/learned.hpp"
#include "paper/plan.hpp"
#include "paper/plots.hpp"
#include "paper/report.hpp"
#include "paper/results.hpp"
#include "paper/run_util.hpp"
#include "paper/scene_figures.hpp"
#include "paper/tables.hpp"
#include "shared/maco_ablation.hpp"
#include "shared/production_line.hpp"
#include "shared/rng.hpp"

#include <antcd/collide.hpp>
#include <antcd/error.hpp>
#include <antcd/file.hpp>
#include <antcd/random.hpp>
#include <antcd/scene.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd::experiments {
namespace {

namespace fs = std::filesystem;
using namespace paper;
using shared::GeneratedScene;
using shared::ProductionLineOptions;
using shared::SceneStats;

}  // namespace

void run_paper_bench(const PaperBenchOptions& options, std::ostream& log) {
  if (options.out.empty()) throw antcd::ArgumentError("bench paper: --out must not be empty");
  if (options.threads < 1) throw antcd::ArgumentError("bench paper: --threads must be >= 1");
  const auto start = Clock::now();
  const fs::path out = options.out;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    throw Error(out.string() + ": cannot create the output folder" +
                (ec ? ": " + ec.message() : std::string()));
  }
  const Gnuplot gnuplot(options.gnuplot, out);
  gnuplot.check();

  Results R;
  R.plan = make_plan(options.quick);
  R.options = options;
  const Plan& P = R.plan;
  auto stage = [&](const std::string& what) {
    log << "[" << num(ms_since(start) / 1000, 1) << " s] " << what << std::endl;
  };

  // 1. The scene: generate, write, load.
  stage("generating the production line into " + (out / "scene").string());
  ProductionLineOptions line;
  line.seed = options.seed;
  const GeneratedScene generated = shared::generate_production_line(line);
  const SceneStats stats = shared::scene_stats(generated);
  R.objects = stats.objects;
  R.meshes = stats.meshes;
  R.average_vertices = stats.average_vertices;
  const fs::path scene_file = shared::write_scene(generated, out / "scene");
  const Scene scene(load_scene(scene_file));
  R.frames = scene.description().frames;

  // 2. Exact pass: the ground truth of every frame.
  stage("exact pass over " + std::to_string(R.frames) + " frames");
  std::vector<FrameTruth> truth(R.frames);
  {
    SceneQuery exact;
    exact.method = Method::Exact;
    parallel_for(R.frames, options.threads, [&](std::size_t f) {
      const FrameResult fr = scene.run_frame(f, exact);
      truth[f] = {fr.pairs, fr.candidates, fr.time_ms};
    });
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> contact_frames;
  double exact_ms = 0;
  for (std::size_t f = 0; f < R.frames; ++f) {
    for (const auto& pr : truth[f].pairs) contact_frames[pr].push_back(f);
    R.scene_colliding += truth[f].pairs.size();
    R.scene_candidates += truth[f].candidates.size();
    exact_ms += truth[f].time_ms;
  }
  R.exact_frame_ms = exact_ms / static_cast<double>(std::max<std::size_t>(1, R.frames));
  if (contact_frames.empty()) throw Error("bench paper: the generated scene has no collision");
  auto chosen = contact_frames.begin();
  for (auto it = contact_frames.begin(); it != contact_frames.end(); ++it) {
    if (it->second.size() > chosen->second.size()) chosen = it;
  }
  const std::uint32_t obj_a = chosen->first.first;
  const std::uint32_t obj_b = chosen->first.second;
  R.name_a = scene.description().objects[obj_a].name;
  R.name_b = scene.description().objects[obj_b].name;
  R.contact_frames = chosen->second.size();
  log << "  measured pair: " << R.name_a << " - " << R.name_b << ", in contact in "
      << R.contact_frames << " frames" << std::endl;

  // 3. The measured pair, re-tessellated (same layout and motion, finer meshes) until each side
  // has at least max(features) candidate triangles at delta = 0 in every measured frame, so the
  // largest row samples a truly n x n space.
  struct PairFrame {
    std::size_t frame = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> contacts;  ///< sorted
  };
  struct FinePair {
    std::unique_ptr<GeneratedScene> generated;
    const SceneObject* a = nullptr;
    const SceneObject* b = nullptr;
    std::unique_ptr<Model> model_a, model_b;
    std::vector<PairFrame> frames;
    std::size_t min_candidates_a = 0, min_candidates_b = 0;
  };
  auto make_fine_pair = [&](std::size_t vertices) {
    FinePair fp;
    ProductionLineOptions fine_line = line;
    fine_line.vertices = vertices;
    fp.generated = std::make_unique<GeneratedScene>(shared::generate_production_line(fine_line));
    auto object = [&](const std::string& name) -> const SceneObject* {
      for (const SceneObject& o : fp.generated->scene.objects) {
        if (o.name == name) return &o;
      }
      throw Error("bench paper: object '" + name + "' is missing from the re-tessellated scene");
    };
    auto model = [&](const SceneObject& o) {
      for (const auto& [file, mesh] : fp.generated->meshes) {
        if (file == o.mesh_text) return std::make_unique<Model>(mesh, BuildOptions{}, file);
      }
      throw Error("bench paper: mesh '" + o.mesh_text +
                  "' is missing from the re-tessellated scene");
    };
    fp.a = object(R.name_a);
    fp.b = object(R.name_b);
    fp.model_a = model(*fp.a);
    fp.model_b = model(*fp.b);
    // Frames: the pair's contact frames with the most candidate triangles at delta = 0 (the
    // fewer of the two sides; ties: the earlier frame), kept when the fine meshes touch. The
    // candidates are counted before sampling, so one sample per side is enough.
    struct Ranked {
      std::size_t frame, candidates_a, candidates_b;
    };
    std::vector<Ranked> ranked;
    for (const std::size_t f : chosen->second) {
      SamplingOptions one;
      one.samples_per_side = 1;
      one.triangle_masks = false;  // the paper's preliminary detection: sphere and OBB only
      const FeatureSpace sp =
          build_feature_space(*fp.model_a, fp.a->pose(f), *fp.model_b, fp.b->pose(f), one, 0);
      ranked.push_back({f, sp.candidates_a, sp.candidates_b});
    }
    std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& x, const Ranked& y) {
      return std::min(x.candidates_a, x.candidates_b) > std::min(y.candidates_a, y.candidates_b);
    });
    fp.min_candidates_a = fp.min_candidates_b = std::numeric_limits<std::size_t>::max();
    for (const auto& [f, candidates_a, candidates_b] : ranked) {
      if (fp.frames.size() >= P.pair_frames) break;
      const CollisionResult c =
          collide(*fp.model_a, fp.a->pose(f), *fp.model_b, fp.b->pose(f), {0.0, true, 0});
      if (c.contacts.empty()) continue;
      PairFrame pf;
      pf.frame = f;
      for (const Contact& x : c.contacts) pf.contacts.emplace_back(x.triangle_a, x.triangle_b);
      std::sort(pf.contacts.begin(), pf.contacts.end());
      pf.contacts.erase(std::unique(pf.contacts.begin(), pf.contacts.end()), pf.contacts.end());
      fp.frames.push_back(std::move(pf));
      fp.min_candidates_a = std::min(fp.min_candidates_a, candidates_a);
      fp.min_candidates_b = std::min(fp.min_candidates_b, candidates_b);
    }
    std::sort(fp.frames.begin(), fp.frames.end(),
              [](const PairFrame& x, const PairFrame& y) { return x.frame < y.frame; });
    return fp;
  };
  const std::uint32_t needed = *std::max_element(P.features.begin(), P.features.end());
  std::size_t vertices = P.fine_vertices;
  FinePair fine;
  for (;;) {
    stage("re-tessellating the measured pair with " + std::to_string(vertices) +
          " vertices per mesh");
    fine = make_fine_pair(vertices);
    R.fine_tried.push_back(vertices);
    if (fine.frames.empty()) {
      throw Error("bench paper: the re-tessellated pair " + R.name_a + " - " + R.name_b +
                  " never touches");
    }
    const std::size_t fewest = std::min(fine.min_candidates_a, fine.min_candidates_b);
    log << "  candidate triangles at delta = 0 (fewest over the frames): " << fine.min_candidates_a
        << " and " << fine.min_candidates_b << std::endl;
    if (fewest >= needed || vertices >= P.max_fine_vertices) break;
    // Candidates grow about linearly with the vertex count (same contact area, denser mesh).
    const double grow =
        1.15 * static_cast<double>(needed) / static_cast<double>(std::max<std::size_t>(1, fewest));
    vertices =
        std::min(P.max_fine_vertices,
                 static_cast<std::size_t>(static_cast<double>(vertices) * std::max(grow, 1.25)));
  }
  R.fine_vertices = vertices;
  R.fine_candidates_a = fine.min_candidates_a;
  R.fine_candidates_b = fine.min_candidates_b;
  const SceneObject& fine_a = *fine.a;
  const SceneObject& fine_b = *fine.b;
  const Model* const model_a = fine.model_a.get();
  const Model* const model_b = fine.model_b.get();
  R.fine_triangles_a = model_a->mesh().triangles.size();
  R.fine_triangles_b = model_b->mesh().triangles.size();
  R.fine_delta = default_delta(*model_a, *model_b);
  const std::vector<PairFrame>& pair_frames = fine.frames;
  for (const PairFrame& pf : pair_frames) R.pair_frames.push_back(pf.frame);

  auto build_space = [&](const PairFrame& pf, std::uint32_t n, std::uint64_t seed) {
    SamplingOptions sampling;
    sampling.samples_per_side = n;
    sampling.triangle_masks = false;  // the paper's preliminary detection: sphere and OBB only
    return build_feature_space(*model_a, fine_a.pose(pf.frame), *model_b, fine_b.pose(pf.frame),
                               sampling, seed);
  };

  // 4. Tables 1-2: one run per (features, frame, seed), every search on the same space.
  {
    struct Spec {
      std::uint32_t n;
      std::size_t frame_index;
      std::size_t seed_index;
    };
    std::vector<Spec> specs;
    for (const std::uint32_t n : P.features) {
      for (std::size_t k = 0; k < pair_frames.size(); ++k) {
        for (std::size_t s = 0; s < P.pair_seeds; ++s) specs.push_back({n, k, s});
      }
    }
    const auto variants = shared::maco_ablation();
    stage("Tables 1-2: " + std::to_string(specs.size()) + " runs × " +
          std::to_string(std::size(kTableMethods)) + " searches (+ " +
          std::to_string(variants.size()) + " MACO variants at " + squared(P.ablation_features) +
          ")");
    R.runs.resize(specs.size());
    std::atomic<std::size_t> done{0};
    std::mutex log_mutex;
    parallel_for(specs.size(), options.threads, [&](std::size_t idx) {
      const Spec& sp = specs[idx];
      const PairFrame& pf = pair_frames[sp.frame_index];
      const std::uint64_t seed =
          shared::derive_seed(options.seed, 1, sp.n, pf.frame, sp.seed_index);
      PairRun run;
      run.features = sp.n;
      run.frame = pf.frame;
      const auto t0 = Clock::now();
      const FeatureSpace space = build_space(pf, sp.n, seed);
      run.build_ms = ms_since(t0);
      run.space_a = space.a.size();
      run.space_b = space.b.size();
      run.candidates_a = space.candidates_a;
      run.candidates_b = space.candidates_b;
      run.truth = count_colliding(space);
      run.contacts = pf.contacts.size();
      const std::set<std::uint32_t> in_a(space.a.triangle.begin(), space.a.triangle.end());
      const std::set<std::uint32_t> in_b(space.b.triangle.begin(), space.b.triangle.end());
      for (const auto& [ta, tb] : pf.contacts) {
        run.contacts_in_space += in_a.count(ta) && in_b.count(tb) ? 1 : 0;
      }
      const bool ablation = sp.n == P.ablation_features;
      const std::size_t searches = std::size(kTableMethods) + (ablation ? variants.size() : 0);
      run.marks.assign(searches, std::vector<MarkResult>(4));
      if (run.truth > 0) {
        for (std::size_t g = 0; g < searches; ++g) {
          const bool variant = g >= std::size(kTableMethods);
          // Every variant runs with MACO's own seed: the switches alone differ.
          SearchRequest req = paper_request(variant ? Method::Maco : kTableMethods[g],
                                            shared::derive_seed(seed, 2, variant ? 0 : g));
          if (variant) req.ant.maco = variants[g - std::size(kTableMethods)].switches;
          req.restarts = std::numeric_limits<std::uint32_t>::max();
          req.progress_marks.assign(std::begin(kRates), std::end(kRates));
          req.stop.target_share = kRates[3];
          req.stop.reference_count = run.truth;
          req.stop.max_evaluations = P.table_cap;
          const SearchResult res = search(space, req);
          for (std::size_t k = 0; k < 4 && k < res.progress.size(); ++k) {
            const ProgressMark& pm = res.progress[k];
            MarkResult& m = run.marks[g][k];
            if (!pm.reached) continue;
            m.reached = true;
            m.ms = pm.seconds * 1000;
            m.evaluations = static_cast<double>(pm.evaluations);
            std::set<std::pair<std::uint32_t, std::uint32_t>> found;
            const std::size_t upto = std::min<std::size_t>(pm.hits, res.hits.size());
            for (std::size_t h = 0; h < upto; ++h) {
              const auto key = std::make_pair(res.hits[h].triangle_a, res.hits[h].triangle_b);
              if (std::binary_search(pf.contacts.begin(), pf.contacts.end(), key)) {
                found.insert(key);
              }
            }
            m.found_contacts = found.size();
          }
        }
      }
      R.runs[idx] = std::move(run);
      const std::size_t d = ++done;
      const std::lock_guard<std::mutex> lock(log_mutex);
      if (d % std::max<std::size_t>(1, specs.size() / 10) == 0 || d == specs.size()) {
        log << "  " << d << "/" << specs.size() << " runs done (" << num(ms_since(start) / 1000, 1)
            << " s)" << std::endl;
      }
    });
  }

  // 5. Figure 3: MACO with each colony size for N = 100 iterations.
  {
    struct Spec {
      std::uint32_t n;
      std::size_t frame_index;
      std::size_t seed_index;
    };
    std::vector<Spec> specs;
    const std::size_t frames = std::min(P.fig3_frames, pair_frames.size());
    for (const std::uint32_t n : P.features) {
      for (std::size_t k = 0; k < frames; ++k) {
        for (std::size_t s = 0; s < P.fig3_seeds; ++s) specs.push_back({n, k, s});
      }
    }
    stage("Figure 3: " + std::to_string(specs.size()) + " spaces × " +
          std::to_string(P.colony_sizes.size()) + " colony sizes");
    std::vector<std::vector<Fig3Run>> found(specs.size());
    parallel_for(specs.size(), options.threads, [&](std::size_t idx) {
      const Spec& sp = specs[idx];
      const PairFrame& pf = pair_frames[sp.frame_index];
      const std::uint64_t seed =
          shared::derive_seed(options.seed, 1, sp.n, pf.frame, sp.seed_index);
      const FeatureSpace space = build_space(pf, sp.n, seed);
      const std::uint64_t t = count_colliding(space);
      if (t == 0) return;
      for (const std::uint32_t m : P.colony_sizes) {
        SearchRequest req = paper_request(Method::Maco, shared::derive_seed(seed, 3, m));
        req.ant.ants = m;
        const auto t0 = Clock::now();
        const SearchResult res = search(space, req);
        found[idx].push_back({sp.n, m,
                              static_cast<double>(res.hits.size()) / static_cast<double>(t),
                              ms_since(t0), static_cast<double>(res.evaluations)});
      }
    });
    for (auto& v : found) R.fig3.insert(R.fig3.end(), v.begin(), v.end());
  }

  // 6. Figures 4-5: every candidate pair of sampled frames, every method and budget.
  measure_scene_figures(scene, truth, R, log, start);

  // 6b. Figure 5's learned baselines: trained on generated scenes, run on the same frames.
  stage(learned_available()
            ? "Figure 5: box-dnn and box-lstm, trained on " + std::to_string(P.learned_scenes) +
                  " generated scenes (never this one)"
            : "Figure 5: box-dnn and box-lstm skipped (built without libtorch)");
  measure_learned(
      scene,
      [&](std::size_t f, std::uint32_t i, std::uint32_t j) {
        return std::binary_search(truth[f].pairs.begin(), truth[f].pairs.end(),
                                  std::make_pair(i, j));
      },
      R, log);

  // 7. Files.
  stage("writing tables, plots and report.md");
  R.seconds = ms_since(start) / 1000;
  const std::vector<std::string> fig4_methods = fig4_series(R);
  const std::vector<std::string> fig5_methods = fig5_series(R);
  write_file_atomic(out / "table1.csv", table1_csv(R));
  write_file_atomic(out / "table1.md", table1_md(R));
  write_file_atomic(out / "table2.csv", table2_csv(R));
  write_file_atomic(out / "table2.md", table2_md(R));
  write_file_atomic(out / "fig3.csv", fig3_csv(R));
  write_file_atomic(out / "fig4.csv", scene_csv(R, fig4_methods));
  write_file_atomic(out / "fig5.csv", scene_csv(R, fig5_methods));
  write_file_atomic(out / "delta_sensitivity.csv", delta_sensitivity_csv(R));
  write_file_atomic(out / "ablation.csv", ablation_csv(R));
  gnuplot.plot("table1", table_plot(R, true));
  gnuplot.plot("table2", table_plot(R, false));
  gnuplot.plot("fig3", fig3_plot(R));
  gnuplot.plot("fig4",
               scene_plot(R, "Figure 4: detection against time, Sphere-OBB, ACO and MACO",
                          fig4_methods, {{"sphere-obb", 0.65}, {"aco", 0.80}, {"maco", 0.85}}));
  gnuplot.plot(
      "fig5",
      scene_plot(R,
                 R.learned.empty() ? "Figure 5: detection against time, MACO, PSO, GA and exact"
                                   : "Figure 5: detection against time, MACO, PSO, GA, "
                                     "BOX-DNN, BOX-LSTM and exact",
                 fig5_methods,
                 {{"maco", 0.85}, {"pso", 0.80}, {"box-dnn", 0.82}, {"box-lstm", 0.76}}));
  R.seconds = ms_since(start) / 1000;
  write_file_atomic(out / "report.md", write_report(R));
  stage("done: " + (out / "report.md").string());
}

}  // namespace antcd::experiments
