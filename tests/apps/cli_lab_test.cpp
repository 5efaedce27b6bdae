// The split between `antcd` and `antcd-lab` (apps/antcd/lab.hpp): the main tool hands learn, bench
// and run --method box-* to antcd-lab beside it, lists them in its help, and says in one line which
// tool is missing when antcd-lab cannot be found.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;

fs::path work_dir(const std::string& name) {
  const fs::path dir = test::fresh_temp_dir("cli_lab_" + name);
  fs::remove_all(dir.parent_path() / (dir.filename().string() + "_io"));
  return dir;
}

TEST(CliLab, HelpListsTheLabCommands) {
  const test::CliRun r = test::run_program(ANTCD_CLI, {"--help"}, work_dir("help"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("learn"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bench"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("antcd-lab"), std::string::npos) << r.out;
}

TEST(CliLab, BenchIsHandedToTheLab) {
  // Only antcd-lab has `bench paper`'s options: --quick in the help proves the hand-over.
  const test::CliRun r =
      test::run_program(ANTCD_CLI, {"bench", "paper", "--help"}, work_dir("bench"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("--quick"), std::string::npos) << r.out;
}

TEST(CliLab, MissingLabIsOneLineExit2) {
  // The main tool copied alone into an empty folder, with no antcd-lab on PATH.
  const fs::path dir = work_dir("alone");
  const fs::path tool = dir / "antcd";
  fs::copy_file(ANTCD_CLI, tool);
  fs::permissions(tool, fs::perms::owner_all);
  const test::CliRun r = test::run_program(
      "/usr/bin/env", {"PATH=" + dir.string(), tool.string(), "learn", "train"}, dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("error: `antcd learn` runs in antcd-lab", 0), 0U) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
}

}  // namespace
}  // namespace antcd
