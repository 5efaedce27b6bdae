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
// Thread safety: the World forbids mutations concurrent with anything else, so queries take a
// shared lock and add / remove / set_pose an exclusive one: Python threads may query one manager
// while another moves its objects. Every Model added is pinned (model_guard.hpp) until its object
// is removed or the manager destroyed: the broad phase keeps boxes of its positions at add time, so
// Model.set_vertices refuses it meanwhile. Lock order: this manager's lock, then a Model's
// (model_guard.hpp) — add() and the *_single queries take them so, set_vertices takes a Model's
// alone — so a set_vertices waiting at a Model's gate cannot close a cycle with them.
#pragma once

#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/world.hpp>

#include <cstdint>
#include <memory>
#include <shared_mutex>
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
    Id b = 0;  ///< the other object (collide_internal: a later-added one; collide_other: the other
               ///< world's; collide_single: 0)
    CollisionResult result;  ///< A = object a's model, B = object b's (collide_single: the query's)
    std::shared_ptr<const Model> model_a;  ///< object a's model and pose at query time
    Transform pose_a;
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

  /// Adds an object and pins its Model (under the Model's shared lock).
  Id add(std::shared_ptr<const Model> model, const Transform& pose);
  /// False if there is no such object. Unpins its Model.
  bool remove(Id id);
  bool set_pose(Id id, const Transform& pose);
  [[nodiscard]] std::size_t size() const;

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

  World world_;
  mutable std::shared_mutex mutex_;
};

}  // namespace antcd::python
