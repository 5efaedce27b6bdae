// Private: convexity detection and the exact penetration depth of two convex polytopes by the
// separating-axis theorem over the facets of their Minkowski difference (convex.cpp).
#pragma once

#include <antcd/bvh.hpp>

#include <cstdint>
#include <vector>

namespace antcd::detail {

/// A convex closed model posed in the world: vertices, outward unit face normals, and the edges
/// between non-coplanar faces with their two faces' normals.
struct ConvexPolytope {
  struct Edge {
    Vec3 p0, p1;  ///< end points, world frame
    Vec3 n0, n1;  ///< outward unit normals of the two faces
    Vec3 arc;     ///< n1 x n0 (the Gauss-map arc's plane normal)
  };
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;     ///< one per non-degenerate triangle
  std::vector<Vec3> face_point;  ///< a vertex of that triangle
  std::vector<Edge> edges;
  Vec3 centroid = Vec3::Zero();

  [[nodiscard]] std::size_t support_index(const Vec3& n) const;  ///< argmax n·v
};

/// Sign of the mesh's orientation: +1 outward, -1 inward, 0 when its signed volume is 0. Exact
/// predicate per edge, see penetration.hpp (Convexity).
bool convex_mesh(const Mesh& mesh, int* orientation = nullptr);

ConvexPolytope make_polytope(const Model& model, const Transform& pose);

struct ConvexDepth {
  Scalar depth = 0;  ///< min over Minkowski facets of the support value; <= 0: no overlap
  Vec3 direction = Vec3::UnitX();  ///< unit, the way to move A
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
};

ConvexDepth convex_depth(const ConvexPolytope& a, const ConvexPolytope& b);

}  // namespace antcd::detail
