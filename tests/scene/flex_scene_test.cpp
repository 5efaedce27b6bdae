// Deforming scene objects, the run side: `scene generate --flexible` scenes run frame by frame
// against brute force (collide and self_intersections on Models rebuilt from each frame's
// vertices), at several thread counts, from memory and from the written files; the other methods
// on deforming objects; the CLI's refusals.
#include <antcd/collide.hpp>
#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/scene.hpp>
#include <antcd/self.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene/flex_support.hpp"
#include "shared/production_line.hpp"
#include "shared/run_result.hpp"
#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

shared::GeneratedScene small_flexible(std::size_t frames = 12) {
  shared::ProductionLineOptions o;
  o.objects = 18;  // one conveyor (10 rollers, 2 sheets, bed, portal) and a filler
  o.vertices = 120;
  o.frames = frames;
  o.seed = 5;
  o.flexible = true;
  return shared::generate_production_line(o);
}

struct Truth {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<SelfPairs> self_pairs;
};

/// Brute force over every object pair: Models built afresh from the frame's meshes (a deforming
/// object's mesh with the frame's vertices, scaled), collide() on each pair at `delta`, and
/// self_intersections on each self_collision object.
Truth brute_force(const Scene& scene, std::size_t frame, Scalar delta) {
  const auto& objects = scene.description().objects;
  std::vector<std::shared_ptr<const Model>> models;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const SceneObject& o = objects[i];
    if (!o.deforming()) {
      models.push_back(nullptr);
      continue;
    }
    Mesh mesh = scene.model_of(i).mesh();
    const auto v = o.vertex_frames->frame(frame);
    for (std::size_t k = 0; k < v.size(); ++k) mesh.vertices[k] = v[k] * o.scale;
    models.push_back(std::make_shared<const Model>(std::move(mesh)));
  }
  const auto model = [&](std::size_t i) -> const Model& {
    return models[i] ? *models[i] : scene.model_of(i);
  };
  Truth t;
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    if (objects[i].self_collision) {
      SelfIntersectionResult r = self_intersections(model(i));
      if (r.intersecting) {
        t.pairs.emplace_back(i, i);
        t.self_pairs.push_back({i, std::move(r.pairs)});
      }
    }
    for (std::uint32_t j = i + 1; j < objects.size(); ++j) {
      CollisionResult r;
      if (collide(model(i), objects[i].pose(frame), model(j), objects[j].pose(frame),
                  {delta, false, 0}, r)) {
        t.pairs.emplace_back(i, j);
      }
    }
  }
  return t;
}

void expect_same(const FrameResult& r, const Truth& t, const std::string& what) {
  EXPECT_EQ(r.pairs, t.pairs) << what;
  ASSERT_EQ(r.self_pairs.size(), t.self_pairs.size()) << what;
  for (std::size_t k = 0; k < t.self_pairs.size(); ++k) {
    EXPECT_EQ(r.self_pairs[k].object, t.self_pairs[k].object) << what;
    EXPECT_EQ(r.self_pairs[k].triangles, t.self_pairs[k].triangles) << what;
  }
}

TEST(FlexScene, GeneratorMakesSaggingDroopingAndFoldingSheets) {
  const shared::GeneratedScene g = small_flexible();
  std::size_t deforming = 0;
  for (const SceneObject& o : g.scene.objects) {
    if (!o.deforming()) continue;
    ++deforming;
    EXPECT_TRUE(o.self_collision);
    ASSERT_NE(o.vertex_frames, nullptr);
    EXPECT_EQ(o.vertex_frames->frames, g.scene.frames);
    EXPECT_EQ(o.vertex_file_text, "frames/" + o.name + ".avf");
    // Sag and droop: the sheet is not flat; nothing rises above the rollers' contact line except
    // a folding flap.
    Scalar lowest = 0;
    for (const Vec3& p : o.vertex_frames->positions) lowest = std::min(lowest, p.z());
    EXPECT_LT(lowest, -0.005) << o.name;
  }
  EXPECT_GE(deforming, 2u);
  // Deterministic: the same options give the same scene, positions bit for bit.
  const shared::GeneratedScene h = small_flexible();
  ASSERT_EQ(h.scene.objects.size(), g.scene.objects.size());
  for (std::size_t i = 0; i < g.scene.objects.size(); ++i) {
    if (!g.scene.objects[i].deforming()) continue;
    EXPECT_EQ(h.scene.objects[i].vertex_frames->positions,
              g.scene.objects[i].vertex_frames->positions);
  }
  // Rigid scenes are unchanged by the option's existence: no deforming object without it.
  shared::ProductionLineOptions rigid;
  rigid.objects = 18;
  rigid.frames = 4;
  for (const SceneObject& o : shared::generate_production_line(rigid).scene.objects) {
    EXPECT_FALSE(o.deforming());
  }
}

TEST(FlexScene, ExactRunEqualsBruteForceAtAnyThreadCount) {
  const shared::GeneratedScene g = small_flexible();
  const Scene scene = shared::make_scene(g);
  std::size_t self_frames = 0;
  std::size_t sheet_roller_pairs = 0;
  for (const Scalar delta : {0.0, 0.003}) {
    SceneQuery q;
    q.delta = delta;
    for (std::size_t f = 0; f < g.scene.frames; ++f) {
      const Truth t = brute_force(scene, f, delta);
      q.threads = 1;
      const FrameResult one = scene.run_frame(f, q);
      expect_same(one, t, "frame " + std::to_string(f) + " delta " + std::to_string(delta));
      q.threads = 3;
      expect_same(scene.run_frame(f, q), t, "threads 3, frame " + std::to_string(f));
      self_frames += t.self_pairs.empty() ? 0 : 1;
      for (const auto& [i, j] : t.pairs) {
        if (i != j && (g.scene.objects[i].deforming() || g.scene.objects[j].deforming())) {
          ++sheet_roller_pairs;
        }
      }
    }
  }
  // The folding sheet passes through itself in some frames (and not in all), and the sheets
  // touch the rollers: the comparison is not vacuous.
  EXPECT_GT(self_frames, 0u);
  EXPECT_LT(self_frames, 2 * g.scene.frames);
  EXPECT_GT(sheet_roller_pairs, 0u);
  // Frames in any order give the same answer (the refitted Model depends on its frame alone).
  SceneQuery q;
  const FrameResult late = scene.run_frame(7, q);
  (void)scene.run_frame(2, q);
  expect_same(scene.run_frame(7, q), {late.pairs, late.self_pairs}, "frame 7 again");
}

TEST(FlexScene, WrittenFilesRunAsTheSceneInMemory) {
  const shared::GeneratedScene g = small_flexible(9);
  const auto dir = test::fresh_temp_dir("flex_scene_files");
  const auto path = shared::write_scene(g, dir);
  EXPECT_TRUE(std::filesystem::exists(dir / "frames"));
  const Scene loaded(load_scene(path));
  const Scene memory = shared::make_scene(g);
  for (std::size_t f = 0; f < g.scene.frames; ++f) {
    const FrameResult a = loaded.run_frame(f, {});
    const FrameResult b = memory.run_frame(f, {});
    expect_same(a, {b.pairs, b.self_pairs}, "frame " + std::to_string(f));
  }
  // The run result carries the self pairs with their triangles, and reads back.
  const shared::RunResult r = shared::run_scene(loaded, {}, "scene.json");
  const shared::RunResult back = shared::parse_run_result(shared::to_json(r), "r.json");
  std::size_t self = 0;
  for (std::size_t f = 0; f < r.frames.size(); ++f) {
    EXPECT_EQ(back.frames[f].self_pairs, r.frames[f].self_pairs);
    self += r.frames[f].self_pairs.size();
    for (const auto& [name, triangles] : r.frames[f].self_pairs) {
      EXPECT_FALSE(triangles.empty());
      EXPECT_NE(std::find(r.frames[f].pairs.begin(), r.frames[f].pairs.end(),
                          shared::NamePair{name, name}),
                r.frames[f].pairs.end());
    }
  }
  EXPECT_GT(self, 0u);
}

TEST(FlexScene, OtherMethodsRunOnTheRefittedModels) {
  const shared::GeneratedScene g = small_flexible(6);
  const Scene scene = shared::make_scene(g);
  for (std::size_t f = 0; f < g.scene.frames; ++f) {
    const Truth t = brute_force(scene, f, 0);
    std::set<std::pair<std::uint32_t, std::uint32_t>> exact;
    for (const auto& p : t.pairs) {
      if (p.first != p.second) exact.insert(p);
    }
    // Sphere-OBB reports leaf-volume overlaps of the refitted hierarchies: a superset of the
    // exact pairs (a hierarchy left at the rest shape would miss the sagging parts).
    SceneQuery sphere;
    sphere.method = Method::SphereObb;
    const FrameResult s = scene.run_frame(f, sphere);
    EXPECT_TRUE(s.self_pairs.empty());
    for (const auto& p : exact) {
      EXPECT_NE(std::find(s.pairs.begin(), s.pairs.end(), p), s.pairs.end())
          << "frame " << f << " pair " << p.first << "," << p.second;
    }
    // The random methods: witnesses are exact triangle hits, so every reported pair is an exact
    // pair; the same answer at 1 and 3 threads.
    SceneQuery aco;
    aco.method = Method::Aco;
    aco.seed = 11;
    const FrameResult a1 = scene.run_frame(f, aco);
    aco.threads = 3;
    const FrameResult a3 = scene.run_frame(f, aco);
    EXPECT_EQ(a1.pairs, a3.pairs);
    EXPECT_EQ(a1.evaluations, a3.evaluations);
    for (const auto& p : a1.pairs) EXPECT_TRUE(exact.count(p) > 0) << "frame " << f;
  }
}

#ifdef ANTCD_CLI
TEST(FlexScene, CliGeneratesRunsAndRefusesBadSideFiles) {
  const auto dir = test::fresh_temp_dir("flex_scene_cli");
  const auto gen = test::run_program(ANTCD_CLI,
                                     {"scene", "generate", "--out", "s", "--flexible", "--objects",
                                      "18", "--frames", "10", "--vertices", "100"},
                                     dir);
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_NE(gen.out.find("flexible sheets"), std::string::npos) << gen.out;
  const std::string first = test::read_all(dir / "s" / "frames" / "sheet_00.avf");
  // Same options, same bytes.
  const auto again = test::run_program(ANTCD_CLI,
                                       {"scene", "generate", "--out", "t", "--flexible",
                                        "--objects", "18", "--frames", "10", "--vertices", "100"},
                                       dir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::read_all(dir / "t" / "frames" / "sheet_00.avf"), first);
  EXPECT_EQ(test::read_all(dir / "t" / "scene.json"), test::read_all(dir / "s" / "scene.json"));

  const auto run = test::run_program(ANTCD_CLI, {"run", "s/scene.json", "--out", "r.json"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(test::read_all(dir / "r.json").find("\"self_pairs\""), std::string::npos);

  // Bad side files: exit 2, one line naming the file and the problem.
  const auto side = dir / "s" / "frames" / "sheet_00.avf";
  test::write_file(side, first.substr(0, first.size() - 8));
  test::expect_clean_refusal(test::run_program(ANTCD_CLI, {"run", "s/scene.json"}, dir),
                             "sheet_00.avf: truncated");
  std::string magic = first;
  magic[1] = 'X';
  test::write_file(side, magic);
  test::expect_clean_refusal(test::run_program(ANTCD_CLI, {"run", "s/scene.json"}, dir),
                             "wrong magic");
  std::filesystem::remove(side);
  test::expect_clean_refusal(test::run_program(ANTCD_CLI, {"run", "s/scene.json"}, dir),
                             "sheet_00.avf: no such file");
  test::expect_clean_refusal(test::run_program(ANTCD_CLI,
                                               {"scene", "generate", "--out", "u", "--flexible",
                                                "--mesh", "s/meshes/veneer_sheet_flexible.obj"},
                                               dir),
                             "--flexible");
}
#endif

}  // namespace
}  // namespace antcd
