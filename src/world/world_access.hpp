// Private: the World entries of the scene runner (src/scene/scene.cpp), which has checked its
// poses once when it was built and asks for the same World queries every frame. Not public API:
// exported from antcd::antcd only because the runner lives in antcd::random.
#pragma once

#include <antcd/export.hpp>
#include <antcd/world.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace antcd::detail {

struct WorldAccess {
  using SlotPair = std::pair<std::uint32_t, std::uint32_t>;

  /// World::set_poses(ids, poses) without its argument checks: the caller guarantees that the
  /// spans have one length, every id is live and every pose passes detail::pose_problem
  /// (util/pose_check.hpp). The World ends in the same state as after set_poses. A mutation.
  ANTCD_API static void set_checked_poses(World& world, std::span<const ObjectId> ids,
                                          std::span<const Transform> poses);

  /// World::candidate_pairs(delta) as slot pairs (a.slot, b.slot), the same pairs in the same
  /// order, written into `out` (cleared first; its storage is reused). `scratch` holds the tree's
  /// pairs between the steps (its storage reused too). delta must be finite and non-negative.
  /// Const and thread-safe like candidate_pairs, given distinct `out` and `scratch` per thread.
  ANTCD_API static void candidate_slots(const World& world, Scalar delta,
                                        std::vector<SlotPair>& out, std::vector<SlotPair>& scratch);
};

}  // namespace antcd::detail
