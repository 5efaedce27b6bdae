// The World against brute force: seeded random sequences of add / remove / move / filter / query
// on worlds of generated and real meshes; after every step each query must equal the answer of
// collide() run on every admitted object pair (collide() itself is checked against all triangle
// pairs in the exact tests), with the filters applied by a reference kept here.
#include <antcd/geometry.hpp>
#include <antcd/load.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

// Real meshes scaled to a bounding radius of `radius`.
ModelPtr scaled_model(Mesh mesh, Scalar radius, const std::string& source) {
  const Aabb b = mesh.bounds();
  const Vec3 c = 0.5 * (b.min + b.max);
  const Scalar r = 0.5 * (b.max - b.min).norm();
  for (Vec3& v : mesh.vertices) v = (v - c) * (radius / r);
  return std::make_shared<const Model>(std::move(mesh), BuildOptions{}, source);
}

std::vector<ModelPtr> generated_models() {
  return {std::make_shared<const Model>(make_sphere(0.5, 12, 6)),
          std::make_shared<const Model>(make_box(Vec3(0.6, 0.2, 0.3), 2)),
          std::make_shared<const Model>(make_torus(0.5, 0.15, 16, 8)),
          std::make_shared<const Model>(make_cylinder(0.2, 1.2, 12))};
}

std::vector<ModelPtr> real_models() {
  return {scaled_model(load_mesh(test::assimp_model("OBJ/spider.obj")), 0.7, "spider"),
          scaled_model(load_mesh(test::assimp_model("PLY/Wuson.ply")), 0.6, "wuson"),
          scaled_model(load_mesh(test::assimp_model("OFF/Cube.off")), 0.5, "cube"),
          scaled_model(load_mesh(test::assimp_model("STL/sphereWithHole.stl")), 0.5, "hole")};
}

// What the test believes the world holds.
struct RefObject {
  ModelPtr model;
  Transform pose;
  std::uint32_t group = 1;
  std::uint32_t mask = ~0U;
};

class Reference {
 public:
  std::map<ObjectId, RefObject> objects;
  std::set<std::pair<ObjectId, ObjectId>> ignored;  // (smaller, larger)

  bool admits(ObjectId a, ObjectId b) const {
    const RefObject& x = objects.at(a);
    const RefObject& y = objects.at(b);
    if ((x.group & y.mask) == 0 || (y.group & x.mask) == 0) return false;
    return ignored.count({std::min(a, b), std::max(a, b)}) == 0;
  }

  std::vector<ObjectPair> colliding(Scalar delta) const {
    std::vector<ObjectPair> out;
    for (auto i = objects.begin(); i != objects.end(); ++i) {
      for (auto j = std::next(i); j != objects.end(); ++j) {
        if (!admits(i->first, j->first)) continue;
        const CollisionResult r = collide(*i->second.model, i->second.pose, *j->second.model,
                                          j->second.pose, CollisionRequest{delta, false, 0});
        if (r.colliding) out.push_back({i->first, j->first});
      }
    }
    return out;
  }
};

std::vector<ObjectPair> pairs_of(const std::vector<PairContacts>& r) {
  std::vector<ObjectPair> out;
  for (const PairContacts& p : r) out.push_back({p.a, p.b});
  return out;
}

// Small moves (inside the fattened boxes, mostly) and occasional jumps.
Transform nudged(const Transform& t, std::mt19937_64& rng, Scalar extent) {
  std::uniform_real_distribution<Scalar> u(-1, 1);
  if (u(rng) > 0.8) return test::random_pose(rng, extent);
  Transform out = t;
  out.translation += 0.08 * Vec3(u(rng), u(rng), u(rng));
  out.rotation =
      Transform::from_axis_angle(Vec3(u(rng), u(rng), u(rng) + 2), 0.1 * u(rng)).rotation *
      t.rotation;
  return out;
}

void run_random_sequence(const std::vector<ModelPtr>& models, std::uint64_t seed, int steps,
                         Scalar extent) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> op(0, 9);
  World world;
  Reference ref;
  const auto pick = [&]() {
    auto it = ref.objects.begin();
    std::advance(it, std::uniform_int_distribution<std::size_t>(0, ref.objects.size() - 1)(rng));
    return it->first;
  };
  const std::uint32_t groups[] = {1, 2, 3};
  const std::uint32_t masks[] = {~0U, ~0U, 1, 2, ~0U ^ 2U};
  std::size_t colliding_seen = 0;
  std::size_t steps_with_filtered_collisions = 0;
  for (int step = 0; step < steps; ++step) {
    const int o = ref.objects.size() < 6 ? 0 : op(rng);
    if (o <= 2 && ref.objects.size() < 40) {  // add
      RefObject r;
      r.model = models[std::uniform_int_distribution<std::size_t>(0, models.size() - 1)(rng)];
      r.pose = test::random_pose(rng, extent);
      ObjectOptions opt;
      opt.name = "o" + std::to_string(step);
      if (step % 3 == 0) {
        opt.group = groups[rng() % 3];
        opt.mask = masks[rng() % 5];
      }
      r.group = opt.group;
      r.mask = opt.mask;
      const ObjectId id = world.add(r.model, r.pose, opt);
      ASSERT_EQ(ref.objects.count(id), 0u) << "a fresh id must not equal a live one";
      ref.objects[id] = r;
    } else if (o == 3) {  // remove
      const ObjectId id = pick();
      world.remove(id);
      ref.objects.erase(id);
      std::erase_if(ref.ignored, [&](const auto& p) { return p.first == id || p.second == id; });
      EXPECT_FALSE(world.contains(id));
      EXPECT_THROW(world.set_pose(id, Transform{}), ArgumentError);
    } else if (o <= 5) {  // batch move of about half the objects
      std::vector<ObjectId> ids;
      std::vector<Transform> poses;
      for (auto& [id, r] : ref.objects) {
        if (rng() % 2 == 0) continue;
        r.pose = nudged(r.pose, rng, extent);
        ids.push_back(id);
        poses.push_back(r.pose);
      }
      world.set_poses(ids, poses);
    } else if (o == 6) {  // single move
      const ObjectId id = pick();
      ref.objects[id].pose = nudged(ref.objects[id].pose, rng, extent);
      world.set_pose(id, ref.objects[id].pose);
    } else if (o == 7) {  // ignore / re-admit a pair
      const ObjectId a = pick();
      const ObjectId b = pick();
      if (a != b) {
        const auto key = std::make_pair(std::min(a, b), std::max(a, b));
        const bool now = ref.ignored.count(key) == 0;
        world.ignore_pair(a, b, now);
        if (now) {
          ref.ignored.insert(key);
        } else {
          ref.ignored.erase(key);
        }
        EXPECT_EQ(world.pair_ignored(b, a), now);
      }
    } else if (o == 8) {  // change a filter
      const ObjectId id = pick();
      RefObject& r = ref.objects[id];
      r.group = groups[rng() % 3];
      r.mask = masks[rng() % 5];
      world.set_filter(id, r.group, r.mask);
    }
    // o == 9: query only.

    ASSERT_EQ(world.size(), ref.objects.size());
    const std::vector<ObjectPair> expected = ref.colliding(0);
    const std::vector<ObjectPair> got = pairs_of(world.collide_all());
    ASSERT_EQ(got, expected) << "seed " << seed << " step " << step;
    colliding_seen += expected.size();

    // The broad phase keeps every colliding pair, sorted, each once.
    const std::vector<ObjectPair> candidates = world.candidate_pairs(0);
    EXPECT_TRUE(std::is_sorted(candidates.begin(), candidates.end()));
    EXPECT_EQ(std::adjacent_find(candidates.begin(), candidates.end()), candidates.end());
    for (const ObjectPair& p : expected) {
      EXPECT_TRUE(std::binary_search(candidates.begin(), candidates.end(), p));
    }

    if (step % 7 == 0) {  // distance queries
      const Scalar d = 0.1;
      EXPECT_EQ(world.pairs_within(d), ref.colliding(d)) << "seed " << seed << " step " << step;
    }
    if (step % 5 == 0) {  // one object against the world
      const ObjectId id = pick();
      std::vector<ObjectId> want;
      for (const ObjectPair& p : expected) {
        if (p.a == id) want.push_back(p.b);
        if (p.b == id) want.push_back(p.a);
      }
      std::sort(want.begin(), want.end());
      std::vector<ObjectId> have;
      for (const ObjectContacts& c : world.collide_object(id)) {
        have.push_back(c.object);
        ASSERT_EQ(c.contacts.size(), 1u);
      }
      EXPECT_EQ(have, want) << "seed " << seed << " step " << step;
      std::size_t filtered = 0;
      for (const auto& [other, r] : ref.objects) {
        if (other != id && !ref.admits(id, other) &&
            collide(*ref.objects[id].model, ref.objects[id].pose, *r.model, r.pose).colliding) {
          ++filtered;
        }
      }
      steps_with_filtered_collisions += filtered > 0;
    }
    if (step % 5 == 2) {  // an external model against the world, with a filter
      const ModelPtr& m = models[rng() % models.size()];
      const Transform pose = test::random_pose(rng, extent * 0.5);
      const QueryFilter filter{2, rng() % 2 ? ~0U : 1U};
      std::vector<ObjectId> want;
      for (const auto& [id, r] : ref.objects) {
        if ((filter.group & r.mask) == 0 || (r.group & filter.mask) == 0) continue;
        if (collide(*m, pose, *r.model, r.pose).colliding) want.push_back(id);
      }
      std::vector<ObjectId> have;
      for (const ObjectContacts& c : world.collide_model(*m, pose, {}, filter)) {
        have.push_back(c.object);
      }
      EXPECT_EQ(have, want) << "seed " << seed << " step " << step;
    }
    if (step % 11 == 0) {  // all contacts equal collide()'s, pair by pair
      CollisionRequest all;
      all.all_contacts = true;
      for (const PairContacts& p : world.collide_all(all)) {
        const RefObject& a = ref.objects.at(p.a);
        const RefObject& b = ref.objects.at(p.b);
        const CollisionResult r = collide(*a.model, a.pose, *b.model, b.pose, all);
        ASSERT_EQ(p.contacts.size(), r.contacts.size());
        for (std::size_t k = 0; k < r.contacts.size(); ++k) {
          EXPECT_EQ(p.contacts[k].triangle_a, r.contacts[k].triangle_a);
          EXPECT_EQ(p.contacts[k].triangle_b, r.contacts[k].triangle_b);
        }
      }
    }
  }
  // Not vacuous: the sequence produced collisions, and filters that hid some.
  EXPECT_GT(colliding_seen, static_cast<std::size_t>(steps));
  EXPECT_GT(steps_with_filtered_collisions, 0u);
}

TEST(World, RandomSequencesOnGeneratedMeshesMatchBruteForce) {
  const auto models = generated_models();
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    run_random_sequence(models, seed, 150, 2.5);
  }
}

TEST(World, RandomSequencesOnRealMeshesMatchBruteForce) {
  run_random_sequence(real_models(), 7, 200, 1.6);
}

TEST(World, FiltersAndIgnoredPairs) {
  auto sphere = std::make_shared<const Model>(make_sphere(1.0, 16, 8));
  World world;
  const auto at = [](Scalar x) {
    return Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0, 0));
  };
  // Three overlapping spheres in a row: a-b and b-c touch, a-c overlap too (distance 1.5 < 2).
  const ObjectId a = world.add(sphere, at(0), {"a", 10, 1, ~0U});
  const ObjectId b = world.add(sphere, at(0.75), {"b", 11, 2, ~0U});
  const ObjectId c = world.add(sphere, at(1.5), {"c", 12, 4, ~0U});
  EXPECT_EQ(pairs_of(world.collide_all()), (std::vector<ObjectPair>{{a, b}, {a, c}, {b, c}}));
  // c does not collide with group 1 (a).
  world.set_filter(c, 4, ~0U ^ 1U);
  EXPECT_EQ(pairs_of(world.collide_all()), (std::vector<ObjectPair>{{a, b}, {b, c}}));
  EXPECT_FALSE(world.may_collide(a, c));
  // One-sided masks are enough to exclude: a no longer accepts group 2 (b).
  world.set_filter(a, 1, ~0U ^ 2U);
  EXPECT_EQ(pairs_of(world.collide_all()), (std::vector<ObjectPair>{{b, c}}));
  world.ignore_pair(c, b);
  EXPECT_TRUE(world.collide_all().empty());
  EXPECT_TRUE(world.candidate_pairs().empty());
  EXPECT_TRUE(world.collide_object(b).empty());
  world.ignore_pair(b, c, false);
  EXPECT_EQ(pairs_of(world.collide_all()), (std::vector<ObjectPair>{{b, c}}));
  // Removing an object forgets its ignored pairs; the slot's next object starts clean.
  world.ignore_pair(b, c);
  world.remove(c);
  const ObjectId d = world.add(sphere, at(1.5), {"d", 13, 4, ~0U});
  EXPECT_NE(c, d);
  EXPECT_FALSE(world.pair_ignored(b, d));
  EXPECT_EQ(world.options(d).user_tag, 13u);
  // External queries: the filter's group must be in the object's mask and vice versa.
  EXPECT_EQ(world.collide_model(*sphere, at(0.75), {}, {1, ~0U}).size(), 3u);  // a, b, d
  EXPECT_EQ(world.collide_model(*sphere, at(0.75), {}, {8, 2}).size(), 1u);    // only b
  EXPECT_TRUE(world.collide_model(*sphere, at(0.75), {}, {8, 0}).empty());
}

TEST(World, InvalidArgumentsNameTheArgumentAndChangeNothing) {
  auto sphere = std::make_shared<const Model>(make_sphere(1.0, 8, 4));
  World world;
  const ObjectId a = world.add(sphere, Transform{}, {"arm", 0, 1, ~0U});
  const ObjectId b = world.add(sphere, Transform{}, {"base", 0, 1, ~0U});
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const ArgumentError& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  Transform nan;
  nan.translation.x() = std::numeric_limits<Scalar>::quiet_NaN();
  Transform skew;
  skew.rotation(0, 1) = 0.5;
  EXPECT_NE(message([&] { world.set_pose(a, nan); }).find("'arm'"), std::string::npos);
  EXPECT_NE(message([&] { world.set_pose(a, nan); }).find("not finite"), std::string::npos);
  EXPECT_NE(message([&] { world.set_pose(a, skew); }).find("rigid"), std::string::npos);
  EXPECT_NE(message([&] { (void)world.add(nullptr, Transform{}); }).find("model is null"),
            std::string::npos);
  EXPECT_NE(message([&] { (void)world.add(sphere, nan, {"x"}); }).find("'x'"), std::string::npos);
  // A batch with one bad pose changes no pose.
  const Transform moved = Transform::from_axis_angle(Vec3::UnitX(), 0, Vec3(5, 0, 0));
  const std::vector<ObjectId> ids{a, b};
  const std::vector<Transform> poses{moved, nan};
  EXPECT_NE(message([&] { world.set_poses(ids, poses); }).find("poses[1] of object 'base'"),
            std::string::npos);
  EXPECT_EQ(world.pose(a).translation, Vec3::Zero());
  EXPECT_NE(message([&] { world.set_poses(ids, std::vector<Transform>{moved}); }).find("2 ids"),
            std::string::npos);
  world.remove(b);
  EXPECT_NE(message([&] { world.set_pose(b, moved); }).find("id (slot 1"), std::string::npos);
  EXPECT_NE(message([&] { world.remove(b); }).find("removed, or never added"), std::string::npos);
  EXPECT_NE(message([&] { world.ignore_pair(a, b); }).find(": b "), std::string::npos);
  EXPECT_NE(message([&] { world.ignore_pair(a, a); }).find("same"), std::string::npos);
  EXPECT_NE(message([&] { (void)world.pairs_within(-1); }).find("distance"), std::string::npos);
  EXPECT_NE(message([&] {
              (void)world.collide_all({std::nan(""), false, 0});
            }).find("delta"),
            std::string::npos);
  EXPECT_NE(message([&] {
              (void)world.raycast(Ray{Vec3::Zero(), Vec3::Zero()});
            }).find("ray.direction"),
            std::string::npos);
  EXPECT_NE(message([&] { (void)World(WorldOptions{-1}); }).find("fat_fraction"),
            std::string::npos);
  // Slots are reused with a new generation: the old id stays invalid.
  const ObjectId c = world.add(sphere, Transform{});
  EXPECT_EQ(c.slot, b.slot);
  EXPECT_FALSE(world.contains(b));
  EXPECT_TRUE(world.contains(c));
}

// Many objects moving a little each frame: the incremental tree must keep answering exactly, with
// far fewer tree updates than objects (checked through the answers only: the coherence is a cost
// matter for the benchmarks).
TEST(World, ManySmallMovesMatchBruteForce) {
  auto box = std::make_shared<const Model>(make_box(Vec3(0.3, 0.3, 0.3), 1));
  auto ball = std::make_shared<const Model>(make_sphere(0.3, 8, 4));
  World world;
  Reference ref;
  std::mt19937_64 rng(99);
  for (int i = 0; i < 300; ++i) {
    RefObject r{i % 2 ? box : ball, test::random_pose(rng, 6), 1, ~0U};
    ref.objects[world.add(r.model, r.pose)] = r;
  }
  for (int frame = 0; frame < 20; ++frame) {
    std::vector<ObjectId> ids;
    std::vector<Transform> poses;
    for (auto& [id, r] : ref.objects) {
      r.pose = nudged(r.pose, rng, 6);
      ids.push_back(id);
      poses.push_back(r.pose);
    }
    world.set_poses(ids, poses);
    ASSERT_EQ(pairs_of(world.collide_all()), ref.colliding(0)) << "frame " << frame;
  }
}

// A small world whose objects teleport: many at once on even frames (more than a sixteenth of the
// objects: they stay in the tree and the refit covers them), a couple on odd frames among small
// moves (reinserted). Every frame the exact pairs equal the oracle, and the candidate pairs equal
// those of a world built afresh at the same poses (no box or posed root volume left stale).
TEST(World, SmallWorldWithManyJumpsMatchesOracleAndAFreshWorld) {
  const std::vector<ModelPtr> models = generated_models();
  constexpr int kObjects = 48;
  constexpr Scalar kExtent = 2.2;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  World world;
  Reference ref;
  std::vector<ObjectId> ids;
  for (int i = 0; i < kObjects; ++i) {
    RefObject r;
    r.model = models[i % models.size()];
    r.pose = test::random_pose(rng, kExtent);
    ids.push_back(world.add(r.model, r.pose));
    ref.objects[ids.back()] = r;
  }
  std::size_t colliding_seen = 0;
  for (int frame = 0; frame < 24; ++frame) {
    std::vector<Transform> poses;
    for (int i = 0; i < kObjects; ++i) {
      RefObject& r = ref.objects[ids[i]];
      const bool jump = frame % 2 == 0 ? i % 3 == frame % 3 : i == frame % kObjects || i == 7;
      if (jump) {
        r.pose = test::random_pose(rng, kExtent);
      } else {
        r.pose.translation += 0.05 * Vec3(u(rng), u(rng), u(rng));
      }
      poses.push_back(r.pose);
    }
    world.set_poses(ids, poses);
    const std::vector<ObjectPair> expected = ref.colliding(0);
    ASSERT_EQ(pairs_of(world.collide_all()), expected) << "frame " << frame;
    colliding_seen += expected.size();
    World fresh;
    for (int i = 0; i < kObjects; ++i) fresh.add(ref.objects[ids[i]].model, poses[i]);
    // Same slots in the same order: the ids agree.
    ASSERT_EQ(world.candidate_pairs(0), fresh.candidate_pairs(0)) << "frame " << frame;
    ASSERT_EQ(world.candidate_pairs(0.1), fresh.candidate_pairs(0.1)) << "frame " << frame;
  }
  EXPECT_GT(colliding_seen, 24u);  // the frames test colliding pairs, not only empty answers
}

// candidate_pairs against its definition, pair by pair: filters admit the pair, the posed root
// spheres are within delta and geometry::obb_overlap finds the posed root boxes within delta (plus
// the rounding allowance stated in query.cpp). Objects crowded together, so that many root boxes
// overlap deeply (the pairs accepted without the separating-axis test) and many nearly touch.
TEST(World, CandidatePairsEqualTheirDefinitionOnACrowdedWorld) {
  const std::vector<ModelPtr> models = generated_models();
  constexpr int kObjects = 40;
  std::mt19937_64 rng(13);
  World world;
  std::vector<ObjectId> ids;
  std::vector<Transform> poses;
  for (int i = 0; i < kObjects; ++i) {
    poses.push_back(test::random_pose(rng, 1.4));
    ids.push_back(world.add(models[i % models.size()], poses.back()));
  }
  const auto posed = [&](int i) {
    Obb b = models[i % models.size()]->root().obb();
    b.axes = poses[i].rotation * b.axes;
    b.center = poses[i].apply(b.center);
    return b;
  };
  std::size_t accepted = 0;
  std::size_t rejected_by_boxes = 0;
  for (int frame = 0; frame < 8; ++frame) {
    for (int i = 0; i < kObjects; ++i) poses[i] = test::random_pose(rng, 1.4);
    world.set_poses(ids, poses);
    for (const Scalar delta : {0.0, 0.03}) {
      std::vector<ObjectPair> expected;
      for (int i = 0; i < kObjects; ++i) {
        for (int j = i + 1; j < kObjects; ++j) {
          const Obb a = posed(i);
          const Obb b = posed(j);
          const Scalar reach = models[i % models.size()]->root().radius +
                               models[j % models.size()]->root().radius + delta;
          if ((a.center - b.center).squaredNorm() > reach * reach) continue;
          const Scalar margin = delta + 1e-9 * (reach + std::max(a.center.norm(), b.center.norm()));
          if (!geometry::obb_overlap(a, b, margin)) {
            ++rejected_by_boxes;
            continue;
          }
          expected.push_back({ids[i], ids[j]});
        }
      }
      ASSERT_EQ(world.candidate_pairs(delta), expected) << "frame " << frame << " delta " << delta;
      accepted += expected.size();
    }
  }
  EXPECT_GT(accepted, 200u);
  EXPECT_GT(rejected_by_boxes, 20u);  // the box test decides some pairs the spheres let through
}

// A large world (the parallel paths: batches of poses checked, fitted and written by oneTBB tasks,
// new leaf boxes and a refit, objects that jump reinserted, the all-pairs traversal split into
// tasks): every frame equals an oracle that does not use the World's boxes (root spheres, then
// collide()), and the answers are identical in arenas of one and of three threads.
TEST(World, LargeMovingWorldMatchesOracleAtAnyThreadCount) {
  auto box = std::make_shared<const Model>(make_box(Vec3(0.3, 0.2, 0.15), 1));
  auto ball = std::make_shared<const Model>(make_sphere(0.25, 6, 3));
  constexpr int kObjects = 3000;
  const Scalar extent = std::cbrt(6.0 * kObjects) / 2;
  std::mt19937_64 rng(7);
  World world;
  std::vector<ObjectId> ids;
  std::vector<ModelPtr> models;
  std::vector<Transform> poses;
  for (int i = 0; i < kObjects; ++i) {
    models.push_back(i % 2 ? box : ball);
    poses.push_back(test::random_pose(rng, extent));
    ObjectOptions options;
    options.group = i % 7 == 0 ? 2U : 1U;
    options.mask = i % 7 == 0 ? 2U : ~0U;  // every 7th object meets only its own kind
    ids.push_back(world.add(models.back(), poses.back(), options));
  }
  const auto admitted = [](int i, int j) { return (i % 7 == 0) == (j % 7 == 0); };
  tbb::task_arena one(1);
  tbb::task_arena three(3);
  std::size_t colliding_seen = 0;
  for (int frame = 0; frame < 6; ++frame) {
    std::uniform_real_distribution<Scalar> u(-1, 1);
    for (int i = 0; i < kObjects; ++i) {
      if (frame == 0) break;
      if (u(rng) > 0.98) {
        poses[i] = test::random_pose(rng, extent);  // a jump across the world
      } else {
        poses[i].translation += 0.04 * Vec3(u(rng), u(rng), u(rng));
      }
    }
    world.set_poses(ids, poses);
    // Oracle: pairs whose root spheres (placed by the pose) meet, then collide().
    std::vector<ObjectPair> expected;
    std::vector<Vec3> centre(kObjects);
    for (int i = 0; i < kObjects; ++i) centre[i] = poses[i].apply(models[i]->root().center);
    for (int i = 0; i < kObjects; ++i) {
      for (int j = i + 1; j < kObjects; ++j) {
        if (!admitted(i, j)) continue;
        const Scalar reach = models[i]->root().radius + models[j]->root().radius;
        if ((centre[i] - centre[j]).squaredNorm() > reach * reach * (1 + 1e-9)) continue;
        if (collide(*models[i], poses[i], *models[j], poses[j]).colliding) {
          expected.push_back({std::min(ids[i], ids[j]), std::max(ids[i], ids[j])});
        }
      }
    }
    std::sort(expected.begin(), expected.end());
    const auto all1 = one.execute([&] { return world.collide_all(); });
    const auto all3 = three.execute([&] { return world.collide_all(); });
    ASSERT_EQ(pairs_of(all1), expected) << "frame " << frame;
    ASSERT_EQ(pairs_of(all3), expected) << "frame " << frame;
    for (std::size_t k = 0; k < all1.size(); ++k) {
      ASSERT_EQ(all1[k].contacts.size(), all3[k].contacts.size());
      EXPECT_EQ(all1[k].contacts[0].triangle_a, all3[k].contacts[0].triangle_a);
      EXPECT_EQ(all1[k].contacts[0].triangle_b, all3[k].contacts[0].triangle_b);
    }
    const auto cand1 = one.execute([&] { return world.candidate_pairs(0.05); });
    const auto cand3 = three.execute([&] { return world.candidate_pairs(0.05); });
    ASSERT_EQ(cand1, cand3);
    for (const ObjectPair& p : expected)
      ASSERT_TRUE(std::binary_search(cand1.begin(), cand1.end(), p));
    colliding_seen += expected.size();
  }
  EXPECT_GT(colliding_seen, 100u);  // not vacuous
}

}  // namespace
}  // namespace antcd
