// `antcd depth` and `antcd distance --signed` against the library on the same files and poses.
#include <antcd/distance.hpp>
#include <antcd/load.hpp>
#include <antcd/penetration.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

class CliDepth : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = test::fresh_temp_dir("cli_depth");
    save_obj(make_box(Vec3(1, 1, 1), 2), work_ / "box.obj");
    save_obj(make_torus(2, 0.5, 24, 12), work_ / "torus.obj");
    Mesh open = make_box(Vec3(1, 1, 1));
    open.triangles.pop_back();
    save_obj(open, work_ / "open.obj");
  }
  test::CliRun run(const std::vector<std::string>& args) const {
    return test::run_program(ANTCD_CLI, args, work_);
  }
  std::filesystem::path work_;
};

TEST_F(CliDepth, JsonEqualsTheLibrary) {
  const test::CliRun r = run({"depth", "box.obj", "box.obj", "--pose-b", "1.7,0.3,0.2", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["overlapping"].get<bool>());
  EXPECT_TRUE(j["exact"].get<bool>());
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_NEAR(j["lower"].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(j["upper"].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(j["direction"][0].get<double>(), -1, 1e-12);
  EXPECT_EQ(j["witness"].size(), 3u);

  // A torus on a box, general bounds: the same interval as the library's.
  const test::CliRun t = run({"depth", "torus.obj", "box.obj", "--pose-a", "0,0,1.35",
                              "--rel-tolerance", "0.02", "--json"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const nlohmann::json k = nlohmann::json::parse(t.out);
  const Model torus(load_mesh(work_ / "torus.obj"));
  const Model box(load_mesh(work_ / "box.obj"));
  PenetrationRequest req;
  req.rel_tolerance = 0.02;
  const PenetrationResult lib = penetration(torus, Transform(Mat3::Identity(), Vec3(0, 0, 1.35)),
                                            box, Transform::identity(), req);
  EXPECT_FALSE(k["exact"].get<bool>());
  EXPECT_EQ(k["lower"].get<double>(), lib.lower);
  EXPECT_EQ(k["upper"].get<double>(), lib.upper);
}

TEST_F(CliDepth, SignedDistanceAndErrors) {
  const test::CliRun d =
      run({"distance", "box.obj", "box.obj", "--pose-b", "1.7,0.3,0.2", "--signed", "--json"});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NEAR(nlohmann::json::parse(d.out)["distance"].get<double>(), -0.3, 1e-12);

  const test::CliRun open = run({"depth", "open.obj", "box.obj"});
  EXPECT_EQ(open.exit_code, 2);
  EXPECT_NE(open.err.find("error: "), std::string::npos);
  EXPECT_NE(open.err.find("open.obj"), std::string::npos) << open.err;
  EXPECT_NE(open.err.find("not closed"), std::string::npos) << open.err;
  const test::CliRun shape = run({"depth", "box.obj", "box.obj", "--shape", "round"});
  EXPECT_EQ(shape.exit_code, 2);
  EXPECT_NE(shape.err.find("--shape"), std::string::npos);
}

}  // namespace
}  // namespace antcd
