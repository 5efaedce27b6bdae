// Random collision detection (include/antcd/random.hpp): feature spaces, the five searches, stop
// criteria, determinism. Ground truth is computed here from the meshes themselves, independently
// of the library's feature code.
#include <antcd/collide.hpp>
#include <antcd/random.hpp>

#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace antcd {
namespace {

using TrianglePair = std::pair<std::uint32_t, std::uint32_t>;

constexpr Method kAllMethods[] = {Method::Aco, Method::Maco, Method::Pso, Method::Ga,
                                  Method::Exhaustive};
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

/// Sorted (triangle_a, triangle_b) pairs of non-degenerate triangles whose world centroids are
/// within delta, over ALL triangles of both meshes. Pairs within 1e-9 delta of the threshold are
/// left out of `pairs` and counted in `ambiguous` (rounding may decide them either way).
struct Truth {
  std::vector<TrianglePair> pairs;
  std::size_t ambiguous = 0;
};

std::vector<std::pair<std::uint32_t, Vec3>> world_centroids(const Mesh& mesh,
                                                            const Transform& pose) {
  std::vector<std::pair<std::uint32_t, Vec3>> out;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3& v0 = mesh.vertices[tri[0]];
    const Vec3& v1 = mesh.vertices[tri[1]];
    const Vec3& v2 = mesh.vertices[tri[2]];
    if (geometry::is_degenerate_triangle(v0, v1, v2)) continue;
    out.emplace_back(t, pose.apply((v0 + v1 + v2) / 3));
  }
  return out;
}

Truth brute_force_centroid_pairs(const Scenario& s, Scalar delta) {
  Truth truth;
  const auto ca = world_centroids(s.a->mesh(), s.pose_a);
  const auto cb = world_centroids(s.b->mesh(), s.pose_b);
  for (const auto& [ta, pa] : ca) {
    for (const auto& [tb, pb] : cb) {
      const Scalar d = (pa - pb).norm();
      if (std::abs(d - delta) <= 1e-9 * delta) {
        ++truth.ambiguous;
      } else if (d < delta) {
        truth.pairs.emplace_back(ta, tb);
      }
    }
  }
  std::sort(truth.pairs.begin(), truth.pairs.end());
  return truth;
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

// With every candidate taken (samples >= triangles), enumerating the space finds exactly the
// centroid pairs within delta over ALL triangles of both meshes: the Sphere-OBB culling with
// margin delta loses none, and the map back to mesh triangles is right.
TEST(RandomFeatures, ExhaustiveSpaceEqualsBruteForceOverAllTriangles) {
  for (const Scenario& s : touching_scenarios()) {
    SCOPED_TRACE(s.name);
    const FeatureSpace space = build(s, 1u << 30);
    ASSERT_FALSE(space.empty());
    EXPECT_EQ(space.a.size(), space.candidates_a);
    EXPECT_EQ(space.b.size(), space.candidates_b);
    const Truth truth = brute_force_centroid_pairs(s, space.delta);
    ASSERT_FALSE(truth.pairs.empty()) << "scenario must touch";
    EXPECT_LE(truth.ambiguous, 2u);

    SearchRequest r = request_for(Method::Exhaustive, 0);
    const SearchResult result = search(space, r);
    EXPECT_EQ(result.stop, StopReason::Iterations);
    EXPECT_EQ(result.evaluations, space.cells());
    std::vector<TrianglePair> found;
    for (const FeaturePair& h : result.hits) {
      const Scalar d = (space.a.centroid(h.i) - space.b.centroid(h.j)).norm();
      if (std::abs(d - space.delta) <= 1e-9 * space.delta) continue;  // ambiguous band
      found.emplace_back(h.triangle_a, h.triangle_b);
    }
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, truth.pairs);
    EXPECT_EQ(count_colliding(space), result.hits.size());
  }
}

TEST(RandomFeatures, SamplingTakesDistinctTrianglesWithWorldCentroids) {
  const Scenario s = touching_scenarios()[1];  // spider pair: hundreds of candidates per side
  for (const std::uint32_t samples : {50u, 200u, 100000u}) {
    SCOPED_TRACE(samples);
    const FeatureSpace space = build(s, samples, 3);
    ASSERT_GT(space.candidates_a, 200u);
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
        EXPECT_LT((side->centroid(k) - c).norm(), 1e-9 * (1 + c.norm()));
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
      ASSERT_GT(side.size(), 50u);
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

// Every pair any search reports is a true colliding pair of the space (never f > delta), each
// once, with the right triangles and distance; best_distance is the true fitness of `best`.
TEST(RandomSearch, ReportedPairsAreTrueCollidingPairs) {
  for (const Scenario& s : touching_scenarios()) {
    const FeatureSpace space = build(s, 1000, 7);
    const auto truth = colliding_cells(space, space.delta);
    ASSERT_FALSE(truth.empty()) << s.name;
    for (const Method m : kAllMethods) {
      for (std::uint64_t seed = 0; seed < 3; ++seed) {
        SCOPED_TRACE(s.name + " " + std::string(method_name(m)) + " seed " + std::to_string(seed));
        SearchRequest request = request_for(m, seed);
        request.iterations = 40;
        const SearchResult r = search(space, request);
        EXPECT_EQ(r.found, !r.hits.empty());
        EXPECT_EQ(r.delta, space.delta);
        std::set<std::pair<std::uint32_t, std::uint32_t>> distinct;
        for (const FeaturePair& h : r.hits) {
          ASSERT_LT(h.i, space.a.size());
          ASSERT_LT(h.j, space.b.size());
          EXPECT_TRUE(truth.count({h.i, h.j})) << "(" << h.i << ", " << h.j << ") does not collide";
          EXPECT_TRUE(distinct.emplace(h.i, h.j).second) << "reported twice";
          EXPECT_EQ(h.triangle_a, space.a.triangle[h.i]);
          EXPECT_EQ(h.triangle_b, space.b.triangle[h.j]);
          EXPECT_DOUBLE_EQ(h.distance, space.distance(h.i, h.j));
          EXPECT_LE(h.distance, space.delta);
          EXPECT_GE(h.distance, r.best_distance);
        }
        EXPECT_DOUBLE_EQ(r.best_distance, space.distance(r.best.i, r.best.j));
        if (m == Method::Exhaustive) {
          EXPECT_EQ(distinct.size(), truth.size());
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
        EXPECT_FALSE(res.found) << method_name(m);
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
    SCOPED_TRACE(method_name(m));
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
    SCOPED_TRACE(method_name(m));
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
    if (m == Method::Exhaustive) {
      EXPECT_EQ(res.iterations, space.a.size());
      EXPECT_EQ(res.evaluations, space.cells());
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
    SCOPED_TRACE(method_name(m));
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
    SCOPED_TRACE(method_name(m));
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
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.delta = std::nan(""); })),
               antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.iterations = 0; })),
               antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.ant.ants = 0; })), antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.ant.rho = 1.5; })), antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.stop.target_share = 2; })),
               antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) {
                        r.progress_marks = {0.5, 0};
                      })),
               antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) {
                        r.method = Method::Ga;
                        r.ga.population = 1;
                      })),
               antcd::ArgumentError);
  // The deterministic methods are not searches.
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.method = Method::Exact; })),
               antcd::ArgumentError);
  EXPECT_THROW(search(space, bad([](SearchRequest& r) { r.method = Method::SphereObb; })),
               antcd::ArgumentError);
  SamplingOptions so;
  so.samples_per_side = 0;
  EXPECT_THROW(build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so), antcd::ArgumentError);
  so.samples_per_side = 10;
  so.delta = std::nan("");
  EXPECT_THROW(build_feature_space(*s.a, s.pose_a, *s.b, s.pose_b, so), antcd::ArgumentError);
}

}  // namespace
}  // namespace antcd
