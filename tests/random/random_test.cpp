// Random collision detection (include/antcd/random.hpp): feature spaces, the five searches, stop
// criteria, determinism. Ground truth is computed here from the meshes themselves, independently
// of the library's feature code.
#include <antcd/collide.hpp>
#include <antcd/error.hpp>
#include <antcd/load.hpp>
#include <antcd/random.hpp>

#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace antcd {
namespace {

using TrianglePair = std::pair<std::uint32_t, std::uint32_t>;

constexpr Method kAllMethods[] = {Method::Aco, Method::Maco,       Method::Pso,
                                  Method::Ga,  Method::Exhaustive, Method::Grid};
constexpr Method kStochastic[] = {Method::Aco, Method::Maco, Method::Pso, Method::Ga};

struct Scenario {
  std::string name;
  std::shared_ptr<const Model> a;
  std::shared_ptr<const Model> b;
  Transform pose_a;
  Transform pose_b;
};

std::shared_ptr<const Model> load_model(const std::string& relative) {
  return std::make_shared<const Model>(load_mesh(test::assimp_model(relative)), BuildOptions{},
                                       relative);
}

std::shared_ptr<const Model> shape(Mesh mesh) {
  return std::make_shared<const Model>(std::move(mesh));
}

/// Model pairs at poses where their surfaces meet, from real meshes (assimp test models) and
/// generated ones. Some overlap deeply, some only graze.
std::vector<Scenario> touching_scenarios() {
  const auto wuson = load_model("OBJ/WusonOBJ.obj");
  const auto spider = load_model("OBJ/spider.obj");
  std::vector<Scenario> out;
  // Wuson against a copy turned a quarter about its vertical axis and pushed sideways.
  out.push_back({"wuson-wuson", wuson, wuson, Transform::identity(),
                 Transform::from_axis_angle(Vec3::UnitY(), 1.5708, Vec3(0.35, 0.05, 0.4))});
  // Spider against a copy tilted and shifted by about a leg's length.
  out.push_back({"spider-spider", spider, spider, Transform::identity(),
                 Transform::from_axis_angle(Vec3(1, 1, 0), 0.6, Vec3(30, 5, -20))});
  // Wuson standing on a floor slab (its lowest point just inside the slab's top face): grazing.
  const auto slab = shape(make_box(Vec3(1.0, 0.05, 2.0), 24));
  out.push_back({"wuson-on-slab", wuson, slab, Transform::identity(),
                 Transform::from_axis_angle(Vec3::UnitY(), 0.2, Vec3(0, -0.05 + 0.002, 0))});
  // A torus threaded on a cylinder, touching its side.
  const auto torus = shape(make_torus(1.0, 0.25, 64, 24));
  const auto rod = shape(make_cylinder(0.76, 3.0, 64, 8));
  out.push_back({"torus-rod", torus, rod, Transform::identity(),
                 Transform::from_axis_angle(Vec3::UnitX(), 0.1, Vec3(0.02, 0, 0))});
  // A sphere pressed slightly into a box face: a small contact patch.
  const auto ball = shape(make_sphere(0.5, 48, 24));
  const auto box = shape(make_box(Vec3(1, 1, 1), 16));
  out.push_back({"ball-on-box", ball, box,
                 Transform::from_axis_angle(Vec3(0.3, 1, 0.2), 0.7, Vec3(0.1, -0.2, 1.49)),
                 Transform::identity()});
  // Two balls that barely kiss (overlap 0.002 along x): only a handful of colliding pairs.
  const auto coarse = shape(make_sphere(0.5, 40, 20));
  out.push_back({"ball-kiss", ball, coarse, Transform::identity(),
                 Transform::from_axis_angle(Vec3(1, 2, 3), 0.4, Vec3(0.998, 0.0, 0.0))});
  return out;
}

/// The space's colliding cells by plain enumeration (the test's own loop, not the library's).
std::set<std::pair<std::uint32_t, std::uint32_t>> colliding_cells(const FeatureSpace& space,
                                                                  Scalar delta) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
  for (std::uint32_t i = 0; i < space.a.size(); ++i) {
    for (std::uint32_t j = 0; j < space.b.size(); ++j) {
      if ((space.a.centroid(i) - space.b.centroid(j)).squaredNorm() <= delta * delta) {
        cells.emplace(i, j);
      }
    }
  }
  return cells;
}

FeatureSpace build(const Scenario& s, std::uint32_t samples = 1000, std::uint64_t seed = 1,
                   FeatureOrder order = FeatureOrder::Leaf) {
  SamplingOptions options;
  options.samples_per_side = samples;
  options.order = order;
  return build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, options, seed);
}

SearchRequest request_for(Method method, std::uint64_t seed) {
  SearchRequest r;
  r.method = method;
  r.seed = seed;
  return r;
}

/// Everything observable about a search, for equality checks.
struct Fingerprint {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> hits;
  std::uint64_t evaluations;
  std::uint32_t iterations;
  Scalar best_distance;
  std::uint32_t best_i, best_j;
  bool operator==(const Fingerprint&) const = default;
};

Fingerprint fingerprint(const SearchResult& r) {
  Fingerprint f{{}, r.evaluations, r.iterations, r.best_distance, r.best.i, r.best.j};
  for (const FeaturePair& h : r.hits) f.hits.emplace_back(h.i, h.j);
  return f;
}

// ---- Feature spaces ----

/// Every contact collide() reports (all contacts, at delta), as sorted triangle pairs.
std::vector<TrianglePair> contacts_of(const Scenario& s, Scalar delta) {
  CollisionRequest cr;
  cr.delta = delta;
  cr.all_contacts = true;
  std::vector<TrianglePair> out;
  for (const Contact& c : collide(*s.a, s.pose_a, *s.b, s.pose_b, cr).contacts) {
    out.emplace_back(c.triangle_a, c.triangle_b);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The flow of section 4 loses nothing: with every candidate taken, the space built from the leaf
// pairs of the preliminary detection at delta holds every contact collide() reports, and the
// exhaustive scan in the witness verdict finds exactly those (the early negative never misses a
// pair whose leaves overlap; the witness test is collide()'s).
TEST(RandomFeatures, ExhaustiveWitnessesEqualEveryContactOfCollide) {
  for (const Scenario& s : touching_scenarios()) {
    for (const Scalar delta : {0.0, 0.01}) {
      SCOPED_TRACE(s.name + " delta " + std::to_string(delta));
      SamplingOptions options;
      options.samples_per_side = 1u << 30;
      options.delta = delta;
      const FeatureSpace space = build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, options, 1);
      ASSERT_FALSE(space.empty());
      EXPECT_TRUE(space.complete);
      EXPECT_EQ(space.a.size(), space.candidates_a);
      EXPECT_EQ(space.b.size(), space.candidates_b);
      const std::vector<TrianglePair> truth = contacts_of(s, delta);
      ASSERT_FALSE(truth.empty()) << "scenario must touch";

      for (const Method m : {Method::Exhaustive, Method::Grid}) {
        const SearchResult result = search(space, request_for(m, 0));
        EXPECT_EQ(result.stop, StopReason::Iterations);
        if (m == Method::Exhaustive) {
          EXPECT_EQ(result.evaluations, space.cells());
        } else {
          EXPECT_LT(result.evaluations, space.cells());
        }
        std::vector<TrianglePair> found;
        for (const FeaturePair& h : result.hits) found.emplace_back(h.triangle_a, h.triangle_b);
        std::sort(found.begin(), found.end());
        EXPECT_EQ(found, truth) << method_label(m);
      }
      EXPECT_EQ(count_colliding(space), truth.size());
    }
  }
}

// No leaf pair at delta: the space is empty and nothing is searched.
TEST(RandomFeatures, NoLeafPairMeansAnEmptySpaceAndNoSearch) {
  const Scenario s = touching_scenarios()[4];
  const Transform far = Transform::from_axis_angle(Vec3::UnitX(), 0.0, Vec3(10, 0, 0));
  const FeatureSpace space = build_feature_space(*s.a, s.pose_a, *s.b, far, {}, 1);
  EXPECT_EQ(space.leaf_pairs, 0u);
  EXPECT_TRUE(space.empty());
  const SearchResult r = search(space, request_for(Method::Maco, 1));
  EXPECT_EQ(r.stop, StopReason::EmptySpace);
  EXPECT_EQ(r.evaluations, 0u);
  DetectRequest dr;
  const DetectResult d = random_detect(*s.a, s.pose_a, *s.b, far, dr);
  EXPECT_FALSE(d.colliding);
  EXPECT_TRUE(d.no_leaf_pair);
  EXPECT_EQ(d.search.evaluations, 0u);
}

// Features spread wider than the double range (a model with parts near both ends of it): the
// Morton order's cell arithmetic made a NaN, converted to a cell index (undefined behaviour under
// scripts/sanitize.sh's float-cast-overflow) before it was clamped. Same features either order.
TEST(RandomFeatures, FeaturesSpreadPastTheDoubleRangeAreOrdered) {
  const Scalar far = 1e308;
  Mesh parts;
  for (const Scalar x : {-far, 0.0, far}) {
    const Mesh box = make_box(Vec3(1, 1, 1), 1);
    parts = merge(
        {parts, transformed(box, Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0, 0)))});
  }
  const Model a(parts, {}, "far parts");
  const Transform touching = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(0.5, 0.5, 0));
  std::vector<Vec3> centroids[2];
  for (const FeatureOrder order : {FeatureOrder::Leaf, FeatureOrder::Morton}) {
    SamplingOptions options;
    options.order = order;
    const FeatureSpace space =
        build_feature_space(a, Transform::identity(), a, touching, options, 1);
    ASSERT_GT(space.a.size(), 0u);
    auto& out = centroids[order == FeatureOrder::Morton ? 1 : 0];
    for (std::uint32_t k = 0; k < space.a.size(); ++k) out.push_back(space.a.centroid(k));
    std::sort(out.begin(), out.end(), [](const Vec3& p, const Vec3& q) {
      return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    });
  }
  EXPECT_EQ(centroids[0], centroids[1]);
}

TEST(RandomFeatures, SamplingTakesDistinctTrianglesWithWorldCentroids) {
  const Scenario s = touching_scenarios()[1];  // spider pair: hundreds of candidates per side
  for (const std::uint32_t samples : {20u, 60u, 100000u}) {
    SCOPED_TRACE(samples);
    const FeatureSpace space = build(s, samples, 3);
    ASSERT_GT(space.candidates_a, 100u);
    EXPECT_EQ(space.a.size(), std::min<std::size_t>(samples, space.candidates_a));
    EXPECT_EQ(space.b.size(), std::min<std::size_t>(samples, space.candidates_b));
    for (const auto* side : {&space.a, &space.b}) {
      const Model& model = side == &space.a ? *s.a : *s.b;
      const Transform& pose = side == &space.a ? s.pose_a : s.pose_b;
      std::set<std::uint32_t> seen;
      for (std::uint32_t k = 0; k < side->size(); ++k) {
        const std::uint32_t t = side->triangle[k];
        ASSERT_LT(t, model.mesh().triangles.size());
        EXPECT_TRUE(seen.insert(t).second) << "triangle sampled twice";
        const auto& tri = model.mesh().triangles[t];
        const Vec3 c = pose.apply((model.mesh().vertices[tri[0]] + model.mesh().vertices[tri[1]] +
                                   model.mesh().vertices[tri[2]]) /
                                  3);
        // Float centroids: within float rounding of the world centroid.
        EXPECT_LT((side->centroid(k) - c).norm(), 1e-6 * (1 + c.norm()));
        // The radius covers every vertex (the reach filter must never reject a contact).
        for (const auto v : tri) {
          EXPECT_LE((pose.apply(model.mesh().vertices[v]) - side->centroid(k)).norm(),
                    static_cast<Scalar>(side->radius[k]));
        }
      }
    }
  }
  // The sampling seed matters when sampling is active, and only then.
  EXPECT_NE(build(s, 100, 1).a.triangle, build(s, 100, 2).a.triangle);
  EXPECT_EQ(build(s, 100, 1).a.triangle, build(s, 100, 1).a.triangle);
  EXPECT_EQ(build(s, 100000, 1).a.triangle, build(s, 100000, 2).a.triangle);
}

// Neighbouring indices are neighbours in space: consecutive features are far closer together
// than features drawn at random, for both orders.
TEST(RandomFeatures, FeatureOrderIsSpatiallyCoherent) {
  for (const Scenario& s : touching_scenarios()) {
    for (const FeatureOrder order : {FeatureOrder::Leaf, FeatureOrder::Morton}) {
      SCOPED_TRACE(s.name + (order == FeatureOrder::Leaf ? " leaf" : " morton"));
      const FeatureSpace space = build(s, 1000, 1, order);
      const FeatureSide& side = space.a;
      if (side.size() < 100) continue;  // a small contact patch: too few features to compare
      double consecutive = 0, random_pairs = 0;
      std::mt19937_64 rng(5);
      std::uniform_int_distribution<std::uint32_t> pick(0, side.size() - 1);
      for (std::uint32_t k = 0; k + 1 < side.size(); ++k) {
        consecutive += (side.centroid(k + 1) - side.centroid(k)).norm();
        random_pairs += (side.centroid(pick(rng)) - side.centroid(pick(rng))).norm();
      }
      EXPECT_LT(consecutive, 0.35 * random_pairs);
    }
  }
}

TEST(RandomFeatures, DefaultDeltaIsTheSumOfMedianFeatureRadii) {
  // A box face split into s x s squares, each cut into two right isosceles triangles with legs
  // L = 2h/s: the farthest vertex is L sqrt(5)/3 from the centroid.
  const Model box(make_box(Vec3(1, 1, 1), 10));
  const Scalar expected = 0.2 * std::sqrt(5.0) / 3;
  EXPECT_NEAR(feature_radius(box), expected, 1e-12);
  const Model small(make_box(Vec3(0.5, 0.5, 0.5), 10));
  EXPECT_NEAR(default_delta(box, small), expected * 1.5, 1e-12);
  const auto wuson = load_model("OBJ/WusonOBJ.obj");
  EXPECT_GT(default_delta(*wuson, *wuson), 0);
}

// What the default threshold promises: two touching triangles, neither larger than its model's
// median, have centroids within default_delta.
TEST(RandomFeatures, DefaultDeltaCoversTouchingTrianglesOfTypicalSize) {
  std::size_t typical = 0;  // contacts where the promise applies, over all scenarios
  for (const Scenario& s : touching_scenarios()) {
    SCOPED_TRACE(s.name);
    const Scalar ra = feature_radius(*s.a);
    const Scalar rb = feature_radius(*s.b);
    const Scalar delta = default_delta(*s.a, *s.b);
    CollisionRequest cr;
    cr.all_contacts = true;
    const CollisionResult contacts = collide(*s.a, s.pose_a, *s.b, s.pose_b, cr);
    ASSERT_TRUE(contacts.colliding);
    auto radius = [](const Mesh& m, std::uint32_t t) {
      const auto& tri = m.triangles[t];
      const Vec3 c = (m.vertices[tri[0]] + m.vertices[tri[1]] + m.vertices[tri[2]]) / 3;
      Scalar r = 0;
      for (const auto v : tri) r = std::max(r, (m.vertices[v] - c).norm());
      return r;
    };
    for (const Contact& c : contacts.contacts) {
      if (radius(s.a->mesh(), c.triangle_a) > ra || radius(s.b->mesh(), c.triangle_b) > rb)
        continue;
      ++typical;
      const auto& ta = s.a->mesh().triangles[c.triangle_a];
      const auto& tb = s.b->mesh().triangles[c.triangle_b];
      const Vec3 ca = s.pose_a.apply((s.a->mesh().vertices[ta[0]] + s.a->mesh().vertices[ta[1]] +
                                      s.a->mesh().vertices[ta[2]]) /
                                     3);
      const Vec3 cb = s.pose_b.apply((s.b->mesh().vertices[tb[0]] + s.b->mesh().vertices[tb[1]] +
                                      s.b->mesh().vertices[tb[2]]) /
                                     3);
      EXPECT_LE((ca - cb).norm(), delta * (1 + 1e-12));
    }
  }
  EXPECT_GT(typical, 100u);
}

// ---- Searches ----

/// Whether collide()'s exact test, at delta, confirms mesh triangles ta and tb at the
/// scenario's poses (in A's frame, as collide() tests).
bool collide_confirms(const Scenario& s, std::uint32_t ta, std::uint32_t tb, Scalar delta) {
  const Transform b_to_a = s.pose_a.inverse() * s.pose_b;
  const Mesh& ma = s.a->mesh();
  const Mesh& mb = s.b->mesh();
  Vec3 va[3], vb[3];
  for (int v = 0; v < 3; ++v) {
    va[v] = ma.vertices[ma.triangles[ta][v]];
    vb[v] = b_to_a.apply(mb.vertices[mb.triangles[tb][v]]);
  }
  return geometry::triangles_within(va[0], va[1], va[2], vb[0], vb[1], vb[2], delta);
}

// Every pair any search reports is a real contact (the witness verdict: collide()'s triangle test
// confirms it, so precision is 1 by construction) or, in the paper's verdict, a centroid pair
// within the threshold; each once, with the right triangles and distance.
TEST(RandomSearch, ReportedPairsAreConfirmedWitnesses) {
  for (const Scenario& s : touching_scenarios()) {
    const FeatureSpace space = build(s, 1000, 7);
    const auto centroid_truth = colliding_cells(space, space.centroid_delta);
    const std::vector<TrianglePair> contacts = contacts_of(s, 0);
    const std::set<TrianglePair> contact_set(contacts.begin(), contacts.end());
    for (const Verdict verdict : {Verdict::Witness, Verdict::PaperCentroid}) {
      for (const Method m : kAllMethods) {
        for (std::uint64_t seed = 0; seed < 2; ++seed) {
          SCOPED_TRACE(s.name + " " + std::string(method_label(m)) + " " +
                       std::string(to_string(verdict)) + " seed " + std::to_string(seed));
          SearchRequest request = request_for(m, seed);
          request.verdict = verdict;
          request.iterations = 20;
          const SearchResult r = search(space, request);
          EXPECT_EQ(r.found, !r.hits.empty());
          std::set<std::pair<std::uint32_t, std::uint32_t>> distinct;
          for (const FeaturePair& h : r.hits) {
            ASSERT_LT(h.i, space.a.size());
            ASSERT_LT(h.j, space.b.size());
            EXPECT_TRUE(distinct.emplace(h.i, h.j).second) << "reported twice";
            EXPECT_EQ(h.triangle_a, space.a.triangle[h.i]);
            EXPECT_EQ(h.triangle_b, space.b.triangle[h.j]);
            EXPECT_NEAR(h.distance, space.distance(h.i, h.j), 1e-6 * (1 + h.distance));
            if (verdict == Verdict::Witness) {
              EXPECT_TRUE(collide_confirms(s, h.triangle_a, h.triangle_b, 0));
              EXPECT_TRUE(contact_set.count({h.triangle_a, h.triangle_b}))
                  << "a witness collide() does not report";
            } else {
              EXPECT_TRUE(centroid_truth.count({h.i, h.j})) << "not within the threshold";
            }
          }
          if (m == Method::Exhaustive) {
            EXPECT_EQ(distinct.size(), count_colliding(space, verdict));
          }
        }
      }
    }
  }
}

// Models farther apart than delta have no colliding feature pair: nothing is ever reported,
// whether the preliminary detection culls everything or leaves a few leaf pairs.
TEST(RandomSearch, SeparatedModelsAreNeverReported) {
  for (const Scenario& touching : touching_scenarios()) {
    const Scalar delta = default_delta(*touching.a, *touching.b);
    const Aabb ba = touching.a->mesh().bounds();
    const Aabb bb = touching.b->mesh().bounds();
    const Scalar size = (ba.extent().norm() + bb.extent().norm());
    for (const Scalar gap : {2.0 * size, 1.5 * delta}) {
      Scenario s = touching;
      s.pose_a = Transform::identity();
      // B placed beyond A along x, its lowest x exactly `gap` past A's highest x.
      s.pose_b = Transform::identity();
      s.pose_b.translation = Vec3(ba.max.x() - bb.min.x() + gap, 0, 0);
      SCOPED_TRACE(s.name + " gap " + std::to_string(gap));
      const FeatureSpace space = build(s);
      if (gap > size) {
        EXPECT_TRUE(space.empty());
      }
      EXPECT_EQ(count_colliding(space), 0u);
      for (const Method m : kAllMethods) {
        SearchRequest r = request_for(m, 11);
        r.iterations = 20;
        const SearchResult res = search(space, r);
        EXPECT_FALSE(res.found) << method_label(m);
        EXPECT_TRUE(res.hits.empty());
        if (space.empty()) {
          EXPECT_EQ(res.stop, StopReason::EmptySpace);
          EXPECT_EQ(res.evaluations, 0u);
        } else {
          EXPECT_GT(res.best_distance, delta);
        }
      }
      EXPECT_FALSE(random_collide(*s.a, s.pose_a, *s.b, s.pose_b).found);
    }
  }
}

// The paper's configuration (m = 60, alpha = beta = 1, N = 100, n = 50) finds a collision on
// every touching pose, with every seed of the suite.
// The thresholds below the default leave as few as one colliding pair in the space.
TEST(RandomSearch, MacoDefaultBudgetFindsACollisionOnEveryTouchingPose) {
  for (const Scenario& s : touching_scenarios()) {
    for (const Scalar factor : {1.0, 0.25, 0.1}) {
      SamplingOptions so;
      so.delta = factor * default_delta(*s.a, *s.b);
      const FeatureSpace space = build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so, 2);
      ASSERT_GT(count_colliding(space), 0u) << s.name << " factor " << factor;
      for (std::uint64_t seed = 0; seed < 20; ++seed) {
        SearchRequest r = request_for(Method::Maco, seed);
        r.stop.first_hit = true;
        const SearchResult res = search(space, r);
        EXPECT_TRUE(res.found) << s.name << " factor " << factor << " seed " << seed;
        EXPECT_EQ(res.stop, StopReason::FirstHit);
        EXPECT_EQ(res.hits.size(), 1u);
        EXPECT_LE(res.iterations, 100u);
      }
    }
  }
}

// Each of the four improvements changes the search when switched off alone, and with all four
// off MACO is exactly ACO.
TEST(RandomSearch, EachMacoSwitchChangesTheSearch) {
  const Scenario s = touching_scenarios()[0];
  const FeatureSpace space = build(s, 600, 1);
  SearchRequest all = request_for(Method::Maco, 42);
  all.iterations = 12;
  const Fingerprint full = fingerprint(search(space, all));
  ASSERT_FALSE(full.hits.empty());
  for (int which = 0; which < 4; ++which) {
    SearchRequest r = all;
    MacoSwitches& sw = r.ant.maco;
    (which == 0   ? sw.adaptive_exponents
     : which == 1 ? sw.adaptive_evaporation
     : which == 2 ? sw.path_heuristic
                  : sw.reward_punishment) = false;
    EXPECT_NE(fingerprint(search(space, r)), full) << "switch " << which + 1 << " is a no-op";
  }
  // The other reading of Eq. 12, the greedy moves of section 3.4 (1), and the start cells.
  SearchRequest corridor = all;
  corridor.ant.maco.heuristic = PathHeuristic::Corridor;
  EXPECT_NE(fingerprint(search(space, corridor)), full) << "Eq. 12 reading is a no-op";
  SearchRequest greedy = all;
  greedy.ant.maco.greedy_moves = true;
  EXPECT_NE(fingerprint(search(space, greedy)), full) << "greedy moves are a no-op";
  SearchRequest uniform = all;
  uniform.ant.start = AntStart::Uniform;
  EXPECT_NE(fingerprint(search(space, uniform)), full) << "start cells are a no-op";
  SearchRequest none = all;
  none.ant.maco = {false, false, false, false};
  SearchRequest aco = all;
  aco.method = Method::Aco;
  EXPECT_EQ(fingerprint(search(space, none)), fingerprint(search(space, aco)));
  // ACO ignores the switches.
  SearchRequest aco_switches = aco;
  aco_switches.ant.maco = {true, true, true, true};
  EXPECT_EQ(fingerprint(search(space, aco_switches)), fingerprint(search(space, aco)));
}

TEST(RandomSearch, SameSeedSameResultDifferentSeedDifferentSearch) {
  const Scenario s = touching_scenarios()[3];
  const FeatureSpace space = build(s, 800, 9);
  for (const Method m : kStochastic) {
    SCOPED_TRACE(std::string(method_label(m)));
    SearchRequest r = request_for(m, 123);
    r.iterations = 30;
    const Fingerprint first = fingerprint(search(space, r));
    EXPECT_EQ(fingerprint(search(space, r)), first);
    r.seed = 124;
    EXPECT_NE(fingerprint(search(space, r)), first);
  }
  // The one-call form is build + search with the request's seed.
  SearchRequest r = request_for(Method::Maco, 5);
  r.iterations = 10;
  SamplingOptions so;
  so.samples_per_side = 300;
  const FeatureSpace space5 = build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so, 5);
  EXPECT_EQ(fingerprint(random_collide(*s.a, s.pose_a, *s.b, s.pose_b, r, so)),
            fingerprint(search(space5, r)));
}

// Concurrent searches on one shared space give the serial answers (no hidden shared state).
TEST(RandomSearch, ConcurrentSearchesMatchSerialOnes) {
  const Scenario s = touching_scenarios()[0];
  const FeatureSpace space = build(s, 500, 1);
  std::vector<SearchRequest> requests;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    SearchRequest r = request_for(kAllMethods[seed % 5], seed);
    r.iterations = 15;
    requests.push_back(r);
  }
  std::vector<Fingerprint> serial, parallel(requests.size());
  for (const SearchRequest& r : requests) serial.push_back(fingerprint(search(space, r)));
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < requests.size(); ++k) {
    threads.emplace_back([&, k] { parallel[k] = fingerprint(search(space, requests[k])); });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(parallel, serial);
}

TEST(RandomSearch, StopCriteria) {
  const Scenario s = touching_scenarios()[0];
  const FeatureSpace space = build(s, 700, 1);
  const std::uint64_t truth = count_colliding(space);
  ASSERT_GT(truth, 20u);
  for (const Method m : kAllMethods) {
    SCOPED_TRACE(std::string(method_label(m)));
    SearchRequest r = request_for(m, 3);
    r.stop.first_hit = true;
    SearchResult res = search(space, r);
    EXPECT_EQ(res.stop, StopReason::FirstHit);
    EXPECT_EQ(res.hits.size(), 1u);

    r = request_for(m, 3);
    r.stop.max_evaluations = 777;
    res = search(space, r);
    EXPECT_EQ(res.evaluations, 777u);
    EXPECT_EQ(res.stop, StopReason::Evaluations);

    r = request_for(m, 3);
    r.iterations = 7;
    res = search(space, r);
    if (m == Method::Exhaustive || m == Method::Grid) {
      EXPECT_EQ(res.iterations, space.a.size());
      if (m == Method::Exhaustive) {
        EXPECT_EQ(res.evaluations, space.cells());
      }
    } else {
      EXPECT_EQ(res.iterations, 7u);
    }
    EXPECT_EQ(res.stop, StopReason::Iterations);

    r = request_for(m, 3);
    r.stop.max_seconds = 1e-9;
    res = search(space, r);
    EXPECT_EQ(res.stop, StopReason::Time);
  }
  // Target share: the search stops exactly when the share is reached, with the truth counted by
  // the search or given.
  for (const Method m : {Method::Exhaustive, Method::Aco, Method::Maco}) {
    SCOPED_TRACE(std::string(method_label(m)));
    SearchRequest r = request_for(m, 3);
    r.iterations = 100000;
    r.stop.target_share = 0.2;
    SearchResult res = search(space, r);
    EXPECT_EQ(res.stop, StopReason::Target);
    EXPECT_EQ(res.hits.size(), static_cast<std::size_t>(std::ceil(0.2 * truth)));
    r.stop.reference_count = 10;
    r.stop.target_share = 0.5;
    res = search(space, r);
    EXPECT_EQ(res.stop, StopReason::Target);
    EXPECT_EQ(res.hits.size(), 5u);
  }
}

// Restarts continue the search with fresh runs: the first run is unchanged, iterations add up,
// hits accumulate. Progress marks record when each share of the truth was reached.
TEST(RandomSearch, RestartsAndProgressMarks) {
  const Scenario s = touching_scenarios()[0];
  const FeatureSpace space = build(s, 700, 1);
  const std::uint64_t truth = count_colliding(space);
  for (const Method m : kStochastic) {
    SCOPED_TRACE(std::string(method_label(m)));
    SearchRequest one = request_for(m, 8);
    one.iterations = 5;
    SearchRequest three = one;
    three.restarts = 2;
    const SearchResult r1 = search(space, one);
    const SearchResult r3 = search(space, three);
    EXPECT_EQ(r1.runs, 1u);
    EXPECT_EQ(r3.runs, 3u);
    EXPECT_EQ(r3.iterations, 15u);
    EXPECT_EQ(r3.stop, StopReason::Iterations);
    EXPECT_GT(r3.evaluations, r1.evaluations);
    ASSERT_GE(r3.hits.size(), r1.hits.size());
    for (std::size_t k = 0; k < r1.hits.size(); ++k) {
      EXPECT_EQ(r3.hits[k].i, r1.hits[k].i);
      EXPECT_EQ(r3.hits[k].j, r1.hits[k].j);
    }
    // Restarts bounded by an evaluation budget.
    SearchRequest budget = one;
    budget.restarts = 1000000;
    budget.stop.max_evaluations = 50000;
    const SearchResult rb = search(space, budget);
    EXPECT_EQ(rb.stop, StopReason::Evaluations);
    EXPECT_EQ(rb.evaluations, 50000u);
  }
  // Marks against the order hits were found in: exhaustive search is row by row, so the k-th hit
  // and the evaluation count at that moment are known exactly.
  SearchRequest ex = request_for(Method::Exhaustive, 0);
  ex.progress_marks = {0.5, 0.1, 1.0};
  const SearchResult full = search(space, ex);
  ASSERT_EQ(full.progress.size(), 3u);
  for (const ProgressMark& mark : full.progress) {
    EXPECT_TRUE(mark.reached);
    EXPECT_EQ(mark.hits, static_cast<std::uint64_t>(std::ceil(mark.share * truth)));
    const FeaturePair& h = full.hits[mark.hits - 1];
    EXPECT_EQ(mark.evaluations, std::uint64_t{h.i} * space.b.size() + h.j + 1);
  }
  EXPECT_LT(full.progress[1].evaluations, full.progress[0].evaluations);
  EXPECT_LE(full.progress[1].seconds, full.progress[0].seconds);
  SearchRequest few = request_for(Method::Maco, 0);
  few.iterations = 2;
  few.progress_marks = {1e-9, 1.0};
  const SearchResult partial = search(space, few);
  EXPECT_EQ(partial.progress[0].hits, 1u);
  EXPECT_EQ(partial.progress[0].reached, partial.found);
  EXPECT_FALSE(partial.progress[1].reached);
}

TEST(RandomSearch, InvalidArgumentsThrow) {
  const Scenario s = touching_scenarios()[4];
  const FeatureSpace space = build(s, 100);
  auto bad = [&](auto edit) {
    SearchRequest r;
    edit(r);
    return r;
  };
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.centroid_delta = std::nan(""); })),
               ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.iterations = 0; })), ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.ant.ants = 0; })), ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.ant.rho = 1.5; })), ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.stop.target_share = 2; })),
               ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) {
                        r.progress_marks = {0.5, 0};
                      })),
               ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) {
                        r.method = Method::Ga;
                        r.ga.population = 1;
                      })),
               ArgumentError);
  SamplingOptions so;
  so.samples_per_side = 0;
  EXPECT_THROW(build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so), ArgumentError);
  so.samples_per_side = 10;
  so.delta = std::nan("");
  EXPECT_THROW(build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so), ArgumentError);
}

// ---- Temporal coherence and the whole flow ----

// A colony's memory carries the last search's witnesses: at the next pose, a search with that
// memory finds at least every remembered witness that is still a contact.
TEST(RandomMemory, WarmStartedSearchFindsTheStillValidWitnesses) {
  std::size_t still_valid = 0;  // over all scenarios
  for (const Scenario& s : touching_scenarios()) {
    SCOPED_TRACE(s.name);
    SamplingOptions options;
    options.samples_per_side = 1u << 30;
    const FeatureSpace first = build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, options, 1);
    SearchRequest r = request_for(Method::Maco, 3);
    r.iterations = 4;
    ColonyMemory memory;
    const SearchResult r1 = search(first, r, &memory);
    ASSERT_TRUE(r1.found);
    ASSERT_FALSE(memory.witnesses.empty());
    EXPECT_GT(memory.iterations, 0u);
    const auto remembered = memory.witnesses;
    // Next frame: B moved a little.
    Scenario moved = s;
    moved.pose_b = Transform::from_axis_angle(Vec3(0, 0, 1), 2e-4, Vec3(1e-4, 0, 0)) * s.pose_b;
    const FeatureSpace next =
        build_feature_space(*moved.a, moved.pose_a, *moved.b, moved.pose_b, options, 2);
    SearchRequest r2 = r;
    r2.seed = 99;
    r2.iterations = 1;
    r2.ant.ants = 1;
    const SearchResult found = search(next, r2, &memory);
    std::set<TrianglePair> hits;
    for (const FeaturePair& h : found.hits) hits.emplace(h.triangle_a, h.triangle_b);
    const auto tris_a = moved.a->leaf_triangles();
    const auto tris_b = moved.b->leaf_triangles();
    for (const auto& [pa, pb] : remembered) {
      const std::uint32_t ta = tris_a[pa], tb = tris_b[pb];
      if (!collide_confirms(moved, ta, tb, 0)) continue;
      ++still_valid;
      EXPECT_TRUE(hits.count({ta, tb})) << "still-valid witness not found again";
    }
  }
  EXPECT_GT(still_valid, 20u);
}

// confirm_witnesses: still-valid witnesses decide at once; a contact that slid to a neighbouring
// triangle is found again by the neighbourhood scan; an invalid one is dropped.
TEST(RandomMemory, ConfirmWitnessesKeepsValidOnesAndScansNeighbours) {
  const Scenario s = touching_scenarios()[3];  // torus on rod: a long contact band
  const std::vector<TrianglePair> contacts = contacts_of(s, 0);
  ASSERT_FALSE(contacts.empty());
  // Leaf positions of one contact.
  const auto tris_a = s.a->leaf_triangles();
  const auto tris_b = s.b->leaf_triangles();
  auto position = [](std::span<const std::uint32_t> tris, std::uint32_t t) {
    return static_cast<std::uint32_t>(std::find(tris.begin(), tris.end(), t) - tris.begin());
  };
  const std::uint32_t pa = position(tris_a, contacts[0].first);
  const std::uint32_t pb = position(tris_b, contacts[0].second);
  ColonyMemory memory;
  memory.witnesses = {{pa, pb}};
  WitnessCheck c = confirm_witnesses(*s.a, s.pose_a, *s.b, s.pose_b, 0, memory, true, 0);
  EXPECT_EQ(c.valid, 1u);
  EXPECT_EQ(memory.witnesses.size(), 1u);
  // Shifted by two positions on A: no longer a contact itself, but within the neighbourhood.
  const std::uint32_t shifted = pa + 2 < tris_a.size() ? pa + 2 : pa - 2;
  memory.witnesses = {{shifted, pb}};
  if (!collide_confirms(s, tris_a[shifted], tris_b[pb], 0)) {
    c = confirm_witnesses(*s.a, s.pose_a, *s.b, s.pose_b, 0, memory, true, 0);
    EXPECT_EQ(c.valid, 0u);
    EXPECT_TRUE(memory.witnesses.empty());
    memory.witnesses = {{shifted, pb}};
    c = confirm_witnesses(*s.a, s.pose_a, *s.b, s.pose_b, 0, memory, true, 4);
    ASSERT_EQ(c.valid, 1u);
    EXPECT_GT(c.evaluations, 0u);
    const auto [na, nb] = memory.witnesses.front();
    EXPECT_TRUE(collide_confirms(s, tris_a[na], tris_b[nb], 0));
  }
  // Far apart: every witness is dropped.
  memory.witnesses = {{pa, pb}};
  const Transform far = Transform::from_axis_angle(Vec3::UnitX(), 0.0, Vec3(10, 0, 0));
  c = confirm_witnesses(*s.a, s.pose_a, *s.b, far, 0, memory, true, 4);
  EXPECT_EQ(c.valid, 0u);
  EXPECT_TRUE(memory.witnesses.empty());
}

// random_detect on every touching pose: a witness collide() confirms; with a memory, the next
// call at the same pose is decided by the memory alone.
TEST(RandomMemory, DetectFindsAWitnessAndTheMemoryDecidesTheNextFrame) {
  for (const Scenario& s : touching_scenarios()) {
    SCOPED_TRACE(s.name);
    DetectRequest request;
    request.search.seed = 5;
    ColonyMemory memory;
    const DetectResult first = random_detect(*s.a, s.pose_a, *s.b, s.pose_b, request, &memory);
    ASSERT_TRUE(first.colliding);
    ASSERT_FALSE(first.search.hits.empty());
    const FeaturePair& h = first.search.hits.front();
    EXPECT_TRUE(collide_confirms(s, h.triangle_a, h.triangle_b, 0));
    const DetectResult second = random_detect(*s.a, s.pose_a, *s.b, s.pose_b, request, &memory);
    EXPECT_TRUE(second.colliding);
    EXPECT_TRUE(second.by_memory);
  }
}

}  // namespace
}  // namespace antcd
