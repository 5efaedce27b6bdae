// The learned baselines (antcd_learned): feature invariance, learning beyond a constant guess,
// deterministic training, model files (round trip, refusal of bad ones), the CLI's errors, and the
// by-mesh split (meshes.hpp): folds are disjoint sets of meshes, held-out meshes never reach a
// training scene, a model trained on some meshes beats the constant guess on meshes it never saw.
#include <gtest/gtest.h>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd_learned/classifier.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/features.hpp>
#include <antcd_learned/meshes.hpp>

#include <sys/wait.h>

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

std::string one_model_bytes(const fs::path& dir) {
  Dataset d;
  d.window = 1;
  for (int i = 0; i < 64; ++i) {
    for (std::size_t k = 0; k < kFeatureCount; ++k) {
      d.features.push_back(static_cast<float>((i * 7 + static_cast<int>(k)) % 13) / 13.0F);
    }
    d.labels.push_back(i % 3 == 0 ? 1 : 0);
  }
  TrainOptions o;
  o.epochs = 2;
  Classifier::train(d, o).save(dir / "good.pt");
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
  std::string err;
};

CliRun cli(const std::string& args, const fs::path& dir) {
  const std::string err = (dir / "stderr.txt").string();
  const std::string cmd =
      std::string("'") + ANTCD_CLI + "' " + args + " > /dev/null 2> '" + err + "'";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  r.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
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
#endif

}  // namespace
}  // namespace antcd::learned

// ---- The by-mesh split ----

namespace antcd::learned {
namespace {

std::vector<fs::path> names(std::size_t n) {
  std::vector<fs::path> v;
  for (std::size_t i = 0; i < n; ++i) v.emplace_back("m" + std::to_string(i) + ".obj");
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
      auto a = "m" + std::to_string(i) + ".obj";
      auto b = "m" + std::to_string((i + 1) % n) + ".obj";
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

TEST(LearnedMeshSplit, AModelBeatsTheConstantGuessOnMeshesItNeverSaw) {
  // Train on generated shapes and two assimp meshes; judge on a scene of two other assimp meshes.
  const fs::path dir = test::fresh_temp_dir("learned_mesh_split");
  save_obj(make_torus(0.8, 0.25, 32, 12), dir / "torus.obj");
  save_obj(make_sphere(0.6, 20, 10), dir / "sphere.obj");
  TrainingSetOptions o;
  o.scenes = 2;  // a production line, then mesh pairs
  o.frames = 60;
  o.seed = 5;
  o.min_objects = 20;
  o.max_objects = 24;
  o.mesh_files = {dir / "torus.obj", dir / "sphere.obj",
                  test::assimp_model("STL/sphereWithHole.stl"),
                  test::assimp_model("FBX/huesitos.fbx")};
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

}  // namespace
}  // namespace antcd::learned
