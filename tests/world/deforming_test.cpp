// Deforming objects in the World (World::set_vertices) and per-object self-collision
// (ObjectOptions::self_collision): frame after frame, a World whose sheet is deformed in place must
// answer every query exactly as a World built afresh from the moved mesh; its self pairs must be
// antcd::self_intersections of the moved mesh; bad input must throw and change nothing.
#include <antcd/self.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "self/self_meshes.hpp"

namespace antcd {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

// A 2 x 2 sheet of nx x ny quads about the origin, rippled by a wave that travels with `t` and
// sagging in the middle: at t = 0 it is flat.
Mesh rippled_sheet(int nx, int ny, Scalar t) {
  return test::grid_sheet(nx, ny, [=](int i, int j) {
    const Scalar x = 2.0 * i / nx - 1;
    const Scalar y = 2.0 * j / ny - 1;
    const Scalar z =
        t * (0.25 * std::sin(std::numbers::pi * (1.5 * x + y + 2 * t)) - 0.3 * (1 - x * x));
    return Vec3(x, y, z);
  });
}

// The sheet's vertices blended from flat (s = 0) to test::looped_sheet (s = 1), which passes
// through itself.
Mesh looping_sheet(int nx, int ny, Scalar s) {
  const Mesh flat = test::grid_sheet(
      nx, ny, [=](int i, int j) { return Vec3(-1.5 + 3.0 * i / nx, Scalar(j) / ny, 0); });
  Mesh loop = test::looped_sheet(nx, ny);
  for (std::size_t v = 0; v < loop.vertices.size(); ++v) {
    loop.vertices[v] = (1 - s) * flat.vertices[v] + s * loop.vertices[v];
  }
  return loop;
}

Transform at(const Vec3& t) {
  Transform p;
  p.translation = t;
  return p;
}

// One object of a test world: a shared model (or the deforming sheet: model null), pose, options.
struct Spec {
  ModelPtr model;
  Transform pose;
  ObjectOptions options;
};

// Sorted contacts of one pair, as tuples that compare exactly.
using ContactKey = std::tuple<std::uint32_t, std::uint32_t, Scalar, Scalar, Scalar, Scalar>;
std::vector<ContactKey> keys(const std::vector<Contact>& contacts) {
  std::vector<ContactKey> out;
  for (const Contact& c : contacts) {
    out.emplace_back(c.triangle_a, c.triangle_b, c.point.x(), c.point.y(), c.point.z(), c.distance);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Every query of `got` against `want` (a World built from the moved mesh with the same objects in
// the same order, so with the same ids). Contacts are compared as sets: their order within a pair
// is the traversal's, which differs between a refitted and a rebuilt hierarchy.
void expect_same_answers(const World& got, const World& want, ObjectId sheet,
                         const std::string& frame) {
  SCOPED_TRACE(frame);
  ASSERT_EQ(got.objects(), want.objects());
  for (const Scalar delta : {0.0, 0.05}) {
    CollisionRequest all;
    all.all_contacts = true;
    all.delta = delta;
    const std::vector<PairContacts> g = got.collide_all(all);
    const std::vector<PairContacts> w = want.collide_all(all);
    ASSERT_EQ(g.size(), w.size()) << "delta " << delta;
    for (std::size_t k = 0; k < g.size(); ++k) {
      EXPECT_EQ(g[k].a, w[k].a);
      EXPECT_EQ(g[k].b, w[k].b);
      EXPECT_EQ(keys(g[k].contacts), keys(w[k].contacts)) << "pair " << k << " delta " << delta;
      EXPECT_EQ(g[k].self_pairs, w[k].self_pairs) << "pair " << k << " delta " << delta;
    }
    CollisionRequest boolean;
    boolean.delta = delta;
    const std::vector<PairContacts> gb = got.collide_all(boolean);
    const std::vector<PairContacts> wb = want.collide_all(boolean);
    ASSERT_EQ(gb.size(), wb.size());
    for (std::size_t k = 0; k < gb.size(); ++k) {
      EXPECT_EQ(std::tie(gb[k].a, gb[k].b), std::tie(wb[k].a, wb[k].b));
      EXPECT_EQ(gb[k].contacts.size() + gb[k].self_pairs.size(), 1u);
    }
    EXPECT_EQ(got.pairs_within(delta), want.pairs_within(delta));
    const std::vector<ObjectContacts> go = got.collide_object(sheet, all);
    const std::vector<ObjectContacts> wo = want.collide_object(sheet, all);
    ASSERT_EQ(go.size(), wo.size());
    for (std::size_t k = 0; k < go.size(); ++k) {
      EXPECT_EQ(go[k].object, wo[k].object);
      EXPECT_EQ(keys(go[k].contacts), keys(wo[k].contacts));
    }
  }
  const std::optional<NearestPair> gn = got.nearest_object(sheet);
  const std::optional<NearestPair> wn = want.nearest_object(sheet);
  ASSERT_EQ(gn.has_value(), wn.has_value());
  if (gn) {
    EXPECT_EQ(gn->b, wn->b);
    EXPECT_EQ(gn->result.distance, wn->result.distance);
  }
  for (int k = 0; k < 12; ++k) {
    const Ray ray{Vec3(-1.3 + 0.21 * k, 0.17 * k - 1, 3), Vec3(0.05, 0.02, -1)};
    const std::vector<RayHit> gr = got.raycast_all(ray);
    const std::vector<RayHit> wr = want.raycast_all(ray);
    ASSERT_EQ(gr.size(), wr.size()) << "ray " << k;
    for (std::size_t h = 0; h < gr.size(); ++h) {
      EXPECT_EQ(std::tie(gr[h].object, gr[h].triangle, gr[h].distance),
                std::tie(wr[h].object, wr[h].triangle, wr[h].distance));
    }
  }
}

// The rigid objects around the sheet: one sphere model shared by three objects, one box model by
// two; the sheet's model is also given (rigid) to a second object, which must never see the
// deformation.
std::vector<Spec> rigid_objects(const ModelPtr& sheet_model) {
  const auto sphere = std::make_shared<const Model>(make_sphere(0.3, 16, 8));
  const auto box = std::make_shared<const Model>(make_box(Vec3(0.25, 0.4, 0.1), 2));
  return {{sphere, at(Vec3(-0.6, -0.3, -0.1)), {}}, {box, at(Vec3(0.5, 0.4, 0.05)), {}},
          {sphere, at(Vec3(0.1, 0.6, -0.35)), {}},  {sheet_model, at(Vec3(0, 0, -3)), {}},
          {box, at(Vec3(-0.2, 0.1, 0.2)), {}},      {sphere, at(Vec3(0.8, -0.7, -0.2)), {}}};
}

void deform_frame_by_frame(double rebuild_above) {
  constexpr int kN = 24;
  const Mesh start = rippled_sheet(kN, kN, 0);
  const auto original = std::make_shared<const Model>(start);
  const std::vector<Spec> rigid = rigid_objects(original);
  ObjectOptions sheet_options;
  sheet_options.name = "sheet";
  sheet_options.rebuild_above = rebuild_above;
  const Transform sheet_pose = at(Vec3(0.05, -0.02, 0.01));
  // The sheet between the rigid objects (slot 3), so its pairs go both ways in id order.
  const auto populate = [&](World& world, const ModelPtr& sheet_model) {
    ObjectId sheet;
    for (std::size_t k = 0; k < rigid.size(); ++k) {
      if (k == 3) sheet = world.add(sheet_model, sheet_pose, sheet_options);
      world.add(rigid[k].model, rigid[k].pose, rigid[k].options);
    }
    return sheet;
  };
  World world;
  const ObjectId sheet = populate(world, original);
  std::size_t pairs_seen = 0;
  bool rebuilt = false;
  for (int frame = 1; frame <= 12; ++frame) {
    const Mesh moved = rippled_sheet(kN, kN, 0.1 * frame);
    world.set_vertices(sheet, moved.vertices);
    ASSERT_EQ(world.model(sheet).mesh().vertices, moved.vertices);
    rebuilt = rebuilt || world.model(sheet).refit_growth() == 1.0;
    World fresh;
    ASSERT_EQ(populate(fresh, std::make_shared<const Model>(moved)), sheet);
    expect_same_answers(world, fresh, sheet, "frame " + std::to_string(frame));
    pairs_seen += world.collide_all().size();
  }
  EXPECT_GT(pairs_seen, 12u) << "the sheet touches nothing: the test would be trivial";
  // The shared Model was never changed: the rigid copy of the sheet still has the flat mesh.
  EXPECT_EQ(original->mesh().vertices, start.vertices);
  if (rebuild_above > 0) {
    EXPECT_TRUE(rebuilt) << "the rebuild rule never fired";
  }
}

TEST(WorldDeforming, SheetFrameByFrameEqualsWorldRebuiltFromMovedMesh) { deform_frame_by_frame(0); }

TEST(WorldDeforming, SheetWithRebuildRuleEqualsWorldRebuiltFromMovedMesh) {
  deform_frame_by_frame(1.02);
}

TEST(WorldDeforming, PrivateCopyOnFirstSetVerticesAndHeldPointersNeverChange) {
  const Mesh start = rippled_sheet(10, 10, 0);
  const auto original = std::make_shared<const Model>(start);
  World world;
  const ObjectId a = world.add(original, Transform{});
  const ObjectId b = world.add(original, at(Vec3(0, 0, 2)));
  const std::size_t rigid_bytes = world.memory_bytes();
  EXPECT_EQ(world.model_ptr(a), original);

  const Mesh f1 = rippled_sheet(10, 10, 0.5);
  world.set_vertices(a, f1.vertices);
  EXPECT_NE(world.model_ptr(a), original) << "the shared Model must not be refitted";
  EXPECT_EQ(world.model_ptr(b), original);
  EXPECT_EQ(original->mesh().vertices, start.vertices);
  EXPECT_EQ(world.model(a).mesh().vertices, f1.vertices);
  // Memory: one private Model (what the shared one costs), counted once. (The broad-phase tree's
  // own storage may change by some bytes when the object's leaf moves, hence the slack, a quarter
  // of the copy: counting the copy twice or not at all fails.)
  const auto copy_bytes = [&] { return sizeof(Model) + world.model(a).stats().memory_bytes; };
  EXPECT_EQ(world.model(a).stats().memory_bytes, original->stats().memory_bytes);
  const auto expect_one_copy = [&] {
    const double extra = double(world.memory_bytes()) - double(rigid_bytes);
    EXPECT_NEAR(extra, double(copy_bytes()), double(copy_bytes()) / 4);
  };
  EXPECT_EQ(world.memory_bytes(), rigid_bytes + copy_bytes());

  // Refitted in place while nothing else holds the private copy...
  const Model* before = &world.model(a);
  const Mesh f2 = rippled_sheet(10, 10, 0.7);
  world.set_vertices(a, f2.vertices);
  EXPECT_EQ(&world.model(a), before);
  expect_one_copy();

  // ...copied again while a model_ptr() of it is held, so the holder's Model never changes.
  const ModelPtr held = world.model_ptr(a);
  const Mesh f3 = rippled_sheet(10, 10, 0.9);
  world.set_vertices(a, f3.vertices);
  EXPECT_NE(world.model_ptr(a), held);
  EXPECT_EQ(held->mesh().vertices, f2.vertices);
  EXPECT_EQ(world.model(a).mesh().vertices, f3.vertices);
  expect_one_copy();

  // The object's bounds follow its mesh: moved far up, it leaves b's neighbourhood and comes back.
  Mesh up = f3;
  for (Vec3& v : up.vertices) v.z() += 10;
  world.set_vertices(a, up.vertices);
  EXPECT_TRUE(world.collide_all(CollisionRequest{0.5}).empty());
  Mesh near_b = f3;
  for (Vec3& v : near_b.vertices) v.z() += 2;  // onto b (the same sheet at z + 2)
  world.set_vertices(a, near_b.vertices);
  ASSERT_EQ(world.collide_all().size(), 1u);
  EXPECT_EQ(world.collide_all()[0].a, a);
  EXPECT_EQ(world.collide_all()[0].b, b);

  // Removing the object frees its private copy.
  world.remove(a);
  EXPECT_LT(world.memory_bytes(), rigid_bytes + sizeof(Model) + original->stats().memory_bytes);
}

// Self pairs, frame by frame while the sheet curls from flat into a loop through itself: (id, id)
// with self_intersections' pairs, sorted with the other pairs; none for an object without the
// option; none in pairs_within.
TEST(WorldDeforming, SelfPairsEqualSelfIntersectionsOfTheMovedMesh) {
  constexpr int kNx = 60;
  constexpr int kNy = 8;
  const auto flat = std::make_shared<const Model>(looping_sheet(kNx, kNy, 0));
  const auto sphere = std::make_shared<const Model>(make_sphere(0.2, 12, 6));
  ObjectOptions selfish;
  selfish.name = "curling";
  selfish.self_collision = true;
  const auto populate = [&](World& world, const ModelPtr& curling, const ModelPtr& plain) {
    world.add(sphere, at(Vec3(-1.4, 0.5, 0)));  // slot 0, touching the curling sheet's end
    const ObjectId c = world.add(curling, Transform{}, selfish);
    world.add(sphere, at(Vec3(0, 0.5, 0.1)));  // slot 2, touching it while it is flat-ish
    const ObjectId p = world.add(plain, at(Vec3(0, 5, 0)));  // curls too, without the option
    return std::pair{c, p};
  };
  World world;
  const auto [curling, plain] = populate(world, flat, flat);
  std::size_t self_frames = 0;
  for (int frame = 0; frame <= 10; ++frame) {
    const Mesh moved = looping_sheet(kNx, kNy, 0.1 * frame);
    world.set_vertices(curling, moved.vertices);
    world.set_vertices(plain, moved.vertices);
    const auto moved_model = std::make_shared<const Model>(moved);
    World fresh;
    populate(fresh, moved_model, moved_model);
    expect_same_answers(world, fresh, curling, "curl frame " + std::to_string(frame));

    const SelfIntersectionResult expected = self_intersections(Model(moved));
    CollisionRequest all;
    all.all_contacts = true;
    const std::vector<PairContacts> pairs = world.collide_all(all);
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
      return std::tie(x.a, x.b) < std::tie(y.a, y.b);
    }));
    std::vector<ObjectId> self_ids;
    for (const PairContacts& p : pairs) {
      if (p.a != p.b) {
        EXPECT_TRUE(p.self_pairs.empty());
        continue;
      }
      self_ids.push_back(p.a);
      EXPECT_TRUE(p.contacts.empty());
      EXPECT_EQ(p.self_pairs, expected.pairs) << "frame " << frame;
    }
    if (expected.intersecting) {
      ++self_frames;
      EXPECT_EQ(self_ids, std::vector<ObjectId>{curling}) << "frame " << frame;
      // Boolean query: the first pair self_intersections' first-only mode finds.
      SelfIntersectionRequest first;
      first.first_only = true;
      const SelfIntersectionResult one = self_intersections(world.model(curling), first);
      bool found = false;
      for (const PairContacts& p : world.collide_all()) {
        if (p.a != curling || p.b != curling) continue;
        found = true;
        EXPECT_EQ(p.self_pairs, one.pairs);
      }
      EXPECT_TRUE(found);
      // max_contacts keeps the first pairs of the sorted list.
      CollisionRequest capped = all;
      capped.max_contacts = 3;
      for (const PairContacts& p : world.collide_all(capped)) {
        if (p.a != p.b) continue;
        const std::size_t n = std::min<std::size_t>(3, expected.pairs.size());
        EXPECT_EQ(p.self_pairs, std::vector(expected.pairs.begin(), expected.pairs.begin() + n));
      }
      for (const ObjectPair& p : world.pairs_within(0.01)) EXPECT_NE(p.a, p.b);
    } else {
      EXPECT_TRUE(self_ids.empty()) << "frame " << frame;
    }
  }
  EXPECT_GT(self_frames, 2u) << "the sheet never passes through itself: the test would be trivial";
  EXPECT_LT(self_frames, 11u) << "the sheet intersects itself from the start";
}

// Every bad argument throws ArgumentError naming it, and leaves the World as it was.
TEST(WorldDeforming, BadInputThrowsAndChangesNothing) {
  // A sheet plus a separate zero-area triangle (three collinear vertices), left out of the
  // hierarchy at build time.
  Mesh mesh = rippled_sheet(6, 6, 0);
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), {Vec3(0, 0, 1), Vec3(0.5, 0, 1), Vec3(1, 0, 1)});
  mesh.triangles.push_back({base, base + 1, base + 2});
  const auto model = std::make_shared<const Model>(mesh);
  const auto sphere = std::make_shared<const Model>(make_sphere(0.4, 12, 6));
  World world;
  ObjectOptions named;
  named.name = "veneer";
  named.self_collision = true;
  const ObjectId sheet = world.add(model, Transform{}, named);
  world.add(sphere, at(Vec3(0.2, 0.1, 0)));
  const ObjectId gone = world.add(sphere, at(Vec3(5, 0, 0)));
  world.remove(gone);
  ObjectOptions bad_rule = named;
  bad_rule.rebuild_above = -0.5;
  try {
    (void)world.add(model, Transform{}, bad_rule);
    FAIL() << "a negative rebuild_above must throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("World::add: options.rebuild_above of object 'veneer' "
                                         "must be >= 0 (or +inf), got -0.5"),
              std::string::npos)
        << e.what();
  }

  const auto snapshot = [&] {
    CollisionRequest all;
    all.all_contacts = true;
    // memory_bytes() counts the answers collide_all keeps for unchanged pairs (world.hpp,
    // "Unchanged pairs"), which the first calls after a change fill in: settle them first.
    for (int k = 0; k < 2; ++k) (void)world.collide_all(all);
    std::vector<std::tuple<ObjectId, ObjectId, std::vector<ContactKey>>> out;
    for (const PairContacts& p : world.collide_all(all))
      out.emplace_back(p.a, p.b, keys(p.contacts));
    // The Model's address, not a model_ptr(): holding one would make set_vertices copy.
    return std::tuple(world.model(sheet).mesh().vertices, world.memory_bytes(), out,
                      &world.model(sheet));
  };
  const auto expect_throw = [&](ObjectId id, const std::vector<Vec3>& v,
                                const std::vector<std::string>& words) {
    const auto before = snapshot();
    try {
      world.set_vertices(id, v);
      ADD_FAILURE() << "no throw";
    } catch (const ArgumentError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("World::set_vertices"), std::string::npos) << what;
      for (const std::string& w : words) EXPECT_NE(what.find(w), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    EXPECT_EQ(snapshot(), before);
  };
  ASSERT_FALSE(world.collide_all().empty()) << "the sphere should touch the sheet";

  const std::vector<Vec3> good = mesh.vertices;
  for (int round = 0; round < 2; ++round) {  // the shared Model, then the private copy
    SCOPED_TRACE(round);
    expect_throw(gone, good, {"id", "not an object"});
    expect_throw(ObjectId{}, good, {"id"});
    std::vector<Vec3> short_list(good.begin(), good.end() - 1);
    expect_throw(sheet, short_list, {"vertices", "'veneer'", std::to_string(good.size() - 1)});
    expect_throw(sheet, {}, {"vertices", "got 0"});
    std::vector<Vec3> nan = good;
    nan[7].y() = std::numeric_limits<Scalar>::quiet_NaN();
    expect_throw(sheet, nan, {"vertices", "vertex 7", "not finite"});
    std::vector<Vec3> inf = good;
    inf.back().x() = std::numeric_limits<Scalar>::infinity();
    expect_throw(sheet, inf, {"vertex " + std::to_string(good.size() - 1)});
    std::vector<Vec3> gains_area = good;
    gains_area[base + 1].z() += 0.5;  // the left-out triangle gets an area
    expect_throw(sheet, gains_area, {"vertices", "'veneer'", "triangle"});
    world.set_vertices(sheet, good);  // a valid call: the next round meets the private copy
  }
  ObjectOptions bad;
  bad.rebuild_above = -1;
  EXPECT_THROW(world.add(sphere, Transform{}, bad), ArgumentError);
  bad.rebuild_above = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(world.add(sphere, Transform{}, bad), ArgumentError);
  EXPECT_EQ(world.size(), 2u);
}

}  // namespace
}  // namespace antcd
