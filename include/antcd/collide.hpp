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
};

struct Contact {
  std::uint32_t triangle_a = 0;  ///< triangle index in A's mesh
  std::uint32_t triangle_b = 0;  ///< triangle index in B's mesh
  Vec3 point = Vec3::Zero();     ///< world frame: a common point, or the closest points' midpoint
  Scalar distance = 0;           ///< triangle distance (0 when they intersect)
};

struct CollisionResult {
  bool colliding = false;
  /// Boolean query: the one contact found (if any). All contacts: every colliding triangle pair,
  /// each once, in traversal order.
  std::vector<Contact> contacts;
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
    traversal = {};
    triangle_tests = 0;
    contained = false;
    surface_only = false;
  }
};

/// Exact collision query. Clears `result` first, fills it, returns result.colliding.
/// Throws antcd::ArgumentError if request.delta is negative or not finite.
ANTCD_API bool collide(const Model& a, const Transform& pose_a, const Model& b,
                       const Transform& pose_b, const CollisionRequest& request,
                       CollisionResult& result);

/// Convenience overload returning a fresh result.
ANTCD_API CollisionResult collide(const Model& a, const Transform& pose_a, const Model& b,
                                  const Transform& pose_b, const CollisionRequest& request = {});

}  // namespace antcd
