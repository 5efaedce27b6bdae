// Every subcommand of antcd (and the antcd-lab commands it hands over) against bad option values
// and bad files, table-driven (issue 28): each case must be refused at once with exit code 2 and
// one printable, bounded "error: ..." line naming the option or file, nothing on stdout, and no
// output file or temporary file left behind.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <antcd/file.hpp>

#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::vector<std::string> args;
  std::string named;  ///< text the error line must hold (the option or the file)
};

const char* kTet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    names.insert(fs::relative(e.path(), dir).string());
  }
  return names;
}

class CliBadInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    work_ = new fs::path(test::fresh_temp_dir("cli_bad_input"));
    const fs::path& w = *work_;
    test::write_file(w / "tet.obj", kTet);
    test::write_file(w / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    test::write_file(w / "scene.json", R"({ "format": "antcd-scene/1", "frames": 2, "objects": [
      { "name": "a", "mesh": "tet.obj", "poses": [ {} ] },
      { "name": "b", "mesh": "tet.obj", "poses": [ { "translation": [0.5, 0, 0] },
                                                   { "translation": [5, 0, 0] } ] } ] })");
    test::write_file(w / "points.csv", "0.1,0.1,0.1\n2,2,2\n");
    std::string query;  // one vertex-face query: 8 rows of exact rationals and a truth column
    for (int row = 0; row < 8; ++row) query += std::to_string(row % 4) + ",1,0,1,0,1,0\n";
    test::write_file(w / "query.csv", query);
    test::write_file(w / "empty.txt", "");
    std::string noise;
    for (int i = 0; i < 4096; ++i) noise += static_cast<char>((i * 7919 + i / 13) & 0xFF);
    test::write_file(w / "noise.bin", noise);
    fs::create_directories(w / "folder");
    ASSERT_EQ(::mkfifo((w / "fifo").c_str(), 0600), 0) << std::strerror(errno);
    const test::CliRun run =
        test::run_program(ANTCD_CLI, {"run", "scene.json", "--out", "result.json"}, w);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  static void TearDownTestSuite() {
    delete work_;
    work_ = nullptr;
  }

  /// Runs each case in the shared folder: the refusal contract, and the folder unchanged.
  static void expect_all_refused(const std::vector<Case>& cases,
                                 const std::string& program = ANTCD_CLI) {
    for (const Case& c : cases) {
      std::string line = fs::path(program).filename().string();
      for (const auto& a : c.args) line += " '" + a + "'";
      SCOPED_TRACE(printable_line(line));
      const auto before = listing(*work_);
      test::expect_clean_refusal(test::run_program(program, c.args, *work_, 30), c.named);
      EXPECT_EQ(listing(*work_), before);
    }
  }

  /// `base` with `option` set to each of `values` (appended, or replacing its value in `base`;
  /// an integer option is the position of a positional argument in `base`).
  static std::vector<Case> each(const std::vector<std::string>& base, const std::string& option,
                                const std::vector<std::string>& values, std::string named = {}) {
    std::vector<Case> out;
    for (const std::string& v : values) {
      std::vector<std::string> args = base;
      const auto at = std::find(args.begin(), args.end(), option);
      if (at != args.end() && at + 1 != args.end()) {
        *(at + 1) = v;
      } else {
        args.push_back(option);
        args.push_back(v);
      }
      out.push_back({args, named.empty() ? option : named});
    }
    return out;
  }
  /// `base` with its positional argument `position` replaced by each bad file, named in the error.
  static std::vector<Case> files(const std::vector<std::string>& base, std::size_t position,
                                 const std::vector<std::string>& names) {
    std::vector<Case> out;
    for (const std::string& name : names) {
      std::vector<std::string> args = base;
      args[position] = name;
      out.push_back({args, name == "bad\x1b[31mname.obj" ? "bad\\x1B[31mname.obj" : name});
    }
    return out;
  }

  static inline fs::path* work_ = nullptr;
};

// Option values: numbers that must be finite decimals >= 0, integers, poses, outputs.
const std::vector<std::string> kBadNumbers = {
    "-1", "nan", "-inf", "1e999", "", "abc", "0x10", "1\x1b[2J", std::string(300, '7') + "x"};
const std::vector<std::string> kBadCounts = {"-1", "0",   "1e3", "99999999999999999999999",
                                             "",   "nan", "1.5", "\x07"};
const std::vector<std::string> kBadSeeds = {"-1", "1e3",  "99999999999999999999999",
                                            "",   "0x10", "1.5"};
const std::vector<std::string> kBadPoses = {
    "1,2", "nan,0,0", "", "0,0,0,2,0,0,0", "\x1b[2J", "1e999,0,0", "0,0,0,0,0,0,0"};
const std::vector<std::string> kBadMeshes = {
    "missing.obj", "folder",    "fifo",     "/dev/zero",
    "empty.txt",   "noise.bin", "flat.obj", "bad\x1b[31mname.obj"};
const std::vector<std::string> kBadOutputs = {"", "folder", "absent_folder/out.json", "fifo",
                                              "/dev/null"};

TEST_F(CliBadInput, MeshQueries) {
  std::vector<Case> cases;
  for (const char* command : {"collide", "distance", "depth", "sweep"}) {
    const std::vector<std::string> base = {std::string(command), "tet.obj", "tet.obj"};
    for (const auto& c : files(base, 1, kBadMeshes)) cases.push_back(c);
    for (const auto& c : files(base, 2, {"missing.obj", "fifo"})) cases.push_back(c);
  }
  const auto add = [&](const std::vector<Case>& more) {
    cases.insert(cases.end(), more.begin(), more.end());
  };
  const std::vector<std::string> collide = {"collide", "tet.obj", "tet.obj"};
  add(each(collide, "--delta", kBadNumbers));
  add(each(collide, "--pose-a", kBadPoses));
  add(each(collide, "--manifold", kBadCounts));
  add(each(collide, "--leaf-size", {"0", "-3", "abc"}));
  add(each(collide, "--covariance", {"median", "", "\x01"}));
  const std::vector<std::string> distance = {"distance", "tet.obj", "tet.obj"};
  add(each(distance, "--upper-bound", {"-1", "nan", "-inf", "0x10", "abc"}));
  add(each(distance, "--abs-tolerance", {"-1", "nan", "inf"}));
  add(each(distance, "--rel-tolerance", {"-1", "nan", "1", "2"}));
  add(each({"distance", "tet.obj", "tet.obj", "--signed"}, "--pose-b", {"1,2", "inf,0,0"}));
  const std::vector<std::string> depth = {"depth", "tet.obj", "tet.obj"};
  add(each(depth, "--rel-tolerance", {"-1", "nan", "1"}));
  add(each(depth, "--abs-tolerance", {"-1", "inf"}));
  add(each(depth, "--max-evaluations", {"0", "-1", "abc"}));
  add(each(depth, "--shape", {"round", ""}));
  const std::vector<std::string> sweep = {"sweep", "tet.obj", "tet.obj", "--pose-b1", "0.5,0,0"};
  add(each(sweep, "--pose-a1", kBadPoses));
  add(each(sweep, "--min-separation", {"-1", "nan", "0x10"}));
  add(each(sweep, "--time-tolerance", {"0", "-1", "inf"}));
  add(each(sweep, "--max-iterations", {"0", "-1"}));
  add(each({"info", "tet.obj"}, "--leaf-size", {"0", "abc"}));
  for (const auto& c : files({"info", "tet.obj"}, 1, {"noise.bin", "/dev/zero"})) {
    cases.push_back(c);
  }
  expect_all_refused(cases);
}

TEST_F(CliBadInput, PointsAndQueryFiles) {
  std::vector<Case> cases = files({"points", "tet.obj", "points.csv"}, 2,
                                  {"missing.csv", "folder", "fifo", "/dev/zero", "empty.txt",
                                   "noise.bin", "bad\x1b[31mname.obj"});
  const auto add = [&](const std::vector<Case>& more) {
    cases.insert(cases.end(), more.begin(), more.end());
  };
  add(files({"points", "tet.obj", "points.csv"}, 1, {"flat.obj", "fifo"}));
  add(each({"points", "tet.obj", "points.csv"}, "--pose", kBadPoses));
  add(each({"points", "tet.obj"}, "--random", kBadCounts));
  add(each({"points", "tet.obj", "--random", "5"}, "--seed", kBadSeeds));
  // ccd-queries read a regular file only, with bounded lines, and at least one query.
  add(files(
      {"ccd-queries", "query.csv", "--kind", "vf"}, 1,
      {"missing.csv", "folder", "fifo", "/dev/zero", "empty.txt", "noise.bin", "points.csv"}));
  add(each({"ccd-queries", "query.csv"}, "--kind", {"fv", "", "vf\x1b"}));
  add(each({"ccd-queries", "query.csv", "--kind", "vf"}, "--min-separation", kBadNumbers));
  add(each({"ccd-queries", "query.csv", "--kind", "vf"}, "--time-tolerance", {"0", "-1", "inf"}));
  expect_all_refused(cases);
}

TEST_F(CliBadInput, ScenesRunsAndResults) {
  std::vector<Case> cases = files(
      {"run", "scene.json"}, 1,
      {"missing.json", "folder", "fifo", "/dev/zero", "empty.txt", "noise.bin", "result.json"});
  const auto add = [&](const std::vector<Case>& more) {
    cases.insert(cases.end(), more.begin(), more.end());
  };
  const std::vector<std::string> run = {"run", "scene.json", "--out", "new.json"};
  add(each(run, "--method", {"telepathy", "", "maco\x1b"}));
  add(each(run, "--delta", kBadNumbers));
  add(each({"run", "scene.json", "--method", "maco"}, "--feature-delta", {"0", "-1", "nan"}));
  add(each(run, "--seed", kBadSeeds));
  add(each(run, "--threads", {"0", "-1", "257", "abc"}));
  add(each({"run", "scene.json", "--method", "maco"}, "--ants", kBadCounts));
  add(each({"run", "scene.json", "--method", "maco"}, "--frame-seconds", {"-1", "nan", "0x10"}));
  add(each({"run", "scene.json"}, "--out", kBadOutputs));
#ifdef ANTCD_TEST_LEARNED
  // A bad --model file (antcd-lab: seconds to start). A build without libtorch refuses box-* before
  // it reads any model, naming the missing baselines instead of the file.
  for (const std::string bad : {"fifo", "noise.bin"}) {
    cases.push_back({{"run", "scene.json", "--method", "box-dnn", "--model", bad}, bad});
  }
#endif
  // compare and view read results: a scene, noise, a FIFO are no result.
  for (const std::string bad : {"scene.json", "noise.bin", "fifo", "folder", "missing.json"}) {
    cases.push_back({{"compare", bad, "result.json"}, bad});
    cases.push_back({{"compare", "result.json", bad}, bad});
    cases.push_back({{"view", "scene.json", "--result", bad, "--out", "page.html"}, bad});
  }
  add(each({"view", "scene.json"}, "--out", kBadOutputs));
  add(each({"view", "scene.json", "--out", "page.html"}, "--contacts", {"-1", "abc", "1e9"}));
  expect_all_refused(cases);
}

TEST_F(CliBadInput, GeneratorsAndLabCommandsFailAtOnce) {
  // Each is refused while the command line is read: with a valid value they run for minutes,
  // so a refusal that came after the work would hit the 30 s limit and count as a hang.
  std::vector<Case> cases;
  const auto add = [&](const std::vector<Case>& more) {
    cases.insert(cases.end(), more.begin(), more.end());
  };
  const std::vector<std::string> generate = {"scene", "generate", "--out", "generated"};
  add(each(generate, "--out", {"", "tet.obj", "fifo/inside"}));
  add(each(generate, "--objects", {"1", "-1", "abc"}));
  add(each(generate, "--vertices", {"7", "-1"}));
  add(each(generate, "--frames", {"0", "1e3"}));
  add(each(generate, "--seed", kBadSeeds));
  cases.push_back(
      {{"scene", "generate", "--out", "generated", "--mesh", "missing.obj"}, "missing.obj"});
  cases.push_back({{"scene", "generate", "--out", "generated", "--mesh", "flat.obj"}, "flat.obj"});
  add(each({"demo"}, "--objects", {"1", "abc"}));
  add(each({"demo"}, "--seed", kBadSeeds));
  add(each({"demo"}, "--view", {"", "folder", "absent_folder/view.html", "fifo"}));
  // antcd-lab's commands (libtorch takes seconds to load: a few cases each). The issue's cases:
  // a bad seed and an unwritable --out used to be found after minutes of work.
  cases.push_back({{"bench", "paper", "--quick", "--out", "bench", "--seed", "-1"}, "--seed"});
  cases.push_back({{"bench", "paper", "--quick", "--out", "tet.obj"}, "--out"});
  cases.push_back({{"bench", "peers", "--quick", "--out", "fifo/inside"}, "--out"});
  cases.push_back({{"bench", "peers", "--quick", "--frames", "0"}, "--frames"});
  cases.push_back({{"learn", "train", "--method", "box-dnn", "--out", "folder"}, "--out"});
  cases.push_back(
      {{"learn", "train", "--method", "box-dnn", "--out", "m.pt", "--epochs", "0"}, "--epochs"});
  // An unknown subcommand is named.
  cases.push_back({{"frobnicate"}, "frobnicate"});
  cases.push_back({{"scene", "frobnicate"}, "frobnicate"});
  cases.push_back({{"bench", "frobnicate"}, "frobnicate"});
  expect_all_refused(cases);
}

// An unknown option is named (issue 35): at the top level, where CLI11 alone said only "A
// subcommand is required"; before a command's required arguments, where it said "A is required";
// inside commands that have subcommands; and in antcd-lab, directly and through the hand-over.
// Nothing may run first: a command line with a valid command and a bad option writes nothing.
TEST_F(CliBadInput, UnknownOptionsAreNamed) {
  const std::vector<Case> cases = {
      {{"--bogus"}, "'--bogus'"},
      {{"-x"}, "'-x'"},
      {{"--bogus=1"}, "'--bogus=1'"},
      {{"--bogus", "info", "tet.obj"}, "'--bogus'"},
      {{"info", "tet.obj", "--bogus"}, "'--bogus'"},
      {{"collide", "--bogus"}, "'--bogus'"},
      {{"collide", "tet.obj", "tet.obj", "--bogus"}, "'--bogus'"},
      {{"collide", "tet.obj", "--delta", "0", "-q", "tet.obj"}, "'-q'"},
      {{"scene", "--bogus"}, "'--bogus'"},
      {{"scene", "generate", "--out", "generated", "--bogus"}, "'--bogus'"},
      {{"run", "scene.json", "--out", "again.json", "--bogus"}, "'--bogus'"},
      {{"demo", "--bogus"}, "'--bogus'"},
      {{"info", "tet.obj", "extra.obj"}, "'extra.obj'"},
      // antcd-lab's commands, handed over.
      {{"bench", "--bogus"}, "'--bogus'"},
      {{"bench", "paper", "--quick", "--out", "bench", "--bogus"}, "'--bogus'"},
      {{"learn", "--bogus"}, "'--bogus'"},
      {{"run", "scene.json", "--method", "box-dnn", "--bogus"}, "'--bogus'"},
  };
  expect_all_refused(cases);
  expect_all_refused({{{"--bogus"}, "'--bogus'"},
                      {{"bench", "peers", "--bogus"}, "'--bogus'"},
                      {{"collide", "--bogus"}, "'--bogus'"}},
                     ANTCD_LAB);
}

}  // namespace
}  // namespace antcd
