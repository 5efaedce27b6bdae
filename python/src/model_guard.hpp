// python/src/model_guard.hpp — what keeps a Model whole while Python threads share it and one of
// them calls Model.set_vertices (Model::refit, which must not run while a query reads the Model).
//
// - Reader/writer locks: every query (and every accessor reading positions or the hierarchy)
//   holds a shared lock on each Model it reads while it runs without the GIL; set_vertices holds
//   the exclusive one while it refits. A query therefore sees the positions before or after a
//   set_vertices, never a mix. The locks are a fixed table of stripes, a Model's stripe chosen by
//   its address (two Models on one stripe only wait for each other's set_vertices); a guard locks
//   its stripes in ascending order and writers hold one stripe, so no two guards can deadlock.
//   A waiting writer goes before readers that arrive after it (no set_vertices starved by
//   queries in turn). Nothing here is held while the GIL is taken. With a Model's lock held, the
//   only lock taken is the pin table's mutex (nothing is locked under it); a CollisionManager
//   takes its own lock before a Model's, never after (manager.hpp).
// - Pins: a Model held by a CollisionManager (the Model each object uses now, manager.hpp) or a
//   Scene is pinned. Their broad phase keeps boxes derived from the positions at the time it took
//   the Model, so set_vertices refuses a pinned Model (ValueError) instead of leaving those boxes
//   stale. Pinning happens under the Model's
//   shared lock, the pin check under its exclusive one: a Model is never refitted while it is
//   being added.
#pragma once

#include <antcd/bvh.hpp>

#include <cstdint>
#include <shared_mutex>

namespace antcd::python {

/// Shared locks on the stripes of one or two Models (a Model given twice is locked once).
class ModelReadLock {
 public:
  explicit ModelReadLock(const Model& a);
  ModelReadLock(const Model& a, const Model& b);
  ~ModelReadLock();
  ModelReadLock(const ModelReadLock&) = delete;
  ModelReadLock& operator=(const ModelReadLock&) = delete;

 private:
  std::uint64_t stripes_ = 0;  ///< bit k: stripe k is held
};

/// The exclusive lock on a Model's stripe.
class ModelWriteLock {
 public:
  explicit ModelWriteLock(const Model& model);
  ~ModelWriteLock();
  ModelWriteLock(const ModelWriteLock&) = delete;
  ModelWriteLock& operator=(const ModelWriteLock&) = delete;

 private:
  std::shared_mutex& mutex_;
};

/// Marks `model` as held by a broad phase (counted: pinned twice, unpinned twice). The caller
/// holds a ModelReadLock on it.
void pin_model(const Model& model);
/// Undoes one pin_model.
void unpin_model(const Model& model);
/// Whether `model` is pinned. The caller holds a ModelWriteLock on it.
[[nodiscard]] bool model_pinned(const Model& model);

}  // namespace antcd::python
