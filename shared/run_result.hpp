// shared/run_result.hpp — results of a scene run (the `antcd run` output format) and the metrics
// that compare two runs.
//
// Output format (JSON):
//   { "method": "maco", "build_ms": 41.0, "total_ms": 36.2,
//     "frames": [ { "frame": 0, "pairs": [["roller_07", "press_02"]], "time_ms": 0.12 } ] }
// plus, per frame, "candidates" (the broad phase's pairs, same form as "pairs") and, for random
// methods, "feature_hits" / "feature_truth", "evaluations" and "undecided" (candidate pairs left
// without a witness when a frame budget ran out; same form as "pairs"); and at the top "scene",
// "delta", "seed", "threads", and for random methods "verdict", "memory" (whether the colonies
// were carried from frame to frame) and "leaf_scan" (AntParams::scan_covered_spaces).
// "pairs" lists each colliding object pair once, the two names in scene order. On request
// (add_distances, `antcd run --report-distance`), each frame also has "distances": the exact
// minimum distance between the two surfaces of each pair (antcd::distance, 0 when they meet),
// in the order of "pairs"; and with SceneQuery::volume the top level says "volume": true.
// Both are absent otherwise, so older readers see the format they know.
// Continuous runs (SceneQuery::continuous, `antcd run --continuous`) say "continuous": true at the
// top, and each frame's "pairs" are the pairs that touched during the step from the previous
// frame; per pair, in the order of "pairs", "toi" holds the first time of impact in [0, 1] over
// that step (0: the previous frame, 1: this one) and "contact_points" the contact point there
// ([x, y, z], world frame). Results without these fields (older files) still load. A continuous
// run's self pairs ([name, name], deforming or self_collision objects) have a toi and a contact
// point like the others and no "self_pairs" entry.
// Self pairs (exact method, objects with "self_collision"): a frame's "pairs" holds [name, name]
// for each such object that intersects itself, and the frame has "self_pairs": one entry per such
// pair, in the order of "pairs": {"object": name, "triangles": [[a, b], ...]} (mesh triangle
// indices, a < b, sorted; FrameResult::self_pairs). Absent when a frame has no self pair.
#pragma once

#include <antcd/scene.hpp>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared {

using NamePair = std::pair<std::string, std::string>;

struct FrameRecord {
  std::size_t frame = 0;
  std::vector<NamePair> pairs;
  std::vector<NamePair> candidates;
  double time_ms = 0;
  std::optional<std::uint64_t> feature_hits;
  std::optional<std::uint64_t> feature_truth;
  std::optional<std::uint64_t> evaluations;  ///< random methods: fitness evaluations of the frame
  std::vector<NamePair> undecided;           ///< random methods: pairs left without a witness
  /// With report_distance: the surface distance of each pair, in the order of `pairs`.
  std::optional<std::vector<double>> distances;
  /// Continuous runs: per pair, the first time of impact over the step from the previous frame.
  std::optional<std::vector<double>> toi;
  /// Continuous runs: per pair, the contact point at that time (world frame).
  std::optional<std::vector<std::array<double, 3>>> contact_points;
  /// Self pairs: the object's name and its intersecting triangle pairs.
  std::vector<std::pair<std::string, std::vector<std::array<std::uint32_t, 2>>>> self_pairs;
};

struct RunResult {
  std::string method;
  std::string scene;
  double delta = 0;
  std::uint64_t seed = 0;
  int threads = 1;
  std::string verdict;      ///< random methods: "witness" or "paper-centroid"; empty otherwise
  bool memory = false;      ///< random methods: colonies carried from frame to frame (SceneMemory)
  bool leaf_scan = false;   ///< random methods: AntParams::scan_covered_spaces
  bool volume = false;      ///< SceneQuery::volume was set
  bool continuous = false;  ///< SceneQuery::continuous was set
  double build_ms = 0;
  double total_ms = 0;  ///< sum of the frames' time_ms
  std::vector<FrameRecord> frames;
};

/// Runs frames 0, frame_step, 2 frame_step, ... of `scene` with `query` (every frame by
/// default); `progress(done, total)` is called after each frame run when set. `build_ms` is taken
/// from the scene (loading and building). Random methods carry their colonies from each frame run
/// to the next (one SceneMemory for the whole run) unless `memory` is false. Throws antcd::Error if
/// frame_step is 0, or not 1 for a continuous query (each frame sweeps from the one before).
RunResult run_scene(const Scene& scene, const SceneQuery& query, const std::string& scene_name,
                    const std::function<void(std::size_t, std::size_t)>& progress = {},
                    std::size_t frame_step = 1, bool memory = true);

/// Fills FrameRecord::distances of every frame of `result` (a run of `scene`, any method): the
/// exact minimum distance between the two surfaces of each reported pair at that frame
/// (antcd::distance; 0 when they meet, > 0 for a pair reported by δ or by containment). Throws
/// antcd::Error when a pair names an object the scene does not have.
void add_distances(const Scene& scene, RunResult& result);

std::string to_json(const RunResult& result);
/// Parses a run result; errors (antcd::Error) name `source` and the problem.
RunResult parse_run_result(std::string_view text, const std::string& source);

struct Metrics {
  std::size_t frames = 0;
  std::uint64_t true_pairs = 0;      ///< colliding object pairs in the truth, summed over frames
  std::uint64_t reported_pairs = 0;  ///< pairs the result reports, summed over frames
  std::uint64_t true_positives = 0;
  std::uint64_t candidate_pairs = 0;  ///< broad-phase candidates of the truth, summed over frames
  std::uint64_t correct_candidates = 0;  ///< candidates the result classifies like the truth
  double recall = 0;                     ///< TP / true pairs (1 when the truth has none)
  double precision = 0;                  ///< TP / reported pairs (1 when nothing was reported)
  double accuracy = 0;                   ///< correct / candidates (1 when there are none)
  std::optional<double> feature_recall;  ///< Σ feature_hits / Σ feature_truth (the paper's A/B)
  double mean_ms = 0;  ///< of the result's frames (statistics.hpp: NaN when there are none)
  double p99_ms = 0;
  double truth_mean_ms = 0;
  double truth_p99_ms = 0;
};

/// Compares `result` against `truth` (normally an `exact` run) frame by frame. Throws
/// antcd::Error if the two runs do not cover the same frames.
Metrics compare_runs(const RunResult& truth, const RunResult& result);

}  // namespace antcd::shared
