// antcd/collide.hpp — exact mesh–mesh collision between two posed models.
//
// Conventions
// - Frames: each Model's geometry is in its own frame; pose_a / pose_b map those frames to the
//   world (p_world = R p + t). Contact points are returned in WORLD coordinates.
// - What counts as colliding: with delta == 0, the two surfaces share at least one point.
//   Triangles are closed, so touching at a vertex or along an edge, and coplanar overlap, collide.
//   Nested models whose surfaces do not meet (one entirely inside the other) do NOT collide by
//   default: antcd tests surfaces. With CollisionRequest::volume, two closed models (see
//   Model::is_closed) also collide when one lies wholly inside the other; open models keep the
//   surface semantics and the result says so (surface_only).
// - delta (the paper's collision threshold δ, Eq. 5) is a distance in mesh units, >= 0: the models
//   collide when some triangle of A is within distance delta of some triangle of B. Distances are
//   exact triangle–triangle distances, never centroid distances.
// - Contact normal and depth (CollisionRequest::contact_normals): one definition for every
//   contact, geometry::triangle_penetration on the contact's triangle pair. The normal is a unit
//   vector in the WORLD frame pointing from B towards A; the depth is the length of the shortest
//   translation separating the two triangles (separating-axis theorem over both face normals and
//   the 9 edge-edge cross products), so moving A by depth along the normal, or B by depth against
//   it, leaves that pair touching and any further separates it. Touching pairs have depth 0;
//   pairs reported only because of delta > 0 have depth -distance and the normal from B's closest
//   point to A's. The depth is per triangle pair, not the depth of the solids.
// - Each colliding triangle pair is reported once: leaves partition each model's triangles, so no
//   pair is tested twice.
// - Zero-area triangles are ignored (see Model).
// - Thread safety: collide() only reads its Models; any number of threads may query the same
//   Models concurrently, each with its own CollisionResult.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>

#include <cstdint>
#include <vector>

namespace antcd {

struct CollisionRequest {
  /// Collision threshold δ in mesh units (>= 0).
  Scalar delta = 0;
  /// false: stop at the first contact (boolean query). true: report every colliding pair.
  bool all_contacts = false;
  /// With all_contacts, stop after this many contacts (0 = no limit).
  std::size_t max_contacts = 0;
  /// Solids: when both models are closed and their surfaces do not meet (within delta), they
  /// still collide when a vertex of one lies inside the other (winding number of one vertex of
  /// each, so one model wholly inside the other; a model made of several disjoint closed parts is
  /// represented by the vertex of one part). Skipped when a surface contact was found.
  bool volume = false;
  /// Fill Contact::normal and Contact::depth (see the conventions above). Off by default: it adds
  /// a separating-axis pass per contact (bench/contact_bench.cpp measures it).
  bool contact_normals = false;
  /// Contact manifold for physics users: > 0 reduces the contacts found (all of them with
  /// all_contacts, up to max_contacts) to at most this many per touching region and implies
  /// contact_normals. Regions: contacts taken deepest first join the first region whose deepest
  /// contact's normal is within manifold_angle of theirs, else open a new one. Per region the
  /// deepest contact is kept, then repeatedly the one farthest from those kept (the extremes of
  /// the patch), so 4 points span a flat face-on-face contact. 0 = every contact.
  std::uint32_t manifold_points = 0;
  /// Angle (radians, in [0, pi]) between normals of one manifold region.
  Scalar manifold_angle = 0.35;
};

struct Contact {
  std::uint32_t triangle_a = 0;  ///< triangle index in A's mesh
  std::uint32_t triangle_b = 0;  ///< triangle index in B's mesh
  Vec3 point = Vec3::Zero();     ///< world frame: a common point, or the closest points' midpoint
  Scalar distance = 0;           ///< triangle distance (0 when they intersect)
  /// With contact_normals: unit normal, world frame, from B towards A (zero otherwise).
  Vec3 normal = Vec3::Zero();
  /// With contact_normals: penetration depth of the triangle pair (>= 0), -distance when apart.
  Scalar depth = 0;
  /// With manifold_points: the contact's region (0 .. CollisionResult::regions - 1).
  std::uint32_t region = 0;
};

struct CollisionResult {
  bool colliding = false;
  /// Boolean query: the one contact found (if any). All contacts: every colliding triangle pair,
  /// each once, in traversal order. With manifold_points: the kept contacts, region by region,
  /// each region's deepest first.
  std::vector<Contact> contacts;
  /// With manifold_points: the number of touching regions (0 when not colliding).
  std::uint32_t regions = 0;
  TraversalStats traversal;
  std::uint64_t triangle_tests = 0;
  /// With request.volume: colliding because one model lies inside the other (no contacts then).
  bool contained = false;
  /// With request.volume: a model is not closed, so only the surfaces were tested.
  bool surface_only = false;

  /// Empties the result but keeps the contacts' storage, so a reused result does not allocate.
  void clear() {
    colliding = false;
    contacts.clear();
    regions = 0;
    traversal = {};
    triangle_tests = 0;
    contained = false;
    surface_only = false;
  }
};

/// Exact collision query. Clears `result` first, fills it, returns result.colliding.
/// Throws antcd::ArgumentError if request.delta is negative or not finite, or manifold_angle is
/// outside [0, pi].
ANTCD_API bool collide(const Model& a, const Transform& pose_a, const Model& b,
                       const Transform& pose_b, const CollisionRequest& request,
                       CollisionResult& result);

/// Convenience overload returning a fresh result.
ANTCD_API CollisionResult collide(const Model& a, const Transform& pose_a, const Model& b,
                                  const Transform& pose_b, const CollisionRequest& request = {});

/// Where the last boolean query of two models found its contact (leaf node indices), for queries
/// of the same object pair frame after frame. A hint only: the verdict never depends on it; the
/// work does (two objects that touched last frame and moved little still touch there). A witness
/// of other models is dropped. One witness per object pair; not shared between threads.
struct PairWitness {
  const Model* a = nullptr;  ///< the models the leaves index
  const Model* b = nullptr;
  bool valid = false;
  std::uint32_t leaf_a = 0;
  std::uint32_t leaf_b = 0;
};

/// collide(a, pose_a, b, pose_b, request, result) starting from `witness` (temporal coherence),
/// which it then updates: the leaf pair of the last contact is tested first, and the hierarchies
/// are walked from the root when none of its triangles collides. For a boolean request
/// (all_contacts false, manifold_points 0) the verdict (colliding, contained, surface_only) is
/// collide()'s; the one contact reported may be another colliding triangle pair, and the
/// traversal statistics differ. Any other request is answered by collide() itself and leaves the
/// witness as it was. Allocation-free for a boolean request; errors as collide().
ANTCD_API bool collide(const Model& a, const Transform& pose_a, const Model& b,
                       const Transform& pose_b, const CollisionRequest& request,
                       CollisionResult& result, PairWitness& witness);

}  // namespace antcd
