// python/src/manager.cpp — see manager.hpp.
#include "manager.hpp"

#include "model_guard.hpp"

#include <antcd/geometry.hpp>

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

// A self pair's triangle pairs (i, j) as contacts of the model with itself: a point the two
// triangles share (world frame), distance 0, and the pair's depth and normal (triangle_penetration,
// as request_for's contact_normals gives two objects' pairs).
CollisionResult self_result(const Model& model, const Transform& pose,
                            const std::vector<std::array<std::uint32_t, 2>>& pairs) {
  const std::vector<Vec3>& v = model.mesh().vertices;
  const std::vector<TriangleIndices>& t = model.mesh().triangles;
  std::vector<Contact> contacts;
  contacts.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    const Vec3 &a0 = v[t[i][0]], &a1 = v[t[i][1]], &a2 = v[t[i][2]];
    const Vec3 &b0 = v[t[j][0]], &b1 = v[t[j][1]], &b2 = v[t[j][2]];
    const geometry::TriangleDistance d = geometry::triangle_distance(a0, a1, a2, b0, b1, b2);
    const geometry::TrianglePenetration p = geometry::triangle_penetration(a0, a1, a2, b0, b1, b2);
    Contact c;
    c.triangle_a = i;
    c.triangle_b = j;
    c.point = pose.apply(0.5 * (d.pa + d.pb));
    c.distance = d.distance;
    c.normal = pose.apply_vector(p.normal);
    c.depth = p.depth;
    contacts.push_back(c);
  }
  return as_result(std::move(contacts));
}

std::vector<ObjectId> unpack_all(std::span<const Id> ids) {
  std::vector<ObjectId> out;
  out.reserve(ids.size());
  for (const Id id : ids) out.push_back(unpack(id));
  return out;
}

// World::sweep_motion's arguments from a Motion (the spans point into `motion`).
struct MotionArgs {
  std::vector<ObjectId> ids;
  std::vector<VertexMotion> deforming;

  explicit MotionArgs(const ManagedWorld::Motion& motion) : ids(unpack_all(motion.pose_ids)) {
    if (motion.pose_ids.size() != motion.poses.size() ||
        motion.vertex_ids.size() != motion.vertices.size()) {
      throw std::invalid_argument("ManagedWorld: motion ids and values differ in count");
    }
    for (std::size_t k = 0; k < motion.vertex_ids.size(); ++k) {
      deforming.push_back(VertexMotion{unpack(motion.vertex_ids[k]), motion.vertices[k]});
    }
  }
};

std::vector<ManagedWorld::MotionHit> as_motion_hits(std::vector<MotionToi> tois) {
  std::vector<ManagedWorld::MotionHit> out;
  out.reserve(tois.size());
  for (MotionToi& t : tois) out.push_back({pack(t.a), pack(t.b), std::move(t)});
  return out;
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

Id ManagedWorld::add(std::shared_ptr<const Model> model, const Transform& pose,
                     ObjectOptions options) {
  if (!model) throw std::invalid_argument("ManagedWorld::add: null model");
  std::unique_lock lock(mutex_);
  const ModelReadLock model_lock(*model);  // no set_vertices while the World reads it
  const Model& pinned = *model;
  const Id id = pack(world_.add(std::move(model), pose, std::move(options)));
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
  private_models_.erase(id);
  return true;
}

bool ManagedWorld::set_pose(Id id, const Transform& pose) {
  std::unique_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return false;
  world_.set_pose(unpack(id), pose);
  return true;
}

template <class F>
auto ManagedWorld::deform(std::span<const Id> ids, F&& mutate) {
  struct Before {
    Id id = 0;
    const Model* model = nullptr;  // null: no such object (mutate() throws)
    // The Model given to add(), which the World copies in any case: held so that its address
    // cannot be another Model's before it is unpinned below. A private one is not held (that
    // would stop the in-place refit); when the World replaces it, someone else holds it.
    std::shared_ptr<const Model> keep;
  };
  std::vector<Before> before;
  before.reserve(ids.size());
  for (const Id id : ids) {
    const ObjectId oid = unpack(id);
    if (!world_.contains(oid)) {
      before.push_back({id, nullptr, nullptr});
      continue;
    }
    before.push_back(
        {id, &world_.model(oid), private_models_.contains(id) ? nullptr : world_.model_ptr(oid)});
  }
  auto out = mutate();
  for (const Before& b : before) {
    const Model& now = world_.model(unpack(b.id));
    if (&now == b.model) continue;  // refitted in place
    {
      const ModelReadLock model_lock(now);
      pin_model(now);
    }
    unpin_model(*b.model);
    private_models_.insert(b.id);
  }
  return out;
}

bool ManagedWorld::set_vertices(Id id, std::span<const Vec3> vertices) {
  std::unique_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return false;
  return deform(std::span<const Id>(&id, 1), [&] {
    world_.set_vertices(unpack(id), vertices);
    return true;
  });
}

std::size_t ManagedWorld::size() const {
  std::shared_lock lock(mutex_);
  return world_.size();
}

std::shared_ptr<const Model> ManagedWorld::model(Id id) const {
  std::shared_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return nullptr;
  return world_.model_ptr(unpack(id));
}

std::optional<std::size_t> ManagedWorld::vertex_count(Id id) const {
  std::shared_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return std::nullopt;
  return world_.model(unpack(id)).mesh().vertices.size();
}

std::vector<ManagedWorld::MotionHit> ManagedWorld::sweep_motion(const Motion& motion) const {
  const MotionArgs args(motion);
  std::shared_lock lock(mutex_);
  return as_motion_hits(
      world_.sweep_motion(args.ids, motion.poses, args.deforming, motion.request));
}

std::vector<ManagedWorld::MotionHit> ManagedWorld::set_motion_continuous(const Motion& motion) {
  const MotionArgs args(motion);
  std::unique_lock lock(mutex_);
  return deform(motion.vertex_ids, [&] {
    return as_motion_hits(
        world_.set_motion_continuous(args.ids, motion.poses, args.deforming, motion.request));
  });
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
    CollisionResult result = p.a == p.b
                                 ? self_result(world_.model(p.a), world_.pose(p.a), p.self_pairs)
                                 : as_result(std::move(p.contacts));
    hits.push_back(Hit{pack(p.a), pack(p.b), std::move(result), world_.model_ptr(p.a),
                       world_.pose(p.a), world_.model_ptr(p.b), world_.pose(p.b)});
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
                       world_.model_ptr(o.object), world_.pose(o.object), nullptr, Transform{}});
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
                           world_.model_ptr(o.object), world_.pose(o.object),
                           other.world_.model_ptr(b), other.world_.pose(b)});
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
