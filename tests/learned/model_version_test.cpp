// Model files written by libtorch directly (the only test file that includes torch headers): a
// model of another feature version, and a libtorch archive that is not an antcd model.
#include <gtest/gtest.h>
#include <antcd_learned/classifier.hpp>

#include <torch/torch.h>

#include <string>
#include <utility>

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

}  // namespace
}  // namespace antcd::learned
