// Private: the World's state, shared by its mutations (world.cpp) and its queries (query.cpp).
#pragma once

#include <antcd/world.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "world/aabb_tree.hpp"

namespace antcd {

struct World::Impl {
  struct Object {
    std::shared_ptr<const Model> model;
    Transform pose;
    ObjectOptions options;
    /// World box containing every triangle of the posed mesh (rounding included).
    Aabb box;
    /// Absolute rounding allowance of this object's world-frame volumes.
    Scalar tolerance = 0;
    /// Slots of the objects this one must not be paired with, sorted.
    std::vector<std::uint32_t> ignored;
    std::int32_t leaf = detail::AabbTree::kNull;
    std::uint32_t generation = 0;
    bool alive = false;
  };

  WorldOptions settings;
  std::vector<Object> objects;
  std::vector<std::uint32_t> free_slots;
  detail::AabbTree tree;
  std::size_t live = 0;

  /// The live object of `id`, or an ArgumentError naming `function` and `argument`.
  const Object& get(ObjectId id, const char* function, const char* argument) const;
  Object& get(ObjectId id, const char* function, const char* argument) {
    return const_cast<Object&>(std::as_const(*this).get(id, function, argument));
  }
  [[nodiscard]] ObjectId id_of(std::uint32_t slot) const {
    return {slot, objects[slot].generation};
  }

  /// The filter between two live objects: groups, masks, ignored pairs.
  [[nodiscard]] bool admits(const Object& a, std::uint32_t slot_b, const Object& b) const {
    if ((a.options.group & b.options.mask) == 0 || (b.options.group & a.options.mask) == 0) {
      return false;
    }
    return a.ignored.empty() ||
           !std::binary_search(a.ignored.begin(), a.ignored.end(), slot_b);
  }
  static bool admits(const QueryFilter& f, const Object& b) {
    return (f.group & b.options.mask) != 0 && (b.options.group & f.mask) != 0;
  }

  /// The fattened box the tree stores for an object.
  [[nodiscard]] Aabb fattened(const Object& o) const;
};

/// World box of a posed model (from its root sphere and root box, whichever is tighter per axis),
/// widened by a rounding allowance; `tolerance` receives that allowance.
Aabb posed_box(const Model& model, const Transform& pose, Scalar& tolerance);

/// `box` grown by `by` on every side.
inline Aabb grown(Aabb box, Scalar by) {
  box.min.array() -= by;
  box.max.array() += by;
  return box;
}

}  // namespace antcd
