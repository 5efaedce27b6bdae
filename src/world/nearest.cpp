// The World's nearest queries (world.hpp): a best-first branch and bound over the broad-phase
// tree(s). Node pairs wait in a priority queue keyed by the gap between their boxes, which bounds
// from below the distance of every object pair under them (tree boxes contain the objects' posed
// boxes grown by their rounding allowances, and those contain the meshes). The search pops the
// smallest gap, splits the larger node, and measures a pair of leaves with distance() bounded by
// the best distance so far; it ends when the smallest gap left exceeds that distance. Keys never
// exceed the distance of the pairs below them and pruning is strict, so every pair that could tie
// with the best is measured: the answer is the least (distance, a, b), whatever the tree's shape.
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/penetration.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include "world/world_impl.hpp"

namespace antcd {

namespace {

using Object = World::Impl::Object;
using Tree = detail::AabbTree;

constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();

// Euclidean gap between two boxes: a lower bound of the distance between anything inside them
// (0 when they overlap).
Scalar box_gap(const Aabb& p, const Aabb& q) {
  return (p.min - q.max).cwiseMax(q.min - p.max).cwiseMax(Vec3::Zero()).norm();
}

// One side of a search: the objects of a World (its tree's nodes), or one query box (world null:
// a single leaf, node 0).
struct Side {
  const World::Impl* world = nullptr;
  Aabb query_box;

  [[nodiscard]] bool empty() const { return world != nullptr && world->tree.root() == Tree::kNull; }
  [[nodiscard]] std::int32_t root() const { return world != nullptr ? world->tree.root() : 0; }
  [[nodiscard]] bool leaf(std::int32_t n) const {
    return world == nullptr || world->tree.is_leaf(n);
  }
  [[nodiscard]] Aabb box(std::int32_t n) const {
    return world != nullptr ? world->tree.node_box(n) : query_box;
  }
  /// A leaf's own box (tighter than the tree's fattened one).
  [[nodiscard]] Aabb exact_box(std::int32_t n) const {
    return world != nullptr ? world->bounds[world->tree.object(n)].box : query_box;
  }
  [[nodiscard]] std::uint32_t object(std::int32_t n) const {
    return world != nullptr ? world->tree.object(n) : 0;
  }
};

struct Entry {
  Scalar key;      // lower bound of the distance of every pair under (a, b)
  std::int32_t a;  // node of side A
  std::int32_t b;  // node of side B; in a self search a == b stands for the pairs within a
  bool ready;      // a pair of leaves admitted by the filter, keyed by their own boxes
  bool operator>(const Entry& o) const { return key > o.key; }
};

// The best-first search of one query: `admit(object_a, object_b)` filters leaf pairs,
// `measure(object_a, object_b, upper_bound)` returns the pair's answer, or nothing when it is
// farther than upper_bound. `self`: A and B are one world and the pairs are its distinct
// unordered pairs.
class Search {
 public:
  Search(const Side& a, const Side& b, bool self) : a_(a), b_(b), self_(self) {}

  template <class Admit, class Measure>
  std::optional<NearestPair> run(Admit&& admit, Measure&& measure) {
    if (a_.empty() || b_.empty()) return std::nullopt;
    if (self_) {
      push(0, a_.root(), a_.root(), false);
    } else {
      push_nodes(a_.root(), b_.root());
    }
    while (!heap_.empty()) {
      const Entry e = heap_.top();
      heap_.pop();
      if (e.key > cutoff()) break;  // every entry left is farther
      if (e.ready) {
        offer(measure(a_.object(e.a), b_.object(e.b), cutoff()));
        continue;
      }
      if (self_ && e.a == e.b) {
        if (a_.leaf(e.a)) continue;
        const std::int32_t c0 = a_.world->tree.child(e.a, 0);
        const std::int32_t c1 = a_.world->tree.child(e.a, 1);
        push(0, c0, c0, false);
        push(0, c1, c1, false);
        push_nodes(c0, c1);
        continue;
      }
      const bool leaf_a = a_.leaf(e.a);
      const bool leaf_b = b_.leaf(e.b);
      if (leaf_a && leaf_b) {
        if (!admit(a_.object(e.a), b_.object(e.b))) continue;
        push(std::max(e.key, box_gap(a_.exact_box(e.a), b_.exact_box(e.b))), e.a, e.b, true);
      } else if (leaf_b || (!leaf_a && span(a_.box(e.a)) >= span(b_.box(e.b)))) {
        for (int k = 0; k < 2; ++k) push_nodes(a_.world->tree.child(e.a, k), e.b);
      } else {
        for (int k = 0; k < 2; ++k) push_nodes(e.a, b_.world->tree.child(e.b, k));
      }
    }
    return std::move(best_);
  }

 private:
  static Scalar span(const Aabb& box) { return (box.max - box.min).sum(); }

  // Entries above this cannot hold a pair closer than the best (or tied with it). A signed best
  // below 0 keeps every overlapping pair (gap 0) in the search: it may overlap deeper.
  [[nodiscard]] Scalar cutoff() const {
    return best_ ? std::max<Scalar>(best_->result.distance, 0) : kInf;
  }
  void push(Scalar key, std::int32_t a, std::int32_t b, bool ready) {
    if (key <= cutoff()) heap_.push({key, a, b, ready});
  }
  void push_nodes(std::int32_t a, std::int32_t b) {
    push(box_gap(a_.box(a), b_.box(b)), a, b, false);
  }
  void offer(std::optional<NearestPair> c) {
    if (!c) return;
    if (!best_ || std::tie(c->result.distance, c->a, c->b) <
                      std::tie(best_->result.distance, best_->a, best_->b)) {
      best_ = std::move(c);
    }
  }

  const Side& a_;
  const Side& b_;
  bool self_;
  std::optional<NearestPair> best_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap_;
};

// distance() of one pair under `request`, or nothing when it is beyond `upper_bound` (or there is
// no triangle to measure).
std::optional<NearestPair> measure(ObjectId a, const Model& ma, const Transform& pa, ObjectId b,
                                   const Model& mb, const Transform& pb,
                                   const NearestRequest& request, Scalar upper_bound) {
  DistanceRequest dr;
  dr.upper_bound = upper_bound;
  DistanceResult r = request.signed_distance && ma.is_closed() && mb.is_closed()
                         ? signed_distance(ma, pa, mb, pb, dr)
                         : distance(ma, pa, mb, pb, dr);
  if (r.beyond_upper_bound || !std::isfinite(r.distance)) return std::nullopt;
  return NearestPair{a, b, std::move(r)};
}

}  // namespace

std::optional<NearestPair> World::nearest_pair(const NearestRequest& request) const {
  const Impl& w = *impl_;
  const Side side{&w, {}};
  return Search(side, side, true)
      .run([&](std::uint32_t i, std::uint32_t j) { return w.admits(i, j); },
           [&](std::uint32_t i, std::uint32_t j, Scalar upper) {
             if (j < i) std::swap(i, j);  // slot order is id order among live objects
             const Object& a = w.objects[i];
             const Object& b = w.objects[j];
             return measure(w.id_of(i), *a.model, a.pose, w.id_of(j), *b.model, b.pose, request,
                            upper);
           });
}

std::optional<NearestPair> World::nearest_object(ObjectId id, const NearestRequest& request) const {
  const Impl& w = *impl_;
  const Object& o = w.get(id, "World::nearest_object", "id");
  const Side objects{&w, {}};
  const Side query{nullptr, w.bounds[id.slot].box};
  return Search(objects, query, false)
      .run([&](std::uint32_t j, std::uint32_t) { return j != id.slot && w.admits(id.slot, j); },
           [&](std::uint32_t j, std::uint32_t, Scalar upper) {
             const Object& b = w.objects[j];
             return measure(id, *o.model, o.pose, w.id_of(j), *b.model, b.pose, request, upper);
           });
}

std::optional<NearestPair> World::nearest_to(const Model& model, const Transform& pose,
                                             const NearestRequest& request,
                                             const QueryFilter& filter) const {
  require_finite_pose(pose, "World::nearest_to");
  const Impl& w = *impl_;
  Scalar tolerance = 0;
  const Side objects{&w, {}};
  const Side query{nullptr, posed_box(model, pose, tolerance)};
  return Search(objects, query, false)
      .run([&](std::uint32_t j, std::uint32_t) { return Impl::admits(filter, w.bounds[j]); },
           [&](std::uint32_t j, std::uint32_t, Scalar upper) {
             const Object& a = w.objects[j];
             return measure(w.id_of(j), *a.model, a.pose, ObjectId{}, model, pose, request, upper);
           });
}

std::optional<NearestPair> World::nearest_pair(const World& other,
                                               const NearestRequest& request) const {
  const Impl& w = *impl_;
  const Impl& v = *other.impl_;
  const Side mine{&w, {}};
  const Side theirs{&v, {}};
  return Search(mine, theirs, false)
      .run(
          [&](std::uint32_t i, std::uint32_t j) {
            const Impl::Bounds& a = w.bounds[i];
            const Impl::Bounds& b = v.bounds[j];
            return (a.group & b.mask) != 0 && (b.group & a.mask) != 0;
          },
          [&](std::uint32_t i, std::uint32_t j, Scalar upper) {
            const Object& a = w.objects[i];
            const Object& b = v.objects[j];
            return measure(w.id_of(i), *a.model, a.pose, v.id_of(j), *b.model, b.pose, request,
                           upper);
          });
}

}  // namespace antcd
