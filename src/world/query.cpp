// The World's queries: pairs from the broad-phase tree, exact narrow phase on each pair (spread
// over oneTBB workers, results in a fixed order), and ray casts.
#include <antcd/error.hpp>
#include <antcd/self.hpp>
#include <antcd/tolerances.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "util/check.hpp"
#include "util/parallel.hpp"
#include "util/portable.hpp"
#include "world/ray_check.hpp"
#include "world/world_impl.hpp"

namespace antcd {

namespace {

using Object = World::Impl::Object;
using Bounds = World::Impl::Bounds;
using SlotPair = std::pair<std::uint32_t, std::uint32_t>;

// Below these sizes (or in an arena of one thread) a query stays on the calling thread: handing
// work to oneTBB costs more.
constexpr std::size_t kParallelObjects = 64;
constexpr std::size_t kParallelPairs = 64;
// Broad-phase tasks per query: enough to balance a few threads, each still thousands of node visits
// on a large world.
constexpr std::size_t kPairTasks = 256;

// Sorts pairs of slots below `slots` by (i, j), as std::sort would: a least-significant-digit
// radix sort of the packed keys (i, j), 11 bits a pass; perf showed std::sort at ~2 % of a large
// world's frame.
void sort_pairs(std::vector<SlotPair>& pairs, std::size_t slots) {
  constexpr std::size_t kSmall = 2048;
  if (pairs.size() < kSmall) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  const int bits = std::max(1, static_cast<int>(std::bit_width(slots)));
  std::vector<std::uint64_t> keys(pairs.size());
  std::vector<std::uint64_t> scratch(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    keys[k] = (std::uint64_t{pairs[k].first} << bits) | pairs[k].second;
  }
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  std::vector<std::size_t> start(kBuckets);
  for (int shift = 0; shift < 2 * bits; shift += kDigit) {
    std::fill(start.begin(), start.end(), 0);
    for (const std::uint64_t key : keys) ++start[(key >> shift) & (kBuckets - 1)];
    std::size_t sum = 0;
    for (std::size_t& c : start) sum += std::exchange(c, sum);
    for (const std::uint64_t key : keys) scratch[start[(key >> shift) & (kBuckets - 1)]++] = key;
    keys.swap(scratch);
  }
  const std::uint64_t low = (std::uint64_t{1} << bits) - 1;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    pairs[k] = {static_cast<std::uint32_t>(keys[k] >> bits),
                static_cast<std::uint32_t>(keys[k] & low)};
  }
}

// Every pair (i, j) of live slots, i < j, whose tree boxes are within `gap` of each other, sorted
// by (i, j); the callers filter them (filters, exact boxes) afterwards, in slot order: during the
// traversal each pair's object data would be a cache miss of its own. One traversal of the tree
// against itself, split into independent tasks on a large world; the order of the answer never
// depends on them.
// Into `out` (cleared first, its storage reused).
void self_pairs(const World::Impl& w, Scalar gap, std::vector<SlotPair>& out) {
  const auto emit_into = [](std::vector<SlotPair>& out) {
    return [&out](std::uint32_t a, std::uint32_t b) {
      out.emplace_back(std::min(a, b), std::max(a, b));
    };
  };
  out.clear();
  if (w.live < kParallelObjects || parallel::max_concurrency() == 1) {
    out.reserve(w.live);  // one allocation, not a doubling series, for up to a pair per object
    w.tree.pairs(w.tree.all_pairs(), gap, emit_into(out));
  } else {
    const std::vector<detail::AabbTree::PairTask> tasks = w.tree.pair_tasks(gap, kPairTasks);
    parallel::PerThread<std::vector<SlotPair>> found;
    parallel::for_ranges(0, tasks.size(), 1, [&](std::size_t first, std::size_t last) {
      std::vector<SlotPair>& mine = found.local();
      for (std::size_t t = first; t != last; ++t) w.tree.pairs(tasks[t], gap, emit_into(mine));
    });
    std::size_t total = 0;
    for (const auto& f : found) total += f.size();
    out.reserve(total);
    for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  }
  sort_pairs(out, w.objects.size());
}
std::vector<SlotPair> self_pairs(const World::Impl& w, Scalar gap) {
  std::vector<SlotPair> out;
  self_pairs(w, gap, out);
  return out;
}

// Runs test(k) for k in [0, m), in parallel when worth it; warm(k) (which may only prefetch) is
// called a few indices ahead of test(k), on the same thread.
template <class Test, class Warm>
void for_each_pair(std::size_t m, Test&& test, Warm&& warm) {
  constexpr std::size_t kAhead = 8;
  const auto run = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < std::min(last, first + kAhead); ++k) warm(k);
    for (std::size_t k = first; k < last; ++k) {
      if (k + kAhead < last) warm(k + kAhead);
      test(k);
    }
  };
  if (m < kParallelPairs || parallel::max_concurrency() == 1) {
    run(0, m);
  } else {
    parallel::for_ranges(0, m, 1, run);
  }
}
template <class Test>
void for_each_pair(std::size_t m, Test&& test) {
  for_each_pair(m, test, [](std::size_t) {});
}

// The box grown for an exact query at distance delta: every point within delta of the object's
// mesh lies inside (boxes contain their meshes with a rounding allowance).
Scalar exact_growth(const Bounds& b, Scalar delta) {
  return tolerance::widened(delta) + b.tolerance;
}

// Whether the posed root spheres are farther apart than delta by more than ten times collide()'s
// own rounding allowance (bvh/traverse.hpp: tolerance::kVolume of a scale that this `scale`
// bounds: |b_to_a.translation| <= |ca| + |cb| + |sa.center| + |sb.center|): collide() would then
// reject the pair at its first test, so skipping it changes no answer. Most pairs whose boxes
// overlap on a large world are rejected here, before collide() sets up the pair.
bool spheres_apart(const Object& a, const Object& b, Scalar delta) {
  const Sphere sa = a.model->root().sphere();
  const Sphere sb = b.model->root().sphere();
  const Vec3 ca = a.pose.apply(sa.center);
  const Vec3 cb = b.pose.apply(sb.center);
  const Scalar scale =
      sa.radius + sb.radius + 2 * (sa.center.norm() + sb.center.norm()) + ca.norm() + cb.norm();
  const Scalar reach = sa.radius + sb.radius + delta + 10 * tolerance::kVolume * scale;
  return (ca - cb).squaredNorm() > reach * reach;
}

}  // namespace

std::vector<ObjectPair> World::candidate_pairs(Scalar delta) const {
  detail::require_non_negative("World::candidate_pairs", "delta", delta);
  std::vector<SlotPair> slots;
  std::vector<SlotPair> scratch;
  impl_->candidate_slots(delta, slots, scratch);
  std::vector<ObjectPair> out;
  out.reserve(slots.size());
  for (const auto& [i, j] : slots) out.push_back({impl_->id_of(i), impl_->id_of(j)});
  return out;
}

void World::candidate_pairs(Scalar delta, std::vector<ObjectPair>& out) const {
  detail::require_non_negative("World::candidate_pairs", "delta", delta);
  // Working storage per thread, kept between calls (so a caller asking every frame allocates only
  // while the frames grow); nothing of it outlives a call's answer.
  thread_local std::vector<SlotPair> slots;
  thread_local std::vector<SlotPair> scratch;
  impl_->candidate_slots(delta, slots, scratch);
  out.clear();
  out.reserve(slots.size());
  for (const auto& [i, j] : slots) out.push_back({impl_->id_of(i), impl_->id_of(j)});
}

void World::Impl::candidate_slots(Scalar delta, std::vector<SlotPair>& out,
                                  std::vector<SlotPair>& scratch) const {
  const Impl& w = *this;
  // The tree boxes contain the root boxes grown by twice their rounding allowance. A pair whose
  // root spheres and root boxes pass the tests below has root boxes whose axis-aligned bounds are
  // within sqrt(3) times the box margin, so growing one of them by twice that (and the other by its
  // allowance) loses none of them; the tree's boxes are then within 2 * delta of each other.
  const Scalar gap = 2 * tolerance::widened(delta);
  const auto accept = [&](std::uint32_t i, std::uint32_t j) {
    const Bounds& ba = w.bounds[i];
    const Bounds& bb = w.bounds[j];
    const Aabb query = grown(ba.box, 2 * (tolerance::widened(delta) + ba.tolerance));
    if (!detail::boxes_overlap(query, grown(bb.box, bb.tolerance))) return false;
    // The posed root spheres (centred on the posed root boxes), then the posed root boxes.
    const World::Impl::Root& ra = w.roots[i];
    const World::Impl::Root& rb = w.roots[j];
    const Vec3& ca = ra.box.center;
    const Vec3& cb = rb.box.center;
    const Scalar reach = ra.radius + rb.radius + delta;
    const Scalar d2 = (ca - cb).squaredNorm();
    if (d2 > reach * reach) return false;
    // Each root box holds the ball of its smallest half extent about its centre: when those balls
    // meet, so do the boxes, and the separating-axis test below (whose margin is some 1e7 times
    // the rounding of these few operations) would find no separating axis. Half of the pairs
    // that reach this point on the production-line scenes.
    const Scalar inner = ra.box.half_extents.minCoeff() + rb.box.half_extents.minCoeff();
    if (d2 < inner * inner) return true;
    // Likewise when either centre lies in the other box (on the same margin argument): about a
    // third of the pairs left on the production-line scenes.
    const Vec3 ab = cb - ca;
    if (((ra.box.axes.transpose() * ab).cwiseAbs().array() <= ra.box.half_extents.array()).all() ||
        ((rb.box.axes.transpose() * ab).cwiseAbs().array() <= rb.box.half_extents.array()).all()) {
      return true;
    }
    // Rounding allowance of the box fit and of the separating-axis arithmetic.
    const Scalar margin = delta + tolerance::kVolume * (reach + std::max(ca.norm(), cb.norm()));
    return geometry::obb_overlap(ra.box, rb.box, margin);
  };
  self_pairs(w, gap, scratch);
  out.clear();
  out.reserve(scratch.size());
  for (const auto& [i, j] : scratch) {
    if (w.admits(i, j) && accept(i, j)) out.emplace_back(i, j);
  }
}

namespace {

using PairMemo = World::Impl::PairMemo;

// Whether two requests are the same field for field (numbers by their bits), so that an answer
// kept for one is the answer to the other. The size check catches a field added to the request
// and not compared here.
struct RequestFields {
  Scalar delta;
  bool all_contacts;
  std::size_t max_contacts;
  bool volume;
  bool contact_normals;
  std::uint32_t manifold_points;
  Scalar manifold_angle;
};
static_assert(sizeof(CollisionRequest) == sizeof(RequestFields),
              "compare the new CollisionRequest field in same_request");
bool same_request(const CollisionRequest& x, const CollisionRequest& y) {
  // memcpy, not std::bit_cast: the WebAssembly build's libc++ (Emscripten 3.1.6) has none.
  const auto bits = [](Scalar v) {
    std::uint64_t b = 0;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  return bits(x.delta) == bits(y.delta) && x.all_contacts == y.all_contacts &&
         x.max_contacts == y.max_contacts && x.volume == y.volume &&
         x.contact_normals == y.contact_normals && x.manifold_points == y.manifold_points &&
         bits(x.manifold_angle) == bits(y.manifold_angle);
}

// The query's hold on the World's memo (world.hpp, "Unchanged pairs"): `held` when this query
// took it; `reuse` when its answers are for this request. Released when the query ends, by a
// throw too (the memo then keeps its last complete state).
class MemoHold {
 public:
  MemoHold(World::Impl::Memo& memo, const CollisionRequest& request)
      : memo_(memo), held_(!memo.busy.exchange(true, std::memory_order_acquire)) {
    reuse_ = held_ && memo_.filled && same_request(memo_.request, request);
  }
  MemoHold(const MemoHold&) = delete;
  MemoHold& operator=(const MemoHold&) = delete;
  ~MemoHold() {
    if (held_) memo_.busy.store(false, std::memory_order_release);
  }
  [[nodiscard]] bool held() const { return held_; }
  [[nodiscard]] bool reuse() const { return reuse_; }

 private:
  World::Impl::Memo& memo_;
  bool held_;
  bool reuse_ = false;
};

constexpr std::size_t kNoMemo = SIZE_MAX;

// The index of the kept answer of pair (a, b) if both objects are as they were when it was
// computed, else kNoMemo.
std::size_t find_memo(const std::vector<PairMemo>& memos, std::uint32_t a, std::uint32_t b,
                      std::uint64_t stamp_a, std::uint64_t stamp_b) {
  const auto it =
      std::lower_bound(memos.begin(), memos.end(), std::pair{a, b},
                       [](const PairMemo& m, const std::pair<std::uint32_t, std::uint32_t>& key) {
                         return std::pair{m.a, m.b} < key;
                       });
  if (it == memos.end() || it->a != a || it->b != b) return kNoMemo;
  return it->stamp_a == stamp_a && it->stamp_b == stamp_b
             ? static_cast<std::size_t>(it - memos.begin())
             : kNoMemo;
}

std::size_t memo_bytes(const std::vector<PairMemo>& memos) {
  std::size_t bytes = memos.capacity() * sizeof(PairMemo);
  for (const PairMemo& m : memos) {
    bytes += m.contacts.capacity() * sizeof(Contact) +
             m.self_pairs.capacity() * sizeof(std::array<std::uint32_t, 2>);
  }
  return bytes;
}

// What a query does with pair k and the memo.
enum class MemoUse : std::uint8_t {
  None = 0,    // not tested, or not kept (an object changed since the last query)
  Reused = 1,  // answered from the memo
  Keep = 2,    // tested now, both objects unchanged since the last query: kept for the next
};

// collide_all(request), with the self pairs when `with_self`.
std::vector<PairContacts> collide_pairs(const World::Impl& w, const CollisionRequest& request,
                                        bool with_self) {
  const Scalar delta = request.delta;
  World::Impl::Memo& memo = w.memo;
  const MemoHold hold(memo, request);
  // Objects not changed since the last query that held the memo: only pairs of two of them are
  // kept (a moving object's pairs would be kept for nothing).
  const std::uint64_t seen = hold.held() ? memo.seen : 0;
  const auto unchanged = [&](std::uint32_t s) { return hold.held() && w.stamps[s] <= seen; };
  // Tree boxes contain the objects' boxes grown by their rounding allowances, so every pair whose
  // boxes pass the box test below has tree boxes within delta of each other.
  const std::vector<SlotPair> candidates = self_pairs(w, tolerance::widened(delta));
  std::vector<PairContacts> results(candidates.size());
  std::vector<char> hit(candidates.size(), 0);
  std::vector<MemoUse> use(hold.held() ? candidates.size() : 0, MemoUse::None);
  std::vector<std::size_t> from(hold.reuse() ? candidates.size() : 0, kNoMemo);
  for_each_pair(
      candidates.size(),
      [&](std::size_t k) {
        const auto [i, j] = candidates[k];
        const Bounds& bi = w.bounds[i];
        if (!detail::boxes_overlap(grown(bi.box, exact_growth(bi, delta)), w.bounds[j].box) ||
            !w.admits(i, j)) {
          return;
        }
        const Object& a = w.objects[i];
        const Object& b = w.objects[j];
        if (spheres_apart(a, b, delta)) return;
        if (unchanged(i) && unchanged(j)) {
          if (hold.reuse()) {
            const std::size_t m = find_memo(memo.pairs, i, j, w.stamps[i], w.stamps[j]);
            if (m != kNoMemo) {
              use[k] = MemoUse::Reused;
              from[k] = m;
              hit[k] = memo.pairs[m].hit ? 1 : 0;
              if (memo.pairs[m].hit) results[k].contacts = memo.pairs[m].contacts;
              return;
            }
          }
          use[k] = MemoUse::Keep;
        }
        CollisionResult r;
        if (collide(*a.model, a.pose, *b.model, b.pose, request, r)) {
          hit[k] = 1;
          results[k].contacts = std::move(r.contacts);
        }
      },
      [&](std::size_t k) {
        // The second objects of the sorted pairs are scattered through memory: load them ahead.
        const std::uint32_t j = candidates[k].second;
        ANTCD_PREFETCH(&w.bounds[j]);
        ANTCD_PREFETCH(&w.objects[j]);
        ANTCD_PREFETCH(&w.objects[j].pose.translation);
      });
  // Self pairs, object by object in slot order (each self test spreads its own work over the
  // workers), merged in: (i, i) comes before every (i, j), j > i. An unchanged object's is kept
  // like a pair's.
  std::vector<PairContacts> selves;
  std::vector<PairMemo> new_selves;
  for (std::uint32_t s = 0; s < w.objects.size(); ++s) {
    if (!with_self || !w.alive(s) || !w.bounds[s].self_collision) continue;
    const std::size_t m = hold.reuse() && unchanged(s)
                              ? find_memo(memo.selves, s, s, w.stamps[s], w.stamps[s])
                              : kNoMemo;
    SelfIntersectionResult r;
    if (m != kNoMemo) {
      r.intersecting = memo.selves[m].hit;
      r.pairs = memo.selves[m].self_pairs;
      new_selves.push_back(memo.selves[m]);  // a copy: a later throw leaves the memo whole
    } else {
      SelfIntersectionRequest self_request;
      self_request.first_only = !request.all_contacts;
      r = self_intersections(*w.objects[s].model, self_request);
      if (request.all_contacts && request.max_contacts != 0 &&
          r.pairs.size() > request.max_contacts) {
        r.pairs.resize(request.max_contacts);
      }
      if (unchanged(s)) {
        new_selves.push_back({s, s, w.stamps[s], w.stamps[s], r.intersecting, {}, {}});
        if (r.intersecting) new_selves.back().self_pairs = r.pairs;
      }
    }
    if (!r.intersecting) continue;
    PairContacts p;
    p.a = p.b = w.id_of(s);
    p.self_pairs = std::move(r.pairs);
    selves.push_back(std::move(p));
  }
  // The memo for the next query: the pairs of unchanged objects tested or reused now (a reused
  // answer moves over; a new one is copied). Every other answer is dropped. Unfilled while the
  // answers move, so that a throw (an allocation) cannot leave a moved-from answer to be reused.
  if (hold.held()) {
    memo.filled = false;
    std::vector<PairMemo> kept;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (use[k] == MemoUse::Reused) {
        kept.push_back(std::move(memo.pairs[from[k]]));
      } else if (use[k] == MemoUse::Keep) {
        const auto [i, j] = candidates[k];
        kept.push_back({i, j, w.stamps[i], w.stamps[j], hit[k] != 0, {}, {}});
        if (hit[k] != 0) kept.back().contacts = results[k].contacts;
      }
    }
    memo.pairs = std::move(kept);
    memo.selves = std::move(new_selves);
    memo.request = request;
    memo.filled = true;
    memo.seen = w.clock;
    memo.bytes.store(memo_bytes(memo.pairs) + memo_bytes(memo.selves), std::memory_order_relaxed);
  }
  std::vector<PairContacts> out;
  std::size_t next_self = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!hit[k]) continue;
    while (next_self < selves.size() && selves[next_self].a.slot <= candidates[k].first) {
      out.push_back(std::move(selves[next_self++]));
    }
    results[k].a = w.id_of(candidates[k].first);
    results[k].b = w.id_of(candidates[k].second);
    out.push_back(std::move(results[k]));
  }
  while (next_self < selves.size()) out.push_back(std::move(selves[next_self++]));
  return out;
}

}  // namespace

std::vector<PairContacts> World::collide_all(const CollisionRequest& request) const {
  detail::require_non_negative("World::collide_all", "request.delta", request.delta);
  return collide_pairs(*impl_, request, true);
}

std::vector<ObjectPair> World::pairs_within(Scalar distance) const {
  detail::require_non_negative("World::pairs_within", "distance", distance);
  CollisionRequest request;
  request.delta = distance;
  std::vector<ObjectPair> out;
  // Distinct objects only (world.hpp).
  for (const PairContacts& p : collide_pairs(*impl_, request, false)) out.push_back({p.a, p.b});
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
    if (admit(j) && detail::boxes_overlap(query, w.bounds[j].box)) candidates.push_back(j);
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
  detail::require_non_negative("World::collide_object", "request.delta", request.delta);
  const Aabb query = grown(w.bounds[id.slot].box, exact_growth(w.bounds[id.slot], request.delta));
  return against_world(w, *o.model, o.pose, query, request,
                       [&](std::uint32_t j) { return j != id.slot && w.admits(id.slot, j); });
}

std::vector<ObjectContacts> World::collide_model(const Model& model, const Transform& pose,
                                                 const CollisionRequest& request,
                                                 const QueryFilter& filter) const {
  detail::require_non_negative("World::collide_model", "request.delta", request.delta);
  require_finite_pose(pose, "World::collide_model");
  Bounds probe;
  probe.box = posed_box(model, pose, probe.tolerance);
  const Aabb query = grown(probe.box, exact_growth(probe, request.delta));
  const Impl& w = *impl_;
  return against_world(w, model, pose, query, request,
                       [&](std::uint32_t j) { return Impl::admits(filter, w.bounds[j]); });
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
    if (!Impl::admits(filter, w.bounds[j])) return;
    const Object& o = w.objects[j];
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
    if (!Impl::admits(filter, w.bounds[j])) return;
    const Object& o = w.objects[j];
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
