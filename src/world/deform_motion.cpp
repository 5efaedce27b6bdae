// The World's continuous motion with deforming objects (World::sweep_motion): rigid pairs by
// antcd::sweep, pairs with a deforming object and self pairs by an exact discrete test at t = 0,
// then deform_sweep. See the block above MotionToi in world.hpp.
#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/error.hpp>
#include <antcd/geometry.hpp>
#include <antcd/self.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "util/check.hpp"
#include "util/parallel.hpp"
#include "world/continuous.hpp"
#include "world/world_impl.hpp"

namespace antcd {

namespace {

/// A deforming object of the motion: its world vertices at both ends.
struct Deforming {
  std::vector<Vec3> v0;
  std::vector<Vec3> v1;
};

/// Checks deforming[k] and returns its world vertices at both ends. Throws ArgumentError naming
/// `function`, the argument and the object.
Deforming check_deforming(const World::Impl& w, const VertexMotion& d, std::size_t k,
                          const Transform& pose1, const char* function) {
  const std::string arg = "deforming[" + std::to_string(k) + "]";
  const World::Impl::Object& o = w.get(d.id, function, (arg + ".id").c_str());
  const auto fail = [&](const std::string& problem) {
    throw ArgumentError(std::string(function) + ": " + arg + ".vertices of " +
                        object_label(o, d.id) + ": " + problem);
  };
  const Model& model = *o.model;
  const std::vector<Vec3>& rest = model.mesh().vertices;
  if (d.vertices.size() != rest.size()) {
    fail("got " + std::to_string(d.vertices.size()) + " vertices, the mesh has " +
         std::to_string(rest.size()));
  }
  for (std::size_t i = 0; i < d.vertices.size(); ++i) {
    if (!d.vertices[i].allFinite()) fail("vertex " + std::to_string(i) + " is not finite");
  }
  // As set_vertices (Model::refit): a triangle left out of the hierarchy must stay zero-area.
  if (model.stats().degenerate_triangles > 0) {
    std::vector<bool> in_tree(model.mesh().triangles.size(), false);
    for (const std::uint32_t t : model.leaf_triangles()) in_tree[t] = true;
    for (std::size_t t = 0; t < in_tree.size(); ++t) {
      const auto& tri = model.mesh().triangles[t];
      if (!in_tree[t] && !geometry::is_degenerate_triangle(d.vertices[tri[0]], d.vertices[tri[1]],
                                                           d.vertices[tri[2]])) {
        fail("triangle " + std::to_string(t) +
             " had zero area when the object's Model was built and has an area now (it is not in "
             "the hierarchy: add the object again with a Model built from the new mesh)");
      }
    }
  }
  Deforming out;
  out.v0.resize(rest.size());
  out.v1.resize(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    out.v0[i] = o.pose.apply(rest[i]);
    out.v1[i] = pose1.apply(d.vertices[i]);
    for (const Vec3* p : {&out.v0[i], &out.v1[i]}) {
      if (!(p->cwiseAbs().maxCoeff() <= kDeformMaxCoordinate)) {
        fail("vertex " + std::to_string(i) +
             "'s world position at t = " + (p == &out.v0[i] ? "0" : "1") + " exceeds " +
             number_text(kDeformMaxCoordinate) + " in magnitude (deform_ccd.hpp)");
      }
    }
  }
  return out;
}

/// The box of a deforming object's world vertices at both ends (linear paths stay in it), padded
/// for rounding.
Aabb deforming_box(const Deforming& d) {
  Aabb box;
  for (const Vec3& p : d.v0) box.extend(p);
  for (const Vec3& p : d.v1) box.extend(p);
  const Scalar scale = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  return grown(box, tolerance::volume_allowance(scale));
}

/// One side of a tested pair: a deforming object (world vertices at both ends) or a rigid one
/// (its model between two poses).
struct Side {
  const Model* model = nullptr;
  const Deforming* deforming = nullptr;
  Transform pose0;
  Transform pose1;

  /// Vertex v's world position at time t.
  [[nodiscard]] Vec3 at(std::uint32_t v, Scalar t) const {
    if (deforming != nullptr) return (1 - t) * deforming->v0[v] + t * deforming->v1[v];
    return ccd::interpolate_pose(pose0, pose1, t).apply(model->mesh().vertices[v]);
  }
};

/// The world point of a deform_sweep pair at its toi (see MotionToi::point): `first` holds the
/// vertex (vertex_in_first) or edge (a0, a1), `second` the rest.
Vec3 primitive_point(const DeformPair& p, const Side& first, const Side& second) {
  const Scalar t = p.toi;
  if (p.kind == DeformPairKind::VertexFace) {
    return (p.vertex_in_first ? first : second).at(p.indices[0], t);
  }
  const Vec3 a0 = first.at(p.indices[0], t);
  const Vec3 a1 = first.at(p.indices[1], t);
  const Vec3 b0 = second.at(p.indices[2], t);
  const Vec3 b1 = second.at(p.indices[3], t);
  // Segments as zero-area triangles: their closest points.
  const geometry::TriangleDistance d = geometry::triangle_distance(a0, a1, a1, b0, b1, b1);
  return (d.pa + d.pb) / 2;
}

/// A deform_sweep answer as a MotionToi (primitive relative to the order first, second).
std::optional<MotionToi> deform_hit(const DeformSweepResult& r, const Side& first,
                                    const Side& second) {
  if (!r.hit) return std::nullopt;
  MotionToi out;
  out.kind = MotionToiKind::Deform;
  out.toi = r.toi;
  out.tolerance_decided = r.tolerance_decided;
  out.primitive = r.pair;
  out.point = primitive_point(r.pair, first, second);
  return out;
}

/// `p` with the roles of its two models exchanged.
DeformPair swapped(DeformPair p) {
  if (p.kind == DeformPairKind::VertexFace) {
    p.vertex_in_first = !p.vertex_in_first;
  } else {
    p.indices = {p.indices[2], p.indices[3], p.indices[0], p.indices[1]};
  }
  return p;
}

/// The checked arguments of a motion and its broad phase's boxes.
struct Prepared {
  std::vector<std::size_t> index;      ///< motion_index's: per slot, new pose index + 1
  std::vector<std::size_t> def_index;  ///< per slot, its entry in `deforming` + 1 (0: rigid)
  std::vector<Deforming> worlds;       ///< by entry of `deforming`
  std::vector<Aabb> boxes;             ///< per slot, its swept box
};

Prepared prepare(const World::Impl& w, std::span<const ObjectId> ids,
                 std::span<const Transform> new_poses, std::span<const VertexMotion> deforming,
                 const char* function) {
  Prepared p;
  p.index = detail::motion_index(w, ids, new_poses, function, true);
  p.def_index.assign(w.objects.size(), 0);
  p.worlds.reserve(deforming.size());
  for (std::size_t k = 0; k < deforming.size(); ++k) {
    const ObjectId id = deforming[k].id;
    const std::string arg = "deforming[" + std::to_string(k) + "].id";
    w.get(id, function, arg.c_str());
    if (p.def_index[id.slot] != 0) {
      throw ArgumentError(std::string(function) + ": " + arg + " repeats deforming[" +
                          std::to_string(p.def_index[id.slot] - 1) +
                          "].id (a continuous motion gives each object one end shape)");
    }
    p.def_index[id.slot] = k + 1;
    const std::size_t at = p.index[id.slot];
    p.worlds.push_back(check_deforming(
        w, deforming[k], k, at == 0 ? w.objects[id.slot].pose : new_poses[at - 1], function));
  }
  // Rigid swept boxes, deforming objects' replaced by their vertex boxes.
  p.boxes = detail::swept_boxes(w, p.index, new_poses);
  for (std::uint32_t s = 0; s < w.objects.size(); ++s) {
    if (p.def_index[s] != 0) p.boxes[s] = deforming_box(p.worlds[p.def_index[s] - 1]);
  }
  return p;
}

}  // namespace

std::vector<ObjectPair> World::swept_candidate_pairs(std::span<const ObjectId> ids,
                                                     std::span<const Transform> new_poses,
                                                     std::span<const VertexMotion> deforming,
                                                     Scalar min_separation) const {
  const char* function = "World::swept_candidate_pairs";
  detail::require_non_negative(function, "min_separation", min_separation);
  const Impl& w = *impl_;
  const Prepared p = prepare(w, ids, new_poses, deforming, function);
  std::vector<ObjectPair> out;
  for (const auto& [i, j] : detail::swept_pairs(w, p.boxes, min_separation)) {
    out.push_back({w.id_of(i), w.id_of(j)});
  }
  return out;
}

std::vector<MotionToi> World::sweep_motion(std::span<const ObjectId> ids,
                                           std::span<const Transform> new_poses,
                                           std::span<const VertexMotion> deforming,
                                           const SweepRequest& request) const {
  const char* function = "World::sweep_motion";
  detail::check_request(request, function);
  const Impl& w = *impl_;
  const Prepared prep = prepare(w, ids, new_poses, deforming, function);
  const std::vector<std::size_t>& index = prep.index;
  const std::vector<std::size_t>& def_index = prep.def_index;
  const std::vector<Deforming>& worlds = prep.worlds;
  const auto end_pose = [&](std::uint32_t s) -> const Transform& {
    return index[s] == 0 ? w.objects[s].pose : new_poses[index[s] - 1];
  };
  std::vector<detail::SlotPair> tasks = detail::swept_pairs(w, prep.boxes, request.min_separation);
  for (std::uint32_t s = 0; s < w.objects.size(); ++s) {
    if (w.alive(s) && w.bounds[s].self_collision) tasks.emplace_back(s, s);
  }
  std::sort(tasks.begin(), tasks.end());

  DeformSweepRequest dreq;
  dreq.min_separation = request.min_separation;
  dreq.time_tolerance = request.time_tolerance;
  const auto side = [&](std::uint32_t s) {
    Side out;
    out.model = w.objects[s].model.get();
    out.deforming = def_index[s] == 0 ? nullptr : &worlds[def_index[s] - 1];
    out.pose0 = w.objects[s].pose;
    out.pose1 = end_pose(s);
    return out;
  };

  // The self pair of slot s.
  const auto self_pair = [&](std::uint32_t s) -> std::optional<MotionToi> {
    const Impl::Object& o = w.objects[s];
    const Model& model = *o.model;
    SelfIntersectionRequest first;
    first.first_only = true;
    const SelfIntersectionResult start = self_intersections(model, first);
    if (start.intersecting) {
      MotionToi out;
      out.kind = MotionToiKind::StartContact;
      out.triangles = start.pairs.front();
      const auto corner = [&](std::uint32_t t, int c) {
        return o.pose.apply(model.mesh().vertices[model.mesh().triangles[t][c]]);
      };
      const std::uint32_t ta = out.triangles[0];
      const std::uint32_t tb = out.triangles[1];
      out.point = geometry::triangle_distance(corner(ta, 0), corner(ta, 1), corner(ta, 2),
                                              corner(tb, 0), corner(tb, 1), corner(tb, 2))
                      .pa;
      return out;
    }
    const Side me = side(s);
    if (me.deforming != nullptr) {
      return deform_hit(deform_sweep(model, me.deforming->v0, me.deforming->v1, dreq), me, me);
    }
    if (request.min_separation > 0) {
      // A rigid motion keeps the shape: its self pairs are those of the model frame, held still.
      Side still = me;
      still.pose1 = still.pose0;
      const std::vector<Vec3>& v = model.mesh().vertices;
      return deform_hit(deform_sweep(model, v, v, dreq), still, still);
    }
    return std::nullopt;
  };

  // A pair of distinct objects i < j.
  const auto object_pair = [&](std::uint32_t i, std::uint32_t j) -> std::optional<MotionToi> {
    const Impl::Object& a = w.objects[i];
    const Impl::Object& b = w.objects[j];
    if (def_index[i] == 0 && def_index[j] == 0) {
      const SweepResult r =
          sweep(*a.model, a.pose, end_pose(i), *b.model, b.pose, end_pose(j), request);
      if (!r.hit) return std::nullopt;
      MotionToi out;
      out.kind = MotionToiKind::RigidSweep;
      out.toi = r.toi;
      out.tolerance_decided = r.tolerance_decided;
      out.point = r.contact.point;
      out.sweep = r;
      return out;
    }
    // deform_sweep finds vertex-face and edge-edge contacts only: surfaces already crossing at
    // t = 0 are found here (exact; within min_separation counts, as over the motion).
    {
      thread_local CollisionResult start;
      if (collide(*a.model, a.pose, *b.model, b.pose, CollisionRequest{request.min_separation},
                  start)) {
        MotionToi out;
        out.kind = MotionToiKind::StartContact;
        out.triangles = {start.contacts.front().triangle_a, start.contacts.front().triangle_b};
        out.point = start.contacts.front().point;
        return out;
      }
    }
    const Side sa = side(i);
    const Side sb = side(j);
    try {
      if (sa.deforming != nullptr && sb.deforming != nullptr) {
        return deform_hit(deform_sweep(*a.model, sa.deforming->v0, sa.deforming->v1, *b.model,
                                       sb.deforming->v0, sb.deforming->v1, dreq),
                          sa, sb);
      }
      if (sa.deforming != nullptr) {
        return deform_hit(deform_sweep(*a.model, sa.deforming->v0, sa.deforming->v1, *b.model,
                                       sb.pose0, sb.pose1, dreq),
                          sa, sb);
      }
      std::optional<MotionToi> hit =
          deform_hit(deform_sweep(*b.model, sb.deforming->v0, sb.deforming->v1, *a.model, sa.pose0,
                                  sa.pose1, dreq),
                     sb, sa);
      if (hit) hit->primitive = swapped(hit->primitive);
      return hit;
    } catch (const ArgumentError& e) {
      // The rigid side's posed vertices beyond deform_sweep's range: name the pair.
      throw ArgumentError(std::string(function) + ": " + object_label(a, w.id_of(i)) + " and " +
                          object_label(b, w.id_of(j)) + ": " + e.what());
    }
  };

  std::vector<std::optional<MotionToi>> results(tasks.size());
  const auto run = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k != last; ++k) {
      const auto [i, j] = tasks[k];
      results[k] = i == j ? self_pair(i) : object_pair(i, j);
    }
  };
  if (tasks.size() < detail::kParallelSweeps || parallel::max_concurrency() == 1) {
    run(0, tasks.size());
  } else {
    parallel::for_ranges(0, tasks.size(), 1, run);
  }
  std::vector<MotionToi> out;
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    if (!results[k]) continue;
    results[k]->a = w.id_of(tasks[k].first);
    results[k]->b = w.id_of(tasks[k].second);
    out.push_back(std::move(*results[k]));
  }
  return out;
}

std::vector<MotionToi> World::set_motion_continuous(std::span<const ObjectId> ids,
                                                    std::span<const Transform> new_poses,
                                                    std::span<const VertexMotion> deforming,
                                                    const SweepRequest& request) {
  // sweep_motion checks every argument set_poses and set_vertices would (counts, finiteness, the
  // hierarchy's left-out triangles), so neither throws below.
  std::vector<MotionToi> out = sweep_motion(ids, new_poses, deforming, request);
  set_poses(ids, new_poses);
  for (const VertexMotion& d : deforming) set_vertices(d.id, d.vertices);
  return out;
}

}  // namespace antcd
