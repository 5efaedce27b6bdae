// shared::run_scene and the run format: random methods carry their colonies from frame to frame
// unless told not to, and the run JSON keeps the verdict, the memory flag, each frame's
// evaluations and its undecided pairs through a round trip.
#include "shared/run_result.hpp"
#include "shared/production_line.hpp"

#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include <antcd/error.hpp>

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared {
namespace {

Scene small_line() {
  ProductionLineOptions options;
  options.objects = 12;
  options.vertices = 150;
  options.frames = 12;
  options.seed = 5;
  return make_scene(generate_production_line(options));
}

TEST(RunScene, RandomRunsCarryTheirColoniesAndSayWhichVerdict) {
  const Scene scene = small_line();
  SceneQuery maco;
  maco.method = Method::Maco;
  const RunResult with = run_scene(scene, maco, "line");
  const RunResult without = run_scene(scene, maco, "line", {}, 1, false);
  EXPECT_EQ(with.verdict, "witness");
  EXPECT_TRUE(with.memory);
  EXPECT_FALSE(without.memory);
  // Same verdicts (precision 1 either way on this scene, and the same contacts found), but a
  // different search: the memory's witnesses decide later frames before any traversal. What it
  // saves is traversals and feature spaces (time: antcd_bench_maco_scene), not evaluations: its
  // witness scans count as evaluations, and since the spaces leave out the leaf pairs the
  // triangle masks cull (SamplingOptions::triangle_masks) a run without memory evaluates fewer
  // centroid pairs on this scene (1311 against 2073).
  const RunResult truth = run_scene(scene, SceneQuery{}, "line");
  EXPECT_TRUE(truth.verdict.empty());
  std::uint64_t evals_with = 0, evals_without = 0, colliding = 0;
  for (std::size_t f = 0; f < truth.frames.size(); ++f) {
    EXPECT_EQ(with.frames[f].pairs, truth.frames[f].pairs) << "frame " << f;
    EXPECT_EQ(without.frames[f].pairs, truth.frames[f].pairs) << "frame " << f;
    ASSERT_TRUE(with.frames[f].evaluations.has_value());
    evals_with += *with.frames[f].evaluations;
    evals_without += *without.frames[f].evaluations;
    colliding += truth.frames[f].pairs.size();
  }
  ASSERT_GT(colliding, 0u) << "the scene must have contacts for this test to mean anything";
  EXPECT_NE(evals_with, evals_without);
}

TEST(RunScene, FrameBudgetLeavesUndecidedPairsThatSurviveTheJsonRoundTrip) {
  const Scene scene = small_line();
  SceneQuery q;
  q.method = Method::Maco;
  q.frame_evaluations = 1;  // far too little: pairs with overlapping leaves stay undecided
  const RunResult r = run_scene(scene, q, "line", {}, 1, false);
  std::size_t undecided = 0;
  for (const FrameRecord& f : r.frames) {
    undecided += f.undecided.size();
    // An undecided pair is never reported as colliding.
    const std::set<NamePair> reported(f.pairs.begin(), f.pairs.end());
    for (const NamePair& p : f.undecided) EXPECT_EQ(reported.count(p), 0u);
  }
  EXPECT_GT(undecided, 0u);
  const RunResult back = parse_run_result(to_json(r), "round trip");
  EXPECT_EQ(back.verdict, r.verdict);
  EXPECT_EQ(back.memory, r.memory);
  ASSERT_EQ(back.frames.size(), r.frames.size());
  for (std::size_t f = 0; f < r.frames.size(); ++f) {
    EXPECT_EQ(back.frames[f].undecided, r.frames[f].undecided);
    EXPECT_EQ(back.frames[f].evaluations, r.frames[f].evaluations);
  }
}

// With the leaf-pair scan (the default), every pair is decided: a witness, or a complete scan of
// the overlapping leaves' triangle pairs; the verdicts are exact's. The colony alone
// (scan_covered_spaces = false) stays precise but may leave pairs undecided. The JSON says which.
TEST(RunScene, LeafScanDecidesEveryPairAndTheJsonSaysSo) {
  const Scene scene = small_line();
  const RunResult truth = run_scene(scene, SceneQuery{}, "line");
  SceneQuery maco;
  maco.method = Method::Maco;
  const RunResult scanned = run_scene(scene, maco, "line");
  maco.random.search.ant.scan_covered_spaces = false;
  const RunResult colony = run_scene(scene, maco, "line");
  EXPECT_TRUE(scanned.leaf_scan);
  EXPECT_FALSE(colony.leaf_scan);
  std::size_t colliding = 0;
  for (std::size_t f = 0; f < truth.frames.size(); ++f) {
    EXPECT_EQ(scanned.frames[f].pairs, truth.frames[f].pairs) << "frame " << f;
    EXPECT_TRUE(scanned.frames[f].undecided.empty()) << "frame " << f;
    const std::set<NamePair> t(truth.frames[f].pairs.begin(), truth.frames[f].pairs.end());
    for (const NamePair& p : colony.frames[f].pairs) EXPECT_EQ(t.count(p), 1u) << "frame " << f;
    colliding += truth.frames[f].pairs.size();
  }
  ASSERT_GT(colliding, 0u);
  // With frame budgets from starved to ample, a pair that is neither reported nor undecided was
  // decided separate, and must be: exact's pairs are always among the reported and undecided.
  for (const std::uint64_t budget : {50u, 400u, 3000u, 100000u}) {
    SceneQuery q;
    q.method = Method::Maco;
    q.frame_evaluations = budget;
    q.random.first_leaf_pairs = 1;  // partial spaces of one leaf pair: most contacts lie beyond
    const RunResult r = run_scene(scene, q, "line");
    for (std::size_t f = 0; f < truth.frames.size(); ++f) {
      std::set<NamePair> open(r.frames[f].pairs.begin(), r.frames[f].pairs.end());
      open.insert(r.frames[f].undecided.begin(), r.frames[f].undecided.end());
      for (const NamePair& p : truth.frames[f].pairs) {
        EXPECT_EQ(open.count(p), 1u) << "budget " << budget << " frame " << f;
      }
    }
  }
  EXPECT_TRUE(parse_run_result(to_json(scanned), "scanned").leaf_scan);
  EXPECT_FALSE(parse_run_result(to_json(colony), "colony").leaf_scan);
}

/// The message of the antcd::Error parse_run_result throws on `text` ("" if none).
std::string refusal(const std::string& text) {
  try {
    (void)parse_run_result(text, "r.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ParseRunResult, NestingIsCheckedBeforeTheTreeIsBuilt) {
  // A few MB of brackets built millions of nested arrays (gigabytes) before the format check.
  const std::string deep = std::string(4'000'000, '[') + std::string(4'000'000, ']');
  EXPECT_EQ(refusal(deep), "r.json: nested deeper than 16 levels");
  const std::string frames = R"({"method":"exact","build_ms":0,"total_ms":0,"frames":)";
  EXPECT_EQ(refusal(frames + std::string(17, '[') + std::string(17, ']') + "}"),
            "r.json: nested deeper than 16 levels");
  // Brackets inside strings are text, not nesting.
  // (append(): GCC 12 reports a false -Wrestrict on chained operator+ here.)
  const std::string name = std::string("a").append(100, '[');
  std::string quoted = frames;
  quoted.append(R"([{"frame":0,"pairs":[[")").append(name).append(R"(","b"]],"time_ms":1}]})");
  EXPECT_EQ(refusal(quoted), "");
  EXPECT_EQ(parse_run_result(quoted, "r.json").frames.at(0).pairs.at(0).first, name);
}

TEST(ParseRunResult, ValueCountIsCheckedBeforeTheTreeIsBuilt) {
  // 2^24 + 1 values in a 32 MB text: refused by the pre-scan, not parsed into ~1 GB of tree.
  std::string many = R"({"method":"exact","build_ms":0,"total_ms":0,"frames":[0)";
  many.reserve(many.size() + 2 * (std::size_t{1} << 24) + 8);
  for (std::size_t i = 0; i < (std::size_t{1} << 24); ++i) many += ",0";
  many += "]}";
  EXPECT_EQ(refusal(many), "r.json: more than 16777216 values");
}

TEST(ParseRunResult, BadFieldsAreRefusedWithOneLine) {
  const std::vector<std::pair<std::string, std::string>> table = {
      {"", "not valid JSON"},
      {"[]", "expected a JSON object"},
      {R"({"method":1})", "missing 'method'"},
      {R"({"method":"exact","build_ms":0,"total_ms":0})", "missing 'frames'"},
      {R"({"method":"exact","build_ms":0,"total_ms":0,"frames":[1]})", "must be an object"},
      {R"({"method":"exact","build_ms":0,"total_ms":0,"frames":[{"frame":-1}]})", "'frame' index"},
      {R"({"method":"exact","build_ms":0,"total_ms":0,"frames":[{"frame":0,"pairs":[["a"]],)"
       R"("time_ms":0}]})",
       "pairs of names"},
      {R"({"method":"exact","build_ms":1e999,"total_ms":0,"frames":[]})", "not valid JSON"},
      {R"({"method":"exact","build_ms":0,"total_ms":0,"frames":[{"frame":0,"pairs":[],)"
       R"("time_ms":0,"distances":[1]}]})",
       "one number per pair"},
  };
  for (const auto& [text, problem] : table) {
    const std::string what = refusal(text);
    EXPECT_NE(what.find(problem), std::string::npos) << text << " -> " << what;
    EXPECT_EQ(what.rfind("r.json: ", 0), 0U) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace antcd::shared
