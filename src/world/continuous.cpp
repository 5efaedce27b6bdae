// The World's continuous motion: swept boxes in a throwaway AABB tree (broad phase), then
// antcd::sweep on each candidate pair (spread over oneTBB workers). See the block in world.hpp.
#include <antcd/ccd.hpp>
#include <antcd/error.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <antcd/pose.hpp>
#include "ccd/motion.hpp"
#include "util/check.hpp"
#include "util/parallel.hpp"
#include "world/continuous.hpp"
#include "world/world_impl.hpp"

namespace antcd {

namespace detail {

std::vector<std::size_t> motion_index(const World::Impl& w, std::span<const ObjectId> ids,
                                      std::span<const Transform> poses, const char* function,
                                      bool sweep_range) {
  if (ids.size() != poses.size()) {
    throw ArgumentError(std::string(function) + ": " + std::to_string(ids.size()) + " ids but " +
                        std::to_string(poses.size()) + " poses");
  }
  std::vector<std::size_t> index(w.objects.size(), 0);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::string arg = "ids[" + std::to_string(k) + "]";
    w.get(ids[k], function, arg.c_str());
    if (index[ids[k].slot] != 0) {
      throw ArgumentError(std::string(function) + ": " + arg + " repeats ids[" +
                          std::to_string(index[ids[k].slot] - 1) +
                          "] (a continuous motion gives each object one end pose)");
    }
    index[ids[k].slot] = k + 1;
    if (const PoseCheck c = check_pose(poses[k]); !c.rigid()) {
      throw ArgumentError(std::string(function) + ": new_poses[" + std::to_string(k) + "] " +
                          c.problem());
    }
    if (sweep_range) {
      ccd::require_sweep_translation(function, "new_poses[" + std::to_string(k) + "]", poses[k]);
      ccd::require_sweep_translation(function, arg + "'s current pose",
                                     w.objects[ids[k].slot].pose);
    }
  }
  return index;
}

Aabb swept_box(const Model& model, const Transform& from, const Aabb& box_from,
               const Transform& to) {
  Scalar tolerance = 0;
  const Aabb box_to = posed_box(model, to, tolerance);
  Aabb box;
  box.min = box_from.min.cwiseMin(box_to.min);
  box.max = box_from.max.cwiseMax(box_to.max);
  const ccd::Spin spin = ccd::spin(from.rotation, to.rotation);
  const Scalar r = ccd::model_reach(model, spin);
  const Scalar rounding = tolerance::kVolume * (ccd::origin_radius(model) +
                                                from.translation.norm() + to.translation.norm());
  return grown(box, tolerance::widened(r * spin.theta * spin.theta / 8) + rounding);
}

std::vector<Aabb> swept_boxes(const World::Impl& w, const std::vector<std::size_t>& index,
                              std::span<const Transform> poses) {
  std::vector<Aabb> boxes(w.objects.size());
  for (std::uint32_t s = 0; s < w.objects.size(); ++s) {
    if (!w.alive(s)) continue;
    const World::Impl::Object& o = w.objects[s];
    const Aabb& now = w.bounds[s].box;
    boxes[s] = index[s] == 0 ? now : swept_box(*o.model, o.pose, now, poses[index[s] - 1]);
  }
  return boxes;
}

std::vector<SlotPair> swept_pairs(const World::Impl& w, const std::vector<Aabb>& boxes,
                                  Scalar min_separation) {
  detail::AabbTree tree;
  for (std::uint32_t s = 0; s < w.objects.size(); ++s) {
    if (w.alive(s)) tree.insert(s, boxes[s]);
  }
  tree.rebuild();
  std::vector<SlotPair> out;
  tree.pairs(tree.all_pairs(), tolerance::widened(min_separation),
             [&](std::uint32_t a, std::uint32_t b) {
               const std::uint32_t i = std::min(a, b);
               const std::uint32_t j = std::max(a, b);
               if (w.admits(i, j)) out.emplace_back(i, j);
             });
  std::sort(out.begin(), out.end());
  return out;
}

void check_request(const SweepRequest& request, const char* function) {
  detail::require_non_negative(function, "request.min_separation", request.min_separation);
  ccd::require_sweep_range(function, "request.min_separation", "", request.min_separation);
  detail::require_positive(function, "request.time_tolerance", request.time_tolerance);
  detail::require_at_least(function, "request.max_iterations", request.max_iterations, 1);
}

}  // namespace detail

using detail::check_request;
using detail::motion_index;
using detail::SlotPair;
using detail::swept_pairs;

std::vector<ObjectPair> World::swept_candidate_pairs(std::span<const ObjectId> ids,
                                                     std::span<const Transform> new_poses,
                                                     Scalar min_separation) const {
  const char* function = "World::swept_candidate_pairs";
  detail::require_non_negative(function, "min_separation", min_separation);
  const Impl& w = *impl_;
  const std::vector<std::size_t> index = motion_index(w, ids, new_poses, function, false);
  std::vector<ObjectPair> out;
  for (const auto& [i, j] :
       swept_pairs(w, detail::swept_boxes(w, index, new_poses), min_separation)) {
    out.push_back({w.id_of(i), w.id_of(j)});
  }
  return out;
}

std::vector<PairToi> World::sweep_poses(std::span<const ObjectId> ids,
                                        std::span<const Transform> new_poses,
                                        const SweepRequest& request) const {
  const char* function = "World::sweep_poses";
  check_request(request, function);
  const Impl& w = *impl_;
  const std::vector<std::size_t> index = motion_index(w, ids, new_poses, function, true);
  const std::vector<SlotPair> pairs =
      swept_pairs(w, detail::swept_boxes(w, index, new_poses), request.min_separation);
  const auto end_pose = [&](std::uint32_t s) -> const Transform& {
    return index[s] == 0 ? w.objects[s].pose : new_poses[index[s] - 1];
  };
  std::vector<SweepResult> results(pairs.size());
  const auto run = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k != last; ++k) {
      const auto [i, j] = pairs[k];
      const Impl::Object& a = w.objects[i];
      const Impl::Object& b = w.objects[j];
      results[k] = sweep(*a.model, a.pose, end_pose(i), *b.model, b.pose, end_pose(j), request);
    }
  };
  if (pairs.size() < detail::kParallelSweeps || parallel::max_concurrency() == 1) {
    run(0, pairs.size());
  } else {
    parallel::for_ranges(0, pairs.size(), 1, run);
  }
  std::vector<PairToi> out;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (results[k].hit)
      out.push_back({w.id_of(pairs[k].first), w.id_of(pairs[k].second), results[k]});
  }
  return out;
}

std::vector<PairToi> World::set_poses_continuous(std::span<const ObjectId> ids,
                                                 std::span<const Transform> new_poses,
                                                 const SweepRequest& request) {
  std::vector<PairToi> out = sweep_poses(ids, new_poses, request);
  set_poses(ids, new_poses);
  return out;
}

}  // namespace antcd
