// antcd learn train, and the learned methods of `antcd run` (box-dnn, box-lstm): the optional
// learned baselines (docs/learned-baselines.md). Built with or without libtorch: without it
// (ANTCD_HAVE_LEARNED undefined) every entry point refuses with one clear error.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli_util.hpp"
#include "shared/run_result.hpp"

#ifdef ANTCD_HAVE_LEARNED
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/detector.hpp>

#include <chrono>
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
  std::size_t scenes = 6;
  std::size_t frames = 150;
  std::size_t epochs = 40;
  std::uint64_t seed = 1;
};

#ifdef ANTCD_HAVE_LEARNED
int run_train(const TrainCommand& o) {
  const learned::Kind kind = learned::parse_kind(o.method);
  learned::TrainingSetOptions set;
  set.scenes = o.scenes;
  set.frames = o.frames;
  set.seed = o.seed;
  set.window = learned::default_window(kind);
  const auto log = [](const std::string& line) { std::cerr << line << std::endl; };
  std::cerr << "generating and labelling " << o.scenes << " training scenes of " << o.frames
            << " frames (exact method)" << std::endl;
  const auto t0 = std::chrono::steady_clock::now();
  const learned::Dataset data = learned::training_set(set, log);
  const double data_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cerr << "training " << learned::kind_name(kind) << " on " << data.size() << " samples ("
            << data.positives() << " colliding)" << std::endl;
  learned::TrainOptions train;
  train.kind = kind;
  train.seed = o.seed;
  train.epochs = o.epochs;
  train.log = log;
  learned::Classifier model = learned::Classifier::train(data, train);
  learned::TrainingRecord record = model.record();
  record.scenes = o.scenes;
  record.frames = o.frames;
  record.data_seconds = data_s;
  model.set_record(record);
  model.save(o.out);
  std::printf(
      "wrote %s (%s, feature version %d, window %zu): %llu samples, %llu colliding, training "
      "accuracy %.4f; data %.1f s, training %.1f s\n",
      o.out.c_str(), std::string(learned::kind_name(kind)).c_str(), model.feature_version(),
      model.window(), static_cast<unsigned long long>(record.samples),
      static_cast<unsigned long long>(record.positives), record.train_accuracy, record.data_seconds,
      record.train_seconds);
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
