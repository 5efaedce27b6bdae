// python/src/manager.hpp — the engine behind antcd.CollisionManager: an antcd::World guarded by a
// reader/writer lock, with the queries trimesh's manager asks for.
//
// Objects (a shared Model and a pose) are added, moved and removed through the World (its dynamic
// AABB tree is the broad phase); collision queries are the World's (collide_all, collide_model)
// with CollisionRequest::volume (a closed object wholly inside another collides), and so are the
// minimum-distance queries (nearest_pair, nearest_object, nearest_to with signed distances).
//
// Ids: an ObjectId packed into 64 bits (slot << 32 | generation). The World never hands out the
// same (slot, generation) twice, so an id is never reused, even after removal.
//
// Deforming objects: set_vertices and set_motion_continuous give an object new vertex positions
// through World::set_vertices, which copies the object's Model into a private one on the first call
// (the Model given to add() is shared and never changed) and afterwards refits that copy in place,
// unless a pointer to it is held (a Python Model object of a query's result: it then copies again,
// so a held Model never changes under its holder). An object's current Model is world_.model_ptr().
//
// Thread safety: the World forbids mutations concurrent with anything else, so queries (and
// sweep_motion) take a shared lock and add / remove / set_pose / set_vertices /
// set_motion_continuous an exclusive one: Python threads may query one manager while another moves
// or deforms its objects. Pins (model_guard.hpp): the Model each object currently uses is pinned,
// from add() (or from the set_vertices that made it the object's) until its object is removed, the
// object's next copy replaces it, or the manager is destroyed: the broad phase keeps boxes of its
// positions, so Model.set_vertices refuses it meanwhile (a result's Model too: it is the World's).
// A Model the object no longer uses is unpinned (the one given to add(), after the first
// set_vertices, is again the caller's to change). Lock order: this manager's lock, then a Model's
// (model_guard.hpp) — add(), set_vertices and the *_single queries take them so, Model.set_vertices
// takes a Model's alone — so a Model.set_vertices waiting at a Model's gate cannot close a cycle
// with them.
#pragma once

#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/world.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <span>
#include <unordered_set>
#include <utility>
#include <vector>

namespace antcd::python {

class ManagedWorld {
 public:
  using Id = std::uint64_t;

  /// What a collision query collects.
  enum class Mode {
    Verdict,   ///< whether any pair collides (one contact per colliding pair)
    Pairs,     ///< every colliding pair, each with its first contact
    Contacts,  ///< every colliding pair with every contact
  };

  struct Hit {
    Id a = 0;  ///< this world's object (collide_single: the object touched)
    Id b = 0;  ///< the other object (collide_internal: a later-added one, or a itself for a self
               ///< pair; collide_other: the other world's; collide_single: 0)
    /// A = object a's model, B = object b's (collide_single: the query's). A self pair (a == b,
    /// an object added with self_collision): one contact per intersecting triangle pair (i, j),
    /// i < j, as World::collide_all's self_pairs, with a common point (world frame), distance 0,
    /// and the pair's triangle_penetration depth and normal (Mode::Contacts only).
    CollisionResult result;
    std::shared_ptr<const Model> model_a;  ///< object a's model and pose at query time
    Transform pose_a;
    std::shared_ptr<const Model> model_b;  ///< object b's (null for collide_single)
    Transform pose_b;
  };

  /// The arguments of sweep_motion / set_motion_continuous: objects given new poses, objects
  /// given new model-frame vertices (World::sweep_motion's ids / new_poses / deforming).
  struct Motion {
    std::vector<Id> pose_ids;
    std::vector<Transform> poses;
    std::vector<Id> vertex_ids;
    std::vector<std::vector<Vec3>> vertices;
    SweepRequest request;
  };

  /// One pair of a continuous motion: World::sweep_motion's MotionToi with packed ids.
  struct MotionHit {
    Id a = 0;  ///< a added before b; a == b: a self pair
    Id b = 0;
    MotionToi toi;  ///< its a / b left as the World gave them
  };

  /// The closest pair of a minimum-distance query.
  struct Nearest {
    bool found = false;     ///< false when there is no pair (then distance is +inf)
    Id a = 0;               ///< this world's object
    Id b = 0;               ///< the other object (distance_single: 0)
    DistanceResult result;  ///< A = object a's model, B = object b's (or the query's)
  };

  ManagedWorld() = default;
  ManagedWorld(const ManagedWorld&) = delete;
  ManagedWorld& operator=(const ManagedWorld&) = delete;
  /// Unpins every object's Model.
  ~ManagedWorld();

  /// Adds an object and pins its Model (under the Model's shared lock). options as World::add's
  /// (name: how the World's errors name it; self_collision; rebuild_above).
  Id add(std::shared_ptr<const Model> model, const Transform& pose, ObjectOptions options = {});
  /// False if there is no such object. Unpins its Model.
  bool remove(Id id);
  bool set_pose(Id id, const Transform& pose);
  /// World::set_vertices (model-frame positions), then the pins moved to the Model the object uses
  /// now. False if there is no such object; ArgumentError as World::set_vertices (nothing changed).
  bool set_vertices(Id id, std::span<const Vec3> vertices);
  [[nodiscard]] std::size_t size() const;
  /// The object's current Model (nothing when there is no such object). Holding it makes the next
  /// set_vertices of the object copy rather than refit in place.
  [[nodiscard]] std::shared_ptr<const Model> model(Id id) const;
  /// The object's vertex count (nothing when there is no such object).
  [[nodiscard]] std::optional<std::size_t> vertex_count(Id id) const;

  /// World::sweep_motion: every pair (and self pair) that comes within
  /// motion.request.min_separation while the objects move and deform; the world is not changed.
  /// ArgumentError as World::sweep_motion.
  [[nodiscard]] std::vector<MotionHit> sweep_motion(const Motion& motion) const;
  /// World::set_motion_continuous: sweep_motion, then the poses and vertices applied (pins moved as
  /// in set_vertices). On error nothing is changed.
  std::vector<MotionHit> set_motion_continuous(const Motion& motion);

  /// Colliding pairs among this world's objects, a added before b (ObjectId order). Sorted by (a,
  /// b).
  [[nodiscard]] std::vector<Hit> collide_internal(Mode mode, Scalar delta = 0) const;
  /// Objects colliding with `model` at `pose`: Hit::a is the object, B is `model`. Sorted by a.
  [[nodiscard]] std::vector<Hit> collide_single(const Model& model, const Transform& pose,
                                                Mode mode, Scalar delta = 0) const;
  /// Colliding pairs (this world's a, other's b), sorted by (a, b). `other` may be *this (every
  /// object then also meets itself, as two managers holding the same objects would).
  [[nodiscard]] std::vector<Hit> collide_other(const ManagedWorld& other, Mode mode,
                                               Scalar delta = 0) const;

  /// The closest pair of distinct objects of this world: signed distance (distance.hpp,
  /// signed_distance: -penetration depth when two closed objects overlap) for closed pairs, the
  /// surface distance otherwise.
  [[nodiscard]] Nearest distance_internal() const;
  /// The object closest to object `id` (a = id, b = the other); not found when `id` is not an
  /// object or there is no other.
  [[nodiscard]] Nearest distance_object(Id id) const;
  /// The object closest to `model` at `pose`.
  [[nodiscard]] Nearest distance_single(const Model& model, const Transform& pose) const;
  /// The closest pair (this world's a, other's b); `other` may be *this.
  [[nodiscard]] Nearest distance_other(const ManagedWorld& other) const;

 private:
  /// Runs f() with shared locks on this world and `other` (in address order, so two threads
  /// querying a-vs-b and b-vs-a while writers wait cannot deadlock).
  template <class F>
  auto with_both_locked(const ManagedWorld& other, F&& f) const;

  /// Runs mutate() (which calls World::set_vertices on `ids`) and then moves the pins of each of
  /// those objects whose Model it replaced. The caller holds the exclusive lock.
  template <class F>
  auto deform(std::span<const Id> ids, F&& mutate);

  World world_;
  /// Objects whose Model is a private copy of the World's (after their first set_vertices).
  std::unordered_set<Id> private_models_;
  mutable std::shared_mutex mutex_;
};

}  // namespace antcd::python
