// `antcd self-intersect` and `antcd self-proximity` against the library: the JSON holds the
// library's pairs in the file's triangle order; exit 0 whether or not the mesh meets itself;
// bad input exits 2 with one "error: ..." line.
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/self.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "self/self_meshes.hpp"
#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class CliSelf : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = test::fresh_temp_dir(std::string("cli_self_") + info->name());
    fs::remove_all(work_.parent_path() / (work_.filename().string() + "_io"));
    save_obj(test::looped_sheet(40, 6), work_ / "looped.obj");
    save_obj(test::flat_sheet(8, 8), work_ / "flat.obj");
  }
  test::CliRun run(const std::vector<std::string>& args) {
    return test::run_program(ANTCD_CLI, args, work_);
  }
  fs::path work_;
};

TEST_F(CliSelf, SelfIntersectJsonHoldsTheLibrarysPairs) {
  const test::CliRun r = run({"self-intersect", "looped.obj", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  const Mesh mesh = load_mesh(work_ / "looped.obj");
  const SelfIntersectionResult lib = self_intersections(Model(mesh));
  ASSERT_FALSE(lib.pairs.empty());
  EXPECT_EQ(j["triangles"], mesh.triangles.size());
  EXPECT_EQ(j["count"], lib.pairs.size());
  ASSERT_EQ(j["pairs"].size(), lib.pairs.size());
  for (std::size_t k = 0; k < lib.pairs.size(); ++k) {
    EXPECT_EQ(j["pairs"][k][0], lib.pairs[k][0]);
    EXPECT_EQ(j["pairs"][k][1], lib.pairs[k][1]);
  }
  EXPECT_GE(j["seconds"].get<double>(), 0);
}

TEST_F(CliSelf, SelfIntersectExitsZeroOnACleanMesh) {
  const test::CliRun r = run({"self-intersect", "flat.obj", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["count"], 0);
  EXPECT_TRUE(j["pairs"].empty());
  const test::CliRun text = run({"self-intersect", "flat.obj"});
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("self-intersecting pairs: 0"), std::string::npos) << text.out;
}

TEST_F(CliSelf, SelfProximityJsonMatchesTheLibrary) {
  const test::CliRun r = run({"self-proximity", "looped.obj", "--delta", "0.05", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  const SelfProximityResult lib = self_proximity(Model(load_mesh(work_ / "looped.obj")), 0.05);
  EXPECT_EQ(j["count"], lib.pairs.size());
  EXPECT_EQ(j["vertex_triangle"].size() + j["edge_edge"].size(), lib.pairs.size());
  EXPECT_GT(lib.pairs.size(), 0u);
}

TEST_F(CliSelf, BadInputIsRefused) {
  test::expect_clean_refusal(run({"self-intersect", "missing.obj"}), "missing.obj");
  test::write_file(work_ / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  test::expect_clean_refusal(run({"self-intersect", "bad.obj", "--json"}), "bad.obj");
  test::expect_clean_refusal(run({"self-proximity", "flat.obj", "--delta", "-1"}), "--delta");
  test::expect_clean_refusal(run({"self-proximity", "flat.obj", "--delta", "nan"}), "--delta");
  test::expect_clean_refusal(run({"self-proximity", "flat.obj"}), "--delta");
}

}  // namespace
}  // namespace antcd
