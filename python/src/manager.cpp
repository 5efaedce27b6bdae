// python/src/manager.cpp — see manager.hpp.
#include "manager.hpp"

#include "model_guard.hpp"

#include <algorithm>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <utility>

namespace antcd::python {

namespace {

using Id = ManagedWorld::Id;

Id pack(ObjectId id) { return (static_cast<Id>(id.slot) << 32) | id.generation; }
ObjectId unpack(Id id) {
  return ObjectId{static_cast<std::uint32_t>(id >> 32),
                  static_cast<std::uint32_t>(id & 0xffffffffU)};
}

CollisionRequest request_for(ManagedWorld::Mode mode, Scalar delta) {
  CollisionRequest request;
  request.delta = delta;
  request.all_contacts = mode == ManagedWorld::Mode::Contacts;
  // Closed meshes collide as solids: one wholly inside another collides (no contacts then).
  request.volume = true;
  // Each contact's triangle-pair depth and normal (FCL's mesh semantics), for ContactData.
  request.contact_normals = mode == ManagedWorld::Mode::Contacts;
  return request;
}

CollisionResult as_result(std::vector<Contact> contacts) {
  CollisionResult r;
  r.colliding = true;
  r.contacts = std::move(contacts);
  return r;
}

// World::collide_model reports the query model as side A; the manager reports the world's object
// as side A. Every per-side field of a contact is swapped here and nowhere else.
void swap_sides(std::vector<Contact>& contacts) {
  for (Contact& c : contacts) {
    std::swap(c.triangle_a, c.triangle_b);
    c.normal = -c.normal;  // from B towards A: the sides changed
  }
}

// Two closed meshes: signed distance (-penetration depth when they overlap, nested included), as
// FCL's signed distance that trimesh's manager reports; open meshes: the surface distance.
constexpr NearestRequest kNearest{true};

ManagedWorld::Nearest as_nearest(const std::optional<NearestPair>& n, bool pack_b = true) {
  ManagedWorld::Nearest out;
  if (!n) return out;
  out.found = true;
  out.a = pack(n->a);
  out.b = pack_b ? pack(n->b) : 0;
  out.result = n->result;
  return out;
}

}  // namespace

Id ManagedWorld::add(std::shared_ptr<const Model> model, const Transform& pose) {
  if (!model) throw std::invalid_argument("ManagedWorld::add: null model");
  std::unique_lock lock(mutex_);
  const ModelReadLock model_lock(*model);  // no set_vertices while the World reads it
  const Model& pinned = *model;
  const Id id = pack(world_.add(std::move(model), pose));
  pin_model(pinned);
  return id;
}

ManagedWorld::~ManagedWorld() {
  for (const ObjectId id : world_.objects()) unpin_model(world_.model(id));
}

bool ManagedWorld::remove(Id id) {
  std::unique_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return false;
  const std::shared_ptr<const Model> model = world_.model_ptr(unpack(id));
  world_.remove(unpack(id));
  unpin_model(*model);
  return true;
}

bool ManagedWorld::set_pose(Id id, const Transform& pose) {
  std::unique_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return false;
  world_.set_pose(unpack(id), pose);
  return true;
}

std::size_t ManagedWorld::size() const {
  std::shared_lock lock(mutex_);
  return world_.size();
}

template <class F>
auto ManagedWorld::with_both_locked(const ManagedWorld& other, F&& f) const {
  if (&other == this) {
    std::shared_lock lock(mutex_);
    return f();
  }
  const bool this_first = std::less<const ManagedWorld*>{}(this, &other);
  std::shared_lock first(this_first ? mutex_ : other.mutex_);
  std::shared_lock second(this_first ? other.mutex_ : mutex_);
  return f();
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_internal(Mode mode, Scalar delta) const {
  std::shared_lock lock(mutex_);
  std::vector<Hit> hits;
  for (PairContacts& p : world_.collide_all(request_for(mode, delta))) {
    hits.push_back(Hit{pack(p.a), pack(p.b), as_result(std::move(p.contacts)),
                       world_.model_ptr(p.a), world_.pose(p.a)});
  }
  return hits;
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_single(const Model& model,
                                                            const Transform& pose, Mode mode,
                                                            Scalar delta) const {
  std::shared_lock lock(mutex_);
  const ModelReadLock model_lock(model);  // after the manager's lock, as in add()
  std::vector<Hit> hits;
  for (ObjectContacts& o : world_.collide_model(model, pose, request_for(mode, delta))) {
    swap_sides(o.contacts);
    hits.push_back(Hit{pack(o.object), 0, as_result(std::move(o.contacts)),
                       world_.model_ptr(o.object), world_.pose(o.object)});
  }
  return hits;
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_other(const ManagedWorld& other, Mode mode,
                                                           Scalar delta) const {
  return with_both_locked(other, [&] {
    // Each of the other world's objects against this world's broad phase.
    const CollisionRequest request = request_for(mode, delta);
    std::vector<Hit> hits;
    for (const ObjectId b : other.world_.objects()) {
      for (ObjectContacts& o :
           world_.collide_model(other.world_.model(b), other.world_.pose(b), request)) {
        swap_sides(o.contacts);
        hits.push_back(Hit{pack(o.object), pack(b), as_result(std::move(o.contacts)),
                           world_.model_ptr(o.object), world_.pose(o.object)});
      }
    }
    std::sort(hits.begin(), hits.end(), [](const Hit& p, const Hit& q) {
      return std::pair{p.a, p.b} < std::pair{q.a, q.b};
    });
    return hits;
  });
}

ManagedWorld::Nearest ManagedWorld::distance_internal() const {
  std::shared_lock lock(mutex_);
  return as_nearest(world_.nearest_pair(kNearest));
}

ManagedWorld::Nearest ManagedWorld::distance_object(Id id) const {
  std::shared_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return {};
  return as_nearest(world_.nearest_object(unpack(id), kNearest));
}

ManagedWorld::Nearest ManagedWorld::distance_single(const Model& model,
                                                    const Transform& pose) const {
  std::shared_lock lock(mutex_);
  const ModelReadLock model_lock(model);  // after the manager's lock, as in add()
  return as_nearest(world_.nearest_to(model, pose, kNearest), false);
}

ManagedWorld::Nearest ManagedWorld::distance_other(const ManagedWorld& other) const {
  return with_both_locked(other,
                          [&] { return as_nearest(world_.nearest_pair(other.world_, kNearest)); });
}

}  // namespace antcd::python
