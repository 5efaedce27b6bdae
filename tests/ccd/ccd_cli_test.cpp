// `antcd ccd-queries` on rational CSV files written from the exact corpus, and its error lines.
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "ccd/exact_truth.hpp"
#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

std::vector<test::CcdQuery> only(const std::vector<test::CcdQuery>& all, test::CcdKind kind) {
  std::vector<test::CcdQuery> out;
  for (const auto& q : all) {
    if (q.kind == kind) out.push_back(q);
  }
  return out;
}

class CcdCli : public ::testing::Test {
 protected:
  // One directory per test: ctest -j runs this fixture's tests side by side.
  void SetUp() override {
    dir_ = test::fresh_temp_dir(std::string("ccd_cli_") +
                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  test::CliRun run(const std::vector<std::string>& args) {
    return test::run_program(ANTCD_CLI, args, dir_);
  }
  std::filesystem::path dir_;
};

TEST_F(CcdCli, CorpusFilesScoreWithoutFalseNegatives) {
  const auto corpus = test::degenerate_corpus();
  for (const auto kind : {test::CcdKind::VertexFace, test::CcdKind::EdgeEdge}) {
    const auto queries = only(corpus, kind);
    const std::string name = kind == test::CcdKind::VertexFace ? "vf" : "ee";
    const auto file = dir_ / (name + ".csv");
    test::write_file(file, test::to_rational_csv(queries));
    const auto r = run({"ccd-queries", file.string(), "--kind", name, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["queries"].get<std::size_t>(), queries.size());
    EXPECT_EQ(j["false_negatives"].get<int>(), 0);
    ASSERT_EQ(j["results"].size(), queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
      // File order, and the same answer as the library on the same doubles.
      const bool truth = *test::ccd_truth(queries[i]);
      if (truth) {
        EXPECT_TRUE(j["results"][i]["hit"].get<bool>()) << queries[i].name;
      }
    }
  }
  const auto text = run({"ccd-queries", (dir_ / "vf.csv").string(), "--kind", "vf"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("false negatives: 0"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("time per query"), std::string::npos) << text.out;
}

TEST_F(CcdCli, InexactRationalsWidenTheSeparation) {
  // A spike through the corner of the face at exactly 1/3, 1/3 (not a double): the exact query
  // touches; the doubles may not, and the widened separation keeps it a hit.
  std::string csv;
  const char* rows[8] = {"1,3,1,3,1,1,1",  "0,1,0,1,0,1,1", "2,3,0,1,0,1,1", "0,1,2,3,0,1,1",
                         "1,3,1,3,-1,1,1", "0,1,0,1,0,1,1", "2,3,0,1,0,1,1", "0,1,2,3,0,1,1"};
  for (const char* row : rows) csv += std::string(row) + "\n";
  test::write_file(dir_ / "third.csv", csv);
  const auto r = run({"ccd-queries", (dir_ / "third.csv").string(), "--kind", "vf"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("false negatives: 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not exact in double: 1"), std::string::npos) << r.out;
}

TEST_F(CcdCli, BadFilesNameTheRow) {
  const std::string good = "0,1,0,1,0,1,0\n";
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {good + "1,2,3\n", "row 2: expected 7 fields"},
      {good + "1,0,0,1,0,1,0\n", "row 2: zero denominator"},
      {good + "1x,1,0,1,0,1,0\n", "row 2: not an integer: '1x'"},
      {good, "row 1: incomplete query (1 of 8 rows)"},
  };
  for (const auto& c : cases) {
    test::write_file(dir_ / "bad.csv", c.text);
    const auto r = run({"ccd-queries", (dir_ / "bad.csv").string(), "--kind", "ee"});
    EXPECT_EQ(r.exit_code, 2) << c.expect;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const auto r = run({"ccd-queries", (dir_ / "bad.csv").string(), "--kind", "xx"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--kind must be vf or ee"), std::string::npos) << r.err;
}

TEST_F(CcdCli, SweepMatchesTheLibrary) {
  const auto box = test::assimp_model("OBJ/box.obj");
  const auto r = run({"sweep", box.string(), box.string(), "--pose-a0", "-5,0,0", "--pose-a1",
                      "5,0,0,0,0,0,1", "--pose-b1", "0,1,0", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const Model m(load_mesh(box), {}, "box");
  const SweepResult s =
      sweep(m, Transform::from_axis_angle(Vec3::UnitZ(), 0, {-5, 0, 0}),
            Transform::from_quaternion({5, 0, 0}, 0, 0, 0, 1), m, Transform::identity(),
            Transform::from_axis_angle(Vec3::UnitZ(), 0, {0, 1, 0}));
  ASSERT_TRUE(s.hit);
  EXPECT_TRUE(j["hit"].get<bool>());
  EXPECT_EQ(j["toi"].get<double>(), s.toi);
  EXPECT_EQ(j["contact"]["triangle_a"].get<std::uint32_t>(), s.contact.triangle_a);
  EXPECT_EQ(j["tolerance_decided"].get<bool>(), s.tolerance_decided);
  const auto bad = run({"sweep", box.string(), box.string(), "--pose-b0", "1,2"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("error: --pose-b0"), std::string::npos) << bad.err;
}

// Issue 41: a pass-through at +-1e155 answered "hit: no (proven ...: inf)"; at +-1e154 the error
// named distance's abs_tolerance. Beyond the coordinate range: exit 2 naming the pose; within it,
// the contact at t = 0.5.
TEST_F(CcdCli, SweepBeyondTheCoordinateRangeIsAnError) {
  const auto box = test::assimp_model("OBJ/box.obj");
  for (const std::string s : {"1e154", "1e155", "1e300", "8.98846567431158e307"}) {
    const auto r = run({"sweep", box.string(), box.string(), "--pose-a0", "-" + s + ",0,0",
                        "--pose-a1", s + ",0,0"});
    EXPECT_EQ(r.exit_code, 2) << s << ": " << r.out;
    EXPECT_EQ(r.err.rfind("error: sweep: pose_a0 translation is beyond the continuous queries' "
                          "coordinate range",
                          0),
              0U)
        << s << ": " << r.err;
    EXPECT_EQ(r.out, "") << s;
  }
  const auto r = run({"sweep", box.string(), box.string(), "--pose-a0", "-1e100,0,0", "--pose-a1",
                      "1e100,0,0", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["hit"].get<bool>());
  EXPECT_LE(j["toi"].get<double>(), 0.5);
}

}  // namespace
}  // namespace antcd
