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
    /// The arc lies in the spherical cap about `cap` (unit, n0 + n1 normalised) whose points are
    /// within chord `chord` (= |n0 - cap|) of it.
    Vec3 cap;
    Scalar chord;
  };
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;     ///< one per non-degenerate triangle
  std::vector<Vec3> face_point;  ///< a vertex of that triangle
  std::vector<Edge> edges;
  /// Vertex graph (every mesh edge), compressed rows: the neighbours of vertex i are
  /// adjacent[adjacent_begin[i] .. adjacent_begin[i + 1]).
  std::vector<std::uint32_t> adjacent_begin;
  std::vector<std::uint32_t> adjacent;

  /// argmax n·v by hill climbing on the vertex graph from `start` (a local maximum of a linear
  /// function over a convex polytope's graph is a global one).
  [[nodiscard]] std::size_t support_index(const Vec3& n, std::size_t start = 0) const;
  /// max over the face planes of n·(p - face point): negative strictly inside (floating point).
  [[nodiscard]] Scalar plane_margin(const Vec3& p) const;
};

/// Six times the signed volume enclosed by the mesh (its sign: + outward, - inward orientation).
Scalar signed_volume6(const Mesh& mesh);

/// Whether a closed model is convex (every edge convex, heights within 1e-10 of its size count
/// as flat, one connected piece); when it is and `out` is not null, fills `out` with the model
/// posed by `pose`. The model-frame analysis is done once per Model (its cache, under a
/// once-flag: thread-safe) and only posed per call.
bool convex_polytope(const Model& model, const Transform& pose, ConvexPolytope* out);

struct ConvexDepth {
  Scalar depth = 0;  ///< min over Minkowski facets of the support value; <= 0: no overlap
  Vec3 direction = Vec3::UnitX();  ///< unit, the way to move A
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
};

ConvexDepth convex_depth(const ConvexPolytope& a, const ConvexPolytope& b);

/// The point deepest inside both polytopes (by their face planes) among a few points of the
/// segment between the depth's points; its margin (negative: inside both by that much) is
/// returned through `margin`.
Vec3 convex_witness(const ConvexPolytope& a, const ConvexPolytope& b, const ConvexDepth& d,
                    Scalar& margin);

/// Moves `p` into both polytopes, at least `depth` inside their face planes, by projecting it onto
/// the most violated (shrunk) half-space, up to 256 times (alternating projections converge for
/// intersecting convex sets). Returns the point, its margin through `margin`.
Vec3 push_inside(const ConvexPolytope& a, const ConvexPolytope& b, Vec3 p, Scalar depth,
                 Scalar& margin);

}  // namespace antcd::detail
