// antcd learn train, and the learned methods of `antcd run` (box-dnn, box-lstm): the optional
// learned baselines (docs/learned-baselines.md). Built with or without libtorch: without it
// (ANTCD_HAVE_LEARNED undefined) every entry point refuses with one clear error.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_util.hpp"
#include "shared/run_result.hpp"

#ifdef ANTCD_HAVE_LEARNED
#include <antcd_learned/calibration.hpp>
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/detector.hpp>
#include <antcd_learned/meshes.hpp>

#include <chrono>
#include <filesystem>
#include <vector>
#endif

namespace antcd::cli {

namespace {

#ifndef ANTCD_HAVE_LEARNED
[[noreturn]] void no_learned() {
  throw UsageError(
      "this antcd was built without the learned baselines (box-dnn, box-lstm need libtorch: "
      "install Debian's libtorch-dev, or run scripts/install-deps.sh, and rebuild)");
}
#endif

struct TrainCommand {
  std::string method;
  std::string out;
  std::size_t scenes = 12;
  std::size_t frames = 150;
  std::size_t epochs = 40;
  std::uint64_t seed = 1;
  std::vector<std::string> train_meshes;  ///< empty: the assimp catalogue
  std::vector<std::string> hold_out;      ///< empty: the default held-out meshes
  bool no_meshes = false;
  std::size_t folds = 0;
  std::optional<double> threshold;  ///< fixed decision threshold (else 0.5 or cross-validated)
  bool ablate = false;
};

#ifdef ANTCD_HAVE_LEARNED
namespace fs = std::filesystem;

void log_line(const std::string& line) { std::cerr << line << std::endl; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

learned::TrainOptions train_options(learned::Kind kind, const TrainCommand& o, bool verbose) {
  learned::TrainOptions train;
  train.kind = kind;
  train.seed = o.seed;
  train.epochs = o.epochs;
  if (verbose) train.log = log_line;
  return train;
}

learned::Classifier train_quiet(learned::Kind kind, const learned::Dataset& data,
                                const TrainCommand& o, bool verbose) {
  return learned::Classifier::train(data, train_options(kind, o, verbose));
}

std::string scores(const learned::Confusion& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "recall %.3f, precision %.3f, accuracy %.3f (%zu colliding of %zu)", c.recall(),
                c.precision(), c.accuracy(), c.tp + c.fn, c.tp + c.fn + c.fp + c.tn);
  return buf;
}

/// k-fold cross-validation by mesh (calibration.hpp): fold i's meshes are kept out of the
/// training scenes and make the evaluated scene. Prints each fold's scores at 0.5 and at the
/// threshold chosen on the pooled out-of-fold probabilities, and returns that threshold.
double cross_validate(learned::Kind kind, const TrainCommand& o,
                      const learned::TrainingSetOptions& set) {
  const learned::CrossValidation cv = learned::cross_validate(
      set, train_options(kind, o, false), o.folds,
      [&](std::size_t i, const learned::FoldResult& f) {
        std::printf("fold %zu/%zu held out {%s}: trained on %zu samples; at 0.5: %s\n", i + 1,
                    o.folds, learned::mesh_names(f.meshes).c_str(), f.train_samples,
                    scores(learned::confusion_at(f.probabilities, f.labels, 0.5)).c_str());
        std::fflush(stdout);
      });
  const double chosen = cv.choice.threshold;
  for (const double t : {0.5, chosen}) {
    double recall = 0;
    double precision = 0;
    for (std::size_t i = 0; i < cv.folds.size(); ++i) {
      const learned::FoldResult& f = cv.folds[i];
      const learned::Confusion c = learned::confusion_at(f.probabilities, f.labels, t);
      recall += c.recall();
      precision += c.precision();
      if (t == chosen) {
        std::printf("fold %zu/%zu at %.4f: %s\n", i + 1, cv.folds.size(), t, scores(c).c_str());
      }
    }
    const auto n = static_cast<double>(cv.folds.size());
    std::printf(
        "cross-validation by mesh, %zu folds, at %.4f: mean recall %.3f, mean precision %.3f; "
        "pooled %s\n",
        cv.folds.size(), t, recall / n, precision / n,
        scores(learned::confusion_at(cv.probabilities, cv.labels, t)).c_str());
  }
  std::printf(
      "chosen decision threshold %.4f (max min(recall, precision) over the pooled out-of-fold "
      "probabilities)\n",
      chosen);
  std::fflush(stdout);
  return chosen;
}

/// Retrains without each feature group (zeroed in training and held-out samples) and reports
/// the held-out scores: what each group adds.
void ablate(learned::Kind kind, const TrainCommand& o, const learned::Dataset& data,
            const learned::Dataset& test) {
  const auto& groups = learned::feature_groups();
  for (std::size_t g = 0; g <= groups.size(); ++g) {
    learned::Dataset d = data;
    learned::Dataset t = test;
    std::string what;
    if (g < groups.size()) {
      d.zero_features(groups[g].first, groups[g].count);
      t.zero_features(groups[g].first, groups[g].count);
      what = "without " + std::string(groups[g].name);
    } else {  // the version-1 groups alone
      for (std::size_t h = 2; h < groups.size(); ++h) {
        d.zero_features(groups[h].first, groups[h].count);
        t.zero_features(groups[h].first, groups[h].count);
      }
      what = "root and levels1-5 only (version 1's groups)";
    }
    const learned::Classifier model = train_quiet(kind, d, o, false);
    const learned::Confusion c = learned::confusion(model.predict(t.features, t.size()), t.labels);
    std::printf("ablation, %s: held-out %s\n", what.c_str(), scores(c).c_str());
    std::fflush(stdout);
  }
}

int run_train(const TrainCommand& o) {
  const learned::Kind kind = learned::parse_kind(o.method);
  if (o.threshold && !(*o.threshold < 1)) {  // > 0 is checked by the option's validator
    throw UsageError("--threshold: expected a number inside (0, 1), got " +
                     std::to_string(*o.threshold));
  }
  std::vector<fs::path> meshes;
  if (!o.no_meshes) {
    if (o.train_meshes.empty()) {
      meshes = learned::mesh_catalogue();
    } else {
      for (const auto& m : o.train_meshes) meshes.emplace_back(m);
    }
  }
  std::vector<fs::path> held;
  if (o.hold_out.empty()) {
    held = learned::default_held_out();
  } else {
    for (const auto& m : o.hold_out) held.emplace_back(m);
  }
  for (const fs::path& m : held) {
    if (!fs::exists(m)) throw UsageError("--hold-out: " + m.string() + ": no such file");
  }
  meshes = learned::without(meshes, held);
  if (o.folds > 0 && o.folds > meshes.size()) {
    throw UsageError("--folds " + std::to_string(o.folds) + ": only " +
                     std::to_string(meshes.size()) + " training meshes");
  }
  if (o.ablate && held.empty()) throw UsageError("--ablate needs held-out meshes");
  learned::TrainingSetOptions set;
  set.scenes = o.scenes;
  set.frames = o.frames;
  set.seed = o.seed;
  set.window = learned::default_window(kind);
  set.mesh_files = meshes;
  std::cerr << "training meshes (" << meshes.size() << "): " << learned::mesh_names(meshes)
            << "\nheld out (" << held.size() << "): " << learned::mesh_names(held) << std::endl;
  std::optional<double> threshold = o.threshold;
  std::string threshold_source;
  if (o.threshold) threshold_source = "given (--threshold)";
  if (o.folds > 0) {
    const double t = cross_validate(kind, o, set);
    if (!o.threshold) {
      threshold = t;
      threshold_source =
          "max min(recall, precision) over the pooled out-of-fold probabilities of " +
          std::to_string(o.folds) + "-fold cross-validation by mesh (seed " +
          std::to_string(o.seed) + ")";
    }
  }
  std::cerr << "generating and labelling " << o.scenes << " training scenes of " << o.frames
            << " frames (exact method)" << std::endl;
  const auto t0 = std::chrono::steady_clock::now();
  const learned::Dataset data = learned::training_set(set, log_line);
  const double data_s = seconds_since(t0);
  std::cerr << "training " << learned::kind_name(kind) << " on " << data.size() << " samples ("
            << data.positives() << " colliding)" << std::endl;
  learned::Classifier model = train_quiet(kind, data, o, true);
  learned::TrainingRecord record = model.record();
  record.scenes = o.scenes;
  record.frames = o.frames;
  record.data_seconds = data_s;
  record.meshes = learned::mesh_names(meshes);
  record.held_out = learned::mesh_names(held);
  record.threshold_source = threshold_source;
  model.set_record(record);
  if (threshold) model.set_threshold(*threshold);
  model.save(o.out);
  std::printf(
      "wrote %s (%s, feature version %d, window %zu, decision threshold %.4f): %llu samples, "
      "%llu colliding, training accuracy %.4f; data %.1f s, training %.1f s\n",
      o.out.c_str(), std::string(learned::kind_name(kind)).c_str(), model.feature_version(),
      model.window(), model.threshold(), static_cast<unsigned long long>(record.samples),
      static_cast<unsigned long long>(record.positives), record.train_accuracy, record.data_seconds,
      record.train_seconds);
  if (!held.empty()) {
    // The held-out check: a scene of the held-out meshes only, never seen in training.
    const learned::Dataset test = learned::mesh_scene_samples(
        held, o.frames, learned::evaluation_seed(o.seed, ~std::uint64_t{0}), set.window, set.delta);
    const std::vector<float> p = model.probabilities(test.features, test.size());
    std::printf("held-out scene {%s} at %.4f: %s\n", learned::mesh_names(held).c_str(),
                model.threshold(),
                scores(learned::confusion_at(p, test.labels, model.threshold())).c_str());
    if (model.threshold() != 0.5) {  // for the record only: the threshold never sees this scene
      std::printf("held-out scene at 0.5 (not used): %s\n",
                  scores(learned::confusion_at(p, test.labels, 0.5)).c_str());
    }
    if (o.ablate) ablate(kind, o, data, test);
  }
  return 0;
}
#endif

}  // namespace

bool is_learned_method(const std::string& method) {
  return method == "box-dnn" || method == "box-lstm";
}

shared::RunResult run_learned(const Scene& scene, const std::string& scene_name,
                              const std::string& method, const std::string& model_path,
                              double delta,
                              const std::function<void(std::size_t, std::size_t)>& progress) {
#ifdef ANTCD_HAVE_LEARNED
  if (model_path.empty()) throw UsageError("--method " + method + " needs --model MODEL.pt");
  const learned::Classifier model = learned::Classifier::load(model_path);
  if (learned::kind_name(model.kind()) != method) {
    throw UsageError(model_path + ": the model is " +
                     std::string(learned::kind_name(model.kind())) + ", not " + method);
  }
  if (model.delta() != delta) {
    throw UsageError(model_path + ": the model was trained for delta " +
                     std::to_string(model.delta()) + ", the run asks for " + std::to_string(delta));
  }
  learned::Detector detector(scene, model);
  shared::RunResult out;
  out.method = method;
  out.scene = scene_name;
  out.delta = delta;
  out.seed = model.record().seed;
  out.threads = 1;
  out.build_ms = scene.build_ms();
  const auto& objects = scene.description().objects;
  const auto names = [&](const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
    std::vector<shared::NamePair> v;
    for (const auto& [i, j] : pairs) v.emplace_back(objects[i].name, objects[j].name);
    return v;
  };
  const std::size_t frames = scene.description().frames;
  for (std::size_t f = 0; f < frames; ++f) {
    const FrameResult r = detector.run_frame(f);
    shared::FrameRecord rec;
    rec.frame = f;
    rec.pairs = names(r.pairs);
    rec.candidates = names(r.candidates);
    rec.time_ms = r.time_ms;
    out.total_ms += r.time_ms;
    out.frames.push_back(std::move(rec));
    if (progress) progress(f + 1, frames);
  }
  return out;
#else
  (void)scene, (void)scene_name, (void)method, (void)model_path, (void)delta, (void)progress;
  no_learned();
#endif
}

void add_learn_commands(CLI::App& app, int& code) {
  CLI::App* learn = app.add_subcommand(
      "learn", "Learned baselines BOX-DNN / BOX-LSTM (optional, needs libtorch)");
  learn->require_subcommand(1);
  auto o = std::make_shared<TrainCommand>();
  CLI::App* train = learn->add_subcommand(
      "train",
      "Train box-dnn or box-lstm on generated scenes labelled by the exact method and save it");
  train->add_option("--method", o->method, "box-dnn | box-lstm")
      ->required()
      ->check(CLI::IsMember({"box-dnn", "box-lstm"}));
  train->add_option("--out", o->out, "Model file to write (atomically)")
      ->required()
      ->check(writable_file())
      ->type_name("MODEL.pt");
  train->add_option("--scenes", o->scenes, "Generated training scenes")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  train->add_option("--frames", o->frames, "Frames per training scene")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  train->add_option("--epochs", o->epochs, "Passes over the training samples")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  train
      ->add_option("--seed", o->seed,
                   "Seed of the training scenes, the initial weights and the "
                   "shuffling")
      ->capture_default_str()
      ->check(unsigned_integer());
  train
      ->add_option("--train-mesh", o->train_meshes,
                   "Mesh files for the mesh-pair training scenes (default: the assimp test models "
                   "of learned/src/meshes.cpp that are installed)")
      ->check(CLI::ExistingFile)
      ->type_name("FILE ...");
  train
      ->add_option("--hold-out", o->hold_out,
                   "Mesh files never used in training, judged after it (default: spider.obj, "
                   "WusonOBJ.obj, 3DSMaxExport.STL, regr01.obj of assimp-testmodels)")
      ->type_name("FILE ...");
  train->add_flag("--no-meshes", o->no_meshes,
                  "Train on generated scenes only (production lines and generated shapes)");
  train
      ->add_option("--folds", o->folds,
                   "Before training: k-fold cross-validation by mesh over the training meshes "
                   "(fold i's meshes out of training, judged on a scene of them); the model "
                   "stores the decision threshold chosen on the folds' pooled probabilities")
      ->check(CLI::Range(0, 100));
  train
      ->add_option("--threshold", o->threshold,
                   "Decision threshold stored in the model (default: 0.5, or with --folds the "
                   "one maximising min(recall, precision) over the out-of-fold probabilities)")
      ->check(positive_finite())
      ->type_name("T");
  train->add_flag("--ablate", o->ablate,
                  "After training: retrain without each feature group and judge each on the "
                  "held-out scene");
  train->callback([o, &code] {
#ifdef ANTCD_HAVE_LEARNED
    code = run_train(*o);
#else
    (void)code;
    no_learned();
#endif
  });
}

}  // namespace antcd::cli
