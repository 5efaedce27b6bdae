// Private: the boolean exact query of one object pair, frame after frame, starting where the last
// frame's query of the same pair found its contact (the scene runner keeps one PairWitness per
// candidate pair).
#pragma once

#include <antcd/collide.hpp>
#include <antcd/export.hpp>

#include <cstdint>

namespace antcd::detail {

/// The leaf pair (node indices) where the last boolean query of two models found its contact.
/// A hint only: the next query tests that leaf pair's triangles first and walks the hierarchies
/// from the root when none of them collides, so the verdict never depends on it; the work does
/// (two objects that touched last frame and moved little still touch there).
struct PairWitness {
  const Model* a = nullptr;  ///< the models the leaves index; a witness of others is dropped
  const Model* b = nullptr;
  bool valid = false;
  std::uint32_t leaf_a = 0;
  std::uint32_t leaf_b = 0;
};

/// collide(a, pose_a, b, pose_b, request, result) for a boolean request (all_contacts false,
/// manifold_points 0): the same verdict (result.colliding, result.contained, result.surface_only),
/// found from `witness` first, which it then updates. The one contact reported may differ from
/// collide()'s (another colliding triangle pair), and so may the traversal statistics. Not
/// thread-safe for one witness; allocation-free. Exported for the scene runner (antcd::random),
/// not part of the public API.
ANTCD_API bool collide_coherent(const Model& a, const Transform& pose_a, const Model& b,
                                const Transform& pose_b, const CollisionRequest& request,
                                CollisionResult& result, PairWitness& witness);

}  // namespace antcd::detail
