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
//   length are normalised; others are an error. Every error names the scene file and the object.
// - Deforming objects (optional; scenes without them load as before): "vertex_frames":
//   "frames/sheet_03.avf" names a binary side file (relative to the scene folder, like "mesh")
//   holding the object's vertex positions, one set per frame (layout below); they replace the
//   mesh's positions at each frame, in the mesh's model frame, before "scale" and the pose apply.
//   The triangles stay the mesh file's. Vertex order: the order of the mesh as loaded
//   (antcd/load.hpp; Model::mesh().vertices): the loaders keep the vertices faces use, in order of
//   first use, and join exactly coincident ones, so an OBJ whose vertices are distinct and listed
//   in the order the faces first use them loads in its file order, and a model file (.antcd) keeps
//   its saved order. The Scene refuses a side file whose vertex count is not the loaded mesh's.
// - "self_collision": true (optional, default false): the exact method also reports where the
//   object's mesh intersects itself (self.hpp), as the pair (object, object) with its triangle
//   pairs (FrameResult::self_pairs). For rigid and deforming objects alike; continuous queries
//   report the self pair (object, object) with a toi (below), without triangle pairs.
//
// Vertex-frames side file (".avf"; every number little-endian):
//   offset 0   8 bytes   magic "ANTCDVFR"
//   offset 8   uint32    format version, 1
//   offset 12  uint32    vertex count n (>= 1; the loaded mesh's vertex count)
//   offset 16  uint64    frame count F (>= 1; the scene's "frames")
//   offset 24  F x n x 3 float64: frame 0's vertex 0 x, y, z, vertex 1 x, y, z, ..., then frame 1
// The file is exactly 24 + 24 n F bytes. Every coordinate must be finite. Reading checks the size
// against the header before anything is allocated (memory is bounded by the file's real size);
// a missing file, a wrong magic or version, a zero count, a truncated file or trailing bytes, a
// non-finite coordinate (its frame and vertex), a frame count other than the scene's or a vertex
// count other than the mesh's is a SceneError naming the scene file, the object and the side file.
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
// With deforming objects (or self_collision ones) a continuous frame is World::sweep_motion
// (world.hpp) from frame f - 1 to frame f: the World first holds frame f - 1's poses and
// vertices, then each deforming object's WORLD vertices move linearly from frame f - 1's to frame
// f's (pose(f-1) * V(f-1) to pose(f) * V(f), scaled; deform_sweep's convention), rigid ones as
// above. Pairs with a deforming object get an exact discrete test at frame f - 1 (toi 0) and then
// deform_sweep; self_collision objects get their self pair (i, i) the same way (self pairs as
// deform_ccd.hpp defines them, plus self-intersection at t = 0). Conservative: a pair that comes
// within delta during the step is reported, toi <= its first contact. FrameResult::self_pairs
// stays empty (the pair that decided is a vertex-face or edge-edge primitive, not a triangle
// pair); the toi and contact point are in toi / contact_points like the other pairs'.
// Deforming objects: each frame first gives the World their vertices of that frame
// (World::set_vertices: the object's own copy of the Model, refitted in O(n), hierarchy topology
// kept, so the Model of frame f depends on frame f's vertices alone), then runs as above on the
// refitted models. Every method handles them: exact and sphere-obb test the refitted hierarchies;
// the random methods sample features of the refitted Models (their default centroid threshold
// comes from the rest mesh's triangle sizes). Self pairs (self_collision) are the exact method's
// only (the random methods search pairs of distinct objects; sphere-obb's leaf overlaps would
// find every pair of neighbouring leaves of a mesh). Frames of a scene with deforming objects
// hold the World's mutex for their whole run (the refitted Models are shared state), so
// concurrent frames take turns; the answer is the same at any thread count (continuous frames:
// up to deform_sweep's budget-exhausted pairs, world.hpp).
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/mesh.hpp>
#include <antcd/method.hpp>
#include <antcd/random.hpp>
#include <antcd/scene_export.hpp>

#include <array>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace antcd {

/// The first 8 bytes of a vertex-frames side file, and the version this build reads and writes.
inline constexpr std::uint8_t kVertexFramesMagic[8] = {'A', 'N', 'T', 'C', 'D', 'V', 'F', 'R'};
inline constexpr std::uint32_t kVertexFramesVersion = 1;

/// A deforming object's vertex positions, frame by frame (a side file's contents).
struct VertexFrames {
  std::uint32_t vertex_count = 0;
  std::size_t frames = 0;
  std::vector<Vec3> positions;  ///< frames x vertex_count: frame 0's vertices, then frame 1's...

  [[nodiscard]] std::span<const Vec3> frame(std::size_t f) const {
    return {positions.data() + f * vertex_count, vertex_count};
  }
};

struct SceneObject {
  std::string name;
  std::filesystem::path mesh;  ///< as resolved against the scene folder
  std::string mesh_text;       ///< as written in the file
  Scalar scale = 1;
  std::vector<Transform> poses;  ///< 1 (static) or `frames`
  /// Deforming objects: the side file ("vertex_frames"), resolved like `mesh`, and as written.
  std::filesystem::path vertex_file;
  std::string vertex_file_text;
  /// Its contents: set by load_scene (parse_scene opens no file; Scene reads it when unset), or
  /// directly for a scene built in memory (then vertex_file_text names where save writes it).
  std::shared_ptr<const VertexFrames> vertex_frames;
  /// "self_collision": the exact method also tests the object against itself.
  bool self_collision = false;

  [[nodiscard]] const Transform& pose(std::size_t frame) const {
    return poses.size() == 1 ? poses.front() : poses[frame];
  }
  [[nodiscard]] bool deforming() const {
    return vertex_frames != nullptr || !vertex_file_text.empty();
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
/// Reads and parses a scene file, and reads the side files of its deforming objects
/// (load_vertex_frames). Throws SceneError.
ANTCD_SCENE_API SceneDescription load_scene(const std::filesystem::path& path);
/// Serialises a scene (mesh paths as in mesh_text) and writes it atomically. Throws Error. Side
/// files are not written (save_vertex_frames).
ANTCD_SCENE_API void save_scene(const SceneDescription& scene, const std::filesystem::path& path);

/// Reads the side file of every deforming object of `scene` whose vertex_frames is unset, and
/// checks its frame count against the scene's. `source` (the scene file) starts every error.
/// Throws SceneError naming the object, the side file and the problem (see the file comment).
ANTCD_SCENE_API void load_vertex_frames(SceneDescription& scene, const std::string& source);
/// Reads one side file (layout in the file comment). Throws SceneError naming `path`.
ANTCD_SCENE_API VertexFrames read_vertex_frames(const std::filesystem::path& path);
/// Decodes a side file's bytes; errors as read_vertex_frames, named `source`.
ANTCD_SCENE_API VertexFrames parse_vertex_frames(std::span<const std::uint8_t> bytes,
                                                 const std::string& source);
/// The side file's bytes for `frames`. Throws ArgumentError when positions.size() is not
/// vertex_count x frames, a count is 0 or a position is not finite.
ANTCD_SCENE_API std::string vertex_frames_bytes(const VertexFrames& frames);
/// Writes vertex_frames_bytes(frames) to `path` atomically (temporary file, then rename).
ANTCD_SCENE_API void save_vertex_frames(const VertexFrames& frames,
                                        const std::filesystem::path& path);
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

/// A self pair of a frame: an object with self_collision whose mesh intersects itself there.
struct SelfPairs {
  std::uint32_t object = 0;
  /// SelfIntersectionResult::pairs (self.hpp): mesh triangle indices {a, b}, a < b, sorted.
  std::vector<std::array<std::uint32_t, 2>> triangles;
};

struct FrameResult {
  std::size_t frame = 0;
  /// Colliding object pairs (i < j, object indices), sorted; exact method: also the self pair
  /// (i, i) of each self_collision object that intersects itself (sorted with the others, so just
  /// before the pairs (i, j)).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  /// Exact method, discrete frames: the triangle pairs of each self pair of `pairs`, in the same
  /// order (continuous frames: empty, see the file comment).
  std::vector<SelfPairs> self_pairs;
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
  /// fails on one), and SceneError naming the object and its side file when a deforming object's
  /// vertex frames cannot be read or do not fit (frame count, vertex count of the loaded mesh, a
  /// mesh with zero-area triangles, positions not finite once scaled), so a frame never fails on
  /// them either.
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
  /// The object's Model as built from its mesh file (scaled). For a deforming object: its rest
  /// shape, the mesh file's positions; run_frame queries a copy refitted to each frame's vertices
  /// (SceneObject::vertex_frames).
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
