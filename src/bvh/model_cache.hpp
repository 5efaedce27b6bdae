// Private: per-model data that queries of the layers above derive on first use (built once, then
// read-only). The hierarchy layer holds the slots and knows nothing of what fills them: each layer
// takes a slot of its own once per process (new_cache_slot) and keeps its data there, type-erased.
// A refit drops the data of the slots (derived from the old positions) and carries over that of
// the kept slots (new_kept_slot: data that depends on the triangles and the tree's topology only,
// such as the self queries' subtree boundaries); a rebuild drops both.
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <memory>
#include <mutex>

namespace antcd::detail {

struct ModelCache {
  /// Slots: more than the layers that take one (today the point index, the point tree and the
  /// convex polytope). new_cache_slot() aborts in a debug build when they run out.
  static constexpr std::size_t kSlots = 8;
  struct Slot {
    std::once_flag once;
    std::shared_ptr<const void> data;
  };
  std::array<Slot, kSlots> slots;
  /// Kept across a refit: built under the mutex on first use (a refit hands the data over, so a
  /// once-flag could not tell it is there).
  struct KeptSlot {
    std::mutex mutex;
    std::shared_ptr<const void> data;
  };
  std::array<KeptSlot, kSlots> kept;

  /// A fresh cache for the refitted model: the kept slots' data, nothing else.
  [[nodiscard]] std::shared_ptr<ModelCache> after_refit() {
    auto fresh = std::make_shared<ModelCache>();
    for (std::size_t i = 0; i < kSlots; ++i) {
      const std::lock_guard<std::mutex> lock(kept[i].mutex);
      fresh->kept[i].data = kept[i].data;
    }
    return fresh;
  }
};

struct ModelCacheAccess {
  static ModelCache& cache(const Model& model) { return *model.cache_; }
};

/// A slot index no other caller gets: take it once, in a function-local static.
inline std::size_t new_cache_slot() {
  static std::atomic<std::size_t> next{0};
  const std::size_t slot = next.fetch_add(1);
  assert(slot < ModelCache::kSlots && "raise ModelCache::kSlots");
  return slot;
}

/// A kept-slot index (ModelCache::kept) no other caller gets: take it once, in a function-local
/// static.
inline std::size_t new_kept_slot() {
  static std::atomic<std::size_t> next{0};
  const std::size_t slot = next.fetch_add(1);
  assert(slot < ModelCache::kSlots && "raise ModelCache::kSlots");
  return slot;
}

/// The data of type T kept in `slot` of the model's cache, made by build() (returning a T) on the
/// first call for this model, exactly once even when threads ask at the same time.
template <class T, class Build>
const T& derived(const Model& model, std::size_t slot, const Build& build) {
  ModelCache::Slot& s = ModelCacheAccess::cache(model).slots[slot];
  std::call_once(s.once, [&] { s.data = std::make_shared<const T>(build()); });
  return *static_cast<const T*>(s.data.get());
}

/// The data of type T kept in kept slot `slot`, made by build() (returning a std::shared_ptr<const
/// T>) when the slot is empty; shared, so a refit that hands it over does not invalidate it.
template <class T, class Build>
std::shared_ptr<const T> kept(const Model& model, std::size_t slot, const Build& build) {
  ModelCache::KeptSlot& s = ModelCacheAccess::cache(model).kept[slot];
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.data) s.data = build();
  return std::static_pointer_cast<const T>(s.data);
}

}  // namespace antcd::detail
