// The World's objects: adding, removing, moving and filtering them, with the broad-phase tree
// kept up to date (a leaf changes only when its object leaves its box; see set_poses).
#include <antcd/world.hpp>

#include <antcd/error.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <antcd/pose.hpp>
#include "util/check.hpp"
#include "util/parallel.hpp"
#include "world/world_impl.hpp"

namespace antcd {

namespace {

// Batches of poses at least this long are checked and fitted by oneTBB tasks.
constexpr std::size_t kParallelBatch = 2048;

std::string describe(ObjectId id) {
  return "(slot " + std::to_string(id.slot) + ", generation " + std::to_string(id.generation) + ")";
}

void require_rigid(const Transform& pose, const std::string& function, const std::string& what) {
  if (const PoseCheck c = check_pose(pose); !c.rigid()) {
    throw ArgumentError(function + ": " + what + " " + c.problem());
  }
}

}  // namespace

std::string object_label(const World::Impl::Object& o, ObjectId id) {
  return (o.options.name.empty() ? std::string("object") : "object '" + o.options.name + "'") +
         " " + describe(id);
}

Aabb posed_box(const Model& model, const Transform& pose, Scalar& tolerance,
               World::Impl::Root& posed) {
  const BvhNode& root = model.root();
  posed.box.center = pose.apply(root.center);
  posed.box.axes = pose.rotation * root.axes();
  posed.box.half_extents = root.half_extents();
  posed.radius = root.radius;
  const Vec3& c = posed.box.center;
  const Vec3 ext = posed.box.axes.cwiseAbs() * posed.box.half_extents;
  // The root box's axis-aligned bounds (not cut by the root sphere: World::candidate_pairs
  // relies on the tree boxes containing the posed root box).
  // Magnitudes by their 1-norms (bounds on the 2-norms, no square roots: this runs for every object
  // of every frame).
  const Scalar sphere_reach = root.radius + c.lpNorm<1>();
  // Relative allowance for the box fit and for rounding in the pose applied here, on a scale at
  // least the hierarchy traversal's (bvh/traverse.hpp).
  tolerance = tolerance::volume_allowance(sphere_reach + c.lpNorm<1>() + ext.lpNorm<1>());
  Aabb box;
  box.min = c - ext;
  box.max = c + ext;
  return grown(box, tolerance);
}

void require_finite_pose(const Transform& pose, const char* function) {
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    throw ArgumentError(std::string(function) + ": pose is not finite (NaN or infinity)");
  }
}

const World::Impl::Object& World::Impl::get(ObjectId id, const char* function,
                                            const char* argument) const {
  if (!contains(id)) {
    throw ArgumentError(std::string(function) + ": " + argument + " " + describe(id) +
                        " is not an object of this world (removed, or never added)");
  }
  return objects[id.slot];
}

Aabb World::Impl::fattened(std::uint32_t slot) const {
  const Bounds& b = bounds[slot];
  return grown(b.box, settings.fat_fraction * objects[slot].model->root().radius + 2 * b.tolerance);
}

World::World(const WorldOptions& options) : impl_(std::make_unique<Impl>()) {
  detail::require_non_negative("World", "options.fat_fraction", options.fat_fraction);
  impl_->settings = options;
}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

ObjectId World::add(std::shared_ptr<const Model> model, const Transform& pose,
                    ObjectOptions options) {
  const std::string label =
      options.name.empty() ? std::string("the new object") : "object '" + options.name + "'";
  if (!model) throw ArgumentError("World::add: model is null (" + label + ")");
  if (!(options.rebuild_above >= 0)) {
    detail::argument_error("World::add", "options.rebuild_above of " + label, ">= 0 (or +inf)",
                           number_text(options.rebuild_above));
  }
  require_rigid(pose, "World::add", "pose of " + label);
  const Transform new_pose = pose;  // `pose` may live in this World (add(m, world.pose(other)))
  Impl& w = *impl_;
  std::uint32_t slot;
  if (!w.free_slots.empty()) {
    slot = w.free_slots.back();
    w.free_slots.pop_back();
  } else {
    if (w.objects.size() >= UINT32_MAX - 1)
      throw ArgumentError("World::add: too many objects (2^32 - 2)");
    slot = static_cast<std::uint32_t>(w.objects.size());
    w.objects.emplace_back();
    w.bounds.emplace_back();
    w.roots.emplace_back();
    w.handles.push_back(0);
    w.stamps.push_back(0);
    w.last_set.push_back(0);
    w.flags.push_back(0);
  }
  Impl::Object& o = w.objects[slot];
  o.model = std::move(model);
  o.own.reset();
  o.pose = new_pose;
  o.options = std::move(options);
  o.ignored.clear();
  w.handles[slot] |= 1;
  w.stamps[slot] = ++w.clock;
  Impl::Bounds& b = w.bounds[slot];
  b.box = posed_box(*o.model, o.pose, b.tolerance, w.roots[slot]);
  b.group = o.options.group;
  b.mask = o.options.mask;
  b.has_ignored = false;
  b.self_collision = o.options.self_collision;
  w.tree.insert(slot, w.fattened(slot));
  ++w.live;
  return w.id_of(slot);
}

void World::remove(ObjectId id) {
  Impl& w = *impl_;
  Impl::Object& o = w.get(id, "World::remove", "id");
  for (const std::uint32_t other : o.ignored) {
    auto& list = w.objects[other].ignored;
    list.erase(std::lower_bound(list.begin(), list.end(), id.slot));
    w.bounds[other].has_ignored = !list.empty();
  }
  w.tree.remove(id.slot);
  o = Impl::Object{};
  w.bounds[id.slot] = Impl::Bounds{};
  const std::uint32_t next = id.generation + 1;  // the old id never matches again
  w.handles[id.slot] = std::uint64_t{next} << 1;
  w.stamps[id.slot] = ++w.clock;
  if (next != 0) w.free_slots.push_back(id.slot);  // a wrapped slot is retired
  --w.live;
}

void World::set_pose(ObjectId id, const Transform& pose) {
  const Impl::Object& o = impl_->get(id, "World::set_pose", "id");
  if (!check_pose(pose).rigid())
    require_rigid(pose, "World::set_pose", "pose of " + object_label(o, id));
  set_poses(std::span<const ObjectId>(&id, 1), std::span<const Transform>(&pose, 1));
}

void World::set_poses(std::span<const ObjectId> ids, std::span<const Transform> poses) {
  Impl& w = *impl_;
  if (ids.size() != poses.size()) {
    throw ArgumentError("World::set_poses: " + std::to_string(ids.size()) + " ids but " +
                        std::to_string(poses.size()) + " poses");
  }
  // Every argument is checked before anything changes: in parallel on a large batch, then the first
  // bad one (if any) again, on this thread, for its message.
  const auto bad = [&](std::size_t k) {
    return !w.contains(ids[k]) || !check_pose(poses[k]).rigid();
  };
  std::size_t first_bad = ids.size();
  if (ids.size() < kParallelBatch) {
    for (std::size_t k = 0; k < ids.size() && first_bad == ids.size(); ++k) {
      if (bad(k)) first_bad = k;
    }
  } else {
    first_bad = parallel::reduce(
        std::size_t{0}, ids.size(), ids.size(),
        [&](std::size_t first, std::size_t last, std::size_t found) {
          for (std::size_t k = first; k != last && k < found; ++k) {
            if (bad(k)) return k;
          }
          return found;
        },
        [](std::size_t x, std::size_t y) { return std::min(x, y); });
  }
  if (first_bad < ids.size()) {
    const std::size_t k = first_bad;
    w.get(ids[k], "World::set_poses", ("ids[" + std::to_string(k) + "]").c_str());
    require_rigid(
        poses[k], "World::set_poses",
        "poses[" + std::to_string(k) + "] of " + object_label(w.objects[ids[k].slot], ids[k]));
  }
  w.apply_poses(ids, poses);
}

void World::Impl::apply_poses(std::span<const ObjectId> ids, std::span<const Transform> poses) {
  Impl& w = *this;
  // Boxes in parallel (independent): an id given more than once ends with its last pose, so only
  // its last occurrence is fitted. An object whose new box left its leaf's box gets the new box
  // (grown by the rounding margin the queries rely on, see fattened()) in its leaf at once; its
  // ancestors are fixed below, by a move or by the refit.
  // Every object given a pose counts as changed, even when the pose is the one it had (see
  // world.hpp, "Unchanged pairs"): comparing poses would cost as much as a frame's box fits.
  const std::uint64_t now = ++w.clock;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    w.last_set[ids[k].slot] = k;
    w.stamps[ids[k].slot] = now;
  }
  const auto fit = [&](std::size_t k) {
    const std::uint32_t slot = ids[k].slot;
    if (w.last_set[slot] != k) return;
    Impl::Object& o = w.objects[slot];
    o.pose = poses[k];
    Impl::Bounds& b = w.bounds[slot];
    b.box = posed_box(*o.model, o.pose, b.tolerance, w.roots[slot]);
    const Aabb leaf = w.tree.box(slot);
    const Aabb tight = grown(b.box, 2 * b.tolerance);
    if (detail::box_contains(leaf, tight)) return;
    // Jumped: the new box does not even meet the old one (a teleport, a respawn) and lies outside
    // the leaf's grandparent (a fast object still among its neighbours in the tree is not one).
    const bool jumped =
        !detail::boxes_overlap(leaf, b.box) && !w.tree.inside_ancestor(slot, tight, 2);
    w.flags[slot] = jumped ? Impl::kEscaped | Impl::kJumped : Impl::kEscaped;
    w.tree.set_box(slot, tight);
  };
  // The leaves are in the tree's order, not the arguments': each one is a cache miss on a large
  // world unless loaded a few objects ahead.
  constexpr std::size_t kAhead = 8;
  const auto fit_range = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < std::min(last, first + kAhead); ++k)
      w.tree.prefetch(ids[k].slot);
    for (std::size_t k = first; k < last; ++k) {
      if (k + kAhead < last) w.tree.prefetch(ids[k + kAhead].slot);
      fit(k);
    }
  };
  if (ids.size() < kParallelBatch) {
    fit_range(0, ids.size());
  } else {
    parallel::for_ranges(0, ids.size(), 1, fit_range);
  }
  std::size_t escaped = 0;
  std::size_t jumped = 0;
  for (const ObjectId id : ids) {
    escaped += w.flags[id.slot] != 0;
    jumped += (w.flags[id.slot] & Impl::kJumped) != 0;
  }
  // Few leaves to update: one removal and insertion each (O(log n)), with the fattened box so that
  // small motions after this one need no update. Many (more than a sixteenth of the objects: a
  // frame of a moving world, where most objects move every frame): one O(n) refit of the new leaf
  // boxes, which rebuilds when the tree got loose; fattening would then buy nothing (the refit
  // costs O(n) anyway) and only let more pairs through the broad phase, so those leaves keep their
  // unfattened boxes. Objects that jumped are taken out before the refit and reinserted after it
  // when they are few (at most a sixteenth of the objects): refitting would stretch every box on
  // their old path across the jump. When more jump, they stay in place: a removal and insertion
  // costs about a sixteenth of a rebuild, so the refit (and the rebuild it starts when the boxes
  // got loose) costs less. Measured with callgrind, one thread, set_poses + candidate_pairs: the
  // 90-object production line (45 moving, about 6 a frame moving more than their size, few
  // outside their grandparent) set_poses 66 -> 33 thousand instructions a frame; 200 boxes with
  // 2 % (20 %) jumping across the world a frame -4 % (-28 %) against reinserting every jump.
  const bool refit = escaped > w.live / 16;
  if (!refit) {
    for (const ObjectId id : ids) {
      if (w.flags[id.slot] == 0) continue;
      w.flags[id.slot] = 0;
      w.tree.move(id.slot, w.fattened(id.slot));
    }
    return;
  }
  const bool reinsert = jumped <= w.live / 16;
  for (const ObjectId id : ids) {
    if (reinsert && (w.flags[id.slot] & Impl::kJumped) != 0 && w.tree.contains(id.slot)) {
      w.tree.remove(id.slot);
    }
  }
  w.tree.refit();
  for (const ObjectId id : ids) {
    const std::uint8_t f = w.flags[id.slot];
    w.flags[id.slot] = 0;
    if (reinsert && (f & Impl::kJumped) != 0) {
      const Impl::Bounds& b = w.bounds[id.slot];
      w.tree.insert(id.slot, grown(b.box, 2 * b.tolerance));
    }
  }
}

void World::set_vertices(ObjectId id, std::span<const Vec3> vertices) {
  Impl& w = *impl_;
  Impl::Object& o = w.get(id, "World::set_vertices", "id");
  const auto fail = [&](const std::string& problem) {
    throw ArgumentError("World::set_vertices: vertices of " + object_label(o, id) + ": " + problem);
  };
  const std::size_t count = o.model->mesh().vertices.size();
  if (vertices.size() != count) {
    fail("got " + std::to_string(vertices.size()) + " vertices, the mesh has " +
         std::to_string(count));
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) fail("vertex " + std::to_string(i) + " is not finite");
  }
  // The private Model is refitted in place only when nothing but this object holds it (o.model and
  // o.own: a use count of 2; a mutation runs alone on this World, so no copy of these two pointers
  // is being made meanwhile). Otherwise (the first call: the Model is the shared one given to
  // add(); or a model_ptr() of the private one is held) a copy is refitted, and replaces it only
  // when the refit succeeded: on a throw nothing has changed.
  std::shared_ptr<Model> target =
      o.own && o.own.use_count() == 2 ? o.own : std::make_shared<Model>(*o.model);
  try {
    target->refit(vertices, o.options.rebuild_above);
  } catch (const Error& e) {
    fail(e.what());
  }
  if (target != o.own) {
    o.own = target;
    o.model = std::move(target);
  }
  // The new root volumes: the object's box, as for a moved object.
  const Transform pose = o.pose;
  w.apply_poses(std::span<const ObjectId>(&id, 1), std::span<const Transform>(&pose, 1));
}

void World::set_filter(ObjectId id, std::uint32_t group, std::uint32_t mask) {
  Impl::Object& o = impl_->get(id, "World::set_filter", "id");
  o.options.group = group;
  o.options.mask = mask;
  impl_->bounds[id.slot].group = group;
  impl_->bounds[id.slot].mask = mask;
}

void World::ignore_pair(ObjectId a, ObjectId b, bool ignored) {
  Impl& w = *impl_;
  Impl::Object& oa = w.get(a, "World::ignore_pair", "a");
  Impl::Object& ob = w.get(b, "World::ignore_pair", "b");
  if (a.slot == b.slot) {
    throw ArgumentError("World::ignore_pair: a and b are the same " + object_label(oa, a));
  }
  const auto set = [&](std::vector<std::uint32_t>& list, std::uint32_t slot) {
    const auto it = std::lower_bound(list.begin(), list.end(), slot);
    const bool present = it != list.end() && *it == slot;
    if (ignored && !present) list.insert(it, slot);
    if (!ignored && present) list.erase(it);
  };
  set(oa.ignored, b.slot);
  set(ob.ignored, a.slot);
  w.bounds[a.slot].has_ignored = !oa.ignored.empty();
  w.bounds[b.slot].has_ignored = !ob.ignored.empty();
}

std::size_t World::size() const { return impl_->live; }

bool World::contains(ObjectId id) const { return impl_->contains(id); }

std::vector<ObjectId> World::objects() const {
  std::vector<ObjectId> out;
  out.reserve(impl_->live);
  for (std::uint32_t s = 0; s < impl_->objects.size(); ++s) {
    if (impl_->alive(s)) out.push_back(impl_->id_of(s));
  }
  return out;
}

const Model& World::model(ObjectId id) const { return *impl_->get(id, "World::model", "id").model; }
const std::shared_ptr<const Model>& World::model_ptr(ObjectId id) const {
  return impl_->get(id, "World::model_ptr", "id").model;
}
const Transform& World::pose(ObjectId id) const { return impl_->get(id, "World::pose", "id").pose; }
const ObjectOptions& World::options(ObjectId id) const {
  return impl_->get(id, "World::options", "id").options;
}

bool World::pair_ignored(ObjectId a, ObjectId b) const {
  const Impl::Object& oa = impl_->get(a, "World::pair_ignored", "a");
  impl_->get(b, "World::pair_ignored", "b");
  return std::binary_search(oa.ignored.begin(), oa.ignored.end(), b.slot);
}

bool World::may_collide(ObjectId a, ObjectId b) const {
  impl_->get(a, "World::may_collide", "a");
  impl_->get(b, "World::may_collide", "b");
  return a.slot != b.slot && impl_->admits(a.slot, b.slot);
}

std::size_t World::memory_bytes() const {
  const Impl& w = *impl_;
  std::size_t bytes =
      sizeof(Impl) + w.objects.capacity() * sizeof(Impl::Object) +
      w.bounds.capacity() * sizeof(Impl::Bounds) + w.roots.capacity() * sizeof(Impl::Root) +
      w.handles.capacity() * sizeof(std::uint64_t) + w.stamps.capacity() * sizeof(std::uint64_t) +
      w.memo.bytes.load(std::memory_order_relaxed) + w.last_set.capacity() * sizeof(std::size_t) +
      w.flags.capacity() + w.free_slots.capacity() * sizeof(std::uint32_t) + w.tree.memory_bytes();
  for (const Impl::Object& o : w.objects) {
    bytes += o.ignored.capacity() * sizeof(std::uint32_t);
    if (o.own) bytes += sizeof(Model) + o.own->stats().memory_bytes;
    if (o.options.name.capacity() > 15) bytes += o.options.name.capacity() + 1;
  }
  return bytes;
}

}  // namespace antcd
