// antcd/self.hpp — self-collision of one Model: where a (deforming) mesh meets or nears itself.
//
// Definitions
// - Deforming model: a Model whose triangles are fixed and whose vertex positions change, every
//   frame or when the user says so (Model::refit, antcd/bvh.hpp). Every query here reads the
//   positions the Model holds now.
// - Sharing: two triangles share a vertex when their index triples hold the same vertex INDEX of
//   the mesh, and share an edge when they hold two common indices. Positions do not count: two
//   vertices of different indices at one point are not shared, and triangles meeting there
//   intersect. The mesh loaders (antcd/load.hpp) join exactly coincident vertices of a file into
//   one index, so a loaded mesh shares what its file's geometry shares.
// - Self-intersection: two distinct triangles of the mesh whose intersection (closed triangles)
//   holds a point their sharing does not require:
//     * sharing nothing: they meet at all (touching counts, as everywhere in antcd);
//     * sharing one vertex v: they meet at a point other than v (they overlap while coplanar, or
//       one folds through the other); decided as: the edge of either opposite v meets the other;
//     * sharing an edge uv: they meet off uv, which happens exactly when the four points are
//       coplanar and the two unshared vertices lie on the same side of the line uv (the pair is
//       folded flat onto itself); triangles bent about uv at any non-zero angle meet on uv only;
//     * sharing all three vertices (a duplicated face, in either orientation): always.
//   Every verdict uses exact-sign predicates (geometry::orient3d and the 2-D orientation in a
//   coordinate plane), as every verdict in antcd does: no tolerance.
// - Degenerate triangle: one whose three corners are exactly collinear (zero area, decided
//   exactly; includes a repeated index). It has no interior and no orientation; it is reported
//   in SelfIntersectionResult::degenerate_triangles and takes part in no pair, whatever it
//   touches. This is what CGAL::Polygon_mesh_processing::self_intersections does (it reports a
//   degenerate face f as the pair (f, f) and no other pair with it); triangles of non-zero area,
//   however thin (including those the hierarchy leaves out as numerically degenerate, see
//   BvhStats::degenerate_triangles), are tested like any other.
// - Self-proximity at delta >= 0: the vertex–triangle pairs (the vertex not a corner of the
//   triangle, by index) and the edge–edge pairs (mesh edges, by index, with no common vertex
//   index) whose distance is at most delta, with the closest points and the distance (computed
//   in doubles as geometry::point_triangle_distance_squared and segment_segment_distance_squared
//   compute them; not an exact verdict at distance == delta). Degenerate triangles take part
//   with their vertices and edges; a pair of primitives is reported once.
//
// Broken meshes are answered, not refused: non-manifold edges, inconsistent orientation, triangle
// soups (nothing shared), duplicated and degenerate faces.
//
// Thread-safety and determinism: both queries are const on the Model and may run from any number
// of threads at once on one Model (not during its refit). They run in parallel through oneTBB
// where the library was built with it (in the caller's task arena) and return the same result,
// pairs and counters alike, at any thread count: the work is split at fixed points of the tree
// and the pairs are sorted.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace antcd {

struct SelfIntersectionRequest {
  /// Stop at the first intersecting pair found (the result then holds one pair, the first of a
  /// fixed serial traversal order: the same at every call; not necessarily the smallest).
  bool first_only = false;
  /// Skip subtrees that provably do not intersect themselves by the normal-cone test (see
  /// SelfIntersectionStats::cone_culled); never changes the pairs, only the cost.
  bool normal_cones = true;
};

/// Counters of one self_intersections call (same values at any thread count).
struct SelfIntersectionStats {
  std::uint64_t node_pairs = 0;      ///< pairs of distinct subtrees whose volumes were tested
  std::uint64_t volume_rejects = 0;  ///< of those, culled by their boxes (of the corners)
  std::uint64_t triangle_pairs = 0;  ///< triangle pairs given to an exact test
  std::uint64_t adjacent_pairs = 0;  ///< of those, pairs sharing a vertex or an edge
  /// Subtrees skipped whole by the normal-cone test: every triangle of the subtree has a
  /// projection of exactly positive area along one coordinate axis direction, its edges are
  /// each used by at most two of its triangles in opposite directions, and its boundary edges
  /// form one directed cycle whose projection is a simple polygon. Such a subtree's triangles
  /// cover each point of the plane at most once (their projected degree is the winding number of
  /// the boundary, 0 or 1), and two of them that met beyond their sharing would cover some point
  /// twice (Volino & Magnenat-Thalmann 1994; Provot 1997; the proof is in src/self/cone.cpp).
  /// Pairs between such a subtree and the rest are still tested.
  std::uint64_t cone_culled = 0;
  std::uint64_t cone_tests = 0;  ///< subtrees whose boundary was tested for the cone cull
  /// Heap bytes of the boundary data the cull keeps with the Model (built on the first call,
  /// kept by Model::refit; not counted in BvhStats::memory_bytes).
  std::uint64_t cone_cache_bytes = 0;
};

struct SelfIntersectionResult {
  /// Some pair of triangles intersects beyond their sharing.
  bool intersecting = false;
  /// The intersecting pairs {i, j}, mesh triangle indices (Model::mesh().triangles, the file's
  /// order for a loaded mesh), i < j, sorted; one pair with first_only.
  std::vector<std::array<std::uint32_t, 2>> pairs;
  /// Exactly zero-area triangles (see the definitions above), ascending; listed in every mode.
  std::vector<std::uint32_t> degenerate_triangles;
  SelfIntersectionStats stats;
};

/// The triangle pairs of `model` that intersect beyond what their shared vertices or edge require
/// (definitions above). Exact. O(n log n) for meshes whose triangles are each near few others.
/// Const and thread-safe.
ANTCD_API SelfIntersectionResult self_intersections(const Model& model,
                                                    const SelfIntersectionRequest& request = {});

/// One self-proximity pair: vertex–triangle (a = vertex index, b = triangle index) or edge–edge
/// (a, b = indices into the list of edges, see SelfProximityResult::edges).
struct SelfProximityPair {
  enum class Kind : std::uint8_t { vertex_triangle, edge_edge };
  Kind kind = Kind::vertex_triangle;
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  Scalar distance = 0;
  Vec3 point_a = Vec3::Zero();  ///< closest point on a (the vertex itself for vertex_triangle)
  Vec3 point_b = Vec3::Zero();  ///< closest point on b
};

struct SelfProximityResult {
  /// The mesh's edges: each unordered pair of vertex indices that is an edge of some triangle,
  /// once, as {lower, higher}, sorted.
  std::vector<std::array<std::uint32_t, 2>> edges;
  /// Vertex–triangle pairs sorted by (vertex, triangle), then edge–edge pairs sorted by (a, b)
  /// with a < b.
  std::vector<SelfProximityPair> pairs;
};

/// The vertex–triangle and edge–edge pairs of `model` within `delta` (definitions above). Throws
/// ArgumentError naming `delta` when it is negative or not finite. Const and thread-safe.
ANTCD_API SelfProximityResult self_proximity(const Model& model, Scalar delta);

}  // namespace antcd
