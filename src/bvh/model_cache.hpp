// Private: per-model data that queries of the layers above derive on first use (built once, then
// read-only). The hierarchy layer holds the slots and knows nothing of what fills them: each layer
// takes a slot of its own once per process (new_cache_slot) and keeps its data there, type-erased.
// A refit drops every slot's data (it was derived from the old positions).
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

/// The data of type T kept in `slot` of the model's cache, made by build() (returning a T) on the
/// first call for this model, exactly once even when threads ask at the same time.
template <class T, class Build>
const T& derived(const Model& model, std::size_t slot, const Build& build) {
  ModelCache::Slot& s = ModelCacheAccess::cache(model).slots[slot];
  std::call_once(s.once, [&] { s.data = std::make_shared<const T>(build()); });
  return *static_cast<const T*>(s.data.get());
}

}  // namespace antcd::detail
