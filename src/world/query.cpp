// The World's queries: pairs from the broad-phase tree, exact narrow phase on each pair (spread
// over oneTBB workers, results in a fixed order), and ray casts.
#include <antcd/world.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <antcd/error.hpp>
#include <string>

#include "world/ray_check.hpp"
#include "world/world_impl.hpp"

namespace antcd {

namespace {

using Object = World::Impl::Object;
using SlotPair = std::pair<std::uint32_t, std::uint32_t>;

// Below these sizes a query stays on the calling thread: handing work to oneTBB costs more.
constexpr std::size_t kParallelObjects = 256;
constexpr std::size_t kParallelPairs = 64;
constexpr std::size_t kBlock = 128;  // objects per broad-phase task

void check_delta(Scalar delta, const char* function, const char* argument) {
  if (!(delta >= 0) || !std::isfinite(delta)) {
    throw ArgumentError(std::string(function) + ": " + argument +
                                " must be finite and >= 0, got " + std::to_string(delta));
  }
}

// Every admitted pair (i, j) of live slots, i < j, such that j's tree box overlaps
// grown(box_i, grow(o_i)) and accept(i, o_i, j, o_j, query box) holds; sorted by (i, j).
template <class Grow, class Accept>
std::vector<SlotPair> self_pairs(const World::Impl& w, Grow&& grow, Accept&& accept) {
  const std::size_t n = w.objects.size();
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<SlotPair>> found(blocks);
  const auto run_block = [&](std::size_t b) {
    std::vector<SlotPair>& out = found[b];
    const auto end = static_cast<std::uint32_t>(std::min(n, (b + 1) * kBlock));
    for (auto i = static_cast<std::uint32_t>(b * kBlock); i < end; ++i) {
      const Object& oi = w.objects[i];
      if (!oi.alive) continue;
      const Aabb query = grown(oi.box, grow(oi));
      const std::size_t first = out.size();
      w.tree.query(query, [&](std::uint32_t j) {
        if (j <= i) return;
        const Object& oj = w.objects[j];
        if (!w.admits(oi, j, oj)) return;
        if (!accept(oi, oj, query)) return;
        out.emplace_back(i, j);
      });
      std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    }
  };
  if (n < kParallelObjects) {
    for (std::size_t b = 0; b < blocks; ++b) run_block(b);
  } else {
    tbb::parallel_for(std::size_t{0}, blocks, run_block);
  }
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  std::vector<SlotPair> out;
  out.reserve(total);
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

// Runs test(k) for k in [0, m), in parallel when worth it.
template <class Test>
void for_each_pair(std::size_t m, Test&& test) {
  if (m < kParallelPairs) {
    for (std::size_t k = 0; k < m; ++k) test(k);
  } else {
    tbb::parallel_for(std::size_t{0}, m, test);
  }
}

// The box grown for an exact query at distance delta: every point within delta of the object's
// mesh lies inside (boxes contain their meshes with a rounding allowance).
Scalar exact_growth(const Object& o, Scalar delta) { return delta * (1 + 1e-12) + o.tolerance; }

Obb posed_obb(const Object& o) {
  Obb b = o.model->root().obb;
  b.axes = o.pose.rotation * b.axes;
  b.center = o.pose.apply(b.center);
  return b;
}

}  // namespace

std::vector<ObjectPair> World::candidate_pairs(Scalar delta) const {
  check_delta(delta, "World::candidate_pairs", "delta");
  const Impl& w = *impl_;
  // The tree boxes contain the root boxes; a pair whose root spheres and root boxes pass the tests
  // below has root boxes whose axis-aligned bounds are within sqrt(3) times the box margin, so
  // growing by twice that loses none of them.
  const auto grow = [&](const Object& o) { return 2 * (delta * (1 + 1e-12) + o.tolerance); };
  const auto accept = [&](const Object& a, const Object& b, const Aabb& query) {
    if (!detail::boxes_overlap(query, grown(b.box, b.tolerance))) return false;
    const Sphere& sa = a.model->root().sphere;
    const Sphere& sb = b.model->root().sphere;
    const Vec3 ca = a.pose.apply(sa.center);
    const Vec3 cb = b.pose.apply(sb.center);
    const Scalar reach = sa.radius + sb.radius + delta;
    if ((ca - cb).squaredNorm() > reach * reach) return false;
    // Rounding allowance of the box fit and of the separating-axis arithmetic.
    const Scalar margin = delta + 1e-9 * (reach + std::max(ca.norm(), cb.norm()));
    return geometry::obb_overlap(posed_obb(a), posed_obb(b), margin);
  };
  const std::vector<SlotPair> slots = self_pairs(w, grow, accept);
  std::vector<ObjectPair> out;
  out.reserve(slots.size());
  for (const auto& [i, j] : slots) out.push_back({w.id_of(i), w.id_of(j)});
  return out;
}

std::vector<PairContacts> World::collide_all(const CollisionRequest& request) const {
  check_delta(request.delta, "World::collide_all", "request.delta");
  const Impl& w = *impl_;
  const Scalar delta = request.delta;
  const std::vector<SlotPair> candidates = self_pairs(
      w, [&](const Object& o) { return exact_growth(o, delta); },
      [](const Object&, const Object& b, const Aabb& query) {
        return detail::boxes_overlap(query, b.box);
      });
  std::vector<PairContacts> results(candidates.size());
  std::vector<char> hit(candidates.size(), 0);
  for_each_pair(candidates.size(), [&](std::size_t k) {
    const Object& a = w.objects[candidates[k].first];
    const Object& b = w.objects[candidates[k].second];
    CollisionResult r;
    if (collide(*a.model, a.pose, *b.model, b.pose, request, r)) {
      hit[k] = 1;
      results[k].contacts = std::move(r.contacts);
    }
  });
  std::vector<PairContacts> out;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!hit[k]) continue;
    results[k].a = w.id_of(candidates[k].first);
    results[k].b = w.id_of(candidates[k].second);
    out.push_back(std::move(results[k]));
  }
  return out;
}

std::vector<ObjectPair> World::pairs_within(Scalar distance) const {
  check_delta(distance, "World::pairs_within", "distance");
  CollisionRequest request;
  request.delta = distance;
  std::vector<ObjectPair> out;
  for (const PairContacts& p : collide_all(request)) out.push_back({p.a, p.b});
  return out;
}

namespace {

// The objects (admitted by `admit`) whose boxes meet `query`, sorted by slot, then the exact
// query of `model` at `pose` against each.
template <class Admit>
std::vector<ObjectContacts> against_world(const World::Impl& w, const Model& model,
                                          const Transform& pose, const Aabb& query,
                                          const CollisionRequest& request, Admit&& admit) {
  std::vector<std::uint32_t> candidates;
  w.tree.query(query, [&](std::uint32_t j) {
    const Object& oj = w.objects[j];
    if (admit(j, oj) && detail::boxes_overlap(query, oj.box)) candidates.push_back(j);
  });
  std::sort(candidates.begin(), candidates.end());
  std::vector<ObjectContacts> results(candidates.size());
  std::vector<char> hit(candidates.size(), 0);
  for_each_pair(candidates.size(), [&](std::size_t k) {
    const Object& b = w.objects[candidates[k]];
    CollisionResult r;
    if (collide(model, pose, *b.model, b.pose, request, r)) {
      hit[k] = 1;
      results[k].contacts = std::move(r.contacts);
    }
  });
  std::vector<ObjectContacts> out;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!hit[k]) continue;
    results[k].object = w.id_of(candidates[k]);
    out.push_back(std::move(results[k]));
  }
  return out;
}

}  // namespace

std::vector<ObjectContacts> World::collide_object(ObjectId id,
                                                  const CollisionRequest& request) const {
  const Impl& w = *impl_;
  const Object& o = w.get(id, "World::collide_object", "id");
  check_delta(request.delta, "World::collide_object", "request.delta");
  const Aabb query = grown(o.box, exact_growth(o, request.delta));
  return against_world(w, *o.model, o.pose, query, request,
                       [&](std::uint32_t j, const Object& oj) {
                         return j != id.slot && w.admits(o, j, oj);
                       });
}

std::vector<ObjectContacts> World::collide_model(const Model& model, const Transform& pose,
                                                 const CollisionRequest& request,
                                                 const QueryFilter& filter) const {
  check_delta(request.delta, "World::collide_model", "request.delta");
  if (!pose.rotation.allFinite() || !pose.translation.allFinite()) {
    throw ArgumentError("World::collide_model: pose is not finite (NaN or infinity)");
  }
  Impl::Object probe;
  probe.box = posed_box(model, pose, probe.tolerance);
  const Aabb query = grown(probe.box, exact_growth(probe, request.delta));
  return against_world(*impl_, model, pose, query, request,
                       [&](std::uint32_t, const Object& oj) { return Impl::admits(filter, oj); });
}

std::optional<RayHit> World::raycast(const Ray& ray, const QueryFilter& filter) const {
  const Vec3 d = detail::checked_ray_direction(ray, "World::raycast");
  const Impl& w = *impl_;
  Vec3 inv;
  for (int k = 0; k < 3; ++k) {
    inv[k] = d[k] == 0 ? std::numeric_limits<Scalar>::infinity() : 1 / d[k];
  }
  Scalar best_distance = ray.max_distance;
  std::optional<RayHit> best;
  w.tree.ray_query(ray.origin, inv, &best_distance, [&](std::uint32_t j) {
    const Object& o = w.objects[j];
    if (!Impl::admits(filter, o)) return;
    std::optional<RayHit> hit = detail::model_ray_first(*o.model, o.pose, ray, d, best_distance);
    if (!hit) return;
    hit->object = w.id_of(j);
    if (!best || hit->distance < best->distance ||
        (hit->distance == best->distance &&
         (hit->object < best->object ||
          (hit->object == best->object && hit->triangle < best->triangle)))) {
      best = *hit;
      best_distance = hit->distance;
    }
  });
  return best;
}

std::vector<RayHit> World::raycast_all(const Ray& ray, const QueryFilter& filter) const {
  const Vec3 d = detail::checked_ray_direction(ray, "World::raycast_all");
  const Impl& w = *impl_;
  Vec3 inv;
  for (int k = 0; k < 3; ++k) {
    inv[k] = d[k] == 0 ? std::numeric_limits<Scalar>::infinity() : 1 / d[k];
  }
  std::vector<RayHit> out;
  const Scalar s_max = ray.max_distance;
  w.tree.ray_query(ray.origin, inv, &s_max, [&](std::uint32_t j) {
    const Object& o = w.objects[j];
    if (!Impl::admits(filter, o)) return;
    const std::size_t first = out.size();
    detail::model_ray_hits(*o.model, o.pose, ray, d, out);
    for (std::size_t k = first; k < out.size(); ++k) out[k].object = w.id_of(j);
  });
  std::sort(out.begin(), out.end(), [](const RayHit& a, const RayHit& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    if (a.object != b.object) return a.object < b.object;
    return a.triangle < b.triangle;
  });
  return out;
}

}  // namespace antcd
