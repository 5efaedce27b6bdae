// The tool's query options against the library: `antcd run --report-distance` writes each
// reported pair's surface distance in the order of "pairs", `antcd run --volume` finds a box
// inside another, `antcd collide --normals/--manifold` prints what collide() computes; without
// the options the output keeps its former fields only.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class CliQueries : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = test::fresh_temp_dir(std::string("cli_queries_") + info->name());
    fs::remove_all(work_.parent_path() / (work_.filename().string() + "_io"));
    save_obj(make_box(Vec3(1, 1, 1)), work_ / "big.obj");
    save_obj(make_box(Vec3(0.2, 0.3, 0.4)), work_ / "small.obj");
    // Frame 0: the small box pokes out of the big one (surfaces cross); frame 1: wholly inside;
    // frame 2: 0.5 beyond the big box's +x face.
    test::write_file(work_ / "scene.json", R"({ "format": "antcd-scene/1", "frames": 3,
      "objects": [ { "name": "big", "mesh": "big.obj", "poses": [ {} ] },
                   { "name": "small", "mesh": "small.obj", "poses": [
                       { "translation": [1, 0, 0] }, { "translation": [0.1, 0, 0] },
                       { "translation": [1.7, 0, 0] } ] } ] })");
  }

  test::CliRun run(const std::vector<std::string>& args) {
    return test::run_program(ANTCD_CLI, args, work_);
  }

  json run_json(const std::vector<std::string>& args, const std::string& out) {
    const test::CliRun r = run(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(test::read_all(work_ / out));
  }

  fs::path work_;
};

TEST_F(CliQueries, RunReportsEachPairsDistanceInTheOrderOfPairs) {
  const json plain =
      run_json({"run", "scene.json", "--delta", "0.65", "--out", "plain.json"}, "plain.json");
  ASSERT_EQ(plain["frames"].size(), 3u);
  for (const json& f : plain["frames"]) EXPECT_FALSE(f.contains("distances"));
  EXPECT_FALSE(plain.contains("volume"));

  const json j =
      run_json({"run", "scene.json", "--delta", "0.65", "--report-distance", "--out", "run.json"},
               "run.json");
  const Model big(load_mesh(work_ / "big.obj"));
  const Model small(load_mesh(work_ / "small.obj"));
  const std::vector<Scalar> x = {1, 0.1, 1.7};
  for (std::size_t f = 0; f < 3; ++f) {
    const json& frame = j["frames"][f];
    ASSERT_EQ(frame["pairs"], plain["frames"][f]["pairs"]) << f;
    ASSERT_TRUE(frame.contains("distances")) << f;
    ASSERT_EQ(frame["distances"].size(), frame["pairs"].size()) << f;
    for (std::size_t k = 0; k < frame["pairs"].size(); ++k) {
      const Scalar truth = distance(big, Transform::identity(), small,
                                    Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x[f], 0, 0)))
                               .distance;
      EXPECT_NEAR(frame["distances"][k].get<double>(), truth, 1e-12) << f;
    }
  }
  // Frame 0 crosses (distance 0), frame 1 is inside with the surfaces 0.6 apart (along z), frame 2
  // is 0.5 beyond the face; all within δ = 0.65. (The files hold float coordinates.)
  EXPECT_EQ(j["frames"][0]["distances"], json::array({0.0}));
  ASSERT_EQ(j["frames"][1]["distances"].size(), 1u);
  EXPECT_NEAR(j["frames"][1]["distances"][0].get<double>(), 0.6, 1e-6);
  ASSERT_EQ(j["frames"][2]["distances"].size(), 1u);
  EXPECT_NEAR(j["frames"][2]["distances"][0].get<double>(), 0.5, 1e-6);
}

TEST_F(CliQueries, RunVolumeFindsTheBoxInsideAndIsOnlyForTheExactMethod) {
  const json surface = run_json({"run", "scene.json", "--out", "surface.json"}, "surface.json");
  EXPECT_EQ(surface["frames"][1]["pairs"], json::array());
  const json volume =
      run_json({"run", "scene.json", "--volume", "--report-distance", "--out", "volume.json"},
               "volume.json");
  EXPECT_EQ(volume["volume"], true);
  EXPECT_EQ(volume["frames"][0]["pairs"], json::parse(R"([["big", "small"]])"));
  EXPECT_EQ(volume["frames"][1]["pairs"], json::parse(R"([["big", "small"]])"));
  EXPECT_EQ(volume["frames"][2]["pairs"], json::array());
  // Contained: colliding, yet the surfaces are apart (the nearest faces 0.6 apart along z).
  EXPECT_NEAR(volume["frames"][1]["distances"][0].get<double>(), 0.6, 1e-6);

  const test::CliRun r = run({"run", "scene.json", "--volume", "--method", "maco"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("--volume"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST_F(CliQueries, CollidePrintsTheLibrarysNormalsDepthsAndManifold) {
  const std::vector<std::string> base = {
      "collide", "big.obj", "small.obj", "--pose-b", "1,0.1,0.05,0.9659258,0,0,0.258819",
      "--all",   "--json"};
  const test::CliRun plain = run(base);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const json p = json::parse(plain.out);
  ASSERT_FALSE(p["contacts"].empty());
  EXPECT_FALSE(p["contacts"][0].contains("normal"));

  std::vector<std::string> args = base;
  args.push_back("--normals");
  const test::CliRun with = run(args);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const json n = json::parse(with.out);
  const Model big(load_mesh(work_ / "big.obj"));
  const Model small(load_mesh(work_ / "small.obj"));
  CollisionRequest req;
  req.all_contacts = true;
  req.contact_normals = true;
  const Transform pb = Transform::from_quaternion(Vec3(1, 0.1, 0.05), 0.9659258, 0, 0, 0.258819);
  const CollisionResult lib = collide(big, Transform::identity(), small, pb, req);
  ASSERT_EQ(n["contacts"].size(), lib.contacts.size());
  for (std::size_t k = 0; k < lib.contacts.size(); ++k) {
    const json& c = n["contacts"][k];
    ASSERT_EQ(c["triangle_a"].get<std::uint32_t>(), lib.contacts[k].triangle_a);
    ASSERT_EQ(c["triangle_b"].get<std::uint32_t>(), lib.contacts[k].triangle_b);
    const Vec3 normal(c["normal"][0].get<double>(), c["normal"][1].get<double>(),
                      c["normal"][2].get<double>());
    EXPECT_NEAR((normal - lib.contacts[k].normal).norm(), 0, 1e-12);
    EXPECT_NEAR(normal.norm(), 1, 1e-12);
    EXPECT_DOUBLE_EQ(c["depth"].get<double>(), lib.contacts[k].depth);
  }

  args = base;
  args.insert(args.end(), {"--manifold", "2"});
  const test::CliRun m = run(args);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const json jm = json::parse(m.out);
  const std::uint32_t regions = jm["regions"].get<std::uint32_t>();
  ASSERT_GE(regions, 1u);
  std::vector<int> per_region(regions, 0);
  for (const json& c : jm["contacts"]) ++per_region.at(c["region"].get<std::uint32_t>());
  for (const int count : per_region) {
    EXPECT_GE(count, 1);
    EXPECT_LE(count, 2);
  }
}

}  // namespace
}  // namespace antcd
