// The learned baselines (antcd_learned): feature invariance, learning beyond a constant guess,
// deterministic training, model files (round trip, refusal of bad ones), the CLI's errors, and the
// by-mesh split (meshes.hpp): folds are disjoint sets of meshes, held-out meshes never reach a
// training scene, a model trained on some meshes beats the constant guess on meshes it never saw;
// and the decision threshold (calibration.hpp): its choice, its use by predict() and the
// detector, its place in the model file and its determinism.
#include <gtest/gtest.h>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd_learned/calibration.hpp>
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/detector.hpp>
#include <antcd_learned/features.hpp>
#include <antcd_learned/meshes.hpp>

#include <sys/wait.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "support/test_support.hpp"

namespace antcd::learned {
namespace {

namespace fs = std::filesystem;

// ---- Features ----

TEST(LearnedFeatures, InvariantToACommonRigidMotionOfBothObjects) {
  const Model a(make_torus(1.0, 0.25, 40, 16));
  const Model b(transformed(make_box(Vec3(0.9, 0.2, 0.3), 2),
                            Transform::from_axis_angle(Vec3(1, 2, 3), 0.4, Vec3(0.1, 0, 0))));
  const Model spider(load_mesh(test::assimp_model("OBJ/spider.obj")));
  std::mt19937_64 rng(7);
  int overlapping_pairs = 0;
  int sampled_pairs = 0;
  const std::size_t kSamplesFeature = feature_groups().back().first;
  ASSERT_EQ(feature_names()[kSamplesFeature], "samples");
  for (const Model* second : {&b, &spider}) {
    const Scalar reach = a.root().radius + second->root().radius;
    for (int trial = 0; trial < 40; ++trial) {
      const Transform pa = test::random_pose(rng, 3.0);
      Transform rel = test::random_pose(rng, 0.8 * reach);
      const Transform pb = pa * rel;
      const FeatureVector f = pair_features(a, pa, *second, pb, 0.0);
      if (f[1] > 0) ++overlapping_pairs;  // spheres overlap: the level features are exercised
      if (f[kSamplesFeature] > 0) ++sampled_pairs;  // leaf pairs read: the shape features too
      for (int motion = 0; motion < 3; ++motion) {
        const Transform m = test::random_pose(rng, 100.0);
        const FeatureVector g = pair_features(a, m * pa, *second, m * pb, 0.0);
        for (std::size_t k = 0; k < kFeatureCount; ++k) {
          ASSERT_NEAR(f[k], g[k], 1e-4 * (1 + std::abs(f[k])))
              << "feature " << feature_names()[k] << ", trial " << trial;
        }
      }
      // A relative motion does change them (the features see the pair's placement).
      const FeatureVector moved = pair_features(
          a, pa, *second, pb * Transform::from_axis_angle(Vec3(0, 0, 1), 0.3, Vec3(0.2, 0.1, 0)),
          0.0);
      float diff = 0;
      for (std::size_t k = 0; k < kFeatureCount; ++k) diff += std::abs(moved[k] - f[k]);
      EXPECT_GT(diff, 1e-3F);
      for (const float v : f) ASSERT_TRUE(std::isfinite(v));
    }
  }
  EXPECT_GT(overlapping_pairs, 20);
  EXPECT_GT(sampled_pairs, 10);
}

TEST(LearnedFeatures, ShapeFeaturesTellCrossingSurfacesFromAShapeInAHole) {
  // A sphere in a torus's hole overlaps its bounding volumes without touching it; moved onto the
  // tube, its surface crosses the torus's. Only the leaf triangles tell the two apart.
  const Model torus(make_torus(1.0, 0.25, 48, 16));
  const Model ball(make_sphere(0.5, 24, 12));
  const auto index = [](std::string_view name) {
    const auto& n = feature_names();
    return static_cast<std::size_t>(std::find(n.begin(), n.end(), name) - n.begin());
  };
  const std::size_t straddle = index("leaf_straddle");
  const std::size_t gap = index("straddle_gap");
  ASSERT_LT(gap, kFeatureCount);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Transform m = test::random_pose(rng, 50.0);
    const Transform in_hole = m * Transform::from_axis_angle(Vec3(1, 1, 0), 0.3, Vec3::Zero());
    const Transform on_tube = m * Transform::from_axis_angle(Vec3(1, 1, 0), 0.3, Vec3(0.9, 0, 0));
    const FeatureVector free = pair_features(torus, m, ball, in_hole, 0.0);
    const FeatureVector crossing = pair_features(torus, m, ball, on_tube, 0.0);
    EXPECT_EQ(free[straddle], 0.0F) << trial;
    EXPECT_EQ(free[gap], 4.0F) << trial;
    EXPECT_GT(crossing[straddle], 0.0F) << trial;
    EXPECT_LT(crossing[gap], 1.0F) << trial;
  }
}

TEST(LearnedFeatures, NamesAreUniqueAndCountMatches) {
  std::vector<std::string_view> names(feature_names().begin(), feature_names().end());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  for (const auto n : names) EXPECT_FALSE(n.empty());
}

// ---- Training on small generated sets ----

TrainingSetOptions tiny(std::uint64_t seed, std::size_t window, std::size_t scenes) {
  TrainingSetOptions o;
  o.scenes = scenes;
  o.frames = 30;
  o.seed = seed;
  o.window = window;
  o.min_objects = 30;
  o.max_objects = 40;
  return o;
}

double accuracy(const std::vector<std::uint8_t>& p, const std::vector<std::uint8_t>& y) {
  std::size_t right = 0;
  for (std::size_t i = 0; i < y.size(); ++i) right += p[i] == y[i] ? 1 : 0;
  return static_cast<double>(right) / static_cast<double>(y.size());
}

class LearnedTraining : public ::testing::TestWithParam<Kind> {};

TEST_P(LearnedTraining, BeatsAConstantPredictorOnHeldOutScenesAndIsDeterministic) {
  const Kind kind = GetParam();
  const std::size_t window = default_window(kind);
  const Dataset train = training_set(tiny(11, window, 3));
  const Dataset held_out = training_set(tiny(12345, window, 2));
  ASSERT_GT(train.positives(), 20U);
  ASSERT_GT(train.size() - train.positives(), 20U);
  ASSERT_GT(held_out.positives(), 5U);
  TrainOptions o;
  o.kind = kind;
  o.seed = 3;
  o.epochs = kind == Kind::Dnn ? 30 : 8;
  const Classifier model = Classifier::train(train, o);
  const double acc = accuracy(model.predict(held_out.features, held_out.size()), held_out.labels);
  const double share =
      static_cast<double>(held_out.positives()) / static_cast<double>(held_out.size());
  const double constant = std::max(share, 1 - share);
  EXPECT_GT(acc, constant + 0.01) << "held-out samples " << held_out.size() << ", colliding "
                                  << held_out.positives();

  // Same data and seed: the same weights, hence bit-identical probabilities.
  const Classifier again = Classifier::train(train, o);
  EXPECT_EQ(model.probabilities(held_out.features, held_out.size()),
            again.probabilities(held_out.features, held_out.size()));
  // Another seed: other weights.
  o.seed = 4;
  o.epochs = 1;
  const Classifier other = Classifier::train(train, o);
  EXPECT_NE(model.probabilities(held_out.features, held_out.size()),
            other.probabilities(held_out.features, held_out.size()));

  // Save → load: identical predictions and metadata.
  const fs::path dir =
      test::fresh_temp_dir(std::string("learned_roundtrip_") + std::string(kind_name(kind)));
  const fs::path file = dir / "model.pt";
  model.save(file);
  const Classifier loaded = Classifier::load(file);
  EXPECT_EQ(loaded.kind(), kind);
  EXPECT_EQ(loaded.window(), window);
  EXPECT_EQ(loaded.feature_version(), kFeatureVersion);
  EXPECT_EQ(loaded.record().samples, model.record().samples);
  EXPECT_EQ(model.probabilities(held_out.features, held_out.size()),
            loaded.probabilities(held_out.features, held_out.size()));
  // Nothing but the model in the folder (the temporary file was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

INSTANTIATE_TEST_SUITE_P(Kinds, LearnedTraining, ::testing::Values(Kind::Dnn, Kind::Lstm),
                         [](const auto& info) {
                           return info.param == Kind::Dnn ? std::string("BoxDnn")
                                                          : std::string("BoxLstm");
                         });

TEST(LearnedTraining, RefusesBadInput) {
  Dataset empty;
  EXPECT_THROW((void)Classifier::train(empty, {}), std::invalid_argument);
  Dataset lstm_data;
  lstm_data.window = 4;
  lstm_data.features.assign(4 * kFeatureCount, 0.0F);
  lstm_data.labels = {1};
  TrainOptions o;
  o.kind = Kind::Dnn;
  EXPECT_THROW((void)Classifier::train(lstm_data, o), std::invalid_argument);
  EXPECT_THROW((void)parse_kind("box-cnn"), Error);
}

// ---- Bad model files ----

/// 64 single-frame samples of patterned noise.
Dataset noise_data() {
  Dataset d;
  d.window = 1;
  for (int i = 0; i < 64; ++i) {
    for (std::size_t k = 0; k < kFeatureCount; ++k) {
      d.features.push_back(static_cast<float>((i * 7 + static_cast<int>(k)) % 13) / 13.0F);
    }
    d.labels.push_back(i % 3 == 0 ? 1 : 0);
  }
  return d;
}

/// A box-dnn trained for two epochs on noise_data(): its probabilities vary.
Classifier noise_model() {
  TrainOptions o;
  o.epochs = 2;
  return Classifier::train(noise_data(), o);
}

/// A threshold strictly between two of `p`'s values (a quarter or three quarters up) at which
/// "p >= t" differs from "p >= 0.5".
double threshold_unlike_one_half(std::vector<float> p) {
  std::sort(p.begin(), p.end());
  for (const std::size_t k : {p.size() / 4, 3 * p.size() / 4}) {
    for (std::size_t m = k; m + 1 < p.size(); ++m) {
      if (p[m] == p[m + 1]) continue;
      // "p >= t" keeps p[m + 1 ..]; "p >= 0.5" the same unless 0.5 lies in (p[m], p[m + 1]].
      if (!(p[m] < 0.5F && p[m + 1] >= 0.5F)) return (static_cast<double>(p[m]) + p[m + 1]) / 2;
      break;
    }
  }
  ADD_FAILURE() << "no threshold splits the probabilities unlike 0.5";
  return 0.5;
}

std::vector<std::uint8_t> at_least(const std::vector<float>& p, double t) {
  std::vector<std::uint8_t> out;
  for (const float v : p) out.push_back(static_cast<double>(v) >= t ? 1 : 0);
  return out;
}

std::string one_model_bytes(const fs::path& dir) {
  noise_model().save(dir / "good.pt");
  std::ifstream in(dir / "good.pt", std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_refused(const fs::path& file, const std::string& needle) {
  try {
    (void)Classifier::load(file);
    ADD_FAILURE() << file << " was accepted";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  }
}

TEST(LearnedModelFile, BadFilesAreRefusedWithOneLineNamingTheFile) {
  const fs::path dir = test::fresh_temp_dir("learned_bad_models");
  const std::string good = one_model_bytes(dir);
  ASSERT_GT(good.size(), 1000U);
  EXPECT_NO_THROW((void)Classifier::load(dir / "good.pt"));
  expect_refused(dir / "missing.pt", "");
  expect_refused(dir, "");  // a folder
  test::write_file(dir / "empty.pt", "");
  expect_refused(dir / "empty.pt", "not an antcd learned model");
  test::write_file(dir / "text.pt", "this is not a model\n");
  expect_refused(dir / "text.pt", "not an antcd learned model");
  test::write_file(dir / "truncated.pt", good.substr(0, good.size() / 2));
  expect_refused(dir / "truncated.pt", "");
  // Corrupt bytes inside the archive (past the first entries' headers).
  std::string flipped = good;
  for (std::size_t i = flipped.size() / 3; i < flipped.size() / 3 + 200; ++i) flipped[i] ^= 0x5A;
  test::write_file(dir / "flipped.pt", flipped);
  expect_refused(dir / "flipped.pt", "");
  // One flipped bit in the network's weights (the archive stores them raw, without a checked CRC).
  const auto at = good.find("PK", good.size() / 2);
  ASSERT_NE(at, std::string::npos);
  std::string bit = good;
  bit[at - 9] = static_cast<char>(bit[at - 9] ^ 0x01);
  test::write_file(dir / "bit.pt", bit);
  expect_refused(dir / "bit.pt", "");
}

TEST(LearnedModelFile, DamagedCopiesAreRefusedNeverACrash) {
  // libtorch's parsers threw std::runtime_error, std::out_of_range and torch::jit::ErrorReport on
  // such copies, past the loader's c10::Error handler: `antcd-lab run --model` died of SIGABRT.
  const fs::path dir = test::fresh_temp_dir("learned_damaged_models");
  const std::string good = one_model_bytes(dir);
  std::mt19937_64 rng(28);
  int refused = 0;
  for (int k = 0; k < 150; ++k) {
    std::string copy = good;
    const int flips = k % 3 == 0 ? 1 : 1 + k % 17;
    for (int f = 0; f < flips; ++f) copy[rng() % copy.size()] = static_cast<char>(rng());
    if (k % 10 == 9) copy.resize(rng() % copy.size());  // and some truncated
    const fs::path file = dir / ("damaged" + std::to_string(k) + ".pt");
    test::write_file(file, copy);
    try {
      (void)Classifier::load(file);  // a flip in a field nobody reads may leave a valid model
    } catch (const ModelError& e) {
      ++refused;
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(what.rfind(file.string(), 0), 0U) << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": not a ModelError: " << e.what();
    }
  }
  EXPECT_GT(refused, 140);
  // Foreign zip archives: a zip64 end record, an unknown compression method.
  std::string zip64 = good;
  const auto end = zip64.rfind(std::string("PK\x05\x06", 4));
  ASSERT_NE(end, std::string::npos);
  zip64[end + 10] = zip64[end + 11] = zip64[end + 8] = zip64[end + 9] = '\xff';
  test::write_file(dir / "zip64.pt", zip64);
  expect_refused(dir / "zip64.pt", "zip64");
  std::string method = good;
  const auto central = method.find(std::string("PK\x01\x02", 4));
  ASSERT_NE(central, std::string::npos);
  method[central + 10] = 14;  // LZMA
  test::write_file(dir / "lzma.pt", method);
  expect_refused(dir / "lzma.pt", "compression method 14");
}

// ---- CLI ----

#ifdef ANTCD_CLI
struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

CliRun cli(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt";
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = std::string("'") + ANTCD_CLI + "' " + args + " > '" + out.string() +
                          "' 2> '" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = test::read_all(out);
  r.err = test::read_all(err);
  return r;
}

TEST(LearnedCli, BadModelsExitTwoWithOneErrorLine) {
  const fs::path dir = test::fresh_temp_dir("learned_cli");
  const std::string good = one_model_bytes(dir);
  const CliRun gen = cli("scene generate --out '" + (dir / "scene").string() +
                             "' --objects 6 --frames 3 --vertices 100",
                         dir);
  ASSERT_EQ(gen.code, 0) << gen.err;
  const std::string scene = "'" + (dir / "scene" / "scene.json").string() + "'";
  const auto expect_error = [&](const std::string& args, const std::string& needle) {
    const CliRun r = cli(args, dir);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0U) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  };
  test::write_file(dir / "junk.pt", "junk");
  expect_error("run " + scene + " --method box-dnn --model '" + (dir / "missing.pt").string() + "'",
               "missing.pt");
  expect_error("run " + scene + " --method box-dnn --model '" + (dir / "junk.pt").string() + "'",
               "not an antcd learned model");
  expect_error("run " + scene + " --method box-lstm --model '" + (dir / "good.pt").string() + "'",
               "the model is box-dnn, not box-lstm");
  expect_error("run " + scene + " --method box-dnn", "--model");
  expect_error("run " + scene + " --method exact --model '" + (dir / "good.pt").string() + "'",
               "--model");
  // The good model runs (its verdicts are not checked here: it was trained on noise).
  const CliRun ok =
      cli("run " + scene + " --method box-dnn --model '" + (dir / "good.pt").string() +
              "' --out '" + (dir / "run.json").string() + "'",
          dir);
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir / "run.json"));
}

TEST(LearnedCli, TheDetectorAndAntcdRunUseTheStoredThreshold) {
  const fs::path dir = test::fresh_temp_dir("learned_cli_threshold");
  const CliRun gen = cli("scene generate --out '" + (dir / "scene").string() +
                             "' --objects 24 --frames 6 --vertices 100",
                         dir);
  ASSERT_EQ(gen.code, 0) << gen.err;
  const Scene scene(load_scene(dir / "scene" / "scene.json"));
  Classifier model = noise_model();
  // Every frame's candidates and their probabilities, computed apart from the detector.
  PairHistory history(scene, 1, 0);
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> candidates;
  std::vector<std::vector<float>> probabilities;
  std::vector<float> all;
  for (std::size_t f = 0; f < scene.description().frames; ++f) {
    candidates.push_back(scene.broad_phase(f, 0));
    std::vector<float> features(candidates.back().size() * kFeatureCount);
    for (std::size_t k = 0; k < candidates.back().size(); ++k) {
      const auto [i, j] = candidates.back()[k];
      history.window_features(i, j, f, features.data() + k * kFeatureCount);
    }
    probabilities.push_back(model.probabilities(features, candidates.back().size()));
    all.insert(all.end(), probabilities.back().begin(), probabilities.back().end());
  }
  ASSERT_GT(all.size(), 20U);
  const double t = threshold_unlike_one_half(all);
  model.set_threshold(t);
  model.save(dir / "t.pt");
  Detector detector(scene, model);
  std::vector<std::size_t> counts;
  for (std::size_t f = 0; f < candidates.size(); ++f) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (std::size_t k = 0; k < candidates[f].size(); ++k) {
      if (static_cast<double>(probabilities[f][k]) >= t) expected.push_back(candidates[f][k]);
    }
    EXPECT_EQ(detector.run_frame(f).pairs, expected) << "frame " << f;
    counts.push_back(expected.size());
  }
  // antcd run reads the threshold from the file: the same pairs per frame.
  const CliRun run =
      cli("run '" + (dir / "scene" / "scene.json").string() + "' --method box-dnn --model '" +
              (dir / "t.pt").string() + "' --out '" + (dir / "run.json").string() + "'",
          dir);
  ASSERT_EQ(run.code, 0) << run.err;
  const nlohmann::json result = nlohmann::json::parse(test::read_all(dir / "run.json"));
  ASSERT_EQ(result.at("frames").size(), counts.size());
  for (std::size_t f = 0; f < counts.size(); ++f) {
    EXPECT_EQ(result.at("frames")[f].at("pairs").size(), counts[f]) << "frame " << f;
  }
}

TEST(LearnedCli, LearnTrainStoresTheCrossValidatedThreshold) {
  const fs::path dir = test::fresh_temp_dir("learned_cli_calibrate");
  save_obj(make_torus(0.8, 0.25, 24, 10), dir / "torus.obj");
  save_obj(make_sphere(0.6, 16, 8), dir / "sphere.obj");
  const std::string meshes = "--train-mesh '" + (dir / "torus.obj").string() + "' '" +
                             (dir / "sphere.obj").string() + "' '" +
                             test::assimp_model("STL/sphereWithHole.stl").string() + "' '" +
                             test::assimp_model("FBX/huesitos.fbx").string() + "' --hold-out '" +
                             test::assimp_model("OBJ/spider.obj").string() + "'";
  const std::string common = "learn train --method box-dnn --scenes 2 --frames 20 --epochs 3 " +
                             meshes + " --out '" + (dir / "m.pt").string() + "'";
  const CliRun r = cli(common + " --folds 2", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string tag = "chosen decision threshold ";
  const auto at = r.out.find(tag);
  ASSERT_NE(at, std::string::npos) << r.out;
  const double printed = std::stod(r.out.substr(at + tag.size()));
  const Classifier model = Classifier::load(dir / "m.pt");
  EXPECT_NEAR(model.threshold(), printed, 5e-5);
  EXPECT_NE(model.record().threshold_source.find("2-fold cross-validation by mesh"),
            std::string::npos)
      << model.record().threshold_source;
  // A given threshold wins over the cross-validated one; out of (0, 1) it is refused.
  const CliRun fixed = cli(common + " --folds 2 --threshold 0.3", dir);
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  EXPECT_EQ(Classifier::load(dir / "m.pt").threshold(), 0.3);
  for (const char* bad : {"1", "0", "1.5", "nan"}) {
    const CliRun refused = cli(common + " --threshold " + bad, dir);
    EXPECT_EQ(refused.code, 2) << bad << ": " << refused.err;
    EXPECT_EQ(refused.err.rfind("error: ", 0), 0U) << refused.err;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    EXPECT_NE(refused.err.find("--threshold"), std::string::npos) << refused.err;
  }
}
#endif

}  // namespace
}  // namespace antcd::learned

// ---- The by-mesh split ----

namespace antcd::learned {
namespace {

/// "m<i>.obj" ("m" + to_string trips GCC 12's -Wrestrict once inlined).
std::string mesh_name(std::size_t i) {
  std::string name = std::to_string(i);
  name.insert(0, 1, 'm');
  name += ".obj";
  return name;
}

std::vector<fs::path> names(std::size_t n) {
  std::vector<fs::path> v;
  for (std::size_t i = 0; i < n; ++i) v.emplace_back(mesh_name(i));
  return v;
}

TEST(LearnedMeshSplit, FoldsAreDisjointCoverEveryMeshAndDependOnlyOnTheSeed) {
  const auto meshes = names(11);
  const auto folds = mesh_folds(meshes, 4, 9);
  ASSERT_EQ(folds.size(), 4U);
  std::set<fs::path> seen;
  for (const auto& f : folds) {
    EXPECT_GE(f.size(), 2U);
    EXPECT_LE(f.size(), 3U);
    for (const auto& m : f) EXPECT_TRUE(seen.insert(m).second) << m << " in two folds";
  }
  EXPECT_EQ(seen.size(), meshes.size());
  EXPECT_EQ(mesh_folds(meshes, 4, 9), folds);
  EXPECT_NE(mesh_folds(meshes, 4, 10), folds);
  EXPECT_THROW((void)mesh_folds(meshes, 0, 1), std::invalid_argument);
  EXPECT_THROW((void)mesh_folds(meshes, 12, 1), std::invalid_argument);
}

TEST(LearnedMeshSplit, HeldOutMeshesAreRemovedAndPairingMeetsNeighbours) {
  const auto meshes = names(5);
  const auto kept = without(meshes, {fs::path("m1.obj"), fs::path("./m3.obj")});
  EXPECT_EQ(kept, (std::vector<fs::path>{"m0.obj", "m2.obj", "m4.obj"}));
  // The file mode pairs objects (2m, 2m+1) cycling over the list: every neighbour pair occurs.
  for (const std::size_t n : {1U, 2U, 4U, 5U}) {
    const auto order = pairing_order(names(n));
    std::set<std::pair<std::string, std::string>> pairs;
    for (std::size_t m = 0; m < n; ++m) {
      auto a = order[(2 * m) % order.size()].string();
      auto b = order[(2 * m + 1) % order.size()].string();
      if (b < a) std::swap(a, b);
      pairs.emplace(a, b);
    }
    for (std::size_t i = 0; i < n && n > 2; ++i) {
      auto a = mesh_name(i);
      auto b = mesh_name((i + 1) % n);
      if (b < a) std::swap(a, b);
      EXPECT_TRUE(pairs.count({a, b})) << n << " meshes: " << a << "-" << b << " never meet";
    }
  }
  // The default held-out meshes are in the catalogue and not among the training meshes.
  const auto catalogue = mesh_catalogue();
  const auto held = default_held_out();
  ASSERT_EQ(held.size(), 4U) << "assimp-testmodels missing";
  for (const auto& h : held) {
    EXPECT_NE(std::find(catalogue.begin(), catalogue.end(), h), catalogue.end());
    const auto train = without(catalogue, held);
    EXPECT_EQ(std::find(train.begin(), train.end(), h), train.end());
  }
}

TEST(LearnedMeshSplit, ConfusionCounts) {
  const Confusion c = confusion({1, 1, 0, 0, 1}, {1, 0, 1, 0, 1});
  EXPECT_EQ(c.tp, 2U);
  EXPECT_EQ(c.fp, 1U);
  EXPECT_EQ(c.fn, 1U);
  EXPECT_EQ(c.tn, 1U);
  EXPECT_DOUBLE_EQ(c.recall(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(c.precision(), 2.0 / 3.0);
}

TEST(LearnedMeshSplit, ZeroedFeatureGroupsAreZeroInEveryFrame) {
  Dataset d;
  d.window = 2;
  d.features.assign(3 * 2 * kFeatureCount, 1.0F);
  d.labels = {0, 1, 0};
  const FeatureGroup& shape = feature_groups().back();
  d.zero_features(shape.first, shape.count);
  for (std::size_t k = 0; k < d.features.size(); ++k) {
    const std::size_t f = k % kFeatureCount;
    EXPECT_EQ(d.features[k], f >= shape.first && f < shape.first + shape.count ? 0.0F : 1.0F);
  }
  EXPECT_THROW(d.zero_features(kFeatureCount - 1, 2), std::out_of_range);
  // The groups cover the vector once, in order.
  std::size_t next = 0;
  for (const FeatureGroup& g : feature_groups()) {
    EXPECT_EQ(g.first, next) << g.name;
    next += g.count;
  }
  EXPECT_EQ(next, kFeatureCount);
}

/// Two training scenes (a production line, then mesh pairs) of the torus.obj and sphere.obj saved
/// in `dir` and two assimp models, `min_objects` to `min_objects` + 4 objects each.
TrainingSetOptions small_mesh_set(const fs::path& dir, std::size_t frames, std::uint64_t seed,
                                  std::size_t min_objects) {
  TrainingSetOptions o;
  o.scenes = 2;
  o.frames = frames;
  o.seed = seed;
  o.min_objects = min_objects;
  o.max_objects = min_objects + 4;
  o.mesh_files = {dir / "torus.obj", dir / "sphere.obj",
                  test::assimp_model("STL/sphereWithHole.stl"),
                  test::assimp_model("FBX/huesitos.fbx")};
  return o;
}

TEST(LearnedMeshSplit, AModelBeatsTheConstantGuessOnMeshesItNeverSaw) {
  // Train on generated shapes and two assimp meshes; judge on a scene of two other assimp meshes.
  const fs::path dir = test::fresh_temp_dir("learned_mesh_split");
  save_obj(make_torus(0.8, 0.25, 32, 12), dir / "torus.obj");
  save_obj(make_sphere(0.6, 20, 10), dir / "sphere.obj");
  const TrainingSetOptions o = small_mesh_set(dir, 60, 5, 20);
  const Dataset train = training_set(o);
  ASSERT_GT(train.positives(), 20U);
  ASSERT_GT(train.size() - train.positives(), 20U);
  const Dataset held_out = mesh_scene_samples(
      {test::assimp_model("OBJ/spider.obj"), test::assimp_model("STL/3DSMaxExport.STL")}, 80, 3, 1,
      0.0);
  ASSERT_GT(held_out.positives(), 10U);
  ASSERT_GT(held_out.size() - held_out.positives(), 10U);
  TrainOptions t;
  t.epochs = 30;
  t.seed = 2;
  const Classifier model = Classifier::train(train, t);
  const Confusion c = confusion(model.predict(held_out.features, held_out.size()), held_out.labels);
  const double share =
      static_cast<double>(held_out.positives()) / static_cast<double>(held_out.size());
  EXPECT_GT(c.accuracy(), std::max(share, 1 - share) + 0.05)
      << "held-out samples " << held_out.size() << ", colliding " << held_out.positives()
      << ", recall " << c.recall() << ", precision " << c.precision();
  EXPECT_GT(c.recall(), 0.6);
  EXPECT_GT(c.precision(), 0.6);
}

// ---- The decision threshold ----

TEST(LearnedThreshold, ChosenToMaximiseTheSmallerOfRecallAndPrecision) {
  const std::vector<float> p = {0.9F, 0.8F, 0.7F, 0.6F, 0.4F, 0.3F, 0.2F, 0.1F};
  // Top 2 exact: recall and precision 1 between 0.7 and 0.8 (0.5 not there: the midpoint).
  ThresholdChoice c = choose_threshold(p, std::vector<std::uint8_t>{1, 1, 0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(c.threshold, 0.75, 1e-6);
  EXPECT_EQ(c.at.tp, 2U);
  EXPECT_EQ(c.at.fp, 0U);
  // Top 4 (recall 1, precision 3/4) beats top 2 and 3 (2/3): its interval (0.4, 0.6] holds 0.5.
  c = choose_threshold(p, std::vector<std::uint8_t>{1, 1, 0, 1, 0, 0, 0, 0});
  EXPECT_EQ(c.threshold, 0.5);
  EXPECT_EQ(c.at.tp, 3U);
  EXPECT_EQ(c.at.fp, 1U);
  // Low probabilities, positives on top: a threshold far below 0.5.
  c = choose_threshold(std::vector<float>{0.2F, 0.1F, 0.05F, 0.01F},
                       std::vector<std::uint8_t>{1, 1, 0, 0});
  EXPECT_NEAR(c.threshold, 0.075, 1e-6);
  // Equally good intervals: the one whose threshold is nearest 0.5. Top 1, top 2 and top 4 of
  // 0.9 (1), 0.7 (0), 0.6 (0), 0.2 (1), 0.1 (0) all give min(recall, precision) 1/2, at 0.8,
  // 0.65 and 0.15. The samples' order does not matter.
  const std::vector<std::uint8_t> y = {1, 0, 0, 1, 0};
  c = choose_threshold(std::vector<float>{0.9F, 0.7F, 0.6F, 0.2F, 0.1F}, y);
  EXPECT_NEAR(c.threshold, 0.65, 1e-6);
  EXPECT_EQ(choose_threshold(std::vector<float>{0.6F, 0.1F, 0.9F, 0.2F, 0.7F},
                             std::vector<std::uint8_t>{0, 0, 1, 1, 0})
                .threshold,
            c.threshold);
  // All equal: nothing splits them, 0.5.
  EXPECT_EQ(
      choose_threshold(std::vector<float>{0.3F, 0.3F}, std::vector<std::uint8_t>{1, 0}).threshold,
      0.5);
  EXPECT_THROW((void)choose_threshold(std::vector<float>{0.3F}, std::vector<std::uint8_t>{}),
               std::invalid_argument);
  EXPECT_THROW((void)choose_threshold(std::vector<float>{}, std::vector<std::uint8_t>{}),
               std::invalid_argument);
  EXPECT_THROW(
      (void)choose_threshold(std::vector<float>{0.3F, 0.6F}, std::vector<std::uint8_t>{0, 0}),
      std::invalid_argument);
  // The counts are those of confusion_at.
  const Confusion at = confusion_at(p, std::vector<std::uint8_t>{1, 1, 0, 1, 0, 0, 0, 0}, 0.65);
  EXPECT_EQ(at.tp, 2U);
  EXPECT_EQ(at.fp, 1U);
  EXPECT_EQ(at.fn, 1U);
  EXPECT_EQ(at.tn, 4U);
}

TEST(LearnedThreshold, PredictUsesTheStoredThresholdAndTheFileKeepsIt) {
  const Dataset d = noise_data();
  Classifier model = noise_model();
  EXPECT_EQ(model.threshold(), 0.5);
  const std::vector<float> p = model.probabilities(d.features, d.size());
  EXPECT_EQ(model.predict(d.features, d.size()), at_least(p, 0.5));
  const double t = threshold_unlike_one_half(p);
  model.set_threshold(t);
  EXPECT_EQ(model.threshold(), t);
  const std::vector<std::uint8_t> at_t = model.predict(d.features, d.size());
  EXPECT_EQ(at_t, at_least(p, t));
  EXPECT_NE(at_t, at_least(p, 0.5));
  for (const double bad : {0.0, 1.0, -0.2, 1.5, std::nan("")}) {
    EXPECT_THROW(model.set_threshold(bad), std::invalid_argument) << bad;
  }
  EXPECT_EQ(model.threshold(), t);
  const fs::path dir = test::fresh_temp_dir("learned_threshold");
  TrainingRecord r = model.record();
  r.threshold_source = "a test";
  model.set_record(r);
  model.save(dir / "t.pt");
  const Classifier loaded = Classifier::load(dir / "t.pt");
  EXPECT_EQ(loaded.threshold(), t);
  EXPECT_EQ(loaded.record().threshold_source, "a test");
  EXPECT_EQ(loaded.predict(d.features, d.size()), at_t);
}

TEST(LearnedThreshold, CrossValidationByMeshIsDeterministicAndPoolsEveryFold) {
  const fs::path dir = test::fresh_temp_dir("learned_calibration");
  save_obj(make_torus(0.8, 0.25, 24, 10), dir / "torus.obj");
  save_obj(make_sphere(0.6, 16, 8), dir / "sphere.obj");
  const TrainingSetOptions o = small_mesh_set(dir, 30, 6, 16);
  TrainOptions t;
  t.epochs = 10;
  t.seed = 2;
  std::size_t calls = 0;
  const CrossValidation a =
      cross_validate(o, t, 2, [&](std::size_t, const FoldResult&) { ++calls; });
  EXPECT_EQ(calls, 2U);
  ASSERT_EQ(a.folds.size(), 2U);
  std::vector<float> pooled;
  std::vector<std::uint8_t> labels;
  for (std::size_t i = 0; i < a.folds.size(); ++i) {
    const FoldResult& f = a.folds[i];
    EXPECT_EQ(f.meshes, mesh_folds(o.mesh_files, 2, o.seed)[i]);
    EXPECT_GT(f.train_samples, 0U);
    ASSERT_EQ(f.probabilities.size(), f.labels.size());
    EXPECT_GT(f.labels.size(), 10U);
    pooled.insert(pooled.end(), f.probabilities.begin(), f.probabilities.end());
    labels.insert(labels.end(), f.labels.begin(), f.labels.end());
  }
  EXPECT_EQ(a.probabilities, pooled);
  EXPECT_EQ(a.labels, labels);
  const ThresholdChoice c = choose_threshold(pooled, labels);
  EXPECT_EQ(a.choice.threshold, c.threshold);
  EXPECT_GT(a.choice.threshold, 0);
  EXPECT_LT(a.choice.threshold, 1);
  // Same options, same seed: the same probabilities and threshold, bit for bit.
  const CrossValidation b = cross_validate(o, t, 2);
  ASSERT_EQ(b.folds.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(b.folds[i].probabilities, a.folds[i].probabilities);
  EXPECT_EQ(b.choice.threshold, a.choice.threshold);
  // Another training seed: other models.
  t.seed = 3;
  const CrossValidation other = cross_validate(o, t, 2);
  EXPECT_NE(other.folds[0].probabilities, a.folds[0].probabilities);
}

}  // namespace
}  // namespace antcd::learned
