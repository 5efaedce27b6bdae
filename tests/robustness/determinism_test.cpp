// Determinism: the same seed gives the same FrameResult (every field but time_ms) across repeated
// runs and across SceneQuery::threads = 1, 2 and 8, for every method, on a small generated
// production-line scene; and a golden hash pins the answers of every method on a fixed scene.
//
// Golden values. kGolden below holds an FNV-1a 64-bit hash, per method, over every frame's
// (frame, pairs, candidates, feature_hits) on the scene of golden_options(). They depend on the
// scene generator (shared/production_line/, its meshes taken in memory), the hierarchy
// build, the broad phase, the narrow phases and the random searches, and on floating-point
// results. A deliberate change to any of these may change them: then check that the change is
// meant, regenerate with
//     ANTCD_PRINT_GOLDEN=1 ./build/tests/robustness_determinism_tests --gtest_filter='*Golden*'
// (Release build), paste the printed lines over kGolden, and check that a Debug/ASan (-O1) build
// (scripts/sanitize.sh asan) prints the same values. An unintended change is a bug.
#include <antcd/scene.hpp>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "shared/production_line.hpp"

namespace antcd {
namespace {

constexpr std::array<Method, 6> kMethods = {Method::Exact, Method::SphereObb, Method::Aco,
                                            Method::Maco,  Method::Pso,       Method::Ga};

// The scene is built in memory (no mesh files, no assimp), so the golden hashes depend on the
// generator and the engine only.
Scene make_scene(const shared::ProductionLineOptions& options) {
  return shared::make_scene(shared::generate_production_line(options));
}

SceneQuery query_for(Method method, std::uint64_t seed, bool search_all) {
  SceneQuery q;
  q.method = method;
  q.seed = seed;
  q.random.samples_per_side = 150;
  q.random.search.iterations = 15;
  q.random.search.set_agents(20);
  q.random.all_witnesses = search_all;
  // Pinned rather than the default, so that tuning the default does not move the goldens.
  q.random.evaluations_per_leaf_pair = 64;
  return q;
}

std::vector<FrameResult> run_all(const Scene& scene, SceneQuery query, int threads) {
  query.threads = threads;
  std::vector<FrameResult> out;
  for (std::size_t f = 0; f < scene.description().frames; ++f) {
    out.push_back(scene.run_frame(f, query));
  }
  return out;
}

void expect_same(const std::vector<FrameResult>& got, const std::vector<FrameResult>& expected,
                 const std::string& what) {
  ASSERT_EQ(got.size(), expected.size()) << what;
  for (std::size_t f = 0; f < got.size(); ++f) {
    EXPECT_EQ(got[f].frame, expected[f].frame) << what;
    EXPECT_EQ(got[f].pairs, expected[f].pairs) << what << " frame " << f;
    EXPECT_EQ(got[f].candidates, expected[f].candidates) << what << " frame " << f;
    EXPECT_EQ(got[f].feature_hits, expected[f].feature_hits) << what << " frame " << f;
    EXPECT_EQ(got[f].feature_truth, expected[f].feature_truth) << what << " frame " << f;
  }
}

TEST(Determinism, SameSeedSameFramesAcrossRunsAndThreadCounts) {
  // oneTBB caps its workers at the core count minus one by default: allow 8 threads to really
  // take part whatever the machine.
  const tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 8);
  shared::ProductionLineOptions options;
  options.objects = 10;
  options.vertices = 100;
  options.frames = 3;
  options.seed = 3;
  const Scene scene = make_scene(options);
  std::size_t pairs = 0;
  std::uint64_t hits = 0;
  for (const Method m : kMethods) {
    for (const bool search_all : {false, true}) {
      if (search_all && (m == Method::Exact || m == Method::SphereObb)) continue;
      SceneQuery q = query_for(m, 17, search_all);
      q.random.count_truth = search_all && m == Method::Maco;
      const std::string what =
          std::string(method_name(m)) + (search_all ? " search_all" : " first hit");
      const std::vector<FrameResult> reference = run_all(scene, q, 1);
      for (const FrameResult& r : reference) {
        pairs += r.pairs.size();
        hits += r.feature_hits;
      }
      expect_same(run_all(scene, q, 1), reference, what + ", threads 1 again");
      for (const int threads : {2, 8}) {
        expect_same(run_all(scene, q, threads), reference,
                    what + ", threads " + std::to_string(threads));
      }
    }
  }
  // Not a trivial scene: the methods report colliding pairs and the searches find features.
  EXPECT_GT(pairs, 0u);
  EXPECT_GT(hits, 0u);
}

// ---- golden hash --------------------------------------------------------------------------------

class Fnv1a64 {
 public:
  void add(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) {  // little-endian bytes, whatever the host
      h_ ^= (v >> (8 * k)) & 0xff;
      h_ *= 0x100000001b3ULL;
    }
  }
  [[nodiscard]] std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

std::uint64_t frames_hash(const std::vector<FrameResult>& frames) {
  Fnv1a64 h;
  for (const FrameResult& r : frames) {
    h.add(r.frame);
    h.add(r.pairs.size());
    for (const auto& [i, j] : r.pairs) {
      h.add(i);
      h.add(j);
    }
    h.add(r.candidates.size());
    for (const auto& [i, j] : r.candidates) {
      h.add(i);
      h.add(j);
    }
    h.add(r.feature_hits);
  }
  return h.value();
}

shared::ProductionLineOptions golden_options() {
  shared::ProductionLineOptions options;
  options.objects = 12;
  options.vertices = 120;
  options.frames = 5;
  options.seed = 2024;
  return options;
}

struct Golden {
  Method method;
  std::uint64_t hash;
};

// Regenerate: see the top of this file (ANTCD_PRINT_GOLDEN=1).
constexpr std::array<Golden, 6> kGolden = {{
    {Method::Exact, 0x3b5301b0bdcdf40aULL},      // 16 colliding pairs, 0 feature hits
    {Method::SphereObb, 0x3b5301b0bdcdf40aULL},  // 16 colliding pairs, 0 feature hits
    {Method::Aco, 0xc61018e7b3bed31eULL},        // 16 colliding pairs, 1474 feature hits
    {Method::Maco, 0x60dad332982f4f67ULL},       // 16 colliding pairs, 1430 feature hits
    {Method::Pso, 0x1761adac2f928b81ULL},        // 16 colliding pairs, 207 feature hits
    {Method::Ga, 0x5312cbb9cc89d100ULL},         // 16 colliding pairs, 104 feature hits
}};

const char* enumerator(Method m) {
  switch (m) {
    case Method::Exact:
      return "Exact";
    case Method::SphereObb:
      return "SphereObb";
    case Method::Aco:
      return "Aco";
    case Method::Maco:
      return "Maco";
    case Method::Pso:
      return "Pso";
    case Method::Ga:
      return "Ga";
    case Method::Exhaustive:
      return "Exhaustive";
    case Method::Grid:
      return "Grid";
  }
  return "?";
}

TEST(Determinism, GoldenHashOfEveryMethodOnAFixedScene) {
  const Scene scene = make_scene(golden_options());
  const char* print = std::getenv("ANTCD_PRINT_GOLDEN");
  const bool printing = print != nullptr && std::string(print) == "1";
  if (printing) std::printf("constexpr std::array<Golden, 6> kGolden = {{\n");
  for (const Golden& golden : kGolden) {
    const std::vector<FrameResult> frames = run_all(scene, query_for(golden.method, 42, true), 2);
    const std::uint64_t hash = frames_hash(frames);
    if (printing) {
      std::size_t pairs = 0;
      std::uint64_t hits = 0;
      for (const FrameResult& r : frames) {
        pairs += r.pairs.size();
        hits += r.feature_hits;
      }
      std::printf("    {Method::%s, 0x%016llxULL},  // %zu colliding pairs, %llu feature hits\n",
                  enumerator(golden.method), static_cast<unsigned long long>(hash), pairs,
                  static_cast<unsigned long long>(hits));
    }
    EXPECT_EQ(hash, golden.hash) << method_name(golden.method)
                                 << ": answers changed; if that is intended, regenerate the golden "
                                    "values (see the top of determinism_test.cpp)";
  }
  if (printing) std::printf("}};\n");
}

}  // namespace
}  // namespace antcd
