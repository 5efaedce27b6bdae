// Private: the pieces of the World's continuous motion shared by sweep_poses (continuous.cpp) and
// sweep_motion (deform_motion.cpp): argument checks, swept boxes and the swept broad phase.
#pragma once

#include <antcd/sweep.hpp>
#include <antcd/world.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "world/world_impl.hpp"

namespace antcd::detail {

using SlotPair = std::pair<std::uint32_t, std::uint32_t>;

/// Below this many candidate pairs (or in an arena of one thread) the sweeps stay on the calling
/// thread.
inline constexpr std::size_t kParallelSweeps = 8;

/// Checks the arguments of a continuous motion (every one, before anything is computed) and
/// returns, per slot, the index + 1 of the object's new pose in `poses` (0: it stays put). With
/// `sweep_range`, each moved object's translations, new and current, must lie within the sweeps'
/// coordinate range (tolerance::kSweepCoordinateRange); an object that stays put is checked by
/// sweep() itself, if a moved one comes near it.
std::vector<std::size_t> motion_index(const World::Impl& w, std::span<const ObjectId> ids,
                                      std::span<const Transform> poses, const char* function,
                                      bool sweep_range);

/// A box holding the object at every t of its rigid motion from `from` to `to` (see world.hpp):
/// the box of its boxes at both poses (each holds its end point of every model point's path),
/// grown by the most a slerped point strays from the chord's point at the same t (r theta^2 / 8:
/// the path minus the chord vanishes at both ends and has second derivative at most r theta^2, r
/// the point's distance from the turning axis, ccd::Spin) and a rounding allowance for the
/// interpolated poses.
Aabb swept_box(const Model& model, const Transform& from, const Aabb& box_from,
               const Transform& to);

/// Per slot, the rigid swept box of each live object (its current box when it stays put; dead
/// slots: empty boxes). `index` is motion_index's.
std::vector<Aabb> swept_boxes(const World::Impl& w, const std::vector<std::size_t>& index,
                              std::span<const Transform> poses);

/// The admitted pairs (i < j, slots, sorted) whose boxes (by slot) come within min_separation.
std::vector<SlotPair> swept_pairs(const World::Impl& w, const std::vector<Aabb>& boxes,
                                  Scalar min_separation);

/// Throws ArgumentError naming `function` for a bad SweepRequest.
void check_request(const SweepRequest& request, const char* function);

}  // namespace antcd::detail
