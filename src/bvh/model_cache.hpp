// Private: per-model data that some queries derive on first use (built once, then read-only).
#pragma once

#include <antcd/bvh.hpp>

#include <memory>
#include <mutex>

namespace antcd::detail {

/// Type-erased so that the hierarchy layer does not depend on the layers that fill it.
struct ModelCache {
  std::once_flag point_index_once;
  std::shared_ptr<const void> point_index;
  std::once_flag point_tree_once;
  std::shared_ptr<const void> point_tree;
  /// Penetration depth (src/penetration/convex.cpp): convexity and the model-frame polytope.
  std::once_flag convex_once;
  std::shared_ptr<const void> convex;
  /// Self queries (src/self/cone.cpp): boundary data of subtrees, which depends on the triangles
  /// and the tree's topology only, so Model::refit carries it over. Built once under the mutex.
  std::mutex self_mutex;
  std::shared_ptr<const void> self_topology;
};

struct ModelCacheAccess {
  static ModelCache& cache(const Model& model) { return *model.cache_; }
};

}  // namespace antcd::detail
