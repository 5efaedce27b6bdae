// experiments/peers/scenes.hpp — the scene protocol: every frame of a scene through antcd exact,
// FCL (OBBRSS and OBB) and Bullet, timed, with every engine's verdicts compared with antcd's.
#pragma once

#include "peers/peers_bench.hpp"

#include <antcd/scene.hpp>

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace antcd::experiments::peers_bench {

/// The times of one engine and query kind, one entry per frame.
struct Series {
  std::string engine;
  std::string query;
  std::vector<double> wall_ms;
  std::vector<double> cpu_ms;
  std::vector<double> process_ms;  ///< CPU time of all threads
  double candidates = 0;           ///< broad-phase pairs, summed over frames
};

struct SceneRun {
  std::string name;
  std::string description;
  std::size_t objects = 0;
  std::size_t moving = 0;
  std::size_t models = 0;
  std::size_t triangles = 0;
  std::size_t frames = 0;
  double colliding = 0;  ///< antcd colliding object pairs, summed over frames
  double contacts = 0;   ///< antcd colliding triangle pairs, summed over frames
  int threads = 1;
  std::vector<Series> series;
  std::vector<Disagreement> disagreements;

  Series& get(const std::string& engine, const std::string& query) {
    for (Series& s : series) {
      if (s.engine == engine && s.query == query) return s;
    }
    series.push_back({engine, query, {}, {}, {}, 0});
    return series.back();
  }
  [[nodiscard]] const Series* find(const std::string& engine, const std::string& query) const {
    for (const Series& s : series) {
      if (s.engine == engine && s.query == query) return &s;
    }
    return nullptr;
  }
};

struct SceneEngines {
  bool fcl_obb = true;
  bool bullet = true;
  bool all_contacts = true;
};

/// Runs `frames` frames (from 0) through the engines: antcd boolean (1 thread, and `threads` when
/// more than 1), antcd all contacts, FCL-OBBRSS and FCL-OBB (boolean and all contacts) and Bullet,
/// as `engines` selects. Progress goes to `log` when set.
SceneRun run_scene(const Scene& scene, std::string_view name, std::size_t frames, int threads,
                   const SceneEngines& engines, std::ostream* log);

}  // namespace antcd::experiments::peers_bench
