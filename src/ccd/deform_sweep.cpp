// CCD of deforming meshes (antcd/deform_ccd.hpp): swept bounds over the model's hierarchy
// (ccd/deform_bounds.hpp), a self- or dual traversal cut into a fixed list of tasks, and the
// primitive queries ccd::vertex_face / ccd::edge_edge on the triangle pairs the bounds keep.
// One piece past 600 lines: the traversal, its horizon pruning and the budget lift that keeps
// pruning from deciding an answer share one Context and one determinism argument; the entry
// points below it are the argument checks and the three pairings (self, two meshes, rigid).
#include <antcd/ccd.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/error.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>

#include "ccd/deform_bounds.hpp"
#include "ccd/normal_cone.hpp"
#include "ccd/primitive_unchecked.hpp"
#include "util/check.hpp"
#include "util/parallel.hpp"

namespace antcd {
namespace {

using detail::DeformBounds;
using detail::SweptNode;

constexpr Scalar kUnitRoundoff = std::numeric_limits<Scalar>::epsilon() / 2;
/// The traversal is cut into at least this many tasks (when the trees allow): a fixed number, so
/// that the answer does not depend on the thread count.
constexpr std::size_t kTasks = 256;
/// Most chord pieces a turning rigid other is followed along.
constexpr int kMaxPieces = 1024;

/// One moving mesh: its triangles, the motion and the per-call bounds.
struct Side {
  const Mesh* mesh = nullptr;
  std::span<const Vec3> v0, v1;
  const DeformBounds* bounds = nullptr;
};

static_assert(DeformSweepRequest{}.primitive_max_boxes == ccd::kMaxBoxes);

struct Context {
  Side a, b;
  bool self = true;
  Scalar sep = 0;
  Scalar tol = 1e-6;
  std::uint32_t max_boxes = ccd::kMaxBoxes;  ///< each primitive query's box budget
  Scalar pad = 0;
  bool all_pairs = false;
  /// Self, min_separation 0: the continuous normal-cone cull of self items (null: none).
  const Model* model = nullptr;
  const detail::DeformCones* cones = nullptr;
  /// First-hit mode: the earliest toi any task has found (shared; read for pruning only).
  std::atomic<Scalar>* shared_best = nullptr;
};

/// A unit of traversal: the self-pairs under node a (self_item) or the pairs between node a of
/// side a and node b of side b.
struct Item {
  std::uint32_t a = 0, b = 0;
  bool self_item = false;
};

struct TaskOut {
  bool hit = false;
  DeformPair best;
  std::vector<DeformPair> pairs;
  std::uint64_t node_pairs = 0;
  std::uint64_t primitive_queries = 0;
  std::uint64_t cone_tests = 0;
  std::uint64_t cone_culled = 0;
  std::size_t stack_peak = 0;
};

auto order_key(const DeformPair& p) {
  return std::make_tuple(p.toi, static_cast<int>(p.kind), !p.vertex_in_first, p.indices);
}
bool earlier(const DeformPair& x, const DeformPair& y) { return order_key(x) < order_key(y); }

bool boxes_overlap(const Vec3& lo_a, const Vec3& hi_a, const Vec3& lo_b, const Vec3& hi_b,
                   Scalar sep) {
  return (lo_a.array() <= hi_b.array() + sep).all() && (lo_b.array() <= hi_a.array() + sep).all();
}

/// Box over [0, s] of the triangle's corners (padded).
void triangle_box(const Side& side, std::uint32_t f, Scalar s, Scalar pad, Vec3& lo, Vec3& hi) {
  lo = Vec3::Constant(std::numeric_limits<Scalar>::infinity());
  hi = -lo;
  for (std::uint32_t v : side.mesh->triangles[f]) {
    const Vec3& p0 = side.v0[v];
    const Vec3 ps = s >= 1 ? side.v1[v] : Vec3(p0 + s * (side.v1[v] - p0));
    lo = lo.cwiseMin(p0).cwiseMin(ps);
    hi = hi.cwiseMax(p0).cwiseMax(ps);
  }
  lo.array() -= pad;
  hi.array() += pad;
}

bool has_vertex(const TriangleIndices& t, std::uint32_t v) {
  return t[0] == v || t[1] == v || t[2] == v;
}

class Traversal {
 public:
  Traversal(const Context& ctx, TaskOut& out) : c_(ctx), out_(out) {}

  void run(const Item& start) {
    std::vector<Item> stack;
    stack.reserve(64);
    stack.push_back(start);
    while (!stack.empty()) {
      out_.stack_peak = std::max(out_.stack_peak, stack.size());
      const Item it = stack.back();
      stack.pop_back();
      if (it.self_item) {
        const SweptNode& n = c_.a.bounds->nodes[it.a];
        if (n.is_leaf()) {
          leaf_pairs(n, n, true);
        } else if (!cone_culls(it.a)) {
          stack.push_back({n.left, n.right, false});
          stack.push_back({n.right, 0, true});
          stack.push_back({n.left, 0, true});
        }
        continue;
      }
      ++out_.node_pairs;
      const SweptNode& na = c_.a.bounds->nodes[it.a];
      const SweptNode& nb = c_.b.bounds->nodes[it.b];
      if (!nodes_overlap(na, nb)) continue;
      if (na.is_leaf() && nb.is_leaf()) {
        leaf_pairs(na, nb, false);
        continue;
      }
      if (split_first(na, nb)) {
        stack.push_back({na.right, it.b, false});
        stack.push_back({na.left, it.b, false});
      } else {
        stack.push_back({it.a, nb.right, false});
        stack.push_back({it.a, nb.left, false});
      }
    }
  }

  [[nodiscard]] bool nodes_overlap(const SweptNode& na, const SweptNode& nb) const {
    Vec3 lo_a, hi_a, lo_b, hi_b;
    detail::swept_box(na, horizon(), c_.pad, lo_a, hi_a);
    detail::swept_box(nb, horizon(), c_.pad, lo_b, hi_b);
    return boxes_overlap(lo_a, hi_a, lo_b, hi_b, c_.sep);
  }

  /// Whether the self pairs under node `node` are culled by its normal cone (ccd/normal_cone.hpp:
  /// none of them touches over [0, 1]).
  bool cone_culls(std::uint32_t node) {
    if (c_.cones == nullptr || node >= c_.cones->node_signs.size() ||
        c_.cones->node_signs[node] == 0 || c_.cones->topology->find(node) == nullptr) {
      return false;
    }
    ++out_.cone_tests;
    if (!detail::deform_cone_culls(*c_.model, *c_.cones, node, c_.a.v0, c_.a.v1, edge_boxes_)) {
      return false;
    }
    ++out_.cone_culled;
    return true;
  }

  /// Split node a (else b): the internal one, the larger swept box when both are.
  static bool split_first(const SweptNode& na, const SweptNode& nb) {
    if (na.is_leaf()) return false;
    if (nb.is_leaf()) return true;
    const Scalar ea = (na.hi0.cwiseMax(na.hi1) - na.lo0.cwiseMin(na.lo1)).sum();
    const Scalar eb = (nb.hi0.cwiseMax(nb.hi1) - nb.lo0.cwiseMin(nb.lo1)).sum();
    return ea >= eb;
  }

 private:
  /// The time up to which contacts still matter: the earliest toi any task found so far, plus the
  /// time tolerance (first-hit mode). A pair apart over [0, horizon] by more than the pad (which
  /// holds the primitives' tolerance reach, see pad_for) has a toi later than that earliest one,
  /// so pruning it never changes the answer, whatever the order the tasks run in.
  [[nodiscard]] Scalar horizon() const {
    if (c_.all_pairs) return 1;
    Scalar best = c_.shared_best->load(std::memory_order_relaxed);
    if (out_.hit) best = std::min(best, out_.best.toi);
    return std::min(Scalar(1), best + c_.tol);
  }

  void leaf_pairs(const SweptNode& na, const SweptNode& nb, bool same) {
    const auto& ta = c_.a.bounds->triangles;
    const auto& tb = c_.b.bounds->triangles;
    for (std::uint32_t i = 0; i < na.count; ++i) {
      const std::uint32_t fa = ta[na.first + i];
      Vec3 lo_a, hi_a;
      triangle_box(c_.a, fa, horizon(), c_.pad, lo_a, hi_a);
      for (std::uint32_t j = same ? i + 1 : 0; j < nb.count; ++j) {
        const std::uint32_t fb = tb[nb.first + j];
        Vec3 lo_b, hi_b;
        triangle_box(c_.b, fb, horizon(), c_.pad, lo_b, hi_b);
        if (!boxes_overlap(lo_a, hi_a, lo_b, hi_b, c_.sep)) continue;
        triangle_pair(fa, fb);
        if (!c_.all_pairs && out_.hit) triangle_box(c_.a, fa, horizon(), c_.pad, lo_a, hi_a);
      }
    }
  }

  void triangle_pair(std::uint32_t fa, std::uint32_t fb) {
    const TriangleIndices& a = c_.a.mesh->triangles[fa];
    const TriangleIndices& b = c_.b.mesh->triangles[fb];
    const detail::OwnerMask ma = c_.a.bounds->owner[fa];
    const detail::OwnerMask mb = c_.b.bounds->owner[fb];
    for (int k = 0; k < 3; ++k) {
      if ((ma >> k) & 1u) {
        if (!(c_.self && has_vertex(b, a[k]))) vertex_face(c_.a, a[k], c_.b, fb, true, fa, fb);
      }
      if ((mb >> k) & 1u) {
        if (!(c_.self && has_vertex(a, b[k]))) {
          vertex_face(c_.b, b[k], c_.a, fa, c_.self, fa, fb);
        }
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (!((ma >> (3 + k)) & 1u)) continue;
      const std::uint32_t a0 = a[k], a1 = a[(k + 1) % 3];
      for (int m = 0; m < 3; ++m) {
        if (!((mb >> (3 + m)) & 1u)) continue;
        const std::uint32_t b0 = b[m], b1 = b[(m + 1) % 3];
        if (c_.self && (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1)) continue;
        edge_edge(a0, a1, b0, b1, fa, fb);
      }
    }
  }

  void vertex_face(const Side& vs, std::uint32_t v, const Side& fs, std::uint32_t f,
                   bool vertex_in_first, std::uint32_t fa, std::uint32_t fb) {
    const TriangleIndices& t = fs.mesh->triangles[f];
    const std::array<Vec3, 4> p0 = {vs.v0[v], fs.v0[t[0]], fs.v0[t[1]], fs.v0[t[2]]};
    const std::array<Vec3, 4> p1 = {vs.v1[v], fs.v1[t[0]], fs.v1[t[1]], fs.v1[t[2]]};
    ++out_.primitive_queries;
    const ccd::PrimitiveResult r =
        ccd::unchecked::vertex_face(p0, p1, c_.sep, c_.tol, c_.max_boxes);
    if (!r.hit) return;
    DeformPair p;
    p.kind = DeformPairKind::VertexFace;
    p.vertex_in_first = vertex_in_first;
    p.indices = {v, f, 0, 0};
    record(p, r, fa, fb);
  }

  void edge_edge(std::uint32_t a0, std::uint32_t a1, std::uint32_t b0, std::uint32_t b1,
                 std::uint32_t fa, std::uint32_t fb) {
    if (a0 > a1) std::swap(a0, a1);
    if (b0 > b1) std::swap(b0, b1);
    if (c_.self && std::make_pair(b0, b1) < std::make_pair(a0, a1)) {
      std::swap(a0, b0);
      std::swap(a1, b1);
    }
    const Side& sa = c_.a;
    const Side& sb = c_.self ? c_.a : c_.b;
    const std::array<Vec3, 4> p0 = {sa.v0[a0], sa.v0[a1], sb.v0[b0], sb.v0[b1]};
    const std::array<Vec3, 4> p1 = {sa.v1[a0], sa.v1[a1], sb.v1[b0], sb.v1[b1]};
    ++out_.primitive_queries;
    const ccd::PrimitiveResult r = ccd::unchecked::edge_edge(p0, p1, c_.sep, c_.tol, c_.max_boxes);
    if (!r.hit) return;
    DeformPair p;
    p.kind = DeformPairKind::EdgeEdge;
    p.indices = {a0, a1, b0, b1};
    record(p, r, fa, fb);
  }

  /// Whether triangles fa (side a) and fb (side b) are apart over [0, s]: the padded boxes that
  /// leaf_pairs tests (a node's box holds them up to the last bits of rounding).
  [[nodiscard]] bool triangles_apart(std::uint32_t fa, std::uint32_t fb, Scalar s) const {
    Vec3 lo_a, hi_a, lo_b, hi_b;
    triangle_box(c_.a, fa, s, c_.pad, lo_a, hi_a);
    triangle_box(c_.b, fb, s, c_.pad, lo_b, hi_b);
    return !boxes_overlap(lo_a, hi_a, lo_b, hi_b, c_.sep);
  }

  /// A primitive that ran out of its box budget answers the start of its earliest unresolved box,
  /// which its geometry does not bound: it can lie before the time the two triangles' padded boxes
  /// prove them apart until, and whether the pair is examined at all depends on the horizon, so on
  /// the task order. Its toi is lifted to the largest s (bisected to time_tolerance / 2) such
  /// that the boxes are apart over [0, s]: still never after the true first contact (apart boxes
  /// are apart surfaces), and a pair that a traversal pruned at horizon h >= best + tol now gets a
  /// toi >= h - tol / 2 > best, so it never changes the answer. Apart over [0, 1]: no contact.
  [[nodiscard]] bool lift_exhausted(DeformPair& p, std::uint32_t fa, std::uint32_t fb) const {
    if (!triangles_apart(fa, fb, p.toi)) return true;
    if (triangles_apart(fa, fb, 1)) return false;
    Scalar lo = p.toi;
    Scalar hi = 1;
    for (int k = 0; k < 64 && hi - lo > c_.tol / 2; ++k) {
      const Scalar mid = lo + (hi - lo) / 2;
      if (mid <= lo || mid >= hi) break;
      (triangles_apart(fa, fb, mid) ? lo : hi) = mid;
    }
    p.toi = lo;
    return true;
  }

  void record(DeformPair& p, const ccd::PrimitiveResult& r, std::uint32_t fa, std::uint32_t fb) {
    p.toi = r.toi;
    p.tolerance_decided = r.tolerance_decided;
    p.budget_exhausted = r.budget_exhausted;
    if (p.budget_exhausted && !lift_exhausted(p, fa, fb)) return;
    if (c_.all_pairs) {
      out_.pairs.push_back(p);
      if (!out_.hit || earlier(p, out_.best)) out_.best = p;
      out_.hit = true;
      return;
    }
    if (!out_.hit || earlier(p, out_.best)) {
      out_.best = p;
      out_.hit = true;
      Scalar seen = c_.shared_best->load(std::memory_order_relaxed);
      while (p.toi < seen &&
             !c_.shared_best->compare_exchange_weak(seen, p.toi, std::memory_order_relaxed)) {
      }
    }
  }

  const Context& c_;
  TaskOut& out_;
  std::vector<detail::EdgeBox> edge_boxes_;  ///< the cone tests' scratch
};

/// The fixed task list: the root item expanded breadth-first (pairs culled over [0, 1]) until there
/// are kTasks items or none can be expanded. Depends on the bounds only.
std::vector<Item> make_tasks(const Context& c, Item root, TaskOut& scratch) {
  std::vector<Item> items = {root};
  std::uint64_t& node_pairs = scratch.node_pairs;
  Context whole = c;  // culled over [0, 1]: no shared best yet
  whole.all_pairs = true;
  Traversal probe(whole, scratch);
  while (items.size() < kTasks) {
    std::vector<Item> next;
    bool changed = false;
    for (const Item& it : items) {
      if (it.self_item) {
        const SweptNode& n = c.a.bounds->nodes[it.a];
        if (n.is_leaf()) {
          next.push_back(it);
        } else if (!probe.cone_culls(it.a)) {
          next.push_back({n.left, 0, true});
          next.push_back({n.right, 0, true});
          next.push_back({n.left, n.right, false});
          changed = true;
        }
        continue;
      }
      const SweptNode& na = c.a.bounds->nodes[it.a];
      const SweptNode& nb = c.b.bounds->nodes[it.b];
      if (na.is_leaf() && nb.is_leaf()) {
        next.push_back(it);
        continue;
      }
      ++node_pairs;
      changed = true;
      if (!probe.nodes_overlap(na, nb)) continue;
      if (Traversal::split_first(na, nb)) {
        next.push_back({na.left, it.b, false});
        next.push_back({na.right, it.b, false});
      } else {
        next.push_back({it.a, nb.left, false});
        next.push_back({it.a, nb.right, false});
      }
    }
    items.swap(next);
    if (!changed) break;
  }
  return items;
}

DeformSweepResult run_sweep(const Context& c, Item root, std::size_t bounds_bytes) {
  DeformSweepResult result;
  TaskOut split;
  const std::vector<Item> tasks = make_tasks(c, root, split);
  result.node_pairs = split.node_pairs;
  result.cone_tests = split.cone_tests;
  result.cone_culled = split.cone_culled;
  std::vector<TaskOut> outs(tasks.size());
  std::atomic<Scalar> shared_best{std::numeric_limits<Scalar>::infinity()};
  Context ctx = c;
  ctx.shared_best = &shared_best;
  parallel::for_each_index(0, tasks.size(), [&](std::size_t k) {
    Traversal t(ctx, outs[k]);
    t.run(tasks[k]);
  });
  std::size_t stack_bytes = 0;
  for (const TaskOut& o : outs) {
    result.node_pairs += o.node_pairs;
    result.primitive_queries += o.primitive_queries;
    result.cone_tests += o.cone_tests;
    result.cone_culled += o.cone_culled;
    stack_bytes = std::max(stack_bytes, std::max<std::size_t>(o.stack_peak, 64) * sizeof(Item));
    if (o.hit && (!result.hit || earlier(o.best, result.pair))) {
      result.hit = true;
      result.pair = o.best;
    }
  }
  if (result.hit) {
    result.toi = result.pair.toi;
    result.tolerance_decided = result.pair.tolerance_decided;
  }
  if (c.all_pairs) {
    std::size_t n = 0;
    for (const TaskOut& o : outs) n += o.pairs.size();
    result.pairs.reserve(n);
    for (const TaskOut& o : outs)
      result.pairs.insert(result.pairs.end(), o.pairs.begin(), o.pairs.end());
    std::sort(result.pairs.begin(), result.pairs.end(), earlier);
  }
  result.tasks = tasks.size();
  // Held at once: the bounds, the task list and outputs, one stack per worker.
  result.scratch_bytes = bounds_bytes + tasks.capacity() * sizeof(Item) +
                         outs.capacity() * sizeof(TaskOut) +
                         static_cast<std::size_t>(parallel::max_concurrency()) * stack_bytes;
  return result;
}

/// Checks the positions; returns their largest |coordinate|.
Scalar check_positions(const char* function, const char* name, std::span<const Vec3> v,
                       const Model& model) {
  const std::size_t expected = model.mesh().vertices.size();
  if (v.size() != expected) {
    throw ArgumentError(std::string(function) + ": " + name + " has " + std::to_string(v.size()) +
                        " positions, model '" + model.source() + "' has " +
                        std::to_string(expected) + " vertices");
  }
  // One branch-free pass (a NaN fails every comparison), then the first bad index if any.
  bool ok = true;
  Scalar m = 0;
  for (const Vec3& p : v) {
    const Scalar x = std::abs(p.x()), y = std::abs(p.y()), z = std::abs(p.z());
    ok &= (x <= kDeformMaxCoordinate) & (y <= kDeformMaxCoordinate) & (z <= kDeformMaxCoordinate);
    m = std::max(m, std::max(x, std::max(y, z)));
  }
  if (ok) return m;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].allFinite() || v[i].cwiseAbs().maxCoeff() > kDeformMaxCoordinate) {
      throw ArgumentError(std::string(function) + ": " + name + "[" + std::to_string(i) +
                          "] must be finite with |coordinate| <= 1e150");
    }
  }
  return m;
}

void check_request(const char* function, const DeformSweepRequest& r) {
  detail::require_non_negative(function, "min_separation", r.min_separation);
  detail::require_positive(function, "time_tolerance", r.time_tolerance);
  detail::require_non_negative(function, "pose_path_tolerance", r.pose_path_tolerance);
  if (r.primitive_max_boxes == 0) {
    throw ArgumentError(std::string(function) + ": primitive_max_boxes must be at least 1, got 0");
  }
}

/// The bounds' padding: their rounding (8 u (M + D + sep)), and the reach of a tolerance-decided
/// primitive hit (ccd.hpp: within min_separation + 3W + rounding per axis at a time in [toi, toi +
/// time_tolerance], W = max(time_tolerance 2 D, 4 eps), eps = 96 u M: the primitive's a-priori
/// rounding bound), so that a pair the bounds drop could not have reported an earlier toi.
Scalar pad_for(const DeformBounds& a, const DeformBounds& b, Scalar sep, Scalar tol) {
  const Scalar m = std::max(a.max_coordinate, b.max_coordinate);
  const Scalar d = std::max(a.max_displacement, b.max_displacement);
  const Scalar eps = 96 * kUnitRoundoff * m + std::numeric_limits<Scalar>::min();
  const Scalar w = std::max(tol * 2 * d, 4 * eps);
  return (8 * kUnitRoundoff * (m + d + sep) + 3 * w + 4 * eps) * (1 + 16 * kUnitRoundoff);
}

DeformSweepResult two_meshes(const Model& a, std::span<const Vec3> A0, std::span<const Vec3> A1,
                             const Model& b, std::span<const Vec3> B0, std::span<const Vec3> B1,
                             Scalar sep, const DeformSweepRequest& request) {
  const DeformBounds ba = detail::make_deform_bounds(a, A0, A1);
  const DeformBounds bb = detail::make_deform_bounds(b, B0, B1);
  Context c;
  c.a = {&a.mesh(), A0, A1, &ba};
  c.b = {&b.mesh(), B0, B1, &bb};
  c.self = false;
  c.sep = sep;
  c.tol = request.time_tolerance;
  c.max_boxes = request.primitive_max_boxes;
  c.pad = pad_for(ba, bb, sep, request.time_tolerance);
  c.all_pairs = request.all_pairs;
  return run_sweep(c, {ba.root, bb.root, false}, ba.scratch_bytes + bb.scratch_bytes);
}

}  // namespace

DeformSweepResult deform_sweep(const Model& model, std::span<const Vec3> V0,
                               std::span<const Vec3> V1, const DeformSweepRequest& request) {
  constexpr const char* kFn = "deform_sweep";
  const Scalar m =
      std::max(check_positions(kFn, "V0", V0, model), check_positions(kFn, "V1", V1, model));
  check_request(kFn, request);
  // The cull proves that no pair touches (distance 0): with a separation it does not apply.
  detail::DeformCones cones;
  if (request.normal_cones && request.min_separation == 0) {
    cones = detail::make_deform_cones(model, V0, V1, m);
  }
  if (cones.root_culled && model.leaf_triangles().size() == model.mesh().triangles.size()) {
    // The root holds every triangle and none of its pairs touches: no bounds, no traversal.
    DeformSweepResult result;
    result.cone_tests = result.cone_culled = 1;
    result.scratch_bytes = cones.bytes();
    return result;
  }
  const DeformBounds bounds = detail::make_deform_bounds(model, V0, V1);
  Context c;
  c.a = {&model.mesh(), V0, V1, &bounds};
  c.b = c.a;
  c.self = true;
  c.sep = request.min_separation;
  c.tol = request.time_tolerance;
  c.max_boxes = request.primitive_max_boxes;
  c.pad = pad_for(bounds, bounds, c.sep, c.tol);
  c.all_pairs = request.all_pairs;
  if (cones.topology) {
    c.model = &model;
    c.cones = &cones;
  }
  return run_sweep(c, {bounds.root, 0, true}, bounds.scratch_bytes + cones.bytes());
}

DeformSweepResult deform_sweep(const Model& a, std::span<const Vec3> A0, std::span<const Vec3> A1,
                               const Model& b, std::span<const Vec3> B0, std::span<const Vec3> B1,
                               const DeformSweepRequest& request) {
  constexpr const char* kFn = "deform_sweep";
  check_positions(kFn, "A0", A0, a);
  check_positions(kFn, "A1", A1, a);
  check_positions(kFn, "B0", B0, b);
  check_positions(kFn, "B1", B1, b);
  check_request(kFn, request);
  return two_meshes(a, A0, A1, b, B0, B1, request.min_separation, request);
}

DeformSweepResult deform_sweep(const Model& a, std::span<const Vec3> A0, std::span<const Vec3> A1,
                               const Model& b, const Transform& pose_b0, const Transform& pose_b1,
                               const DeformSweepRequest& request) {
  constexpr const char* kFn = "deform_sweep";
  check_positions(kFn, "A0", A0, a);
  check_positions(kFn, "A1", A1, a);
  check_request(kFn, request);
  for (const auto* pose : {&pose_b0, &pose_b1}) {
    if (!pose->rotation.allFinite() || !pose->translation.allFinite()) {
      throw ArgumentError(std::string(kFn) + ": " + (pose == &pose_b0 ? "pose_b0" : "pose_b1") +
                          " is not finite");
    }
  }
  const std::vector<Vec3>& local = b.mesh().vertices;
  Scalar r = 0;
  for (const Vec3& p : local) r = std::max(r, p.norm());
  const Quat q0(pose_b0.rotation);
  const Quat q1(pose_b1.rotation);
  const Scalar theta = q0.angularDistance(q1);
  Scalar delta = request.pose_path_tolerance > 0 ? request.pose_path_tolerance : 1e-3 * r;
  int pieces = 1;
  if (theta > 0 && r > 0) {
    const Scalar needed = std::ceil(theta * std::sqrt(r / (8 * std::max(delta, Scalar(1e-300)))));
    pieces = static_cast<int>(std::clamp(needed, Scalar(1), Scalar(kMaxPieces)));
  }
  const Scalar bend = theta > 0 ? r * (theta / pieces) * (theta / pieces) / 8 : 0;
  // Rounding allowance: the interpolated poses, the mapped vertices and the interpolated A.
  Scalar scene =
      r + pose_b0.translation.cwiseAbs().maxCoeff() + pose_b1.translation.cwiseAbs().maxCoeff();
  for (std::size_t v = 0; v < A0.size(); ++v) {
    scene = std::max({scene, A0[v].cwiseAbs().maxCoeff(), A1[v].cwiseAbs().maxCoeff()});
  }
  const Scalar sep = request.min_separation + bend * (1 + 1e-9) + 64 * kUnitRoundoff * scene;
  if (!std::isfinite(sep) || sep > kDeformMaxCoordinate) {
    throw ArgumentError(std::string(kFn) + ": pose_b0, pose_b1: the scene is too large");
  }

  auto world = [&](Scalar t, std::vector<Vec3>& out) {
    const Transform pose = ccd::interpolate_pose(pose_b0, pose_b1, t);
    out.resize(local.size());
    for (std::size_t v = 0; v < local.size(); ++v)
      out[v] = pose.rotation * local[v] + pose.translation;
  };
  auto lerp = [&](Scalar t, std::vector<Vec3>& out) {
    out.resize(A0.size());
    for (std::size_t v = 0; v < A0.size(); ++v)
      out[v] = t == 1 ? A1[v] : Vec3(A0[v] + t * (A1[v] - A0[v]));
  };
  DeformSweepResult total;
  std::vector<Vec3> b_start, b_end, a_start, a_end;
  world(0, b_start);
  lerp(0, a_start);
  for (int k = 0; k < pieces; ++k) {
    const Scalar t0 = static_cast<Scalar>(k) / pieces;
    const Scalar t1 = k + 1 == pieces ? Scalar(1) : static_cast<Scalar>(k + 1) / pieces;
    world(t1, b_end);
    lerp(t1, a_end);
    DeformSweepResult piece = two_meshes(a, a_start, a_end, b, b_start, b_end, sep, request);
    total.node_pairs += piece.node_pairs;
    total.primitive_queries += piece.primitive_queries;
    total.tasks += piece.tasks;
    total.scratch_bytes =
        std::max(total.scratch_bytes, piece.scratch_bytes + 4 * local.size() * sizeof(Vec3));
    // Piece time s -> global time, rounded down (never later than the true one), within the piece.
    auto global = [&](Scalar s) {
      const Scalar t = t0 + s * (t1 - t0);
      return std::max(t0, std::nextafter(std::nextafter(t, Scalar(0)), Scalar(0)));
    };
    for (DeformPair& p : piece.pairs) {
      p.toi = global(p.toi);
      p.tolerance_decided = p.tolerance_decided || theta > 0;
      total.pairs.push_back(p);
    }
    if (piece.hit && !total.hit) {
      total.hit = true;
      total.pair = piece.pair;
      total.pair.toi = global(piece.pair.toi);
      total.pair.tolerance_decided = piece.pair.tolerance_decided || theta > 0;
      total.toi = total.pair.toi;
      total.tolerance_decided = total.pair.tolerance_decided;
      if (!request.all_pairs) break;
    }
    b_start.swap(b_end);
    a_start.swap(a_end);
  }
  if (request.all_pairs) {  // one entry per pair: its earliest piece's
    auto same = [](const DeformPair& x, const DeformPair& y) {
      return x.kind == y.kind && x.vertex_in_first == y.vertex_in_first && x.indices == y.indices;
    };
    std::sort(total.pairs.begin(), total.pairs.end(), [](const DeformPair& x, const DeformPair& y) {
      return std::make_tuple(static_cast<int>(x.kind), !x.vertex_in_first, x.indices, x.toi) <
             std::make_tuple(static_cast<int>(y.kind), !y.vertex_in_first, y.indices, y.toi);
    });
    total.pairs.erase(std::unique(total.pairs.begin(), total.pairs.end(), same), total.pairs.end());
    std::sort(total.pairs.begin(), total.pairs.end(), earlier);
  }
  return total;
}

Scalar collision_free_step(const Model& model, std::span<const Vec3> V0, std::span<const Vec3> V1,
                           Scalar min_separation, Scalar time_tolerance) {
  DeformSweepRequest request;
  request.min_separation = min_separation;
  request.time_tolerance = time_tolerance;
  const DeformSweepResult r = deform_sweep(model, V0, V1, request);
  return r.hit ? r.toi : 1;
}

}  // namespace antcd
