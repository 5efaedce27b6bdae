// World's nearest queries against brute force: on seeded random worlds (closed and open meshes,
// groups, masks, ignored pairs, removals), each answer must be the pair of least (distance, a, b)
// that distance() on every admitted pair gives, with the same distance to the last bit.
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>
#include <antcd/world.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

#include "support/test_support.hpp"

namespace antcd {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

// Closed meshes and one open one (a bent strip of two triangles).
std::vector<ModelPtr> models() {
  Mesh strip;
  strip.vertices = {Vec3(-0.4, -0.3, 0), Vec3(0.4, -0.3, 0.1), Vec3(0.4, 0.3, 0),
                    Vec3(-0.4, 0.3, 0.2)};
  strip.triangles = {{0, 1, 2}, {0, 2, 3}};
  return {std::make_shared<const Model>(make_sphere(0.4, 10, 5)),
          std::make_shared<const Model>(make_box(Vec3(0.5, 0.2, 0.3), 1)),
          std::make_shared<const Model>(make_torus(0.4, 0.12, 12, 6)),
          std::make_shared<const Model>(std::move(strip))};
}

// The least (distance, a, b) over `pairs` of (a, model a, pose a, b, model b, pose b).
struct Candidate {
  ObjectId a;
  const Model* ma;
  Transform pa;
  ObjectId b;
  const Model* mb;
  Transform pb;
};

std::optional<NearestPair> brute_force(const std::vector<Candidate>& pairs, bool signed_distance) {
  std::optional<NearestPair> best;
  for (const Candidate& c : pairs) {
    DistanceRequest request;
    const DistanceResult r = signed_distance && c.ma->is_closed() && c.mb->is_closed()
                                 ? antcd::signed_distance(*c.ma, c.pa, *c.mb, c.pb, request)
                                 : distance(*c.ma, c.pa, *c.mb, c.pb, request);
    if (!best ||
        std::tie(r.distance, c.a, c.b) < std::tie(best->result.distance, best->a, best->b)) {
      best = NearestPair{c.a, c.b, r};
    }
  }
  return best;
}

void expect_same(const std::optional<NearestPair>& got, const std::optional<NearestPair>& want) {
  ASSERT_EQ(got.has_value(), want.has_value());
  if (!want) return;
  EXPECT_EQ(got->a, want->a);
  EXPECT_EQ(got->b, want->b);
  EXPECT_EQ(got->result.distance, want->result.distance);
  EXPECT_EQ(got->result.intersecting, want->result.intersecting);
  EXPECT_FALSE(got->result.beyond_upper_bound);
}

bool filters_admit(const World& w, ObjectId a, const World& v, ObjectId b) {
  const ObjectOptions& x = w.options(a);
  const ObjectOptions& y = v.options(b);
  return (x.group & y.mask) != 0 && (y.group & x.mask) != 0;
}

// A world of n objects in a cube of side `side` (dense enough that some overlap), with random
// groups and masks on a third of them, a few ignored pairs and a few removals.
World random_world(std::mt19937_64& rng, int n, Scalar side, const std::vector<ModelPtr>& shapes) {
  World world;
  std::vector<ObjectId> ids;
  for (int i = 0; i < n; ++i) {
    ObjectOptions options;
    if (rng() % 3 == 0) {
      options.group = 1U << (rng() % 3);
      options.mask = static_cast<std::uint32_t>(rng() % 8);
    }
    ids.push_back(
        world.add(shapes[rng() % shapes.size()], test::random_pose(rng, side / 2), options));
  }
  for (int k = 0; k < n / 6; ++k) {
    const std::size_t i = rng() % ids.size();
    world.ignore_pair(ids[i], ids[(i + 1 + rng() % (ids.size() - 1)) % ids.size()]);
  }
  for (int k = 0; k < n / 8; ++k) {
    const ObjectId id = ids[rng() % ids.size()];
    if (world.contains(id)) world.remove(id);
  }
  return world;
}

std::vector<Candidate> internal_pairs(const World& w) {
  std::vector<Candidate> out;
  const std::vector<ObjectId> ids = w.objects();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      if (!w.may_collide(ids[i], ids[j])) continue;
      out.push_back(
          {ids[i], &w.model(ids[i]), w.pose(ids[i]), ids[j], &w.model(ids[j]), w.pose(ids[j])});
    }
  }
  return out;
}

TEST(WorldNearest, MatchesBruteForceOnRandomWorlds) {
  const std::vector<ModelPtr> shapes = models();
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    // Sparse worlds (every pair apart) and dense ones (many overlap, so ties at 0 and signed
    // depths decide).
    const Scalar side = seed % 2 == 0 ? 9.0 : 3.0;
    const World world = random_world(rng, 26, side, shapes);
    const World other = random_world(rng, 9, side, shapes);
    for (const bool signed_distance : {false, true}) {
      SCOPED_TRACE(signed_distance);
      const NearestRequest request{signed_distance};
      expect_same(world.nearest_pair(request), brute_force(internal_pairs(world), signed_distance));

      const std::vector<ObjectId> ids = world.objects();
      for (std::size_t k = 0; k < ids.size(); k += 5) {
        std::vector<Candidate> pairs;
        for (const ObjectId j : ids) {
          if (j == ids[k] || !world.may_collide(ids[k], j)) continue;
          pairs.push_back({ids[k], &world.model(ids[k]), world.pose(ids[k]), j, &world.model(j),
                           world.pose(j)});
        }
        expect_same(world.nearest_object(ids[k], request), brute_force(pairs, signed_distance));
      }

      const Model& probe = *shapes[seed % shapes.size()];
      const Transform pose = test::random_pose(rng, side / 2);
      const QueryFilter filter{2, 5};
      std::vector<Candidate> pairs;
      for (const ObjectId j : ids) {
        const ObjectOptions& o = world.options(j);
        if ((filter.group & o.mask) == 0 || (o.group & filter.mask) == 0) continue;
        pairs.push_back({j, &world.model(j), world.pose(j), ObjectId{}, &probe, pose});
      }
      expect_same(world.nearest_to(probe, pose, request, filter),
                  brute_force(pairs, signed_distance));

      for (const World* v : {&other, &world}) {
        std::vector<Candidate> across;
        for (const ObjectId i : ids) {
          for (const ObjectId j : v->objects()) {
            if (!filters_admit(world, i, *v, j)) continue;
            across.push_back({i, &world.model(i), world.pose(i), j, &v->model(j), v->pose(j)});
          }
        }
        expect_same(world.nearest_pair(*v, request), brute_force(across, signed_distance));
      }
    }
  }
}

// Two overlapping pairs of solids: the shallow one has the smaller ids and is found first, the
// deeper one must still win (a pruning at gap 0 once a negative distance is known would lose it).
TEST(WorldNearest, SignedDistanceFindsTheDeepestOverlap) {
  const auto ball = std::make_shared<const Model>(make_sphere(1.0, 24, 12));
  World world;
  const auto at = [](Scalar x) {
    return Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0, 0));
  };
  world.add(ball, at(0));
  world.add(ball, at(1.95));  // depth about 0.05
  const ObjectId c = world.add(ball, at(10));
  const ObjectId d = world.add(ball, at(11.4));  // depth about 0.6
  const std::optional<NearestPair> best = world.nearest_pair(NearestRequest{true});
  ASSERT_TRUE(best);
  EXPECT_EQ(best->a, c);
  EXPECT_EQ(best->b, d);
  EXPECT_LT(best->result.distance, -0.5);
  // Surface distances: both pairs intersect (0); the smaller ids win the tie.
  const std::optional<NearestPair> surface = world.nearest_pair();
  ASSERT_TRUE(surface);
  EXPECT_EQ(surface->a.slot, 0U);
  EXPECT_EQ(surface->result.distance, 0);
  EXPECT_TRUE(surface->result.intersecting);
}

TEST(WorldNearest, NoPairAndBadArguments) {
  const auto ball = std::make_shared<const Model>(make_sphere(1.0, 8, 4));
  World world;
  EXPECT_FALSE(world.nearest_pair());
  EXPECT_FALSE(world.nearest_to(*ball, Transform::identity()));
  EXPECT_FALSE(world.nearest_pair(world));
  const ObjectId a = world.add(ball, Transform::identity());
  EXPECT_FALSE(world.nearest_pair());
  EXPECT_FALSE(world.nearest_object(a));
  // The world against itself: the object meets itself.
  const std::optional<NearestPair> self = world.nearest_pair(world);
  ASSERT_TRUE(self);
  EXPECT_EQ(self->a, a);
  EXPECT_EQ(self->b, a);
  EXPECT_EQ(self->result.distance, 0);
  world.remove(a);
  EXPECT_THROW((void)world.nearest_object(a), ArgumentError);
  Transform bad = Transform::identity();
  bad.translation.x() = std::numeric_limits<Scalar>::quiet_NaN();
  EXPECT_THROW((void)world.nearest_to(*ball, bad), ArgumentError);
}

}  // namespace
}  // namespace antcd
