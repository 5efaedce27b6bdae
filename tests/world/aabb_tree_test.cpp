// The World's broad-phase tree on its own (a private class, compiled into this test): box queries
// and the all-pairs traversal (whole, and split into tasks) equal brute force over seeded random
// sequences of insertions, moves, removals and batches of new boxes with a refit, crossing many
// rebuilds; and the tree stays tight on many objects spread through a volume (the case where
// greedy insertion with height-only rotations had produced overlapping slabs, and a world of
// 100 000 objects spent minutes per frame in its broad phase).
#include "world/aabb_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace antcd::detail {
namespace {

Aabb box_at(const Vec3& c, Scalar half) {
  return Aabb{c - Vec3::Constant(half), c + Vec3::Constant(half)};
}

Aabb grown_by(Aabb b, Scalar by) {
  b.min.array() -= by;
  b.max.array() += by;
  return b;
}

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Boxes within `gap` of each other on every axis.
bool near(const Aabb& a, const Aabb& b, Scalar gap) {
  for (int k = 0; k < 3; ++k) {
    if (a.min[k] - gap > b.max[k] || b.min[k] - gap > a.max[k]) return false;
  }
  return true;
}

Pairs sorted(Pairs p) {
  for (auto& [a, b] : p) {
    if (a > b) std::swap(a, b);
  }
  std::sort(p.begin(), p.end());
  return p;
}

TEST(AabbTree, QueriesAndPairsEqualBruteForceAcrossRebuildsAndRefits) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> u(0, 20);
  std::uniform_real_distribution<Scalar> size(0.05, 1.5);
  AabbTree tree;
  std::vector<Aabb> boxes;  // by object
  std::vector<bool> present;
  std::size_t pairs_seen = 0;
  for (int step = 0; step < 3000; ++step) {
    const Scalar op = std::uniform_real_distribution<Scalar>(0, 1)(rng);
    if (op < 0.4 || boxes.empty()) {
      boxes.push_back(box_at(Vec3(u(rng), u(rng), u(rng)), size(rng)));
      present.push_back(true);
      tree.insert(static_cast<std::uint32_t>(boxes.size() - 1), boxes.back());
    } else if (op < 0.97) {
      const std::size_t k = std::uniform_int_distribution<std::size_t>(0, boxes.size() - 1)(rng);
      if (!present[k]) continue;
      if (op < 0.5) {
        tree.remove(static_cast<std::uint32_t>(k));
        present[k] = false;
      } else {
        boxes[k] = box_at(Vec3(u(rng), u(rng), u(rng)), size(rng));
        tree.move(static_cast<std::uint32_t>(k), boxes[k]);
      }
    } else {  // a frame: every object drifts a little, new leaf boxes, one refit
      std::normal_distribution<Scalar> drift(0, 0.3);
      for (std::size_t k = 0; k < boxes.size(); ++k) {
        if (!present[k]) continue;
        const Vec3 d(drift(rng), drift(rng), drift(rng));
        boxes[k].min += d;
        boxes[k].max += d;
        tree.set_box(static_cast<std::uint32_t>(k), boxes[k]);
      }
      tree.refit();
    }
    ASSERT_TRUE(tree.contains(static_cast<std::uint32_t>(boxes.size() - 1)) == present.back());
    if (step % 50 != 0) continue;
    const Aabb query = box_at(Vec3(u(rng), u(rng), u(rng)), 2 * size(rng));
    std::multiset<std::uint32_t> found;
    tree.query(query, [&](std::uint32_t object) { found.insert(object); });
    std::multiset<std::uint32_t> expected;
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      // The tree stores boxes rounded outward to single precision: a brute-force hit is always
      // found, and a box it finds is the object's box or a hair larger.
      if (present[k] && boxes_overlap(boxes[k], query))
        expected.insert(static_cast<std::uint32_t>(k));
    }
    for (const std::uint32_t k : expected) ASSERT_EQ(found.count(k), 1u) << "step " << step;
    for (const std::uint32_t k : found) {
      ASSERT_TRUE(present[k]);
      ASSERT_TRUE(boxes_overlap(grown_by(boxes[k], 1e-5), query)) << "step " << step;
    }

    // All pairs within a gap: one traversal, and the same split into tasks.
    const Scalar gap = step % 100 == 0 ? 0.0 : 0.25;
    Pairs whole;
    tree.pairs(tree.all_pairs(), gap,
               [&](std::uint32_t a, std::uint32_t b) { whole.emplace_back(a, b); });
    Pairs split;
    for (const AabbTree::PairTask t : tree.pair_tasks(gap, 64)) {
      tree.pairs(t, gap, [&](std::uint32_t a, std::uint32_t b) { split.emplace_back(a, b); });
    }
    whole = sorted(whole);
    split = sorted(split);
    ASSERT_EQ(whole, split) << "step " << step;
    ASSERT_EQ(std::adjacent_find(whole.begin(), whole.end()), whole.end()) << "a pair twice";
    Pairs expected_pairs;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
        if (present[i] && present[j] && near(boxes[i], boxes[j], gap))
          expected_pairs.emplace_back(i, j);
      }
    }
    for (const auto& p : expected_pairs) {
      ASSERT_TRUE(std::binary_search(whole.begin(), whole.end(), p)) << "step " << step;
    }
    for (const auto& [a, b] : whole) {
      ASSERT_TRUE(present[a] && present[b]);
      ASSERT_TRUE(near(boxes[a], boxes[b], gap + 1e-5)) << "step " << step;
    }
    pairs_seen += expected_pairs.size();
  }
  EXPECT_GT(pairs_seen, 1000u);  // not vacuous
}

TEST(AabbTree, StaysTightOnManyObjectsSpreadThroughAVolume) {
  // 20 000 unit boxes, 1 per 8 volume units, inserted in random order. A balanced tree of median
  // splits has internal boxes of total area about 100 times the root's here; the tree built by
  // insertion alone had about 545 (and its queries cost grew about quadratically with n).
  constexpr std::size_t kObjects = 20000;
  const Scalar side = std::cbrt(8.0 * kObjects);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<Scalar> u(-0.5, 0.5);
  AabbTree tree;
  for (std::uint32_t i = 0; i < kObjects; ++i) {
    tree.insert(i, box_at(Vec3(side * u(rng), side * u(rng), side * u(rng)), 0.55));
  }
  EXPECT_LT(tree.relative_area(), 200);
  EXPECT_LE(tree.height(), 24);
  // Every object moves once (as in a frame of a moving world): still tight.
  for (std::uint32_t i = 0; i < kObjects; ++i) {
    tree.move(i, box_at(Vec3(side * u(rng), side * u(rng), side * u(rng)), 0.55));
  }
  EXPECT_LT(tree.relative_area(), 200);
  EXPECT_LE(tree.height(), 24);
  // The same through new leaf boxes and refits: the refit rebuilds once the tree got loose.
  for (int frame = 0; frame < 3; ++frame) {
    for (std::uint32_t i = 0; i < kObjects; ++i) {
      tree.set_box(i, box_at(Vec3(side * u(rng), side * u(rng), side * u(rng)), 0.55));
    }
    tree.refit();
    EXPECT_LT(tree.relative_area(), 200);
  }
}

TEST(AabbTree, StoredBoxesContainTheirBoxesAndStayWithinFourUlps) {
  // Leaf boxes are stored in single precision rounded outward without branches: whatever way the
  // conversion rounds, at zero, near the denormals, at float binade boundaries and beyond the float
  // range, the stored box must contain the given one, and not be much looser.
  const Scalar big = static_cast<Scalar>(std::numeric_limits<float>::max());
  const std::vector<Scalar> values = {0.0,  -0.0,      1e-300,     -1e-300,    1e-40,        -1e-40,
                                      1.0,  -1.0,      1 + 1e-12,  1 - 1e-12,  -(1 + 1e-12), 0.1,
                                      -0.1, 1.0 / 3.0, -2.0 / 3.0, 16777217.0, 1e30,         -1e30,
                                      big,  -big,      1e39,       -1e39};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Scalar> u(-1e4, 1e4);
  std::vector<Scalar> all = values;
  for (int k = 0; k < 2000; ++k) all.push_back(u(rng));
  for (const Scalar lo : all) {
    const Aabb b{Vec3::Constant(lo), Vec3::Constant(lo)};
    AabbTree tree;  // one leaf: the rounding alone
    tree.insert(0, b);
    const Aabb stored = tree.box(0);
    EXPECT_TRUE((stored.min.array() <= b.min.array()).all()) << lo;
    EXPECT_TRUE((stored.max.array() >= b.max.array()).all()) << lo;
    if (std::abs(lo) < 1e38) {
      const Scalar ulp = std::max(std::abs(lo) * 0x1p-23, Scalar{1e-37});
      EXPECT_LE(b.min.x() - stored.min.x(), 4 * ulp) << lo;
      EXPECT_LE(stored.max.x() - b.max.x(), 4 * ulp) << lo;
    }
  }
}

}  // namespace
}  // namespace antcd::detail
