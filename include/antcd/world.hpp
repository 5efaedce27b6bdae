// antcd/world.hpp — a live collision world: objects that an application adds, moves and removes
// frame by frame, and the queries it asks each frame ("what touches what now", ray casts).
//
// Conventions
// - Objects: each object is a shared, immutable Model (std::shared_ptr<const Model>, so many
//   objects may share one hierarchy; a deforming object gets its own, see below), a pose (p_world =
//   R p_model + t, see math.hpp), a name and a user tag (free for the application; antcd only
//   reports them), a collision group and a mask.
// - Handles: add() returns an ObjectId. It stays valid until that object is removed; a removed
//   object's id is never valid again (slots are reused with a new generation), so a stale id is
//   reported as an error, never silently aliased to another object.
// - Filtering: a pair (a, b) is considered only when (a.group & b.mask) != 0 and
//   (b.group & a.mask) != 0, and the pair was not ignored with ignore_pair(). Defaults (group 1,
//   mask all bits) let everything collide.
// - Results are exact: the broad phase only discards pairs whose bounding volumes are provably
//   farther apart than the query distance; every reported pair comes from exact triangle tests
//   (collide.hpp), with collide()'s meaning of touching and of delta.
// - Order: results are deterministic and independent of the thread count and of the broad phase's
//   internal shape: pairs are sorted by (a, b) in ObjectId order with a < b, single-object results
//   by the other object's id, ray hits by (distance, object, triangle).
// - Threads: mutating member functions (add, remove, set_pose, set_poses, set_vertices,
//   set_filter, ignore_pair, set_poses_continuous, set_motion_continuous) must not run concurrently
//   with anything else on the same World. Every const member function (all queries) may run from
//   any number of threads at once between mutations. Queries spread their work over oneTBB workers
//   of the calling thread's task arena (wrap a call in a tbb::task_arena to bound it); the answer
//   does not depend on how many. A build without oneTBB (ANTCD_USE_TBB=OFF) runs them on the
//   calling thread, with the same answers.
// - Errors: an invalid argument (an unknown or removed ObjectId, a non-finite or non-rigid pose, a
//   negative or non-finite distance, a zero ray direction, a null model, a wrong vertex count or
//   a non-finite vertex given to set_vertices) throws ArgumentError (error.hpp) whose message
//   names the function, the argument and the object.
// - Broad phase: a dynamic AABB tree (docs/design.md). Moving an object within its leaf's box
//   costs only the box computation; when few objects leave their boxes, each costs one removal and
//   one insertion (O(log n)) with a fattened box; when many do (a frame of a moving world), one
//   O(n) refit. All-pairs queries traverse the tree against itself. Queries never modify it.
// - Deforming objects (set_vertices): an object's mesh keeps its triangles and gets new vertex
//   positions (cloth, a sagging sheet, a skinned part). A Model given to add() is shared and
//   never changed by the World, so the first set_vertices() on an object copies its Model into a
//   private one of the object's (copy on first write) and refits that copy (Model::refit: O(n),
//   the hierarchy keeps its topology); later calls refit the private copy in place. Memory: one
//   whole Model per deforming object (mesh and hierarchy, its BvhStats::memory_bytes: about what
//   the shared one costs, per object, however many objects shared it), counted in
//   memory_bytes(); rigid objects still share theirs. A pointer from model_ptr() is never changed
//   under its holder: while one is held, the next set_vertices() copies again instead of
//   refitting in place. A reference from model() is the object's current Model: it sees the new
//   vertices of an in-place refit, and is valid until the object's next set_vertices() or
//   remove() (a copy may replace the Model it refers to). After set_vertices() every query answers
//   as on a World whose object was added with Model(moved mesh) at the same pose (only costs
//   differ).
// - Unchanged pairs: collide_all() and pairs_within() keep, from one call to the next, the
//   narrow-phase answer (colliding or not, its contacts; a self pair's triangle pairs) of every
//   pair they tested whose two objects had not changed since the call before, and answer such a
//   pair from it again while neither object changes and the request is the same (every field of
//   CollisionRequest equal; pairs_within(d) is the request {delta = d}). An object changes when it
//   is added, given a pose (set_pose/set_poses/set_poses_continuous, even to the pose it had: poses
//   are not compared) or new vertices (set_vertices, set_motion_continuous); a removed id's slot
//   gets new stamps, so a re-added object never meets an old answer. Filters (set_filter,
//   ignore_pair) are applied before the kept answers are looked at, so they need no invalidation.
//   The answers are bit-identical to a fresh World's (collide() is deterministic); only the cost
//   differs: a static pair costs a look-up and a copy of its contacts instead of a traversal. One
//   request's answers are kept (a call with another request replaces them), only for pairs of
//   unchanged objects, so a static pair is tested on the first two calls and reused from the third.
//   Memory: 80 bytes per kept pair (sizeof) plus its contacts (sizeof(Contact) = 80 bytes each; a
//   boolean request keeps one), counted in memory_bytes(). Threads: the kept answers are taken by
//   one query at a time (an atomic flag); a concurrent query, or one nested in a oneTBB task of
//   another, runs without them and gets the same answer.
// - Self-collision: an object added with ObjectOptions::self_collision = true is also tested
//   against itself by collide_all(), with antcd::self_intersections (self.hpp: exact; two
//   triangles sharing a vertex or an edge count only where they meet beyond it). A self pair is
//   reported as (id, id), sorted with the others (so just before the pairs (id, b), b > id), with
//   its triangle pairs in PairContacts::self_pairs. Groups, masks and ignored pairs do not apply to
//   it (the option alone decides), nor does request.delta (a self pair is a self-intersection,
//   never a near miss); other queries (pairs_within, collide_object, nearest, candidates) report
//   distinct objects only.
#pragma once

#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/export.hpp>
#include <antcd/sweep.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace antcd {

namespace detail {}  // namespace detail

/// A handle to an object of a World. Compares and orders by (slot, generation).
struct ObjectId {
  std::uint32_t slot = UINT32_MAX;
  std::uint32_t generation = 0;

  friend auto operator<=>(const ObjectId&, const ObjectId&) = default;
};

struct ObjectOptions {
  std::string name;            ///< reported in errors; need not be unique
  std::uint64_t user_tag = 0;  ///< free for the application
  std::uint32_t group = 1;     ///< the bits this object belongs to
  std::uint32_t mask = ~0U;    ///< the groups it may collide with
  /// collide_all() also tests the object against itself (see "Self-collision" above).
  bool self_collision = false;
  /// For set_vertices(): rebuild the object's hierarchy when its refitted volumes have grown
  /// looser than this (Model::refit's rebuild_above, Model::refit_growth()); 0: never (refit
  /// only). >= 0 (add() throws ArgumentError otherwise).
  double rebuild_above = 0;
};

struct WorldOptions {
  /// Fattening of the broad phase's boxes: each side grows by this fraction of the object's
  /// bounding-sphere radius. Larger: fewer tree updates for moving objects, more candidate pairs.
  Scalar fat_fraction = 0.1;
};

/// An unordered pair of objects, a < b.
struct ObjectPair {
  ObjectId a;
  ObjectId b;
  friend auto operator<=>(const ObjectPair&, const ObjectPair&) = default;
};

/// A colliding pair with what collide() reported for it: contacts[k].triangle_a indexes a's mesh.
/// A self pair (a == b, an object with ObjectOptions::self_collision that intersects itself) has
/// no contacts; its intersecting triangle pairs are in self_pairs.
struct PairContacts {
  ObjectId a;
  ObjectId b;
  std::vector<Contact> contacts;  ///< boolean query: the one contact found; all_contacts: every one
  /// Self pair only: SelfIntersectionResult::pairs of the object's model (mesh triangle indices,
  /// i < j, sorted). Boolean query: the one pair of first_only; all_contacts: every pair (the
  /// first max_contacts of them when that is set). Empty for a pair of two objects.
  std::vector<std::array<std::uint32_t, 2>> self_pairs;
};

/// One object touched by a query object: contacts[k].triangle_a indexes the QUERY's mesh and
/// triangle_b this object's.
struct ObjectContacts {
  ObjectId object;
  std::vector<Contact> contacts;
};

/// Which objects a query about something outside the world may meet (same rule as between
/// objects: (group & object.mask) and (object.group & mask) both non-zero).
struct QueryFilter {
  std::uint32_t group = ~0U;
  std::uint32_t mask = ~0U;
};

/// A ray: the points origin + s * direction / |direction| for 0 <= s <= max_distance.
struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();  ///< non-zero; need not be unit
  Scalar max_distance = std::numeric_limits<Scalar>::infinity();
};

struct RayHit {
  ObjectId object;
  std::uint32_t triangle = 0;  ///< triangle index in the object's mesh
  Scalar distance = 0;         ///< along the ray, world units
  Vec3 point = Vec3::Zero();   ///< world frame
  Vec3 normal = Vec3::Zero();  ///< unit geometric normal of the triangle, world frame, facing the
                               ///< ray (normal . direction <= 0)
};

/// What a nearest query measures between two objects (or an object and a query model).
struct NearestRequest {
  /// A pair of two CLOSED models is measured by its signed distance (distance.hpp: minus the
  /// penetration depth when the solids overlap, nested solids included; FCL's convention, which
  /// trimesh's manager reports); a pair with an open model by its surface distance. false: the
  /// surface distance for every pair (never negative).
  bool signed_distance = false;
};

/// The answer of a nearest query: the pair and distance() of it, with A = object a's model and
/// B = object b's (nearest_to: B = the query model, b left default).
struct NearestPair {
  ObjectId a;
  ObjectId b;
  DistanceResult result;
};

/// Ray against one posed model: every hit triangle (closed triangles; a ray lying in a triangle's
/// plane does not hit it), sorted by (distance, triangle). Thread-safe. `object` is left default.
ANTCD_API std::vector<RayHit> raycast_all(const Model& model, const Transform& pose,
                                          const Ray& ray);
/// The nearest hit of raycast_all (ties: smallest triangle index), or nothing.
ANTCD_API std::optional<RayHit> raycast(const Model& model, const Transform& pose, const Ray& ray);

// ---- continuous motion (src/world/continuous.cpp) ----
//
// Motion: between the current poses (t = 0) and new ones (t = 1) each object moves as in
// antcd/ccd.hpp (translation linear, rotation at constant angular velocity about its model
// origin); objects not given a new pose stay put. A pair's time of impact and its guarantees are
// antcd::sweep's (sweep.hpp): conservative (never a missed contact, toi <= the true first time the
// surfaces come within request.min_separation), proven or tolerance-decided as flagged.
// Broad phase: each object's swept box is the box of its world boxes at both poses, grown by
// r theta^2 / 8 (r: the model's radius about its origin, theta: the rotation angle; the most a
// point on a slerped arc strays from the straight line between its end points) and a rounding
// allowance, so it holds the object at every t; only pairs whose swept boxes come within
// min_separation are swept. Pairs of two unmoved objects count too (toi 0 when they touch).
// Cost: O(n log n) to fit the swept boxes of all n objects, then one sweep per candidate pair
// (spread over oneTBB workers like the other queries).

/// A pair that comes within min_separation during the motion, and antcd::sweep's answer for it.
struct PairToi {
  ObjectId a;  ///< a < b
  ObjectId b;
  /// hit is true; toi, contact (triangle_a indexes a's mesh; world frame at toi), flags.
  SweepResult sweep;
};

// ---- continuous motion of deforming objects (src/world/deform_motion.cpp) ----
//
// Motion (World::sweep_motion): over t in [0, 1] each object moves from its current state (t = 0)
// to a new one (t = 1). An object given only a new pose (or nothing: it stays put) is rigid this
// step and moves as in sweep_poses (ccd.hpp). An object given new vertices (VertexMotion: model
// frame, same count and order as set_vertices, and a new pose or its current one) deforms: its
// WORLD vertices move linearly, x_i(t) = (1 - t) pose0 V0[i] + t pose1 V1[i], V0 its current
// vertices and pose0 its current pose (the convention of deform_ccd.hpp's deform_sweep, which this
// call uses; it is not a rigid motion of the model frame even when V0 = V1 and the pose turns).
// Broad phase: a deforming object's swept box is the box of its world vertices at both ends
// (linear paths stay in it; padded for rounding); rigid objects' as in sweep_poses. Pairs whose
// swept boxes come within request.min_separation are tested:
// - two rigid objects: antcd::sweep, as sweep_poses (kind RigidSweep);
// - a pair with a deforming object: first the exact discrete test at t = 0, collide() of the two
//   current Models at their current poses with delta = min_separation (kind StartContact, toi 0);
//   if it finds nothing, deform_sweep (deform_ccd.hpp) of the world vertices against the other's
//   world vertices (deforming) or its two poses (rigid) (kind Deform, toi deform_sweep's);
// - every object with ObjectOptions::self_collision, against itself, pair (id, id): first
//   self_intersections() of its current Model (exact, kind StartContact, toi 0); if none, a
//   deforming object gets deform_sweep(model, world V0, world V1) (kind Deform; self primitive
//   pairs as deform_ccd.hpp defines them), and a rigid one, whose shape a rigid motion keeps, with
//   min_separation > 0 its model-frame vertices held still (deform_sweep(model, V, V), toi 0).
//   Groups, masks and ignored pairs do not apply to self pairs (as collide_all).
// Why the test at t = 0: deform_sweep finds vertex-face and edge-edge contacts only, so surfaces
// that already cross at t = 0 (a sheet resting 2 mm into a roller, with crossing edges and no
// vertex inside) would be missed. With it the answer is conservative: two closed triangle sets
// apart (or not crossing) at t = 0 that come within min_separation later first do so where a
// vertex meets a triangle or an edge meets an edge (the distance of disjoint triangles is taken
// by such a pair, and crossing surfaces were first touching), which deform_sweep never misses.
// Guarantees: every pair whose surfaces come within min_separation at some t in [0, 1] (self:
// intersect themselves at t = 0, or a self primitive pair comes within min_separation) is
// reported, with toi <= the true first such time (a miss is a proof); tolerance_decided as
// sweep.hpp / deform_ccd.hpp say. Rigid-rigid pairs are exactly sweep_poses' answers.
// Threads: const and thread-safe like sweep_poses; pairs are spread over oneTBB workers, and the
// answer is the same at any thread count (deform_ccd.hpp, "Determinism"; also for pairs whose
// primitive.budget_exhausted is set, common against a turning rigid object). Memory:
// two world-frame copies of each deforming object's vertices for the call, plus deform_sweep's O(n)
// per pair being tested.

/// New vertices of a deforming object for sweep_motion: model frame (as set_vertices), one per
/// vertex of its current mesh, in order. The span must stay valid for the call.
struct VertexMotion {
  ObjectId id;
  std::span<const Vec3> vertices;
};

/// How a continuous-motion pair was decided (see the block above).
enum class MotionToiKind : std::uint8_t {
  RigidSweep = 0,    ///< two rigid objects: antcd::sweep (MotionToi::sweep)
  StartContact = 1,  ///< a deforming pair or a self pair in contact at t = 0 (exact discrete test)
  Deform = 2,        ///< deform_sweep found it (MotionToi::primitive)
};

/// A pair that comes within min_separation during a sweep_motion, and what found it.
struct MotionToi {
  ObjectId a;  ///< a < b; a == b: a self pair
  ObjectId b;
  MotionToiKind kind = MotionToiKind::RigidSweep;
  Scalar toi = 0;  ///< in [0, 1]
  /// The hit rests on a tolerance, not a proof (sweep.hpp / deform_ccd.hpp); false for
  /// StartContact.
  bool tolerance_decided = false;
  /// World point at toi: RigidSweep: sweep.contact.point; StartContact: the triangle pair's common
  /// point, or the midpoint of its closest points (collide()'s Contact::point); Deform: the
  /// vertex's position at toi (vertex-face), or the midpoint of the two edges' closest points
  /// at toi (edge-edge). Reported for display; the certified numbers are toi and the pair.
  Vec3 point = Vec3::Zero();
  /// RigidSweep: antcd::sweep's result (hit true; contact's triangle_a indexes a's mesh).
  SweepResult sweep;
  /// StartContact: {triangle of a, triangle of b} (a self pair: {i, j}, i < j), mesh indices.
  std::array<std::uint32_t, 2> triangles = {0, 0};
  /// Deform: the primitive pair with a's mesh as the first model (vertex_in_first: the vertex is
  /// a's; edge-edge: indices[0..1] is a's edge). Self pairs as deform_ccd.hpp's self pairs.
  DeformPair primitive;
};

class ANTCD_API World {
 public:
  explicit World(const WorldOptions& options = {});
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  // ---- mutations (not concurrent with anything else on this World) ----

  /// Adds an object; O(log n).
  ObjectId add(std::shared_ptr<const Model> model, const Transform& pose,
               ObjectOptions options = {});
  /// Removes an object; its id becomes invalid. O(log n + ignored pairs of the object).
  void remove(ObjectId id);
  void set_pose(ObjectId id, const Transform& pose);
  /// ids[k] gets poses[k]. Checks every argument first: on error nothing is changed.
  void set_poses(std::span<const ObjectId> ids, std::span<const Transform> poses);
  /// New model-frame positions for the vertices of object `id`'s mesh (same count and order, same
  /// triangles; see "Deforming objects" above): its hierarchy is refitted (rebuilt when it grew
  /// looser than its options' rebuild_above) and its broad-phase box updated as set_poses()
  /// updates a moved object's. Throws ArgumentError naming the function, the argument and the
  /// object for an unknown or removed id, a wrong vertex count, a non-finite vertex (its index),
  /// or a triangle that had zero area when the object's Model was built and has an area now (it
  /// is not in the hierarchy: add the object again with a Model built from the new mesh). On a
  /// throw nothing is changed. O(n) in the object's vertices (plus one copy of its Model the
  /// first time, and whenever a model_ptr() of it is held).
  void set_vertices(ObjectId id, std::span<const Vec3> vertices);
  void set_filter(ObjectId id, std::uint32_t group, std::uint32_t mask);
  /// Excludes (ignored = true) or re-admits the pair from every pair query.
  void ignore_pair(ObjectId a, ObjectId b, bool ignored = true);

  // ---- inspection ----

  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] bool contains(ObjectId id) const;
  /// Every live object, in id order.
  [[nodiscard]] std::vector<ObjectId> objects() const;
  [[nodiscard]] const Model& model(ObjectId id) const;
  [[nodiscard]] const std::shared_ptr<const Model>& model_ptr(ObjectId id) const;
  [[nodiscard]] const Transform& pose(ObjectId id) const;
  [[nodiscard]] const ObjectOptions& options(ObjectId id) const;
  [[nodiscard]] bool pair_ignored(ObjectId a, ObjectId b) const;
  /// Whether the filters let a and b collide (groups, masks, ignored pairs).
  [[nodiscard]] bool may_collide(ObjectId a, ObjectId b) const;
  /// Heap bytes of the world's own structures (objects, tree, and the private Models of deforming
  /// objects, by their BvhStats::memory_bytes; not the shared Models).
  [[nodiscard]] std::size_t memory_bytes() const;

  // ---- queries (const, thread-safe between mutations) ----

  /// Broad phase only: the admitted pairs whose root bounding volumes (sphere and OBB) are within
  /// `delta` >= 0, sorted. A superset of the colliding pairs at that delta.
  [[nodiscard]] std::vector<ObjectPair> candidate_pairs(Scalar delta = 0) const;
  /// candidate_pairs(delta) written into `out` (cleared first, its storage reused): the same pairs
  /// in the same order, for a caller that asks every frame (the scene runner). Allocation-free once
  /// `out` and this thread's working storage have grown to the frame's size. Const and
  /// thread-safe like candidate_pairs, given a distinct `out` per thread.
  void candidate_pairs(Scalar delta, std::vector<ObjectPair>& out) const;
  /// Every admitted pair that collides under `request` (delta, all contacts or boolean), and the
  /// self pair (id, id) of every object with ObjectOptions::self_collision that intersects itself,
  /// sorted by (a, b). A pair of objects unchanged since the previous call is answered from that
  /// call's answer under the same request (see "Unchanged pairs" above).
  [[nodiscard]] std::vector<PairContacts> collide_all(const CollisionRequest& request = {}) const;
  /// The admitted pairs whose meshes come within `distance` >= 0 of each other, sorted (kept
  /// answers as collide_all with the request {delta = distance}).
  [[nodiscard]] std::vector<ObjectPair> pairs_within(Scalar distance) const;
  /// The objects that `id` collides with (admitted pairs only), sorted by id.
  [[nodiscard]] std::vector<ObjectContacts> collide_object(
      ObjectId id, const CollisionRequest& request = {}) const;
  /// The objects that an external model at `pose` collides with, sorted by id.
  [[nodiscard]] std::vector<ObjectContacts> collide_model(const Model& model, const Transform& pose,
                                                          const CollisionRequest& request = {},
                                                          const QueryFilter& filter = {}) const;
  /// Nearest queries. Each answer is the pair of least (distance, a, b) over the pairs it ranges
  /// over (exactly what distance() on every such pair, then a sort, would give: ties go to the
  /// smallest ids), or nothing when there is no pair. Internally a best-first branch and bound
  /// over the broad-phase tree: node pairs in order of the gap between their boxes (a lower bound
  /// of the distance of any pair below them), each distance() bounded by the best distance so far
  /// (DistanceRequest::upper_bound); the search stops when the next gap exceeds it. Runs on the
  /// calling thread; const and thread-safe like every query.
  /// The closest admitted pair of distinct objects, a < b.
  [[nodiscard]] std::optional<NearestPair> nearest_pair(const NearestRequest& request = {}) const;
  /// The object closest to object `id` among those admitted with it (a = id, b = the other).
  [[nodiscard]] std::optional<NearestPair> nearest_object(ObjectId id,
                                                          const NearestRequest& request = {}) const;
  /// The object closest to `model` at `pose` among those `filter` admits (a = that object; the
  /// result's A is the object's model, B the query model). A non-finite pose is an ArgumentError.
  [[nodiscard]] std::optional<NearestPair> nearest_to(const Model& model, const Transform& pose,
                                                      const NearestRequest& request = {},
                                                      const QueryFilter& filter = {}) const;
  /// The closest pair (a of this world, b of `other`) whose groups and masks admit each other
  /// (ignored pairs are per world and do not apply across worlds). `other` may be *this: every
  /// object then also meets itself (distance 0). Not concurrent with mutations of either world.
  [[nodiscard]] std::optional<NearestPair> nearest_pair(const World& other,
                                                        const NearestRequest& request = {}) const;

  /// The nearest hit over every admitted object (ties: smallest object id, then triangle).
  [[nodiscard]] std::optional<RayHit> raycast(const Ray& ray, const QueryFilter& filter = {}) const;
  /// Every hit, sorted by (distance, object, triangle).
  [[nodiscard]] std::vector<RayHit> raycast_all(const Ray& ray,
                                                const QueryFilter& filter = {}) const;

  // ---- continuous motion (see the block above the class; src/world/continuous.cpp) ----

  /// Broad phase of a continuous motion: the admitted pairs whose swept boxes come within
  /// `min_separation` >= 0, sorted. ids[k] moves to new_poses[k]; each id at most once.
  [[nodiscard]] std::vector<ObjectPair> swept_candidate_pairs(std::span<const ObjectId> ids,
                                                              std::span<const Transform> new_poses,
                                                              Scalar min_separation = 0) const;
  /// Every admitted pair whose surfaces come within request.min_separation while ids[k] moves
  /// from its pose to new_poses[k] (the others stay), with its first time of impact, sorted by
  /// (a, b). The World is not changed.
  [[nodiscard]] std::vector<PairToi> sweep_poses(std::span<const ObjectId> ids,
                                                 std::span<const Transform> new_poses,
                                                 const SweepRequest& request = {}) const;
  /// sweep_poses(), then set_poses(ids, new_poses): a mutation. On error nothing is changed.
  std::vector<PairToi> set_poses_continuous(std::span<const ObjectId> ids,
                                            std::span<const Transform> new_poses,
                                            const SweepRequest& request = {});
  /// Broad phase of a motion with deforming objects (sweep_motion's arguments and checks): the
  /// admitted pairs of distinct objects whose swept boxes (a deforming object's: the box of its
  /// world vertices at both ends) come within `min_separation` >= 0, sorted.
  [[nodiscard]] std::vector<ObjectPair> swept_candidate_pairs(
      std::span<const ObjectId> ids, std::span<const Transform> new_poses,
      std::span<const VertexMotion> deforming, Scalar min_separation = 0) const;
  /// Continuous motion with deforming objects (see the block above MotionToi): ids[k] moves to
  /// new_poses[k] and deforming[k].id gets deforming[k].vertices (model frame) at t = 1; each id at
  /// most once in each span. Every pair (and self pair) that comes within request.min_separation,
  /// sorted by (a, b). request.max_iterations bounds the rigid sweeps; deform_sweep gets
  /// min_separation and time_tolerance. Throws ArgumentError naming the function, the argument
  /// and the object: as sweep_poses for ids and poses; for deforming[k]: an unknown id, a repeat,
  /// a wrong vertex count, a non-finite vertex or one whose world position (either end) exceeds
  /// kDeformMaxCoordinate, or a zero-area triangle left out of the object's hierarchy that gains
  /// an area (as set_vertices). The World is not changed.
  [[nodiscard]] std::vector<MotionToi> sweep_motion(std::span<const ObjectId> ids,
                                                    std::span<const Transform> new_poses,
                                                    std::span<const VertexMotion> deforming,
                                                    const SweepRequest& request = {}) const;
  /// sweep_motion(), then set_poses(ids, new_poses) and set_vertices() of each deforming object:
  /// a mutation. Every argument is checked first: on error nothing is changed.
  std::vector<MotionToi> set_motion_continuous(std::span<const ObjectId> ids,
                                               std::span<const Transform> new_poses,
                                               std::span<const VertexMotion> deforming,
                                               const SweepRequest& request = {});

  /// The implementation (opaque; defined inside the library).
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace antcd
