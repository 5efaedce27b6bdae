// The scene engine against an all-pairs brute-force run, across methods and thread counts.
#include <antcd/collide.hpp>
#include <antcd/file.hpp>
#include <antcd/random.hpp>
#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <thread>

#include "support/test_support.hpp"

namespace antcd {
namespace {

// A small scene of generated shapes tumbling through a box of side ~6, written to `dir`.
SceneDescription small_scene(const std::filesystem::path& dir, std::size_t objects,
                             std::size_t frames, std::uint64_t seed) {
  save_obj(make_torus(0.6, 0.2, 24, 12), dir / "torus.obj");
  save_obj(make_box(Vec3(0.5, 0.3, 0.2), 2), dir / "box.obj");
  save_obj(make_sphere(0.4, 16, 8), dir / "sphere.obj");
  const char* meshes[] = {"torus.obj", "box.obj", "sphere.obj"};
  std::mt19937_64 rng(seed);
  SceneDescription s;
  s.frames = frames;
  for (std::size_t i = 0; i < objects; ++i) {
    SceneObject o;
    o.name = "obj_" + std::to_string(i);
    o.mesh_text = meshes[i % 3];
    o.mesh = dir / o.mesh_text;
    o.scale = i % 4 == 3 ? 1.5 : 1.0;
    const Transform start = test::random_pose(rng, 3.0);
    const Transform end = test::random_pose(rng, 3.0);
    if (i % 5 == 0) {
      o.poses = {start};  // static
    } else {
      for (std::size_t f = 0; f < frames; ++f) {
        const double t = frames > 1 ? static_cast<double>(f) / static_cast<double>(frames - 1) : 0;
        Transform p;
        p.rotation = Quat(start.rotation).slerp(t, Quat(end.rotation)).toRotationMatrix();
        p.translation = (1 - t) * start.translation + t * end.translation;
        o.poses.push_back(p);
      }
    }
    s.objects.push_back(std::move(o));
  }
  return s;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> brute_force(const Scene& scene,
                                                                 std::size_t frame, Scalar delta) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  const auto& objects = scene.description().objects;
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    for (std::uint32_t j = i + 1; j < objects.size(); ++j) {
      if (collide(scene.model_of(i), objects[i].pose(frame), scene.model_of(j),
                  objects[j].pose(frame), CollisionRequest{delta})
              .colliding) {
        out.emplace_back(i, j);
      }
    }
  }
  return out;
}

TEST(Scene, ExactEqualsAllPairsBruteForce) {
  const auto dir = test::fresh_temp_dir("scene_brute");
  const Scene scene(small_scene(dir, 30, 40, 5));
  EXPECT_EQ(scene.model_count(), 6u);  // 3 meshes, each also at scale 1.5
  std::size_t colliding = 0;
  for (const Scalar delta : {0.0, 0.1}) {
    for (std::size_t f = 0; f < 40; ++f) {
      SceneQuery q;
      q.delta = delta;
      const FrameResult r = scene.run_frame(f, q);
      const auto truth = brute_force(scene, f, delta);
      ASSERT_EQ(r.pairs, truth) << "frame " << f << " delta " << delta;
      // Every colliding pair survived the broad phase, and candidates are ordered and unique.
      for (const auto& p : truth) {
        EXPECT_TRUE(std::binary_search(r.candidates.begin(), r.candidates.end(), p));
      }
      EXPECT_TRUE(std::is_sorted(r.candidates.begin(), r.candidates.end()));
      EXPECT_EQ(std::adjacent_find(r.candidates.begin(), r.candidates.end()), r.candidates.end());
      EXPECT_LT(r.candidates.size(), 30u * 29 / 2);  // the broad phase culls
      colliding += truth.size();
    }
  }
  EXPECT_GT(colliding, 40u);
}

// The exact method starts each pair's query where the pair's last query found its contact (a
// hint kept by the scene): frames run backwards, skipped, repeated or by two threads at once
// answer as frames run in order.
TEST(Scene, ExactFramesAnswerTheSameInAnyOrder) {
  const auto dir = test::fresh_temp_dir("scene_order");
  const Scene scene(small_scene(dir, 30, 24, 5));
  SceneQuery q;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> forward;
  std::size_t colliding = 0;
  for (std::size_t f = 0; f < 24; ++f) {
    forward.push_back(scene.run_frame(f, q).pairs);
    colliding += forward.back().size();
  }
  EXPECT_GT(colliding, 24u);
  for (std::size_t f = 24; f-- > 0;) EXPECT_EQ(scene.run_frame(f, q).pairs, forward[f]) << f;
  for (const std::size_t f : {5u, 17u, 17u, 2u, 23u, 0u}) {
    EXPECT_EQ(scene.run_frame(f, q).pairs, forward[f]) << f;
  }
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> even(24);
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> odd(24);
  std::thread other([&] {
    for (std::size_t f = 1; f < 24; f += 2) odd[f] = scene.run_frame(f, q).pairs;
  });
  for (std::size_t f = 0; f < 24; f += 2) even[f] = scene.run_frame(f, q).pairs;
  other.join();
  for (std::size_t f = 0; f < 24; ++f) EXPECT_EQ(f % 2 == 0 ? even[f] : odd[f], forward[f]) << f;
}

TEST(Scene, ThreadsDoNotChangeAnyMethodsAnswer) {
  const auto dir = test::fresh_temp_dir("scene_threads");
  const Scene scene(small_scene(dir, 24, 6, 8));
  for (const Method m :
       {Method::Exact, Method::SphereObb, Method::Aco, Method::Maco, Method::Pso, Method::Ga}) {
    SceneQuery q;
    q.method = m;
    q.seed = 99;
    q.random.samples_per_side = 200;
    q.random.search.iterations = 20;
    for (std::size_t f = 0; f < 6; ++f) {
      q.threads = 1;
      const FrameResult one = scene.run_frame(f, q);
      for (const int threads : {2, 4}) {
        q.threads = threads;
        const FrameResult many = scene.run_frame(f, q);
        EXPECT_EQ(one.pairs, many.pairs) << method_name(m) << " frame " << f;
        EXPECT_EQ(one.candidates, many.candidates);
        EXPECT_EQ(one.feature_hits, many.feature_hits) << method_name(m) << " frame " << f;
      }
    }
  }
}

TEST(Scene, SphereObbIsASupersetOfExact) {
  // The hierarchy-only baseline reports a pair whenever leaf volumes overlap, so it never misses
  // an exact collision; it may report more.
  const auto dir = test::fresh_temp_dir("scene_sphereobb");
  const Scene scene(small_scene(dir, 30, 20, 13));
  for (std::size_t f = 0; f < 20; ++f) {
    SceneQuery exact;
    SceneQuery boxes;
    boxes.method = Method::SphereObb;
    const auto e = scene.run_frame(f, exact).pairs;
    const auto b = scene.run_frame(f, boxes).pairs;
    EXPECT_TRUE(std::includes(b.begin(), b.end(), e.begin(), e.end())) << "frame " << f;
  }
}

TEST(Scene, RandomMethodsOnlyReportCandidatePairsAndAreSeeded) {
  const auto dir = test::fresh_temp_dir("scene_random");
  const Scene scene(small_scene(dir, 24, 4, 21));
  SceneQuery q;
  q.method = Method::Maco;
  q.seed = 7;
  q.random.count_truth = true;
  q.random.samples_per_side = 400;
  q.random.search.iterations = 40;
  for (std::size_t f = 0; f < 4; ++f) {
    const FrameResult a = scene.run_frame(f, q);
    const FrameResult b = scene.run_frame(f, q);
    EXPECT_EQ(a.pairs, b.pairs);
    EXPECT_EQ(a.feature_hits, b.feature_hits);
    EXPECT_LE(a.feature_hits, a.feature_truth);
    for (const auto& p : a.pairs) {
      EXPECT_TRUE(std::binary_search(a.candidates.begin(), a.candidates.end(), p));
    }
  }
}

TEST(Scene, RejectsBadQueriesAndFrames) {
  const auto dir = test::fresh_temp_dir("scene_bad");
  const Scene scene(small_scene(dir, 4, 2, 1));
  EXPECT_THROW((void)scene.run_frame(2, {}), antcd::ArgumentError);
  SceneQuery q;
  q.delta = -1;
  EXPECT_THROW((void)scene.run_frame(0, q), Error);
  q.delta = 0;
  q.threads = 0;
  EXPECT_THROW((void)scene.run_frame(0, q), Error);
  EXPECT_THROW(parse_method("bogus"), Error);
  EXPECT_EQ(parse_method("sphere-obb"), Method::SphereObb);
  // One name table: every method's name parses back to it, and an unknown name is refused with
  // the list of accepted names.
  for (const Method m : {Method::Exact, Method::SphereObb, Method::Aco, Method::Maco, Method::Pso,
                         Method::Ga, Method::Exhaustive}) {
    EXPECT_EQ(parse_method(method_name(m)), m);
  }
  try {
    (void)parse_method("bogus");
    ADD_FAILURE() << "parse_method accepted 'bogus'";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("maco"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exhaustive"), std::string::npos) << e.what();
  }
  // Random methods: parameters that would make the search meaningless are refused up front.
  const auto expect_refused = [&](const SceneQuery& bad, const char* needle) {
    try {
      (void)scene.run_frame(0, bad);
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  SceneQuery r;
  r.method = Method::Ga;
  r.random.search.set_agents(1);
  expect_refused(r, "scene query: ga.population must be >= 2");
  r.method = Method::Maco;
  r.random.search.set_agents(0);
  expect_refused(r, "scene query: ant.ants must be >= 1");
  r.random.search.set_agents(60);
  r.random.search.iterations = 0;
  expect_refused(r, "iterations");
  r.random.search.iterations = 100;
  r.random.samples_per_side = 0;
  expect_refused(r, "samples");
  r.random.samples_per_side = 1000;
  r.random.search.centroid_delta = std::numeric_limits<Scalar>::infinity();
  expect_refused(r, "centroid_delta must be finite and > 0");
}

// Every pose is checked when the scene is built (the frames hand them to the World unchecked): a
// bad pose of a later frame is refused there, naming the object and the frame.
TEST(Scene, RefusesABadPoseOfAnyFrameWhenBuilt) {
  const auto dir = test::fresh_temp_dir("scene_bad_pose");
  const auto expect_refused = [&](const SceneDescription& s, const char* needle) {
    try {
      const Scene scene(s);
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("object 'obj_1': pose 2 "), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  SceneDescription sheared = small_scene(dir, 4, 3, 1);
  ASSERT_EQ(sheared.objects[1].poses.size(), 3u);
  sheared.objects[1].poses[2].rotation(0, 1) += 0.01;
  expect_refused(sheared, "not a rigid motion");
  SceneDescription nan = small_scene(dir, 4, 3, 1);
  nan.objects[1].poses[2].translation.x() = std::numeric_limits<Scalar>::quiet_NaN();
  expect_refused(nan, "not finite");
  EXPECT_NO_THROW(Scene{small_scene(dir, 4, 3, 1)});
}

// A verdict needs one colliding feature pair: stopping at the first hit (the default) and running
// every search to its end give the same pairs; only the counts of feature pairs found differ.
TEST(Scene, RandomVerdictsDoNotDependOnSearchingToTheEnd) {
  const auto dir = test::fresh_temp_dir("scene_search_all");
  const Scene scene(small_scene(dir, 10, 3, 7));
  for (const Method m : {Method::Aco, Method::Maco, Method::Pso}) {
    SceneQuery first;
    first.method = m;
    first.random.samples_per_side = 200;
    first.random.search.iterations = 20;
    first.random.search.set_agents(10);
    SceneQuery all = first;
    all.random.all_witnesses = true;
    std::size_t candidates = 0;
    for (std::size_t f = 0; f < 3; ++f) {
      const FrameResult a = scene.run_frame(f, first);
      const FrameResult b = scene.run_frame(f, all);
      candidates += a.candidates.size();
      EXPECT_EQ(a.candidates, b.candidates);
      // Same seed, same stream: the longer search meets the same first hit, and a search with
      // no hit runs the same N iterations either way.
      EXPECT_EQ(a.pairs, b.pairs) << method_name(m) << " frame " << f;
      EXPECT_LE(a.feature_hits, b.feature_hits) << method_name(m) << " frame " << f;
      EXPECT_LE(a.feature_hits, a.pairs.size()) << "a first-hit search keeps one hit per pair";
    }
    EXPECT_GT(candidates, 0u);
  }
}

// The random methods' memory and anytime budget: with a SceneMemory carried over the frames, the
// answers are the same at any thread count; every reported pair is one exact reports (witness
// verdict); with a frame budget, every candidate pair is reported colliding, separate or
// undecided (never both).
TEST(Scene, MemoryAndFrameBudgetAreDeterministicAndSound) {
  const auto dir = test::fresh_temp_dir("scene_memory");
  const Scene scene(small_scene(dir, 24, 6, 8));
  SceneQuery exact;
  for (const std::uint64_t budget : {std::uint64_t{0}, std::uint64_t{3000}}) {
    SceneQuery q;
    q.method = Method::Maco;
    q.seed = 7;
    q.frame_evaluations = budget;
    SceneMemory one_memory, many_memory;
    for (std::size_t f = 0; f < 6; ++f) {
      q.threads = 1;
      const FrameResult one = scene.run_frame(f, q, &one_memory);
      q.threads = 3;
      const FrameResult many = scene.run_frame(f, q, &many_memory);
      EXPECT_EQ(one.pairs, many.pairs) << "frame " << f;
      EXPECT_EQ(one.undecided, many.undecided) << "frame " << f;
      EXPECT_EQ(one.evaluations, many.evaluations) << "frame " << f;
      const FrameResult truth = scene.run_frame(f, exact);
      for (const auto& p : one.pairs) {
        EXPECT_TRUE(std::find(truth.pairs.begin(), truth.pairs.end(), p) != truth.pairs.end())
            << "a reported pair exact does not report";
      }
      for (const auto& p : one.undecided) {
        EXPECT_TRUE(std::find(one.pairs.begin(), one.pairs.end(), p) == one.pairs.end());
      }
      EXPECT_LE(one.pairs.size() + one.undecided.size(), one.candidates.size());
    }
    EXPECT_GT(one_memory.size(), 0u);
  }
}

}  // namespace
}  // namespace antcd

namespace antcd {
namespace {

// `antcd run --method maco` (Scene::run_frame with a SceneMemory, as shared::run_scene calls it)
// and random_detect are one implementation: per candidate pair, random_detect with the scene's
// request, the pair's seed and the pair's own memory gives the same verdict, the same undecided
// flag and the same evaluations, frame after frame.
TEST(Scene, RandomRunIsRandomDetectPerPair) {
  const auto dir = test::fresh_temp_dir("scene_detect_parity");
  const Scene scene(small_scene(dir, 24, 8, 31));
  for (const Method m : {Method::Maco, Method::Aco, Method::Pso}) {
    SceneQuery q;
    q.method = m;
    q.seed = 5;
    q.random.samples_per_side = 300;
    q.random.search.iterations = 30;
    q.random.evaluations_per_leaf_pair = m == Method::Pso ? 0 : 16;
    SceneMemory memory;
    std::map<std::pair<std::uint32_t, std::uint32_t>, ColonyMemory> own;
    std::size_t checked = 0;
    std::size_t colliding = 0;
    for (std::size_t f = 0; f < 8; ++f) {
      const FrameResult r = scene.run_frame(f, q, &memory);
      std::uint64_t evaluations = 0;
      for (const auto& [i, j] : r.candidates) {
        DetectRequest request = q.random;
        request.search.method = m;
        request.delta = q.delta;
        request.search.seed = scene_pair_seed(q.seed, f, i, j);
        const auto& objects = scene.description().objects;
        const std::pair<std::uint32_t, std::uint32_t> key{i, j};
        ColonyMemory& mine = own[key];
        const DetectResult d = random_detect(scene.model_of(i), objects[i].pose(f),
                                             scene.model_of(j), objects[j].pose(f), request, &mine);
        const bool in_pairs = std::binary_search(r.pairs.begin(), r.pairs.end(), key);
        const bool in_undecided =
            std::find(r.undecided.begin(), r.undecided.end(), key) != r.undecided.end();
        EXPECT_EQ(d.colliding, in_pairs)
            << method_name(m) << " frame " << f << " " << i << "-" << j;
        EXPECT_EQ(d.undecided, in_undecided) << method_name(m) << " frame " << f;
        const ColonyMemory* kept = memory.find(i, j);
        ASSERT_NE(kept, nullptr);
        EXPECT_EQ(kept->witnesses, mine.witnesses);
        EXPECT_EQ(kept->iterations, mine.iterations);
        evaluations += d.spent;
        colliding += d.colliding ? 1 : 0;
        ++checked;
      }
      EXPECT_EQ(evaluations, r.evaluations) << method_name(m) << " frame " << f;
    }
    EXPECT_GT(checked, 20u) << method_name(m);
    EXPECT_GT(colliding, 3u) << method_name(m);
  }
}

}  // namespace
}  // namespace antcd
