// python/src/manager.cpp — see manager.hpp.
#include "manager.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <tuple>
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

// A posed model with its world-frame box (the root OBB's axis-aligned bounds, grown by a rounding
// allowance so that the box surely contains the posed mesh).
struct Posed {
  Id id = 0;
  const Model* model = nullptr;
  const Transform* pose = nullptr;
  Aabb box;
};

Aabb world_box(const Model& model, const Transform& pose) {
  const Obb obb = model.root().obb();
  const Vec3 center = pose.apply(obb.center);
  const Vec3 half = (pose.rotation * obb.axes).cwiseAbs() * obb.half_extents;
  const Scalar allowance = 1e-9 * (center.norm() + half.norm() + model.root().radius) + 1e-300;
  const Vec3 grow = half.array() + allowance;
  return Aabb{center - grow, center + grow};
}

std::vector<Posed> posed_objects(const World& world) {
  std::vector<Posed> out;
  for (const ObjectId id : world.objects()) {
    const Model& model = world.model(id);
    const Transform& pose = world.pose(id);
    out.push_back(Posed{pack(id), &model, &pose, world_box(model, pose)});
  }
  return out;
}

// Euclidean gap between two boxes: a lower bound of the distance between anything inside them.
Scalar box_gap(const Aabb& p, const Aabb& q) {
  const Vec3 gap = (p.min - q.max).cwiseMax(q.min - p.max).cwiseMax(Vec3::Zero());
  return gap.norm();
}

struct Candidate {
  Scalar bound;
  std::size_t left;
  std::size_t right;
};

// The closest of the candidate pairs (left[i], right[j]): pairs in order of their lower bound, each
// distance query bounded by the best distance so far; stops once the next bound exceeds it.
// Ties keep the first pair found, so the answer is a function of the world's state.
ManagedWorld::Nearest closest(const std::vector<Posed>& left, const std::vector<Posed>& right,
                              std::vector<Candidate> candidates) {
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& p, const Candidate& q) {
    return std::tie(p.bound, left[p.left].id, right[p.right].id) <
           std::tie(q.bound, left[q.left].id, right[q.right].id);
  });
  ManagedWorld::Nearest best;
  DistanceRequest request;
  for (const Candidate& c : candidates) {
    // Signed distances (closed pairs) go below 0, so a pair at 0 does not end the search.
    if (best.found && c.bound > best.result.distance) break;
    request.upper_bound = best.found ? std::max<Scalar>(0, best.result.distance)
                                     : std::numeric_limits<Scalar>::infinity();
    const Posed& a = left[c.left];
    const Posed& b = right[c.right];
    // Two solids: signed distance (-penetration depth when they overlap, nested included), as
    // FCL's signed distance that trimesh's manager reports; open meshes: the surface distance.
    request.signed_distance = a.model->is_closed() && b.model->is_closed();
    DistanceResult r = distance(*a.model, *a.pose, *b.model, *b.pose, request);
    if (r.beyond_upper_bound || !std::isfinite(r.distance)) continue;
    if (!best.found || r.distance < best.result.distance) {
      best.found = true;
      best.a = a.id;
      best.b = b.id;
      best.result = r;
    }
  }
  return best;
}

}  // namespace

Id ManagedWorld::add(std::shared_ptr<const Model> model, const Transform& pose) {
  if (!model) throw std::invalid_argument("ManagedWorld::add: null model");
  std::unique_lock lock(mutex_);
  return pack(world_.add(std::move(model), pose));
}

bool ManagedWorld::remove(Id id) {
  std::unique_lock lock(mutex_);
  if (!world_.contains(unpack(id))) return false;
  world_.remove(unpack(id));
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
  const std::vector<Posed> objects = posed_objects(world_);
  std::vector<Candidate> candidates;
  candidates.reserve(objects.size() * (objects.size() - (objects.empty() ? 0 : 1)) / 2);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      candidates.push_back({box_gap(objects[i].box, objects[j].box), i, j});
    }
  }
  return closest(objects, objects, std::move(candidates));
}

ManagedWorld::Nearest ManagedWorld::distance_single(const Model& model,
                                                    const Transform& pose) const {
  const std::vector<Posed> query{Posed{0, &model, &pose, world_box(model, pose)}};
  std::shared_lock lock(mutex_);
  const std::vector<Posed> objects = posed_objects(world_);
  std::vector<Candidate> candidates;
  candidates.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i)
    candidates.push_back({box_gap(objects[i].box, query[0].box), i, 0});
  return closest(objects, query, std::move(candidates));
}

ManagedWorld::Nearest ManagedWorld::distance_other(const ManagedWorld& other) const {
  return with_both_locked(other, [&] {
    const std::vector<Posed> left = posed_objects(world_);
    const std::vector<Posed> right = posed_objects(other.world_);
    std::vector<Candidate> candidates;
    candidates.reserve(left.size() * right.size());
    for (std::size_t i = 0; i < left.size(); ++i) {
      for (std::size_t j = 0; j < right.size(); ++j) {
        candidates.push_back({box_gap(left[i].box, right[j].box), i, j});
      }
    }
    return closest(left, right, std::move(candidates));
  });
}

}  // namespace antcd::python
