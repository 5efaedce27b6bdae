// experiments/peers/peers_bench.hpp — antcd against FCL 0.7 and Bullet 3.24 on the same scenes and
// mesh pairs, measured side by side (`antcd bench peers`, docs/performance.md).
//
// This code links FCL and Bullet (through the adapters in adapters/); it is built (as the static
// library antcd_peers) only when both are found, and never linked into the antcd library itself.
// Parts: scenes, pairs, build, scale (the protocols), machine (/proc), report.
//
// Sections of the report:
// - scenes: a scene (the generated paper production line and a denser variant, or a scene file)
//   run frame by frame through antcd `exact` (Scene::run_frame, Method::Exact), FCL (BVHModel of
//   OBBRSS and of OBB behind a DynamicAABBTreeCollisionManager, boolean and all-contacts) and
//   Bullet (btGImpactMeshShape in a btCollisionWorld with btDbvtBroadphase). Every frame the
//   colliding object pairs of every engine are compared with antcd's; all-contacts runs also
//   compare the colliding triangle pairs. Per-frame median and p99 times, ratios.
// - pairs: two tori of ~1k … 1M triangles, one tumbling past the other over P poses at four
//   clearances (deep, shallow, touching, just separated); boolean and all-contacts queries, antcd
//   against FCL (OBBRSS), verdicts and triangle-pair sets compared pose by pose.
// - build: hierarchy build time and memory per triangle, antcd Model vs FCL BVHModel.
// - scale: the production line with 1 000 and 10 000 objects (about 2 million triangles), antcd
//   only: objects vs candidate pairs vs time per frame.
#pragma once

#include <antcd/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace antcd::experiments {

struct PeersBenchOptions {
  /// A scene file to run instead of the generated paper scene and its dense variant.
  std::filesystem::path scene_file;
  /// Frames per scene; 0 = the default (300, quick 30), never more than the scene has.
  std::size_t frames = 0;
  /// Worker threads of antcd's second scene run (the oneTBB path); 1 = no threaded run.
  int threads = 2;
  /// Smaller everything: finishes in well under a minute.
  bool quick = false;
  bool run_scenes = true;
  bool run_pairs = true;  ///< pair protocol plus build time and memory
  bool run_scale = true;
  /// Where the generated scenes are written (they are loaded back through Scene like any scene
  /// file); empty = a fresh folder under the system temporary folder, removed afterwards.
  std::filesystem::path work_dir;
};

/// Colliding object pairs (i < j), sorted.
using ObjectPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// One frame on which two engines disagree about one object pair.
struct Disagreement {
  std::string scene;
  std::size_t frame = 0;
  std::uint32_t object_a = 0;
  std::uint32_t object_b = 0;
  std::string name_a;  ///< the objects' names in the scene
  std::string name_b;
  std::string reference;  ///< "antcd"
  std::string other;      ///< "FCL-OBBRSS", "FCL-OBB", "Bullet", …
  bool reference_says = false;
  bool other_says = false;
  std::string detail;  ///< e.g. triangle-pair counts when only those differ
};

/// What the cross-check of one scene found.
struct SceneCheck {
  std::size_t frames = 0;
  std::size_t colliding_pairs = 0;   ///< antcd's colliding object pairs, summed over the frames
  std::size_t candidate_pairs = 0;   ///< antcd's broad-phase survivors, summed over the frames
  std::size_t triangle_pairs = 0;    ///< antcd's colliding triangle pairs (all contacts), summed
  std::vector<Disagreement> fcl;     ///< antcd vs FCL-OBBRSS (boolean and all contacts)
  std::vector<Disagreement> bullet;  ///< antcd vs Bullet GImpact
};

/// Runs `frames` frames (from 0) of `scene` through antcd exact (boolean and all contacts) and
/// FCL-OBBRSS (boolean and all contacts), and Bullet when `with_bullet`; compares the colliding
/// object pairs of every frame and the colliding triangle pairs of the all-contacts runs. Untimed:
/// the cross-check behind the test suite.
SceneCheck check_scene(const Scene& scene, std::string_view name, std::size_t frames,
                       bool with_bullet);

struct PeersBenchResult {
  std::string report_markdown;
  /// CSV files by name (scenes.csv, pairs.csv, build.csv, scale.csv, disagreements.csv).
  std::vector<std::pair<std::string, std::string>> csv;
  /// True when antcd and FCL (both bounding volumes) agreed on every frame and pose.
  bool antcd_fcl_agree = true;
  std::size_t bullet_disagreements = 0;
};

/// Runs the selected sections; progress goes to `log`. Throws antcd::ArgumentError for bad
/// options, antcd::Error for an unreadable scene.
PeersBenchResult run_peers_bench(const PeersBenchOptions& options, std::ostream& log);

}  // namespace antcd::experiments
