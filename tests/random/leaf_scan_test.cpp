// The colonies' leaf-pair scan (AntParams::scan_covered_spaces) and proves_separate: a budget
// that covers every cell of the overlapping leaf pairs scans them instead of searching, and a
// scan that finds no witness in a complete, unsampled space proves the pair separate. Checked
// against collide() on real meshes (assimp test models) at near-miss and touching poses.
#include <antcd/collide.hpp>
#include <antcd/load.hpp>
#include <antcd/random.hpp>

#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace antcd {
namespace {

std::shared_ptr<const Model> load_model(const std::string& relative) {
  return std::make_shared<const Model>(load_mesh(test::assimp_model(relative)), BuildOptions{},
                                       relative);
}

struct Pair {
  std::string name;
  std::shared_ptr<const Model> a;
  std::shared_ptr<const Model> b;
};

std::vector<Pair> pairs() {
  const auto wuson = load_model("OBJ/WusonOBJ.obj");
  const auto spider = load_model("OBJ/spider.obj");
  const auto ball = std::make_shared<const Model>(make_sphere(0.5, 48, 24));
  return {{"wuson-wuson", wuson, wuson},
          {"spider-spider", spider, spider},
          {"wuson-ball", wuson, ball}};
}

Vec3 aabb_centre(const Aabb& box) { return (box.min + box.max) / 2; }

/// B turned about a fixed axis and placed at `offset` from A's centre along `direction`, scaled
/// by the two models' sizes: a sweep from deep overlap through grazing to near misses.
Transform pose_b(const Pair& p, const Vec3& direction, double offset, double angle) {
  const Scalar size = p.a->mesh().bounds().extent().norm() + p.b->mesh().bounds().extent().norm();
  const Vec3 centre_a = aabb_centre(p.a->mesh().bounds());
  const Vec3 centre_b = aabb_centre(p.b->mesh().bounds());
  Transform t = Transform::from_axis_angle(Vec3(1, 2, 3).normalized(), angle, Vec3::Zero());
  t.translation = centre_a - t.rotation * centre_b + direction.normalized() * (offset * size);
  return t;
}

TEST(LeafScan, ACoveredBudgetScansTheLeafPairCellsAndFindsAWitness) {
  const Pair p = pairs()[0];
  const Transform pb = pose_b(p, Vec3(1, 0, 0), 0.12, 0.7);
  ASSERT_TRUE(collide(*p.a, Transform::identity(), *p.b, pb).colliding);
  SamplingOptions so;
  so.samples_per_side = 1u << 30;  // every candidate: no sampling
  const FeatureSpace space = build_feature_space(*p.a, Transform::identity(), *p.b, pb, so, 3);
  ASSERT_FALSE(space.empty());
  ASSERT_EQ(space.candidates_a, space.a.size());
  const std::uint64_t cells = space.leaf_pair_cells();
  EXPECT_GT(cells, 0u);
  EXPECT_LT(cells, space.cells());  // the overlapping leaf pairs hold a part of the grid

  SearchRequest r;
  r.method = Method::Maco;
  r.seed = 5;
  r.stop.first_hit = true;
  r.stop.max_evaluations = cells + 1;
  const SearchResult scanned = search(space, r);
  EXPECT_TRUE(scanned.scanned);
  EXPECT_TRUE(scanned.found);
  EXPECT_EQ(scanned.stop, StopReason::FirstHit);
  EXPECT_LE(scanned.evaluations, cells);
  EXPECT_TRUE(space.collides(scanned.hits.front().i, scanned.hits.front().j, Verdict::Witness));

  // A budget that does not exceed the cells, the switch off, or no first-hit stop: the colony.
  for (int variant = 0; variant < 3; ++variant) {
    SearchRequest c = r;
    if (variant == 0) c.stop.max_evaluations = cells;
    if (variant == 1) c.ant.scan_covered_spaces = false;
    if (variant == 2) c.stop.first_hit = false;
    const SearchResult colony = search(space, c);
    EXPECT_FALSE(colony.scanned) << "variant " << variant;
    EXPECT_FALSE(proves_separate(space, colony));
  }
}

// Near the contact boundary (found by bisection along several directions and turns), whenever
// random_detect's scan proves a pair separate (no witness, budget not exhausted), collide()
// agrees, and whenever it reports a collision, collide() agrees too. Poses just beyond the
// boundary are near misses whose leaves overlap, so the scan's negative answer is exercised.
TEST(LeafScan, ProvenSeparationAgreesWithCollide) {
  std::size_t proven = 0, colliding = 0;
  for (const Pair& p : pairs()) {
    for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, 1, 0.3), Vec3(-0.4, 0.2, 1)}) {
      for (const double angle : {0.3, 1.1, 2.0}) {
        auto touches = [&](double offset) {
          return collide(*p.a, Transform::identity(), *p.b, pose_b(p, dir, offset, angle))
              .colliding;
        };
        // Bisection between a touching offset and a separate one.
        double lo = 0, hi = 1;
        if (!touches(lo) || touches(hi)) continue;
        for (int k = 0; k < 30; ++k) {
          const double mid = (lo + hi) / 2;
          (touches(mid) ? lo : hi) = mid;
        }
        for (const double rel : {-1e-2, -1e-3, 1e-4, 1e-3, 3e-3, 1e-2}) {
          const double offset = hi * (1 + rel);
          const Transform pb = pose_b(p, dir, offset, angle);
          SCOPED_TRACE(p.name + " offset " + std::to_string(offset));
          DetectRequest req;
          req.samples_per_side = 1u << 30;
          req.evaluations_per_leaf_pair = 32;
          req.search.seed = 9;
          const DetectResult det = random_detect(*p.a, Transform::identity(), *p.b, pb, req);
          const bool truth = collide(*p.a, Transform::identity(), *p.b, pb).colliding;
          if (det.colliding) {
            EXPECT_TRUE(truth);
            ++colliding;
          } else if (!det.undecided && !det.no_leaf_pair) {
            EXPECT_TRUE(det.search.scanned);
            EXPECT_FALSE(truth);
            ++proven;
          }
          if (det.no_leaf_pair) {
            EXPECT_FALSE(truth);
          }
        }
      }
    }
  }
  EXPECT_GT(proven, 20u);
  EXPECT_GT(colliding, 20u);
}

}  // namespace
}  // namespace antcd
