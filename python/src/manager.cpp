// python/src/manager.cpp — see manager.hpp.
#include "manager.hpp"

#include <algorithm>
#include <mutex>
#include <stdexcept>

namespace antcd::python {

Aabb world_box(const Model& model, const Transform& pose) {
  const Obb& obb = model.root().obb;
  const Vec3 center = pose.apply(obb.center);
  const Mat3 axes = pose.rotation * obb.axes;
  const Vec3 half = axes.cwiseAbs() * obb.half_extents;
  return Aabb{center - half, center + half};
}

ManagedWorld::Id ManagedWorld::add(std::shared_ptr<const Model> model, const Transform& pose) {
  if (!model) throw std::invalid_argument("ManagedWorld::add: null model");
  const Aabb box = world_box(*model, pose);
  std::unique_lock lock(mutex_);
  const Id id = next_id_++;
  index_.emplace(id, objects_.size());
  objects_.push_back(Object{id, std::move(model), pose, box});
  return id;
}

bool ManagedWorld::remove(Id id) {
  std::unique_lock lock(mutex_);
  const auto it = index_.find(id);
  if (it == index_.end()) return false;
  const std::size_t k = it->second;
  index_.erase(it);
  if (k + 1 != objects_.size()) {
    objects_[k] = std::move(objects_.back());
    index_[objects_[k].id] = k;
  }
  objects_.pop_back();
  return true;
}

bool ManagedWorld::set_pose(Id id, const Transform& pose) {
  std::unique_lock lock(mutex_);
  const auto it = index_.find(id);
  if (it == index_.end()) return false;
  Object& o = objects_[it->second];
  o.pose = pose;
  o.box = world_box(*o.model, pose);
  return true;
}

std::size_t ManagedWorld::size() const {
  std::shared_lock lock(mutex_);
  return objects_.size();
}

std::vector<std::pair<std::size_t, std::size_t>> ManagedWorld::overlapping(const std::vector<Object>& left,
                                                                           const std::vector<Object>* right,
                                                                           Scalar margin) {
  // Sweep and prune along x over both sets (right == nullptr: pairs within `left`).
  struct Entry {
    Scalar min_x;
    std::size_t index;
    bool from_right;
  };
  std::vector<Entry> entries;
  entries.reserve(left.size() + (right ? right->size() : 0));
  for (std::size_t i = 0; i < left.size(); ++i) entries.push_back({left[i].box.min.x(), i, false});
  if (right) {
    for (std::size_t i = 0; i < right->size(); ++i) entries.push_back({(*right)[i].box.min.x(), i, true});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& p, const Entry& q) {
    return p.min_x != q.min_x ? p.min_x < q.min_x : (p.from_right != q.from_right ? !p.from_right : p.index < q.index);
  });
  const auto box_of = [&](const Entry& e) -> const Aabb& {
    return e.from_right ? (*right)[e.index].box : left[e.index].box;
  };
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t p = 0; p < entries.size(); ++p) {
    const Aabb& bp = box_of(entries[p]);
    for (std::size_t q = p + 1; q < entries.size() && entries[q].min_x <= bp.max.x() + margin; ++q) {
      if (right && entries[p].from_right == entries[q].from_right) continue;
      const Aabb& bq = box_of(entries[q]);
      if ((bp.min.array() > bq.max.array() + margin).any() || (bq.min.array() > bp.max.array() + margin).any()) {
        continue;
      }
      const Entry& l = entries[p].from_right ? entries[q] : entries[p];
      const Entry& r = entries[p].from_right ? entries[p] : entries[q];
      out.emplace_back(l.index, r.index);
    }
  }
  return out;
}

std::vector<ManagedWorld::Hit> ManagedWorld::narrow(const std::vector<Object>& left,
                                                    const std::vector<Object>& right,
                                                    std::vector<std::pair<std::size_t, std::size_t>> candidates,
                                                    Mode mode, Scalar delta) {
  // Examine candidates in id order, so Verdict mode reports the same pair whatever the layout.
  for (auto& [i, j] : candidates) {
    if (&left == &right && left[i].id > left[j].id) std::swap(i, j);
  }
  std::sort(candidates.begin(), candidates.end(), [&](const auto& p, const auto& q) {
    const auto kp = std::pair{left[p.first].id, right[p.second].id};
    const auto kq = std::pair{left[q.first].id, right[q.second].id};
    return kp < kq;
  });
  CollisionRequest request;
  request.delta = delta;
  request.all_contacts = mode == Mode::Contacts;
  std::vector<Hit> hits;
  CollisionResult result;
  for (const auto& [i, j] : candidates) {
    const Object& a = left[i];
    const Object& b = right[j];
    if (collide(*a.model, a.pose, *b.model, b.pose, request, result)) {
      hits.push_back(Hit{a.id, b.id, result, a.model, a.pose});
      if (mode == Mode::Verdict) break;
    }
  }
  return hits;
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_internal(Mode mode, Scalar delta) const {
  std::shared_lock lock(mutex_);
  return narrow(objects_, objects_, overlapping(objects_, nullptr, delta), mode, delta);
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_single(const Model& model, const Transform& pose,
                                                            Mode mode, Scalar delta) const {
  const Aabb box = world_box(model, pose);
  std::shared_lock lock(mutex_);
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const Aabb& b = objects_[i].box;
    if (!((b.min.array() > box.max.array() + delta).any() || (box.min.array() > b.max.array() + delta).any())) {
      candidates.push_back(i);
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](std::size_t p, std::size_t q) { return objects_[p].id < objects_[q].id; });
  CollisionRequest request;
  request.delta = delta;
  request.all_contacts = mode == Mode::Contacts;
  std::vector<Hit> hits;
  CollisionResult result;
  for (const std::size_t i : candidates) {
    const Object& o = objects_[i];
    if (collide(*o.model, o.pose, model, pose, request, result)) {
      hits.push_back(Hit{o.id, 0, result, o.model, o.pose});
      if (mode == Mode::Verdict) break;
    }
  }
  return hits;
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_other(const ManagedWorld& other, Mode mode,
                                                           Scalar delta) const {
  if (&other == this) {
    std::shared_lock lock(mutex_);
    return collide_other_locked(other, mode, delta);
  }
  // Shared locks taken in address order, so two threads querying a-vs-b and b-vs-a while writers
  // wait cannot deadlock.
  const bool this_first = std::less<const ManagedWorld*>{}(this, &other);
  std::shared_lock first(this_first ? mutex_ : other.mutex_);
  std::shared_lock second(this_first ? other.mutex_ : mutex_);
  return collide_other_locked(other, mode, delta);
}

std::vector<ManagedWorld::Hit> ManagedWorld::collide_other_locked(const ManagedWorld& other, Mode mode,
                                                                  Scalar delta) const {
  // Distinct vectors even for other == *this: every (a, b) of the product is a candidate pair then,
  // an object against itself included, as two separate managers holding the same objects would give.
  auto candidates = overlapping(objects_, &other.objects_, delta);
  if (&other == this) {
    const std::vector<Object> copy = objects_;
    return narrow(objects_, copy, std::move(candidates), mode, delta);
  }
  return narrow(objects_, other.objects_, std::move(candidates), mode, delta);
}

}  // namespace antcd::python
