// Private: the World's state, shared by its mutations (world.cpp) and its queries (query.cpp).
#pragma once

#include <antcd/world.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "world/aabb_tree.hpp"

namespace antcd {

struct World::Impl {
  struct Object {
    std::shared_ptr<const Model> model;
    /// A deforming object's private Model (the one `model` points to), made by its first
    /// set_vertices(); null for an object whose Model is the shared one given to add().
    std::shared_ptr<Model> own;
    Transform pose;
    ObjectOptions options;
    /// Slots of the objects this one must not be paired with, sorted.
    std::vector<std::uint32_t> ignored;
  };

  /// What the all-pairs traversal reads of each object, kept apart from the rest (a frame of a
  /// large world touches it for every broad-phase pair, the rest only for pairs that pass it).
  struct Bounds {
    /// World box containing every triangle of the posed mesh (rounding included).
    Aabb box;
    /// Absolute rounding allowance of this object's world-frame volumes.
    Scalar tolerance = 0;
    std::uint32_t group = 0;  ///< copies of the object's options.group and options.mask
    std::uint32_t mask = 0;
    bool has_ignored = false;     ///< whether the object's ignored list is non-empty
    bool self_collision = false;  ///< a copy of the object's options.self_collision
  };

  /// An object's root volumes placed by its pose, from the same arithmetic as its box (posed_box):
  /// candidate_pairs tests them for every pair whose boxes meet, and would otherwise pose them
  /// again for each such pair.
  struct Root {
    Obb box;            ///< the root box in the world frame; its centre is the root sphere's too
    Scalar radius = 0;  ///< the root sphere's radius
  };

  /// collide_all's (and pairs_within's) narrow-phase answer of one pair of unchanged objects
  /// (world.hpp, "Unchanged pairs"): slots a < b (a == b: a self pair) and their stamps when it
  /// was computed. `hit` false: the pair was tested and does not collide.
  struct PairMemo {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    std::uint64_t stamp_a = 0;
    std::uint64_t stamp_b = 0;
    bool hit = false;
    std::vector<Contact> contacts;
    std::vector<std::array<std::uint32_t, 2>> self_pairs;
  };
  /// The answers kept from query to query. Taken by one query at a time (`busy`: a query that
  /// finds it taken, by another thread or by itself through a stolen oneTBB task, runs without
  /// it, with the same answer); everything but `busy` and `bytes` is read and written only by the
  /// query holding it.
  struct Memo {
    std::atomic<bool> busy{false};
    bool filled = false;       ///< `request` and `pairs` are from a query that completed
    CollisionRequest request;  ///< the request the answers are for
    /// The world's clock when the last query holding the memo started: an object whose stamp is
    /// not above it was not changed since.
    std::uint64_t seen = 0;
    std::vector<PairMemo> pairs;        ///< distinct pairs, sorted by (a, b)
    std::vector<PairMemo> selves;       ///< self pairs, sorted by slot
    std::atomic<std::size_t> bytes{0};  ///< heap bytes of the above, for memory_bytes()
  };

  WorldOptions settings;
  std::vector<Object> objects;
  /// By slot: the world's clock at the object's last change (add, pose, vertices); stamps are
  /// never reused, so a removed and re-added slot never matches an old one.
  std::vector<std::uint64_t> stamps;
  std::uint64_t clock = 0;
  mutable Memo memo;
  std::vector<Bounds> bounds;  ///< by slot, like objects
  std::vector<Root> roots;     ///< by slot, like objects; set with bounds
  /// By slot: generation << 1 | alive. Dense, so that checking a batch of ids is cheap.
  std::vector<std::uint64_t> handles;
  // Scratch of set_poses (a mutation), by slot: the last index of the object in its arguments, and
  // flags (kEscaped: its new box left the tree's box; kJumped: it left the tree until reinserted).
  std::vector<std::size_t> last_set;
  std::vector<std::uint8_t> flags;
  static constexpr std::uint8_t kEscaped = 1;
  static constexpr std::uint8_t kJumped = 2;
  std::vector<std::uint32_t> free_slots;
  detail::AabbTree tree;
  std::size_t live = 0;

  /// The live object of `id`, or an ArgumentError naming `function` and `argument`.
  const Object& get(ObjectId id, const char* function, const char* argument) const;
  Object& get(ObjectId id, const char* function, const char* argument) {
    return const_cast<Object&>(std::as_const(*this).get(id, function, argument));
  }
  [[nodiscard]] std::uint32_t generation(std::uint32_t slot) const {
    return static_cast<std::uint32_t>(handles[slot] >> 1);
  }
  [[nodiscard]] bool alive(std::uint32_t slot) const { return (handles[slot] & 1) != 0; }
  [[nodiscard]] bool contains(ObjectId id) const {
    return id.slot < handles.size() &&
           handles[id.slot] == ((std::uint64_t{id.generation} << 1) | 1);
  }
  [[nodiscard]] ObjectId id_of(std::uint32_t slot) const { return {slot, generation(slot)}; }

  /// The filter between two live objects: groups, masks, ignored pairs.
  [[nodiscard]] bool admits(std::uint32_t a, std::uint32_t b) const {
    const Bounds& ba = bounds[a];
    const Bounds& bb = bounds[b];
    if ((ba.group & bb.mask) == 0 || (bb.group & ba.mask) == 0) return false;
    if (!ba.has_ignored) return true;
    const std::vector<std::uint32_t>& list = objects[a].ignored;
    return !std::binary_search(list.begin(), list.end(), b);
  }
  static bool admits(const QueryFilter& f, const Bounds& b) {
    return (f.group & b.mask) != 0 && (b.group & f.mask) != 0;
  }

  /// set_poses() after its argument checks (ids live, poses rigid, spans of one length).
  void apply_poses(std::span<const ObjectId> ids, std::span<const Transform> poses);
  /// candidate_pairs(delta) as slot pairs into `out` (cleared); `scratch` receives the tree's.
  void candidate_slots(Scalar delta, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out,
                       std::vector<std::pair<std::uint32_t, std::uint32_t>>& scratch) const;

  /// The fattened box the tree stores for an object: grown by at least twice the rounding
  /// allowance, so that the tree's box of an object always contains grown(box, 2 * tolerance)
  /// (the queries' tree traversals rely on that margin).
  [[nodiscard]] Aabb fattened(std::uint32_t slot) const;
};

/// World box of a posed model (the axis-aligned bounds of its posed root box), widened by a
/// rounding allowance; `tolerance` receives that allowance and `root` the posed root volumes.
Aabb posed_box(const Model& model, const Transform& pose, Scalar& tolerance,
               World::Impl::Root& root);
/// The same box, for a pose that is not an object's (its root volumes are not kept).
inline Aabb posed_box(const Model& model, const Transform& pose, Scalar& tolerance) {
  World::Impl::Root root;
  return posed_box(model, pose, tolerance, root);
}

/// Throws ArgumentError naming `function` unless `pose` is finite (queries about a model outside
/// the world; the world's own poses are checked, rigidity included, when they are set).
void require_finite_pose(const Transform& pose, const char* function);

/// "object 'name' (slot s, generation g)" (or "object (slot ...)" when unnamed), for errors.
std::string object_label(const World::Impl::Object& o, ObjectId id);

/// `box` grown by `by` on every side.
inline Aabb grown(Aabb box, Scalar by) {
  box.min.array() -= by;
  box.max.array() += by;
  return box;
}

}  // namespace antcd
