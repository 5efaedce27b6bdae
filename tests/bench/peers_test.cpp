// antcd against FCL (and Bullet) on a small generated scene: the quick cross-check behind
// `antcd bench peers` (experiments/peers/peers_bench.hpp). Built only when FCL and Bullet are
// found.
#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "peers/peers_bench.hpp"
#include "shared/production_line.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

std::string describe(const std::vector<experiments::Disagreement>& list) {
  std::ostringstream os;
  std::size_t shown = 0;
  for (const experiments::Disagreement& d : list) {
    if (shown++ == 10) {
      os << "… " << list.size() - 10 << " more\n";
      break;
    }
    os << "frame " << d.frame << ", objects " << d.object_a << " (" << d.name_a << ") and "
       << d.object_b << " (" << d.name_b << "): antcd says "
       << (d.reference_says ? "collide" : "apart") << ", " << d.other << " says "
       << (d.other_says ? "collide" : "apart") << (d.detail.empty() ? "" : "; " + d.detail) << '\n';
  }
  return os.str();
}

// A small production line (two stations' worth of objects, coarse meshes), packed along the line
// so that neighbouring equipment overlaps too: resting contacts, deep overlaps and near misses.
std::unique_ptr<Scene> small_scene(std::size_t frames) {
  shared::ProductionLineOptions o;
  o.objects = 40;
  o.vertices = 150;
  o.frames = frames;
  shared::GeneratedScene g = shared::generate_production_line(o);
  for (SceneObject& obj : g.scene.objects) {
    for (Transform& t : obj.poses) t.translation.x() *= 0.6;
  }
  const auto file = shared::write_scene(g, test::fresh_temp_dir("peers_scene"));
  return std::make_unique<Scene>(load_scene(file));
}

TEST(PeersBench, AntcdAndFclAgreeOnEveryFramesCollidingPairs) {
  constexpr std::size_t kFrames = 40;
  const auto scene = small_scene(kFrames);
  const experiments::SceneCheck check =
      experiments::check_scene(*scene, "small line", kFrames, /*with_bullet=*/true);
  EXPECT_EQ(check.frames, kFrames);
  // Not vacuous: there are colliding pairs, and candidates that do not collide.
  EXPECT_GT(check.colliding_pairs, kFrames);
  EXPECT_GT(check.candidate_pairs, check.colliding_pairs);
  EXPECT_GT(check.triangle_pairs, check.colliding_pairs);
  // antcd (boolean and all contacts) against FCL-OBBRSS (boolean and all contacts): the same
  // colliding object pairs on every frame, the same colliding triangle pairs per object pair.
  EXPECT_TRUE(check.fcl.empty()) << check.fcl.size() << " disagreement(s) with FCL:\n"
                                 << describe(check.fcl);
  // Bullet (GImpact, margin 0) is only reported: it is not exact at touching contacts.
  RecordProperty("bullet_disagreements", static_cast<int>(check.bullet.size()));
  if (!check.bullet.empty()) {
    std::cout << "[ note ] Bullet disagreed " << check.bullet.size() << " time(s):\n"
              << describe(check.bullet);
  }
}

}  // namespace
}  // namespace antcd
