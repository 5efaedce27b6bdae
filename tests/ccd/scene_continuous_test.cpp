// `Scene` continuous frames (SceneQuery::continuous), their run-result fields (toi,
// contact_points; older results still load) and `antcd run --continuous`, on the generated
// fast thin-sheet scene where per-frame discrete checks tunnel.
#include <antcd/error.hpp>
#include <antcd/file.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "ccd/continuous_support.hpp"
#include "shared/run_result.hpp"
#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

constexpr int kSheets = 12;
constexpr int kFrames = 21;

SceneDescription sheet_scene() {
  SceneDescription d;
  d.frames = kFrames;
  const auto tracks = test::fast_sheet_tracks(kSheets, kFrames);
  for (int k = 0; k < kSheets; ++k) {
    SceneObject o;
    o.name = "sheet_" + std::to_string(k);
    o.mesh = "sheet.obj";
    o.mesh_text = "sheet.obj";
    o.poses = tracks[static_cast<std::size_t>(k)];
    d.objects.push_back(std::move(o));
  }
  return d;
}

Scene sheet_scene_engine() {
  return Scene(sheet_scene(), [](const SceneObject&) { return make_box(test::fast_sheet_half()); });
}

TEST(SceneContinuous, FastSheetsEveryContactFoundDiscreteTunnels) {
  const Scene scene = sheet_scene_engine();
  SceneQuery continuous;
  continuous.continuous = true;
  const SceneQuery discrete;
  int truth = 0, found = 0, discrete_found = 0, false_alarms = 0;
  for (std::size_t f = 0; f < kFrames; ++f) {
    const FrameResult c = scene.run_frame(f, continuous);
    const FrameResult d = scene.run_frame(f, discrete);
    ASSERT_EQ(c.toi.size(), c.pairs.size());
    ASSERT_EQ(c.contact_points.size(), c.pairs.size());
    if (f == 0) {  // no step before frame 0: the pairs touching there, at toi 0
      EXPECT_EQ(c.pairs, d.pairs);
      for (const Scalar t : c.toi) EXPECT_EQ(t, 0);
      continue;
    }
    for (std::uint32_t i = 0; i < kSheets; ++i) {
      for (std::uint32_t j = i + 1; j < kSheets; ++j) {
        const auto& oi = scene.description().objects[i];
        const auto& oj = scene.description().objects[j];
        const auto dense =
            test::first_substep_contact(scene.model_of(i), oi.pose(f - 1), oi.pose(f),
                                        scene.model_of(j), oj.pose(f - 1), oj.pose(f), 0, 200);
        const auto it = std::find(c.pairs.begin(), c.pairs.end(), std::make_pair(i, j));
        const bool hit = it != c.pairs.end();
        const bool frame_hit =
            std::find(d.pairs.begin(), d.pairs.end(), std::make_pair(i, j)) != d.pairs.end();
        truth += dense ? 1 : 0;
        found += dense && hit ? 1 : 0;
        discrete_found += dense && frame_hit ? 1 : 0;
        false_alarms += !dense && hit ? 1 : 0;
        if (dense) {
          ASSERT_TRUE(hit) << "frame " << f << " pair " << i << "," << j;
          const Scalar toi = c.toi[static_cast<std::size_t>(it - c.pairs.begin())];
          EXPECT_LE(toi, *dense) << "frame " << f << " pair " << i << "," << j;
        }
        if (hit) {
          EXPECT_NE(std::find(c.candidates.begin(), c.candidates.end(), std::make_pair(i, j)),
                    c.candidates.end());
        }
      }
    }
  }
  std::cout << "fast sheet scene (Scene, continuous): " << truth
            << " pair-steps with a sub-stepped contact; continuous finds " << found << ", discrete "
            << discrete_found << "; continuous hits without one: " << false_alarms << '\n';
  EXPECT_GT(truth, 10);
  EXPECT_EQ(found, truth);
  EXPECT_LT(discrete_found, truth / 2);
}

TEST(SceneContinuous, ResultFieldsRoundTripAndOldResultsLoad) {
  const Scene scene = sheet_scene_engine();
  SceneQuery query;
  query.continuous = true;
  const shared::RunResult run = shared::run_scene(scene, query, "sheets.json");
  EXPECT_TRUE(run.continuous);
  const std::string text = shared::to_json(run);
  const shared::RunResult back = shared::parse_run_result(text, "round trip");
  EXPECT_TRUE(back.continuous);
  ASSERT_EQ(back.frames.size(), run.frames.size());
  std::size_t pairs = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    ASSERT_TRUE(back.frames[k].toi && back.frames[k].contact_points);
    EXPECT_EQ(*back.frames[k].toi, *run.frames[k].toi);
    EXPECT_EQ(*back.frames[k].contact_points, *run.frames[k].contact_points);
    pairs += run.frames[k].pairs.size();
  }
  EXPECT_GT(pairs, 10U);
  EXPECT_THROW((void)shared::run_scene(scene, query, "sheets.json", {}, 2), Error);

  // A result written before continuous runs existed (committed file) still loads.
  const auto old_path = std::filesystem::path(ANTCD_CCD_DATA) / "run_result_v1.json";
  const shared::RunResult old = shared::parse_run_result(read_file(old_path), old_path.string());
  EXPECT_FALSE(old.continuous);
  ASSERT_EQ(old.frames.size(), 2U);
  EXPECT_FALSE(old.frames[1].toi.has_value());
  EXPECT_FALSE(old.frames[1].contact_points.has_value());
  EXPECT_EQ(old.frames[1].pairs.size(), 1U);

  // Malformed fields are refused with the frame named.
  nlohmann::json j = nlohmann::json::parse(text);
  for (auto& f : j["frames"]) {
    if (!f["pairs"].empty()) {
      f["toi"][0] = 1.5;
      break;
    }
  }
  try {
    (void)shared::parse_run_result(j.dump(), "bad.json");
    ADD_FAILURE() << "toi 1.5 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'toi' must hold numbers in [0, 1]"), std::string::npos)
        << e.what();
  }
}

TEST(SceneContinuous, RefusedWithOtherMethodsAndVolume) {
  const Scene scene = sheet_scene_engine();
  SceneQuery query;
  query.continuous = true;
  query.method = Method::Aco;
  EXPECT_THROW((void)scene.run_frame(1, query), ArgumentError);
  query.method = Method::Exact;
  query.volume = true;
  EXPECT_THROW((void)scene.run_frame(1, query), ArgumentError);
}

#ifdef ANTCD_CLI
TEST(SceneContinuous, CliRunContinuousWritesToiAndRefusesOtherMethods) {
  const auto dir = test::fresh_temp_dir("scene_continuous_cli");
  save_obj(make_box(test::fast_sheet_half()), dir / "sheet.obj");
  save_scene(sheet_scene(), dir / "scene.json");
  const auto run =
      test::run_program(ANTCD_CLI, {"run", "scene.json", "--continuous", "--out", "r.json"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json r = nlohmann::json::parse(test::read_all(dir / "r.json"));
  EXPECT_EQ(r["continuous"], true);
  std::size_t pairs = 0;
  for (const auto& f : r["frames"]) {
    ASSERT_EQ(f["toi"].size(), f["pairs"].size());
    ASSERT_EQ(f["contact_points"].size(), f["pairs"].size());
    pairs += f["pairs"].size();
  }
  EXPECT_GT(pairs, 10U);
  const auto text = test::run_program(ANTCD_CLI, {"run", "scene.json", "--continuous"}, dir);
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("continuous: pairs touching between frames"), std::string::npos)
      << text.out;
  const auto bad =
      test::run_program(ANTCD_CLI, {"run", "scene.json", "--continuous", "--method", "aco"}, dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("error: --continuous is for --method exact, not aco"), std::string::npos)
      << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}
#endif

}  // namespace
}  // namespace antcd
