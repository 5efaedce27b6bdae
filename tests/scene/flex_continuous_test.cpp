// Continuous frames of scenes with deforming objects (SceneQuery::continuous on `scene generate
// --flexible` scenes; World::sweep_motion underneath): against dense sub-stepping of each step
// with exact discrete tests (collide() on the rigid objects at interpolated poses and on the
// sheets rebuilt from interpolated world vertices, self_intersections on the rebuilt sheets):
// never a missed pair, toi <= the first sub-step in contact; the same answer at 1 and 3 threads
// and in any frame order; `antcd run --continuous` on the generator's output.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/scene.hpp>
#include <antcd/self.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "shared/production_line.hpp"
#include "shared/run_result.hpp"
#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

shared::GeneratedScene small_flexible(std::size_t frames) {
  shared::ProductionLineOptions o;
  o.objects = 18;  // one conveyor (10 rollers, 2 sheets, bed, portal) and a filler
  o.vertices = 120;
  o.frames = frames;
  o.seed = 5;
  o.flexible = true;
  return shared::generate_production_line(o);
}

using Pair = std::pair<std::uint32_t, std::uint32_t>;

/// The first of `steps` + 1 sub-steps of the step from frame - 1 to frame at which each pair is
/// within delta (self pairs (i, i): intersects itself), by exact discrete tests.
std::map<Pair, Scalar> substeps(const Scene& scene, std::size_t frame, Scalar delta, int steps) {
  const auto& objects = scene.description().objects;
  const std::size_t from = frame == 0 ? 0 : frame - 1;
  std::map<Pair, Scalar> first;
  for (int s = 0; s <= steps; ++s) {
    const Scalar t = Scalar(s) / steps;
    std::vector<std::shared_ptr<const Model>> models(objects.size());
    std::vector<Transform> poses(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const SceneObject& o = objects[i];
      if (!o.deforming()) {
        poses[i] = ccd::interpolate_pose(o.pose(from), o.pose(frame), t);
        continue;
      }
      Mesh mesh = scene.model_of(i).mesh();
      const auto v0 = o.vertex_frames->frame(from);
      const auto v1 = o.vertex_frames->frame(frame);
      for (std::size_t k = 0; k < v0.size(); ++k) {
        mesh.vertices[k] = (1 - t) * o.pose(from).apply(v0[k] * o.scale) +
                           t * o.pose(frame).apply(v1[k] * o.scale);
      }
      models[i] = std::make_shared<const Model>(std::move(mesh));
    }
    const auto model = [&](std::size_t i) -> const Model& {
      return models[i] ? *models[i] : scene.model_of(i);
    };
    for (std::uint32_t i = 0; i < objects.size(); ++i) {
      if (objects[i].self_collision && !first.contains({i, i}) &&
          self_intersections(model(i)).intersecting) {
        first[{i, i}] = t;
      }
      for (std::uint32_t j = i + 1; j < objects.size(); ++j) {
        if (first.contains({i, j})) continue;
        CollisionResult r;
        if (collide(model(i), poses[i], model(j), poses[j], {delta, false, 0}, r)) {
          first[{i, j}] = t;
        }
      }
    }
  }
  return first;
}

TEST(FlexContinuous, NeverMissesAPairAgainstSubstepping) {
  const shared::GeneratedScene g = small_flexible(6);
  const Scene scene = shared::make_scene(g);
  std::size_t in_contact = 0;
  std::size_t self_pairs = 0;
  std::size_t sheet_pairs = 0;
  for (const Scalar delta : {0.0, 0.003}) {
    SceneQuery q;
    q.continuous = true;
    q.delta = delta;
    for (std::size_t f = 0; f < g.scene.frames; ++f) {
      const FrameResult r = scene.run_frame(f, q);
      ASSERT_EQ(r.toi.size(), r.pairs.size());
      ASSERT_EQ(r.contact_points.size(), r.pairs.size());
      EXPECT_TRUE(std::is_sorted(r.pairs.begin(), r.pairs.end()));
      std::map<Pair, Scalar> got;
      for (std::size_t k = 0; k < r.pairs.size(); ++k) got[r.pairs[k]] = r.toi[k];
      for (const auto& [pair, t] : substeps(scene, f, delta, 200)) {
        ++in_contact;
        const auto& objects = g.scene.objects;
        if (pair.first == pair.second) ++self_pairs;
        if (objects[pair.first].deforming() != objects[pair.second].deforming()) ++sheet_pairs;
        const auto it = got.find(pair);
        ASSERT_NE(it, got.end()) << "frame " << f << " delta " << delta << ": missed "
                                 << objects[pair.first].name << " / " << objects[pair.second].name
                                 << " (in contact at t = " << t << ")";
        EXPECT_LE(it->second, t) << "frame " << f << " " << objects[pair.first].name << " / "
                                 << objects[pair.second].name;
      }
    }
  }
  // The scene exercises the motion: sheets on rollers, and sheets folding into themselves.
  EXPECT_GT(sheet_pairs, 10U);
  EXPECT_GT(self_pairs, 0U);
  EXPECT_GT(in_contact, 20U);
}

TEST(FlexContinuous, SameAnswerAtAnyThreadCountAndFrameOrder) {
  const shared::GeneratedScene g = small_flexible(8);
  const Scene scene = shared::make_scene(g);
  SceneQuery q;
  q.continuous = true;
  q.delta = 0.002;
  std::vector<FrameResult> forward;
  for (std::size_t f = 0; f < g.scene.frames; ++f) forward.push_back(scene.run_frame(f, q));
  q.threads = 3;
  for (std::size_t f = g.scene.frames; f-- > 0;) {
    const FrameResult r = scene.run_frame(f, q);
    EXPECT_EQ(r.pairs, forward[f].pairs) << f;
    EXPECT_EQ(r.toi, forward[f].toi) << f;
    EXPECT_EQ(r.candidates, forward[f].candidates) << f;
  }
}

#ifdef ANTCD_CLI
TEST(FlexContinuous, CliRunsContinuousOnGeneratedFlexibleScenes) {
  const auto dir = test::fresh_temp_dir("flex_continuous_cli");
  const auto gen = test::run_program(ANTCD_CLI,
                                     {"scene", "generate", "--out", "s", "--flexible", "--objects",
                                      "18", "--frames", "6", "--vertices", "100"},
                                     dir);
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  const auto run =
      test::run_program(ANTCD_CLI, {"run", "s/scene.json", "--continuous", "--out", "r.json"}, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const shared::RunResult r = shared::parse_run_result(test::read_all(dir / "r.json"), "r.json");
  EXPECT_TRUE(r.continuous);
  std::size_t pairs = 0;
  std::size_t self = 0;
  for (const shared::FrameRecord& f : r.frames) {
    ASSERT_TRUE(f.toi.has_value());
    ASSERT_TRUE(f.contact_points.has_value());
    EXPECT_EQ(f.toi->size(), f.pairs.size());
    EXPECT_EQ(f.contact_points->size(), f.pairs.size());
    EXPECT_TRUE(f.self_pairs.empty());  // continuous self pairs carry a toi, not triangle pairs
    pairs += f.pairs.size();
    for (const auto& [a, b] : f.pairs) self += a == b ? 1 : 0;
  }
  EXPECT_GT(pairs, 0U);
  EXPECT_GT(self, 0U);
  const auto text = test::run_program(ANTCD_CLI, {"run", "s/scene.json", "--continuous"}, dir);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("continuous"), std::string::npos) << text.out;
}
#endif

}  // namespace
}  // namespace antcd
