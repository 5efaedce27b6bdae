// antcd/scene.hpp — scenes of many moving meshes: the scene file, and the per-frame engine.
//
// Scene file (JSON, format "antcd-scene/1"):
//   { "format": "antcd-scene/1", "frames": 300,
//     "objects": [ { "name": "roller_07", "mesh": "meshes/roller.obj", "scale": 1.0,
//                    "poses": [ { "translation": [0, 1.5, 0], "rotation_wxyz": [1, 0, 0, 0] } ] } ]
//                    }
// - "mesh" is relative to the scene file's folder (absolute paths are kept as they are).
// - "poses" holds one pose (a static object) or exactly "frames" poses.
// - "scale" is optional, uniform, > 0, default 1; it scales the mesh about its own origin before
//   the pose is applied.
// - Names are unique and non-empty. Quaternions within tolerance::kUnitQuaternion (1e-3) of unit
// length are normalised; others
//   are an error. Every error names the scene file and the object.
//
// Engine: one Model per distinct (mesh file, scale), shared by the objects that use it, and one
// World (world.hpp) holding every object, object index = ObjectId slot. Each frame: the frame's
// poses go to the World (set_poses; its tree moves only the objects that left their fattened
// boxes, so consecutive frames are cheap) → World::candidate_pairs (tree, then the root spheres,
// then the root OBBs) → the chosen narrow phase on each surviving pair. Scene::run_frame is const
// and thread-safe: concurrent calls take turns for the pose update and broad phase (a mutex), and
// run their narrow phases at once; with threads > 1 the work is spread over oneTBB workers and the
// answer is the same as with one thread (each pair's random stream depends only on the seed, the
// frame and the two object indices).
// Continuous queries (SceneQuery::continuous, exact method only): frame f reports the pairs whose
// surfaces come within delta anywhere during the step from frame f - 1 to frame f (frame 0: at
// frame 0), each with its first time of impact in [0, 1] over the step, the objects moving as in
// ccd.hpp (World::sweep_poses, sweep.hpp: conservative, never a missed contact, toi <= the true
// first contact). The candidates are the pairs whose swept boxes come within delta. Such frames
// hold the World's mutex for their whole run, so concurrent continuous frames take turns.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/mesh.hpp>
#include <antcd/method.hpp>
#include <antcd/random.hpp>
#include <antcd/scene_export.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace antcd {

struct SceneObject {
  std::string name;
  std::filesystem::path mesh;  ///< as resolved against the scene folder
  std::string mesh_text;       ///< as written in the file
  Scalar scale = 1;
  std::vector<Transform> poses;  ///< 1 (static) or `frames`

  [[nodiscard]] const Transform& pose(std::size_t frame) const {
    return poses.size() == 1 ? poses.front() : poses[frame];
  }
};

struct SceneDescription {
  std::size_t frames = 1;
  std::vector<SceneObject> objects;
};

/// Parses a scene from JSON text. `source` names the input in errors; relative mesh paths are
/// resolved against `base_dir`. Mesh files are not opened here. Throws SceneError.
ANTCD_SCENE_API SceneDescription parse_scene(std::string_view json_text,
                                             const std::filesystem::path& base_dir,
                                             const std::string& source);
/// Reads and parses a scene file. Throws SceneError.
ANTCD_SCENE_API SceneDescription load_scene(const std::filesystem::path& path);
/// Serialises a scene (mesh paths as in mesh_text) and writes it atomically. Throws Error.
ANTCD_SCENE_API void save_scene(const SceneDescription& scene, const std::filesystem::path& path);
/// The JSON text save_scene writes.
ANTCD_SCENE_API std::string scene_to_json(const SceneDescription& scene);

struct SceneQuery {
  Method method = Method::Exact;
  /// Collision threshold δ in mesh units (exact and sphere-obb: triangle/volume distance).
  Scalar delta = 0;
  /// Random methods (aco, maco, pso, ga, exhaustive, grid): each candidate pair's query is
  /// random_detect's (random.hpp) with this request: verdict, centroid threshold, samples per
  /// side, iterations, agents, all_witnesses (every search runs its N iterations and collects
  /// FrameResult::feature_hits, as the paper's A/B needs), count_truth (FrameResult::
  /// feature_truth), budgets, the partial first pass, the witness neighbourhood. Its `delta` and
  /// `search.method` are ignored (this query's are used), and so is `search.seed`: each pair's
  /// seed is scene_pair_seed(seed, frame, i, j). An unset `search.centroid_delta` is
  /// default_delta of the two models, from the radii the scene caches.
  DetectRequest random;
  /// Random methods: the seed of the whole run.
  std::uint64_t seed = 1;
  /// Random methods, anytime query: fitness evaluations shared by all candidate pairs of the
  /// frame (0 = off). After each pair's witnesses and preliminary detection, the budget is split
  /// equally over the pairs still undecided, in rounds of one search each (the per-leaf-pair
  /// budget is then not used); a pair without a witness when it runs out is reported in
  /// FrameResult::undecided. Deterministic (the split depends only on counts).
  std::uint64_t frame_evaluations = 0;
  /// Random methods, anytime query: wall time for the frame's searches (0 = off; not
  /// deterministic). May be combined with frame_evaluations.
  double frame_seconds = 0;
  /// Worker threads for the narrow phase (1 = the calling thread only).
  int threads = 1;
  /// Exact method: CollisionRequest::volume, so two closed objects also collide when one lies
  /// wholly inside the other (open ones keep surface semantics). Refused with other methods.
  bool volume = false;
  /// Exact method: continuous detection over the step from the previous frame (see above);
  /// `delta` is the sweep's min_separation. Refused with other methods and with `volume`.
  bool continuous = false;
};

/// The seed of object pair (i, j)'s random query in `frame` of a run seeded with `seed`: what
/// Scene::run_frame passes random_detect as DetectRequest::search.seed (without a frame budget,
/// random_detect with it, the scene's other settings and the pair's memory gives the same verdict
/// and evaluations as the frame).
ANTCD_SCENE_API std::uint64_t scene_pair_seed(std::uint64_t seed, std::size_t frame,
                                              std::uint32_t i, std::uint32_t j);

/// What the random methods carry from frame to frame, per object pair: the colony's pheromone,
/// its iteration count and the last witnesses (ColonyMemory, random.hpp). Pass the same memory to
/// the frames of one run, in order; a memory must not be used by two run_frame calls at once.
/// Results then depend on the frames run before (same sequence => same results).
class SceneMemory {
 public:
  void clear() { pairs_.clear(); }
  [[nodiscard]] std::size_t size() const { return pairs_.size(); }
  /// The memory of object pair (i, j), i < j; nullptr if none yet.
  [[nodiscard]] const ColonyMemory* find(std::uint32_t i, std::uint32_t j) const {
    const auto it = pairs_.find({i, j});
    return it == pairs_.end() ? nullptr : &it->second;
  }

 private:
  friend class Scene;
  std::map<std::pair<std::uint32_t, std::uint32_t>, ColonyMemory> pairs_;
};

struct FrameResult {
  std::size_t frame = 0;
  /// Colliding object pairs (i < j, object indices), sorted.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  /// Broad-phase survivors (i < j), sorted: the pairs the narrow phase examined.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  /// Random methods: distinct colliding feature pairs found, summed over the candidate pairs.
  std::uint64_t feature_hits = 0;
  /// Random methods with count_feature_truth: colliding feature pairs in the searched spaces.
  std::uint64_t feature_truth = 0;
  /// Random methods: candidate pairs whose search ran out of budget without a witness. They are
  /// not in `pairs` ("separate" is a guess for them, not a proof); every other candidate pair is
  /// decided (a witness confirmed, no leaf pair at delta, or every triangle pair of the
  /// overlapping leaves scanned without a witness: proves_separate in random.hpp).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> undecided;
  /// Random methods: fitness evaluations spent over the frame.
  std::uint64_t evaluations = 0;
  double time_ms = 0;  ///< pose update + broad phase + narrow phase
  /// Continuous queries: per pair of `pairs`, its first time of impact in [0, 1] over the step
  /// from the previous frame (0 = at frame - 1, 1 = at frame; frame 0: 0), and the contact point
  /// there (world frame, SweepResult::contact). Empty otherwise.
  std::vector<Scalar> toi;
  std::vector<Vec3> contact_points;
};

class ANTCD_SCENE_API Scene {
 public:
  /// Loads every mesh (once per distinct file and scale) and builds the hierarchies.
  /// Throws MeshError / SceneError naming the object whose mesh failed, and SceneError naming the
  /// object and frame of a pose that is not rigid (every pose is checked here, so a frame never
  /// fails on one).
  explicit Scene(SceneDescription description, const BuildOptions& options = {});
  /// The meshes come from `mesh_source` instead of files: it is called once per distinct
  /// (SceneObject::mesh, scale) with the first object that uses that mesh, and returns the mesh
  /// unscaled (the scene applies SceneObject::scale). For scenes built in memory (generators,
  /// tests). A MeshError it throws becomes a SceneError naming the object.
  Scene(SceneDescription description, const std::function<Mesh(const SceneObject&)>& mesh_source,
        const BuildOptions& options = {});
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  [[nodiscard]] const SceneDescription& description() const { return description_; }
  [[nodiscard]] std::size_t object_count() const { return description_.objects.size(); }
  [[nodiscard]] std::size_t model_count() const { return models_.size(); }
  [[nodiscard]] const Model& model_of(std::size_t object) const {
    return *models_[model_index_[object]];
  }
  [[nodiscard]] double build_ms() const { return build_ms_; }

  /// The broad phase of one frame alone: the object pairs (i < j, sorted) whose root bounding
  /// volumes (sphere, then OBB) are within `delta` — the pairs run_frame hands to the narrow phase.
  /// For narrow phases built outside the library. Throws ArgumentError for a frame >= frames or a
  /// negative or non-finite delta. Const as run_frame is (below).
  [[nodiscard]] std::vector<std::pair<std::uint32_t, std::uint32_t>> broad_phase(
      std::size_t frame, Scalar delta) const;

  /// Runs one frame. Throws ArgumentError for a frame >= frames or a bad query.
  /// `memory` (random methods; may be null) carries the colonies from frame to frame.
  /// What `const` means here: the description and the models never change, and the answer
  /// depends on (frame, query, memory) alone, never on the frames run before. The call does
  /// mutate state the Scene keeps for speed: its World (moved to the frame's poses, under a mutex
  /// that serialises the broad phase of concurrent calls) and the exact method's per-pair
  /// witnesses from the last frame (PairWitness, used by one call at a time; a concurrent call
  /// runs without them). So calls from several threads are safe, and frame after frame on one
  /// thread is the fast order.
  [[nodiscard]] FrameResult run_frame(std::size_t frame, const SceneQuery& query,
                                      SceneMemory* memory = nullptr) const;

 private:
  SceneDescription description_;
  std::vector<std::shared_ptr<const Model>> models_;
  std::vector<std::size_t> model_index_;
  std::vector<Scalar> feature_radius_;  ///< per model, for the random methods' default delta
  double build_ms_ = 0;
  struct Broad;  // the World and the mutex that orders its updates (scene.cpp)
  std::unique_ptr<Broad> broad_;
};

}  // namespace antcd
