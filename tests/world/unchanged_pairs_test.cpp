// The answers a World keeps for pairs of unchanged objects (world.hpp, "Unchanged pairs"), and the
// scene runner's verdicts of pairs of fixed objects: after every kind of change (a pose, vertices,
// filters, an id removed and its slot reused, another request) the answer must be exactly that of
// a fresh World built from the same objects, which has nothing kept.
#include <antcd/scene.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "self/self_meshes.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

// A pair's answer with objects named by their user tags (ids differ between worlds), contacts by
// every field (bit-exact: == on doubles, no tolerance).
using ContactKey = std::tuple<std::uint32_t, std::uint32_t, Scalar, Scalar, Scalar, Scalar, Scalar,
                              Scalar, Scalar, Scalar, std::uint32_t>;
struct Answer {
  std::uint64_t a = 0;
  std::uint64_t b = 0;
  std::vector<ContactKey> contacts;
  std::vector<std::array<std::uint32_t, 2>> self_pairs;
  bool operator==(const Answer&) const = default;
};

std::vector<Answer> answer(const World& world, const CollisionRequest& request) {
  std::vector<Answer> out;
  for (const PairContacts& p : world.collide_all(request)) {
    Answer x;
    x.a = world.options(p.a).user_tag;
    x.b = world.options(p.b).user_tag;
    for (const Contact& c : p.contacts) {
      x.contacts.emplace_back(c.triangle_a, c.triangle_b, c.point.x(), c.point.y(), c.point.z(),
                              c.distance, c.normal.x(), c.normal.y(), c.normal.z(), c.depth,
                              c.region);
    }
    x.self_pairs = p.self_pairs;
    out.push_back(std::move(x));
  }
  return out;
}

// A World with the same objects (in slot order, so that the answers' order is comparable), current
// Models, poses, options and ignored pairs, and nothing kept from earlier queries.
World fresh_copy(const World& world) {
  World copy;
  const std::vector<ObjectId> ids = world.objects();
  std::vector<ObjectId> copies;
  for (const ObjectId id : ids) {
    copies.push_back(copy.add(world.model_ptr(id), world.pose(id), world.options(id)));
  }
  for (std::size_t x = 0; x < ids.size(); ++x) {
    for (std::size_t y = x + 1; y < ids.size(); ++y) {
      if (world.pair_ignored(ids[x], ids[y])) copy.ignore_pair(copies[x], copies[y]);
    }
  }
  return copy;
}

// The answer of `world` equals a fresh copy's, asked as many times as it takes to reuse kept
// answers (the third call), for `request`.
void expect_fresh(const World& world, const CollisionRequest& request, const std::string& what) {
  const World copy = fresh_copy(world);
  const std::vector<Answer> expected = answer(copy, request);
  for (int call = 0; call < 3; ++call) {
    EXPECT_EQ(answer(world, request), expected) << what << ", call " << call;
  }
}

CollisionRequest all_contacts() {
  CollisionRequest r;
  r.all_contacts = true;
  return r;
}

// Objects in a row along x, each overlapping its neighbours, tagged 1, 2, ...
struct Row {
  World world;
  std::vector<ObjectId> ids;
  std::shared_ptr<const Model> sphere = std::make_shared<const Model>(make_sphere(0.5, 16, 8));
  std::shared_ptr<const Model> torus = std::make_shared<const Model>(make_torus(0.5, 0.2, 24, 12));

  explicit Row(int n) {
    std::mt19937_64 rng(11);
    for (int i = 0; i < n; ++i) {
      Transform pose = test::random_pose(rng, 0.1);
      pose.translation.x() += 0.8 * i;
      ObjectOptions options;
      options.user_tag = static_cast<std::uint64_t>(i + 1);
      ids.push_back(world.add(i % 2 ? sphere : torus, pose, options));
    }
  }
  // The answers settle on the kept ones (calls 1 and 2 keep them, 3 reuses).
  void settle(const CollisionRequest& request) {
    for (int k = 0; k < 3; ++k) (void)world.collide_all(request);
  }
};

TEST(UnchangedPairs, StaticPairsAreKeptAndEqualAFreshWorld) {
  Row row(8);
  const std::size_t before = row.world.memory_bytes();
  row.settle(all_contacts());
  EXPECT_GT(row.world.memory_bytes(), before) << "no answer was kept";
  const std::vector<Answer> got = answer(row.world, all_contacts());
  ASSERT_GE(got.size(), 5u) << "the row must have colliding pairs";
  expect_fresh(row.world, all_contacts(), "static");
  expect_fresh(row.world, CollisionRequest{}, "static, boolean");
}

TEST(UnchangedPairs, MovingAnObjectDropsItsPairs) {
  Row row(8);
  row.settle(all_contacts());
  // Nudged: still touching its neighbours, other contacts.
  Transform nudged = row.world.pose(row.ids[3]);
  nudged.translation += Vec3(0.05, 0.03, -0.02);
  row.world.set_pose(row.ids[3], nudged);
  expect_fresh(row.world, all_contacts(), "object 3 nudged");
  // Taken away: its pairs are gone.
  Transform away = nudged;
  away.translation += Vec3(0, 50, 0);
  row.world.set_pose(row.ids[4], away);
  const std::vector<Answer> got = answer(row.world, all_contacts());
  for (const Answer& x : got) EXPECT_TRUE(x.a != 5 && x.b != 5) << x.a << " " << x.b;
  expect_fresh(row.world, all_contacts(), "object 4 taken away");
  // Through set_poses, and back where it was.
  const Transform back = row.world.pose(row.ids[3]);
  std::vector<ObjectId> ids = {row.ids[4]};
  std::vector<Transform> poses = {back};
  poses[0].translation.x() += 0.8;
  row.world.set_poses(ids, poses);
  expect_fresh(row.world, all_contacts(), "object 4 back by set_poses");
}

TEST(UnchangedPairs, NewVerticesDropTheObjectsPairs) {
  Row row(6);
  row.settle(all_contacts());
  // Object 2 (a torus) grown by 30 %: more contacts with its neighbours.
  std::vector<Vec3> grown_vertices = row.world.model(row.ids[2]).mesh().vertices;
  for (Vec3& v : grown_vertices) v *= 1.3;
  const std::vector<Answer> before = answer(row.world, all_contacts());
  row.world.set_vertices(row.ids[2], grown_vertices);
  expect_fresh(row.world, all_contacts(), "object 2 grown");
  EXPECT_NE(answer(row.world, all_contacts()), before) << "growing changed nothing: test is void";
  // Refitted in place now (its private Model): again.
  for (Vec3& v : grown_vertices) v *= 0.8;
  row.world.set_vertices(row.ids[2], grown_vertices);
  expect_fresh(row.world, all_contacts(), "object 2 shrunk in place");
}

TEST(UnchangedPairs, FiltersApplyToKeptAnswers) {
  Row row(6);
  row.settle(all_contacts());
  row.world.set_filter(row.ids[1], 2, ~2u);  // object 1 no longer meets its own group
  row.world.set_filter(row.ids[2], 2, ~2u);
  expect_fresh(row.world, all_contacts(), "objects 1 and 2 in one group");
  row.world.set_filter(row.ids[1], 1, ~0u);
  row.world.set_filter(row.ids[2], 1, ~0u);
  expect_fresh(row.world, all_contacts(), "filters back");
  row.world.ignore_pair(row.ids[3], row.ids[4]);
  expect_fresh(row.world, all_contacts(), "pair 3-4 ignored");
  row.world.ignore_pair(row.ids[3], row.ids[4], false);
  expect_fresh(row.world, all_contacts(), "pair 3-4 admitted again");
}

TEST(UnchangedPairs, RemovedIdsSlotNeverMeetsItsOldAnswers) {
  Row row(6);
  row.settle(all_contacts());
  // Object 2 removed, and another model added in its slot, at the same pose: the pairs it makes
  // have other contacts (and the old ones must not come back).
  const Transform pose = row.world.pose(row.ids[2]);
  const std::shared_ptr<const Model> other = row.world.model_ptr(row.ids[1]);
  row.world.remove(row.ids[2]);
  expect_fresh(row.world, all_contacts(), "object 2 removed");
  ObjectOptions options;
  options.user_tag = 3;
  const ObjectId again = row.world.add(other, pose, options);
  EXPECT_EQ(again.slot, row.ids[2].slot) << "the slot was not reused: the test is weaker";
  expect_fresh(row.world, all_contacts(), "object 2 replaced in its slot");
  // Removed and replaced with no query between: the kept answers still hold the slot's pairs.
  row.world.remove(again);
  const ObjectId third = row.world.add(row.world.model_ptr(row.ids[0]), pose, options);
  EXPECT_EQ(third.slot, row.ids[2].slot);
  expect_fresh(row.world, all_contacts(), "object 2 replaced again, no query between");
}

TEST(UnchangedPairs, AnotherRequestIsAnsweredAfresh) {
  Row row(8);
  CollisionRequest near = all_contacts();
  near.delta = 0.05;
  CollisionRequest capped = all_contacts();
  capped.max_contacts = 3;
  CollisionRequest normals = all_contacts();
  normals.contact_normals = true;
  CollisionRequest manifold = all_contacts();
  manifold.manifold_points = 4;
  const std::vector<CollisionRequest> requests = {
      all_contacts(), CollisionRequest{}, near, capped, normals, manifold};
  // Each request settled, then every other one asked: none may get another's answers.
  for (const CollisionRequest& settled : requests) {
    row.settle(settled);
    for (const CollisionRequest& r : requests) {
      const World copy = fresh_copy(row.world);
      EXPECT_EQ(answer(row.world, r), answer(copy, r));
      row.settle(settled);
    }
  }
  // pairs_within shares the kept answers of the request {delta = d}.
  // (Spheres two places apart along the row are 0.6 apart.)
  row.settle(CollisionRequest{0.7, false, 0});
  const World copy = fresh_copy(row.world);
  EXPECT_EQ(row.world.pairs_within(0.7), copy.pairs_within(0.7));
  EXPECT_EQ(row.world.pairs_within(0.05), copy.pairs_within(0.05));
  EXPECT_EQ(row.world.pairs_within(0.7), copy.pairs_within(0.7));
  EXPECT_GT(copy.pairs_within(0.7).size(), copy.pairs_within(0).size())
      << "the distances must matter for the test to mean anything";
}

TEST(UnchangedPairs, SelfPairsAreKeptUntilNewVertices) {
  // A sheet folded through itself (as in the concurrency tests), and a sphere it crosses.
  constexpr int kN = 16;
  const auto sheet_at = [&](Scalar s) {
    return test::grid_sheet(kN, 4, [=](int i, int j) {
      const Scalar u = -1.5 + 3.0 * i / kN;
      return Vec3((1 - s) * u + s * (u * u - 1), 0.25 * j, s * u * (u * u - 1));
    });
  };
  World world;
  ObjectOptions selfish;
  selfish.self_collision = true;
  selfish.user_tag = 1;
  const ObjectId sheet =
      world.add(std::make_shared<const Model>(sheet_at(1)), Transform{}, selfish);
  ObjectOptions plain;
  plain.user_tag = 2;
  world.add(std::make_shared<const Model>(make_sphere(0.3, 12, 6)), Transform{}, plain);
  for (const CollisionRequest& r : {all_contacts(), CollisionRequest{}}) {
    expect_fresh(world, r, "folded sheet");
    ASSERT_FALSE(answer(world, r).empty());
    EXPECT_FALSE(answer(world, r).front().self_pairs.empty()) << "no self pair: test is void";
  }
  world.set_vertices(sheet, sheet_at(0).vertices);  // flat: no self pair any more
  expect_fresh(world, all_contacts(), "flat sheet");
  for (const Answer& x : answer(world, all_contacts())) EXPECT_TRUE(x.self_pairs.empty());
}

TEST(UnchangedPairs, SameAnswersAtAnyThreadCount) {
  // A world over oneTBB's thresholds (64 objects, 64 pairs): half static, half moving.
  const auto sphere = std::make_shared<const Model>(make_sphere(0.5, 12, 6));
  std::mt19937_64 rng(7);
  World world;
  std::vector<ObjectId> movers;
  for (int i = 0; i < 160; ++i) {
    ObjectOptions o;
    o.user_tag = static_cast<std::uint64_t>(i + 1);
    const ObjectId id = world.add(sphere, test::random_pose(rng, 4), o);
    if (i % 2 == 0) movers.push_back(id);
  }
  for (int frame = 0; frame < 4; ++frame) {
    for (const ObjectId id : movers) world.set_pose(id, test::random_pose(rng, 4));
    const World copy = fresh_copy(world);
    const std::vector<Answer> expected = answer(copy, all_contacts());
    ASSERT_GT(expected.size(), 64u);
    for (const int threads : {1, 2, 4, 1}) {
      tbb::task_arena arena(threads);
      arena.execute([&] { EXPECT_EQ(answer(world, all_contacts()), expected) << threads; });
    }
  }
}

// The scene runner keeps the verdict of each pair of fixed objects: it must stay the verdict of
// collide() at every frame, for every delta and volume flag, frames asked in any order.
TEST(UnchangedPairs, SceneVerdictsOfFixedPairs) {
  SceneDescription d;
  d.frames = 6;
  const auto add = [&](const char* mesh, std::vector<Transform> poses) {
    SceneObject o;
    o.name = "o" + std::to_string(d.objects.size());
    o.mesh_text = mesh;
    o.mesh = mesh;  // the key of mesh_source's calls
    o.poses = std::move(poses);
    d.objects.push_back(std::move(o));
  };
  const auto at = [](Scalar x, Scalar y = 0) {
    Transform p;
    p.translation = Vec3(x, y, 0);
    return p;
  };
  // Fixed along x, alternately 0.9 and 1.05 apart: a sphere of radius 0.4 and a torus of outer
  // radius 0.55 then overlap, or are 0.1 apart (apart at delta 0, within delta 0.2).
  for (int i = 0; i < 12; ++i)
    add(i % 2 ? "sphere" : "torus", {at(0.975 * i - (i % 2 ? 0.075 : 0))});
  // Small spheres (radius 0.1) in the holes of the first three tori (inner radius 0.25): their
  // boxes meet the torus's, the surfaces are 0.15 apart (candidates at delta 0, colliding at 0.2).
  for (int i = 0; i < 6; i += 2) add("small", {at(0.975 * i)});
  // Small spheres crossing the tubes of the other three: in the hole, touching the tube, inside
  // it (a volume contact only), touching again as x goes 0, 0.1, ..., 0.5 from the centre.
  for (int i = 6; i < 12; i += 2) {
    std::vector<Transform> poses;
    for (std::size_t f = 0; f < d.frames; ++f) poses.push_back(at(0.975 * i + 0.1 * f));
    add("small", poses);
  }
  const Scene scene(d, [](const SceneObject& o) {
    if (o.mesh_text == "small") return make_sphere(0.1, 12, 6);
    return o.mesh_text == "sphere" ? make_sphere(0.4, 16, 8) : make_torus(0.4, 0.15, 24, 12);
  });
  const auto truth = [&](std::size_t frame, const SceneQuery& q) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    CollisionRequest r{q.delta, false, 0};
    r.volume = q.volume;
    const auto& objects = scene.description().objects;
    for (std::uint32_t i = 0; i < objects.size(); ++i) {
      for (std::uint32_t j = i + 1; j < objects.size(); ++j) {
        CollisionResult res;
        if (collide(scene.model_of(i), objects[i].pose(frame), scene.model_of(j),
                    objects[j].pose(frame), r, res)) {
          out.emplace_back(i, j);
        }
      }
    }
    return out;
  };
  std::vector<SceneQuery> queries(4);
  queries[1].delta = 0.2;
  queries[2].volume = true;
  queries[3].delta = 0.2;
  queries[3].threads = 2;
  for (int round = 0; round < 2; ++round) {
    for (const SceneQuery& q : queries) {
      for (const std::size_t f : {0u, 3u, 5u, 1u, 4u, 3u}) {
        const FrameResult r = scene.run_frame(f, q);
        EXPECT_EQ(r.pairs, truth(f, q)) << "frame " << f << " delta " << q.delta;
      }
    }
  }
  // The test means something only if verdicts change with the frame and with the request.
  EXPECT_NE(truth(0, queries[0]), truth(3, queries[0]));
  EXPECT_NE(truth(0, queries[0]), truth(0, queries[1]));
  EXPECT_NE(truth(4, queries[0]), truth(4, queries[2]));
}

}  // namespace
}  // namespace antcd
