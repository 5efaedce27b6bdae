// Concurrency: many std::threads query the same Models and the same Scene at once and must get
// exactly the answers of a single-threaded run (every field but wall times). Built to run under
// ThreadSanitizer too (scripts/sanitize.sh tsan runs the tests named Concurrency*), so the work
// per thread is kept small.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/random.hpp>
#include <antcd/scene.hpp>
#include <antcd/sweep.hpp>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <atomic>
#include <cstdint>
#include <latch>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "shared/production_line.hpp"
#include "support/sanitizer.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

constexpr int kThreads = 8;

// Under ThreadSanitizer (scripts/sanitize.sh tsan) the Scene test keeps run_frame on the calling
// thread (SceneQuery::threads = 1). Debian's libtbb is not instrumented, so TSan cannot see how
// oneTBB hands tasks over between its threads: every access of the task bodies, antcd's included
// (scene.cpp's per-pair lambda, narrow.cpp), is then reported as a race. Silencing those would
// also silence real races in antcd, so the oneTBB path is checked by the answers in the other
// builds (ASan and Release run this test with threads > 1 inside), not by TSan.
using test::kUnderTsan;

// ---- field-by-field comparisons (times excluded) ------------------------------------------------

bool same(const Vec3& a, const Vec3& b) { return a == b; }

bool same(const CollisionResult& a, const CollisionResult& b) {
  if (a.colliding != b.colliding || a.contacts.size() != b.contacts.size() ||
      a.triangle_tests != b.triangle_tests || a.traversal.node_pairs != b.traversal.node_pairs ||
      a.traversal.sphere_rejects != b.traversal.sphere_rejects ||
      a.traversal.obb_rejects != b.traversal.obb_rejects ||
      a.traversal.leaf_pairs != b.traversal.leaf_pairs) {
    return false;
  }
  for (std::size_t k = 0; k < a.contacts.size(); ++k) {
    const Contact& x = a.contacts[k];
    const Contact& y = b.contacts[k];
    if (x.triangle_a != y.triangle_a || x.triangle_b != y.triangle_b || !same(x.point, y.point) ||
        x.distance != y.distance) {
      return false;
    }
  }
  return true;
}

bool same(const FeaturePair& a, const FeaturePair& b) {
  return a.i == b.i && a.j == b.j && a.triangle_a == b.triangle_a && a.triangle_b == b.triangle_b &&
         a.distance == b.distance;
}

bool same(const SearchResult& a, const SearchResult& b) {
  if (a.found != b.found || a.hits.size() != b.hits.size() || a.best_distance != b.best_distance ||
      !same(a.best, b.best) || a.evaluations != b.evaluations || a.iterations != b.iterations ||
      a.runs != b.runs || a.progress.size() != b.progress.size() || a.stop != b.stop ||
      a.centroid_delta != b.centroid_delta || a.witness_tests != b.witness_tests) {
    return false;
  }
  for (std::size_t k = 0; k < a.hits.size(); ++k) {
    if (!same(a.hits[k], b.hits[k])) return false;
  }
  for (std::size_t k = 0; k < a.progress.size(); ++k) {
    const ProgressMark& x = a.progress[k];
    const ProgressMark& y = b.progress[k];
    if (x.share != y.share || x.hits != y.hits || x.reached != y.reached ||
        x.evaluations != y.evaluations) {  // seconds is a wall time
      return false;
    }
  }
  return true;
}

bool same(const FrameResult& a, const FrameResult& b) {
  return a.frame == b.frame && a.pairs == b.pairs && a.candidates == b.candidates &&
         a.feature_hits == b.feature_hits && a.feature_truth == b.feature_truth;
}

// Runs `job(thread, round)` on kThreads threads released together; returns the mismatch count.
template <class Job>
int run_threads(int rounds, Job job) {
  std::atomic<int> mismatches{0};
  std::latch start(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      start.arrive_and_wait();
      for (int r = 0; r < rounds; ++r) mismatches += job(t, r);
    });
  }
  for (std::thread& th : threads) th.join();
  return mismatches.load();
}

// ---- one Model pair -----------------------------------------------------------------------------

struct PoseCase {
  Transform pose_a;
  Transform pose_b;
  CollisionResult boolean;
  CollisionResult all;
  bool volumes = false;
  DistanceResult distance;
  SearchResult maco;
  SearchResult ga;
};

TEST(Concurrency, ModelQueriesFromManyThreadsMatchSingleThreaded) {
  const Model a(make_torus(1.0, 0.3, 32, 16));
  const Model b(merge({make_box(Vec3(0.6, 0.4, 0.3), 3), make_sphere(0.5, 16, 8)}));
  std::mt19937_64 rng(11);
  std::vector<PoseCase> cases(12);
  std::size_t colliding = 0;
  for (PoseCase& c : cases) {
    c.pose_a = test::random_pose(rng, 0.3);
    c.pose_b = test::random_pose(rng, 1.2);
    c.boolean = collide(a, c.pose_a, b, c.pose_b, {});
    c.all = collide(a, c.pose_a, b, c.pose_b, {.delta = 0.01, .all_contacts = true});
    c.volumes = any_leaf_pair_overlaps(a, c.pose_a, b, c.pose_b, 0.0);
    c.distance = distance(a, c.pose_a, b, c.pose_b);
    SearchRequest maco;
    maco.method = Method::Maco;
    maco.seed = 99;
    maco.iterations = 20;
    maco.progress_marks = {0.5};
    c.maco = random_collide(a, c.pose_a, b, c.pose_b, maco, {.samples_per_side = 200});
    SearchRequest ga = maco;
    ga.method = Method::Ga;
    ga.progress_marks.clear();
    c.ga = random_collide(a, c.pose_a, b, c.pose_b, ga, {.samples_per_side = 200});
    colliding += c.boolean.colliding ? 1 : 0;
  }
  // The poses mix hits and misses, so the comparisons below are not all trivial.
  ASSERT_GT(colliding, 2u);
  ASSERT_LT(colliding, cases.size());

  const int mismatches = run_threads(1, [&](int t, int r) {
    int bad = 0;
    CollisionResult reused;  // a reused result must give the same answer as a fresh one
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const PoseCase& c = cases[(k + static_cast<std::size_t>(t * 5 + r)) % cases.size()];
      collide(a, c.pose_a, b, c.pose_b, {}, reused);
      bad += same(reused, c.boolean) ? 0 : 1;
      bad += same(collide(a, c.pose_a, b, c.pose_b, {.delta = 0.01, .all_contacts = true}), c.all)
                 ? 0
                 : 1;
      bad += any_leaf_pair_overlaps(a, c.pose_a, b, c.pose_b, 0.0) == c.volumes ? 0 : 1;
      const DistanceResult d = distance(a, c.pose_a, b, c.pose_b);
      bad += d.distance == c.distance.distance && d.point_a == c.distance.point_a &&
                     d.point_b == c.distance.point_b && d.triangle_a == c.distance.triangle_a &&
                     d.triangle_b == c.distance.triangle_b
                 ? 0
                 : 1;
      if ((k + static_cast<std::size_t>(t)) % 3 == 0) {  // a third of the random searches
        SearchRequest maco;
        maco.method = Method::Maco;
        maco.seed = 99;
        maco.iterations = 20;
        maco.progress_marks = {0.5};
        bad +=
            same(random_collide(a, c.pose_a, b, c.pose_b, maco, {.samples_per_side = 200}), c.maco)
                ? 0
                : 1;
        maco.method = Method::Ga;
        maco.progress_marks.clear();
        bad += same(random_collide(a, c.pose_a, b, c.pose_b, maco, {.samples_per_side = 200}), c.ga)
                   ? 0
                   : 1;
      }
    }
    return bad;
  });
  EXPECT_EQ(mismatches, 0);
}

// ---- mesh sweeps
// ---------------------------------------------------------------------------------

bool same(const SweepResult& x, const SweepResult& y) {
  return x.hit == y.hit && x.toi == y.toi && x.tolerance_decided == y.tolerance_decided &&
         x.budget_exhausted == y.budget_exhausted && x.distance == y.distance &&
         x.motion_bound == y.motion_bound && x.iterations == y.iterations &&
         x.contact.triangle_a == y.contact.triangle_a &&
         x.contact.triangle_b == y.contact.triangle_b && x.contact.point == y.contact.point &&
         x.contact.normal == y.contact.normal;
}

TEST(Concurrency, SweepsFromManyThreadsMatchSingleThreaded) {
  // Fine enough that the sweeps hand over to their traversal (whose pair queues are per thread),
  // and a roller spinning about its own axis (the turn's axis in every bound).
  const Model torus(make_torus(1.0, 0.3, 60, 30));
  const Model ball(make_sphere(0.5, 40, 20));
  const Model roller(make_cylinder(0.05, 1.3, 32, 8));
  const Model plate(make_box(Vec3(0.3, 0.3, 0.005), 6));
  struct Case {
    const Model* a;
    const Model* b;
    Transform a0, a1, b0, b1;
    SweepResult expected;
  };
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::vector<Case> cases;
  for (int i = 0; i < 6; ++i) {
    Case c{&ball, &torus, {}, {}, Transform::identity(), Transform::identity(), {}};
    const Vec3 dir = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    c.a0 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 2 * unit(rng),
                                      -2.5 * dir);
    // Through the ring's middle region, or (odd i) well off to one side.
    const Vec3 side =
        Vec3(unit(rng), unit(rng), unit(rng)).cross(dir).normalized() * (i % 2 == 0 ? 0.3 : 2.2);
    c.a0.translation += side;
    c.a1 = Transform::from_axis_angle(Vec3(unit(rng), unit(rng), unit(rng)), 2 * unit(rng),
                                      2.5 * dir + side);
    cases.push_back(c);
  }
  for (int i = 0; i < 2; ++i) {
    Case c{&roller, &plate, {}, {}, {}, {}, {}};
    c.a0 = Transform::from_axis_angle(Vec3::UnitX(), 0.3 * i);
    c.a1 = c.a0 * Transform::from_axis_angle(Vec3::UnitZ(), 2.5);
    c.b0 = Transform::from_axis_angle(Vec3::UnitY(), std::numbers::pi / 2, Vec3(0.2, 0, 0));
    c.b1 = c.b0;
    c.b1.translation = Vec3(i == 0 ? 0.07 : 0.04, 0, 0);  // stops short, or touches
    cases.push_back(c);
  }
  std::size_t hits = 0;
  for (Case& c : cases) {
    c.expected = sweep(*c.a, c.a0, c.a1, *c.b, c.b0, c.b1);
    hits += c.expected.hit ? 1 : 0;
  }
  ASSERT_GT(hits, 2u);
  ASSERT_LT(hits, cases.size());
  const int mismatches = run_threads(1, [&](int t, int) {
    int bad = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Case& c = cases[(k + static_cast<std::size_t>(t)) % cases.size()];
      bad += same(sweep(*c.a, c.a0, c.a1, *c.b, c.b0, c.b1), c.expected) ? 0 : 1;
    }
    return bad;
  });
  EXPECT_EQ(mismatches, 0);
}

// ---- one Scene ----------------------------------------------------------------------------------

TEST(Concurrency, SceneFramesFromManyThreadsMatchSingleThreaded) {
  shared::ProductionLineOptions options;
  options.objects = 12;
  options.vertices = 120;
  options.frames = 4;
  options.seed = 5;
  // oneTBB caps its workers at the core count minus one by default (a single worker on a 2-core
  // machine): allow more, so that the arenas of the threads below really run in parallel.
  const tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 2 * kThreads);
  const auto dir = test::fresh_temp_dir("concurrency_scene");
  const Scene scene(
      load_scene(shared::write_scene(shared::generate_production_line(options), dir)));

  struct Job {
    SceneQuery query;
    std::vector<FrameResult> expected;
  };
  std::vector<Job> jobs;
  for (const Method m : {Method::Exact, Method::SphereObb, Method::Maco, Method::Pso}) {
    SceneQuery q;
    q.method = m;
    q.seed = 3;
    q.random.samples_per_side = 100;
    q.random.search.iterations = 10;
    q.random.search.set_agents(20);
    q.random.all_witnesses = m == Method::Pso;
    jobs.push_back({q, {}});
  }
  std::size_t pairs = 0;
  for (Job& job : jobs) {
    for (std::size_t f = 0; f < scene.description().frames; ++f) {
      job.expected.push_back(scene.run_frame(f, job.query));
      pairs += job.expected.back().pairs.size();
    }
  }
  ASSERT_GT(pairs, 0u) << "the scene has no collision: the test would be trivial";

  const int mismatches = run_threads(1, [&](int t, int) {
    int bad = 0;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const Job& job = jobs[(k + static_cast<std::size_t>(t)) % jobs.size()];
      SceneQuery q = job.query;
      q.threads = kUnderTsan || t % 3 == 0 ? 1 : (t % 3 == 1 ? 2 : 4);  // oneTBB inside, too
      for (std::size_t f = 0; f < job.expected.size(); ++f) {
        bad += same(scene.run_frame(f, q), job.expected[f]) ? 0 : 1;
      }
    }
    return bad;
  });
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace antcd
