// python/src/manager.hpp — the live set of posed models behind antcd.CollisionManager.
//
// Objects (a shared Model and a pose) are added, moved and removed; queries find colliding
// pairs with a broad phase on world AABBs (of each root OBB, sweep and prune along x) and the exact
// collide() on the survivors. This is the binding's own small world; its interface (add / remove /
// set_pose / collide_*) mirrors what a library-level world offers, so the Python class can be moved
// onto one without changing behaviour.
//
// Thread safety: queries are const and take a shared lock; add / remove / set_pose take an
// exclusive one, so Python threads may query one manager while another moves its objects.
#pragma once

#include <antcd/collide.hpp>

#include <cstdint>
#include <memory>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

namespace antcd::python {

class ManagedWorld {
 public:
  using Id = std::uint64_t;

  /// What a query collects.
  enum class Mode {
    Verdict,   ///< stop at the first colliding pair, with its first contact
    Pairs,     ///< every colliding pair, each with its first contact
    Contacts,  ///< every colliding pair with every contact
  };

  struct Hit {
    Id a = 0;  ///< this world's object (the query model for collide_single: unused)
    Id b = 0;  ///< the other object (collide_internal: a later-added one; collide_other: the other world's)
    CollisionResult result;  ///< A = object a's model, B = object b's
    std::shared_ptr<const Model> model_a;  ///< object a's model and pose at query time
    Transform pose_a;
  };

  /// Adds an object; ids are never reused.
  Id add(std::shared_ptr<const Model> model, const Transform& pose);
  /// False if there is no such object.
  bool remove(Id id);
  bool set_pose(Id id, const Transform& pose);
  [[nodiscard]] std::size_t size() const;

  /// Colliding pairs among this world's objects, a added before b. Sorted by (a, b).
  [[nodiscard]] std::vector<Hit> collide_internal(Mode mode, Scalar delta = 0) const;
  /// Objects colliding with `model` at `pose`: Hit::a is the object, B is `model`. Sorted by a.
  [[nodiscard]] std::vector<Hit> collide_single(const Model& model, const Transform& pose, Mode mode,
                                                Scalar delta = 0) const;
  /// Colliding pairs (this world's a, other's b). Sorted by (a, b). `other` may be *this.
  [[nodiscard]] std::vector<Hit> collide_other(const ManagedWorld& other, Mode mode, Scalar delta = 0) const;

 private:
  struct Object {
    Id id = 0;
    std::shared_ptr<const Model> model;
    Transform pose;
    Aabb box;  ///< world AABB of the root OBB
  };
  /// Candidate pairs (indices into `left` and `right`) whose boxes overlap.
  static std::vector<std::pair<std::size_t, std::size_t>> overlapping(const std::vector<Object>& left,
                                                                      const std::vector<Object>* right,
                                                                      Scalar margin);
  static std::vector<Hit> narrow(const std::vector<Object>& left, const std::vector<Object>& right,
                                 std::vector<std::pair<std::size_t, std::size_t>> candidates, Mode mode,
                                 Scalar delta);
  [[nodiscard]] std::vector<Hit> collide_other_locked(const ManagedWorld& other, Mode mode, Scalar delta) const;

  std::vector<Object> objects_;
  std::unordered_map<Id, std::size_t> index_;
  Id next_id_ = 0;
  mutable std::shared_mutex mutex_;
};

/// World-frame AABB of a model's root OBB at `pose`.
Aabb world_box(const Model& model, const Transform& pose);

}  // namespace antcd::python
