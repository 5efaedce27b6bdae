// Model files written by libtorch directly (the only test file that includes torch headers): a
// model of another feature version, a libtorch archive that is not an antcd model, a format-1
// model (written by antcd before decision thresholds were stored) and format-2 models whose
// threshold, checksum or format tag was altered (each rewritten whole, so the zip's CRCs hold and
// only the loader's own checks can refuse them).
#include <gtest/gtest.h>
#include <antcd_learned/classifier.hpp>

#include <torch/torch.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "support/test_support.hpp"

namespace antcd::learned {
namespace {

std::string refusal(const std::filesystem::path& file) {
  try {
    (void)Classifier::load(file);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LearnedModelFile, AnotherFeatureVersionIsRefused) {
  // Version 1 (58 bounding-volume features, before the shape features) and a future version.
  const auto dir = test::fresh_temp_dir("learned_version");
  ASSERT_EQ(kFeatureVersion, 2);
  for (const auto& [version, count] :
       {std::pair<std::int64_t, std::int64_t>{1, 58},
        std::pair<std::int64_t, std::int64_t>{kFeatureVersion + 1,
                                              static_cast<std::int64_t>(kFeatureCount)}}) {
    std::string name = std::to_string(version);  // ("v" + to_string trips GCC 12's -Wrestrict)
    name.insert(0, 1, 'v');
    name += ".pt";
    const auto file = dir / name;
    torch::serialize::OutputArchive a;
    a.write("format", c10::IValue(std::string("antcd-learned/1")));
    a.write("feature_version", c10::IValue(version));
    a.write("feature_count", c10::IValue(count));
    a.write("kind", c10::IValue(std::string("box-dnn")));
    a.save_to(file.string());
    const std::string what = refusal(file);
    EXPECT_NE(what.find("model made for feature version " + std::to_string(version) +
                        ", this antcd computes version " + std::to_string(kFeatureVersion) +
                        ": train a new one"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(LearnedModelFile, ATorchArchiveThatIsNoAntcdModelIsRefused) {
  const auto dir = test::fresh_temp_dir("learned_foreign");
  torch::save(torch::ones({3}), (dir / "tensor.pt").string());
  const std::string what = refusal(dir / "tensor.pt");
  EXPECT_NE(what.find("not an antcd learned model"), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  // The right tags but no network: refused, not a crash at prediction time.
  torch::serialize::OutputArchive a;
  a.write("format", c10::IValue(std::string("antcd-learned/1")));
  a.write("feature_version", c10::IValue(static_cast<std::int64_t>(kFeatureVersion)));
  a.write("feature_count", c10::IValue(static_cast<std::int64_t>(kFeatureCount)));
  a.write("kind", c10::IValue(std::string("box-lstm")));
  a.write("window", c10::IValue(static_cast<std::int64_t>(8)));
  a.write("delta", c10::IValue(0.0));
  a.save_to((dir / "headless.pt").string());
  const std::string headless = refusal(dir / "headless.pt");
  EXPECT_NE(headless, "accepted");
  EXPECT_EQ(headless.find('\n'), std::string::npos) << headless;
}

// A box-dnn model of format 1, written by `antcd learn train --method box-dnn --out
// format1-box-dnn.pt --no-meshes --scenes 1 --frames 20 --epochs 2 --seed 7` at commit 1344157.
std::filesystem::path format1_model() {
  std::filesystem::path here(__FILE__);
  // CMake's makefiles compile in the tests' build folder (ANTCD_TEST_TMP's parent) and may pass
  // this file's path relative to it.
  if (here.is_relative()) here = std::filesystem::path(ANTCD_TEST_TMP).parent_path() / here;
  return here.parent_path() / "data" / "format1-box-dnn.pt";
}

TEST(LearnedModelFile, AFormatOneModelLoadsWithTheThresholdItWasUsedWith) {
  const Classifier old = Classifier::load(format1_model());
  EXPECT_EQ(old.threshold(), 0.5);
  EXPECT_EQ(old.kind(), Kind::Dnn);
  EXPECT_EQ(old.record().seed, 7U);
  EXPECT_EQ(old.record().epochs, 2U);
  EXPECT_EQ(old.record().threshold_source, "");
  // Real samples: a generated production line of 20 frames (another seed than the model's).
  TrainingSetOptions o;
  o.scenes = 1;
  o.frames = 20;
  o.seed = 99;
  const Dataset d = training_set(o);
  const std::size_t n = d.size();
  const std::vector<float>& x = d.features;
  const std::vector<float> p = old.probabilities(x, n);
  const std::vector<std::uint8_t> verdict = old.predict(x, n);
  std::size_t colliding = 0;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(verdict[i], p[i] >= 0.5F ? 1 : 0) << i;
    colliding += verdict[i];
  }
  EXPECT_GT(colliding, 0U);
  EXPECT_LT(colliding, n);
  // Saved again, it is a format-2 file with the same model and threshold.
  const auto dir = test::fresh_temp_dir("learned_format1");
  old.save(dir / "again.pt");
  const Classifier again = Classifier::load(dir / "again.pt");
  EXPECT_EQ(again.threshold(), 0.5);
  EXPECT_EQ(again.probabilities(x, n), p);
}

/// Rewrites the box-dnn model file `from` entry by entry into `to`, replacing the entries of
/// `changed` (an empty IValue drops the entry); everything else, the checksum included, is
/// copied.
void rewrite(const std::filesystem::path& from, const std::filesystem::path& to,
             const std::map<std::string, c10::IValue>& changed) {
  torch::serialize::InputArchive in;
  in.load_from(from.string());
  torch::serialize::OutputArchive out;
  const auto copy = [&](const std::string& key) {
    const auto c = changed.find(key);
    if (c != changed.end()) {
      if (!c->second.isNone()) out.write(key, c->second);
      return;
    }
    c10::IValue v;
    in.read(key, v);
    out.write(key, v);
  };
  for (const char* key :
       {"format", "feature_version", "feature_count", "kind", "window", "delta"}) {
    copy(key);
  }
  for (const char* key : {"mean", "stddev"}) {
    torch::Tensor t;
    in.read(key, t);
    out.write(key, t);
  }
  for (const char* key :
       {"record_seed", "record_scenes", "record_frames", "record_samples", "record_positives",
        "record_epochs", "record_final_loss", "record_train_accuracy", "record_data_seconds",
        "record_train_seconds", "record_meshes", "record_held_out", "record_threshold_source",
        "threshold"}) {
    copy(key);
  }
  // The network (box-dnn's layers) through a module of the same shape.
  torch::nn::Module net;
  net.register_module("l1", torch::nn::Linear(static_cast<std::int64_t>(kFeatureCount), 64));
  net.register_module("l2", torch::nn::Linear(64, 32));
  net.register_module("l3", torch::nn::Linear(32, 1));
  torch::serialize::InputArchive net_in;
  in.read("net", net_in);
  net.load(net_in);
  torch::serialize::OutputArchive net_out;
  net.save(net_out);
  out.write("net", net_out);
  copy("checksum");
  out.save_to(to.string());
}

TEST(LearnedModelFile, AnAlteredThresholdIsRefused) {
  const auto dir = test::fresh_temp_dir("learned_bad_threshold");
  Classifier model = Classifier::load(format1_model());
  model.set_threshold(0.3);
  model.save(dir / "good.pt");
  // The rewrite itself keeps a loadable model (so each refusal below is its change's).
  rewrite(dir / "good.pt", dir / "copy.pt", {});
  EXPECT_EQ(Classifier::load(dir / "copy.pt").threshold(), 0.3);
  const auto expect_refused = [&](const std::string& name,
                                  const std::map<std::string, c10::IValue>& changed,
                                  const std::string& needle) {
    const auto file = dir / name;
    rewrite(dir / "good.pt", file, changed);
    const std::string what = refusal(file);
    EXPECT_NE(what.find(needle), std::string::npos) << name << ": " << what;
    EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0U) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  };
  for (const double bad : {0.0, 1.0, 1.5, -0.25, std::nan(""), HUGE_VAL}) {
    expect_refused("range.pt", {{"threshold", c10::IValue(bad)}}, "invalid decision threshold");
  }
  // Inside (0, 1) but not the threshold the checksum was computed with.
  expect_refused("other.pt", {{"threshold", c10::IValue(0.31)}}, "checksum does not match");
  expect_refused("text.pt", {{"threshold", c10::IValue(std::string("0.3"))}},
                 "no 'threshold' entry");
  expect_refused("none.pt", {{"threshold", c10::IValue()}}, "no 'threshold' entry");
  // A format-2 file relabelled format 1 is checked without its threshold: refused too.
  expect_refused("relabelled.pt", {{"format", c10::IValue(std::string("antcd-learned/1"))}},
                 "checksum does not match");
  expect_refused("future.pt", {{"format", c10::IValue(std::string("antcd-learned/3"))}},
                 "model file format 'antcd-learned/3', this antcd reads antcd-learned/2 and "
                 "antcd-learned/1: train a new one");
}

}  // namespace
}  // namespace antcd::learned
