// Concurrency of the World: many std::threads run every const query on one World at once, between
// mutations made by the main thread, and must get exactly the single-threaded answers. Part of the
// executable that scripts/sanitize.sh tsan runs under ThreadSanitizer (tests named Concurrency*).
// The world is kept small (under the sizes at which a query hands work to oneTBB, whose
// uninstrumented code TSan cannot follow; see robustness/concurrency_test.cpp), so what TSan
// checks here is antcd's own code: the queries' reads against each other and against the
// mutations ordered by the latch and the joins.
#include <antcd/world.hpp>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <array>
#include <latch>
#include <memory>
#include <optional>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "self/self_meshes.hpp"
#include "support/sanitizer.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

struct Answers {
  std::vector<ObjectPair> pairs;
  std::vector<ObjectPair> within;
  std::vector<ObjectPair> candidates;
  std::vector<ObjectId> touching_first;
  std::vector<ObjectId> touching_probe;
  std::vector<std::pair<ObjectId, std::uint32_t>> ray_hits;
  std::vector<std::pair<ObjectPair, Scalar>> nearest;  // nearest_pair, _object, _to (signed)
  std::size_t contacts = 0;

  bool operator==(const Answers&) const = default;
};

Answers ask(const World& world, const Model& probe, const Transform& probe_pose) {
  Answers a;
  CollisionRequest all;
  all.all_contacts = true;
  for (const PairContacts& p : world.collide_all(all)) {
    a.pairs.push_back({p.a, p.b});
    a.contacts += p.contacts.size();
  }
  a.within = world.pairs_within(0.05);
  a.candidates = world.candidate_pairs(0);
  const std::vector<ObjectId> ids = world.objects();
  for (const ObjectContacts& c : world.collide_object(ids.front())) {
    a.touching_first.push_back(c.object);
  }
  for (const ObjectContacts& c : world.collide_model(probe, probe_pose)) {
    a.touching_probe.push_back(c.object);
  }
  for (int k = 0; k < 8; ++k) {
    const Ray ray{Vec3(-10, 0.3 * k - 1, 0.1 * k), Vec3(1, 0.01 * k, 0)};
    for (const RayHit& h : world.raycast_all(ray)) a.ray_hits.emplace_back(h.object, h.triangle);
    if (const std::optional<RayHit> h = world.raycast(ray)) {
      a.ray_hits.emplace_back(h->object, h->triangle);
    }
  }
  const auto keep = [&a](const std::optional<NearestPair>& n) {
    if (n) a.nearest.push_back({{n->a, n->b}, n->result.distance});
  };
  keep(world.nearest_pair());
  // Signed distances of overlapping solids run the penetration query, whose depth probe is a
  // oneTBB parallel loop: under TSan (see support/sanitizer.hpp) the surface distance instead.
  const NearestRequest signed_distance{!test::kUnderTsan};
  keep(world.nearest_object(ids.front(), signed_distance));
  keep(world.nearest_to(probe, probe_pose, signed_distance));
  return a;
}

TEST(Concurrency, WorldQueriesFromManyThreadsBetweenMutations) {
  constexpr int kThreads = 6;
  const auto sphere = std::make_shared<const Model>(make_sphere(0.6, 12, 6));
  const auto torus = std::make_shared<const Model>(make_torus(0.6, 0.2, 16, 8));
  const Model probe(make_box(Vec3(1, 1, 1), 2));
  World world;
  std::mt19937_64 rng(3);
  std::vector<ObjectId> ids;
  for (int i = 0; i < 24; ++i) {
    ids.push_back(world.add(i % 2 ? sphere : torus, test::random_pose(rng, 4)));
  }
  std::size_t pairs_seen = 0;
  for (int round = 0; round < 4; ++round) {
    // Mutations (main thread only, no query running).
    for (const ObjectId id : ids) {
      if (world.contains(id)) world.set_pose(id, test::random_pose(rng, 4));
    }
    if (round == 2) {
      world.remove(ids[5]);
      world.ignore_pair(ids[0], ids[1]);
    }
    const Transform probe_pose = test::random_pose(rng, 2);
    const Answers expected = ask(world, probe, probe_pose);
    ASSERT_LT(expected.candidates.size(), 64u) << "keep the world under oneTBB's threshold";
    pairs_seen += expected.pairs.size();
    std::vector<Answers> got(kThreads);
    std::latch start(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        start.arrive_and_wait();
        got[t] = ask(world, probe, probe_pose);
      });
    }
    for (std::thread& th : threads) th.join();
    for (int t = 0; t < kThreads; ++t) EXPECT_TRUE(got[t] == expected) << "thread " << t;
  }
  EXPECT_GT(pairs_seen, 0u);
}

// A deforming object with self-collision among rigid ones: set_vertices (main thread) between
// rounds of collide_all (self pairs included) and the other queries from many threads at once.
// Under TSan every thread runs its queries in an arena of one thread, so that self_intersections'
// oneTBB loop stays on the calling thread (see support/sanitizer.hpp).
TEST(Concurrency, WorldDeformingSelfCollisionQueriesFromManyThreads) {
  constexpr int kThreads = 6;
  constexpr int kN = 16;
  // The sheet blended from flat into a loop through itself (x = u^2 - 1, z = u (u^2 - 1)).
  const auto sheet_at = [&](Scalar s) {
    return test::grid_sheet(kN, 4, [=](int i, int j) {
      const Scalar u = -1.5 + 3.0 * i / kN;
      return Vec3((1 - s) * u + s * (u * u - 1), 0.25 * j, s * u * (u * u - 1));
    });
  };
  const auto sphere = std::make_shared<const Model>(make_sphere(0.3, 12, 6));
  const Model probe(make_box(Vec3(0.5, 0.5, 0.5), 2));
  World world;
  std::mt19937_64 rng(5);
  ObjectOptions selfish;
  selfish.self_collision = true;
  const ObjectId sheet =
      world.add(std::make_shared<const Model>(sheet_at(0)), Transform{}, selfish);
  for (int i = 0; i < 8; ++i) world.add(sphere, test::random_pose(rng, 1.5));
  std::size_t self_pairs_seen = 0;
  for (int round = 0; round <= 5; ++round) {
    world.set_vertices(sheet, sheet_at(0.2 * round).vertices);  // a mutation, on this thread only
    const auto ask_all = [&] {
      std::pair<Answers, std::vector<std::vector<std::array<std::uint32_t, 2>>>> out;
      const auto run = [&] {
        out.first = ask(world, probe, Transform{});
        CollisionRequest all;
        all.all_contacts = true;
        for (const PairContacts& p : world.collide_all(all)) out.second.push_back(p.self_pairs);
      };
      if (test::kUnderTsan) {
        tbb::task_arena(1).execute(run);
      } else {
        run();
      }
      return out;
    };
    const auto expected = ask_all();
    for (const auto& s : expected.second) self_pairs_seen += s.size();
    std::vector<decltype(ask_all())> got(kThreads);
    std::latch start(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        start.arrive_and_wait();
        got[t] = ask_all();
      });
    }
    for (std::thread& th : threads) th.join();
    for (int t = 0; t < kThreads; ++t) EXPECT_TRUE(got[t] == expected) << "thread " << t;
  }
  EXPECT_GT(self_pairs_seen, 0u) << "the sheet never intersects itself: the test would be trivial";
}

// The answers a World keeps for pairs of unchanged objects (world.hpp, "Unchanged pairs") are
// shared state behind const queries: many threads ask collide_all (two requests, so the kept
// answers are taken, replaced and reused under contention) on a world whose static half keeps its
// poses while the other half moves between rounds, and every answer must be a fresh World's.
// Under TSan each thread asks in an arena of one thread, so that the pair loop stays on the calling
// thread (see support/sanitizer.hpp).
TEST(Concurrency, WorldKeptAnswersOfUnchangedPairsFromManyThreads) {
  constexpr int kThreads = 6;
  const auto sphere = std::make_shared<const Model>(make_sphere(0.6, 12, 6));
  const auto torus = std::make_shared<const Model>(make_torus(0.6, 0.2, 16, 8));
  std::mt19937_64 rng(9);
  World world;
  std::vector<ObjectId> movers;
  std::vector<std::shared_ptr<const Model>> models;
  for (int i = 0; i < 24; ++i) {
    models.push_back(i % 2 ? sphere : torus);
    const ObjectId id = world.add(models.back(), test::random_pose(rng, 2.5));
    if (i % 3 == 0) movers.push_back(id);
  }
  CollisionRequest all;
  all.all_contacts = true;
  using Got = std::vector<std::pair<ObjectPair, std::size_t>>;
  const auto ask_world = [&](const World& w) {
    std::pair<Got, Got> out;
    const auto run = [&] {
      for (const PairContacts& p : w.collide_all(all)) {
        out.first.push_back({{p.a, p.b}, p.contacts.size()});
      }
      for (const PairContacts& p : w.collide_all()) out.second.push_back({{p.a, p.b}, 0});
    };
    if (test::kUnderTsan) {
      tbb::task_arena(1).execute(run);
    } else {
      run();
    }
    return out;
  };
  std::size_t pairs_seen = 0;
  for (int round = 0; round < 4; ++round) {
    for (const ObjectId id : movers) world.set_pose(id, test::random_pose(rng, 2.5));
    World fresh;  // same objects in the same slots, nothing kept
    for (const ObjectId id : world.objects()) fresh.add(world.model_ptr(id), world.pose(id));
    const auto expected = ask_world(fresh);
    ASSERT_LT(world.candidate_pairs(0).size(), 64u) << "keep the world under oneTBB's threshold";
    pairs_seen += expected.first.size();
    std::vector<std::vector<std::pair<Got, Got>>> got(kThreads);
    std::latch start(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        start.arrive_and_wait();
        for (int call = 0; call < 3; ++call) got[t].push_back(ask_world(world));
      });
    }
    for (std::thread& th : threads) th.join();
    for (int t = 0; t < kThreads; ++t) {
      for (const auto& g : got[t]) EXPECT_TRUE(g == expected) << "thread " << t;
    }
    EXPECT_GT(world.memory_bytes(), fresh.memory_bytes()) << "no answer was kept";
  }
  EXPECT_GT(pairs_seen, 0u);
}

}  // namespace
}  // namespace antcd
