// antcd/deform_ccd.hpp — continuous collision detection of deforming meshes: every vertex moves on
// its own between two steps of a simulation (cloth, cables, soft parts), and the earliest contact
// and the collision-free step size are wanted.
//
// Definitions
// - Motion: vertex i moves linearly from V0[i] at t = 0 to V1[i] at t = 1, x_i(t) = V0[i] + t
//   (V1[i] - V0[i]), t in [0, 1]; the triangles (the model's mesh().triangles) do not change
//   (IPC's convention). The positions stored in the Model are not read: only its triangles and the
//   topology of its hierarchy (which triangles share a leaf) are; the bounds are computed per call.
// - Primitive pairs. Self (one mesh): a vertex against a triangle it is not a corner of, and an
//   edge against an edge with no shared vertex. Against another mesh B (deforming, or rigid between
//   two poses): every vertex of A against every triangle of B, every vertex of B against every
//   triangle of A, every edge of A against every edge of B. Vertices and edges are those of the
//   triangles (a vertex no triangle uses takes no part); an edge is an unordered pair of distinct
//   vertex indices of one triangle; a triangle is the closed triangle of its three corners, also
//   when it has zero area (then it is its segments or its point: such triangles are not in the
//   hierarchy, and deform_sweep checks them in one flat group, O(k (log n + k)) for k of them).
//   Sharing is by vertex index only.
// - Time of impact t*: the first t in [0, 1] at which some pair's primitives come within distance
//   min_separation (>= 0; 0: they touch). Sets are closed; contact at t = 0 counts.
//
// Guarantees (certified, never estimated; the primitives are ccd::vertex_face / ccd::edge_edge,
// antcd/ccd.hpp, whose guarantees carry over pair by pair)
// - Conservative: when some pair makes contact, the result is a hit with toi <= t*, and t* - toi
//   <= time_tolerance whenever the reported pair itself makes contact (a proven hit: t* = toi up
//   to rounding). A miss is a proof: no pair comes within min_separation over [0, 1].
// - tolerance_decided: the reported pair's primitive hit was decided by the tolerance, not proven
//   (ccd.hpp: at a time in [toi, toi + time_tolerance] the pair is then within min_separation + 3W
//   + rounding per axis); it may be a false positive. A rigid mesh that turns is followed along
//   chords (below), so its hits are always tolerance_decided.
// - Broad phase: per call, every node of the model's hierarchy gets the axis-aligned boxes of its
//   triangles' vertices at t = 0 and t = 1 and the largest displacement of those vertices along
//   each axis, both directions; the box over [0, s] is within [lo0 - s dneg, hi0 + s dpos] and
//   within the union of the two end boxes (padded for rounding by 8 u (M + D + min_separation), M
//   the largest coordinate, D the largest displacement, u = 2^-53). A self-traversal (or a dual
//   one) of those bounds visits every node pair within min_separation; in first-hit mode it prunes
//   with the box over [0, s], s the earliest toi found so far. Each triangle pair's own bounds are
//   checked before its (at most) 6 vertex–face and 9 edge–edge primitive queries; every primitive
//   pair is queried from one triangle pair only (the lowest-indexed triangle holding the vertex or
//   the edge).
// - Normal cones (self, min_separation 0, DeformSweepRequest::normal_cones): a subtree of at least
//   64 triangles that is one surface patch (each edge used by at most two of its triangles, in
//   opposite directions, its boundary one cycle; the static self test's subtrees, antcd/self.hpp)
//   is skipped when, for one axis direction, every triangle's normal has a certified positive
//   component along it at every t in [0, 1] (from the normal's quadratic Bezier form: the normals
//   at t = 0 and 1 and the cross term (e1(0) x e2(1) + e1(1) x e2(0)) / 2), and the boundary,
//   projected along that axis, stays a simple polygon over the whole step (each edge within the
//   hull of its ends' four positions; those hulls separated for edges with no common vertex,
//   consecutive edges never folding back). Then no self pair under it ever touches (the proof is
//   in src/ccd/normal_cone.cpp), so skipping it changes no answer a contact decides. The pairs
//   between the subtree and the rest are kept. Pairs that only the tolerance, not a contact,
//   reported (false positives) may go away with it. The tree's root is tried first; when it is
//   culled and holds every triangle, the call builds no bounds at all.
// - Rigid other (deform_sweep with two poses): B follows ccd::interpolate_pose. Its vertices run on
//   arcs, which the primitives cannot take, so [0, 1] is cut into n equal pieces on which each
//   vertex of B stays within delta = r (theta / n)^2 / 8 of its chord (theta: the rotation angle
//   from pose_b0 to pose_b1, r: the largest |p| of B's vertices in its frame), and each piece is a
//   linear query with min_separation + delta (+ a rounding allowance of 64 u times the scene's
//   size). n is the least that keeps delta <= pose_path_tolerance (0: 1e-3 r), at most 1024 (then
//   delta is the larger value that n = 1024 gives). Conservative as above; a hit means within
//   min_separation + 2 delta. A pure translation is one piece.
// - Determinism: the traversal is cut into a fixed list of tasks run in parallel. In first-hit
//   mode they share the earliest toi found so far; a pair is pruned only when its bounds over [0,
//   that toi + time_tolerance], grown by the primitives' tolerance reach (3W + rounding, ccd.hpp),
//   are apart, which proves its own toi later. So the answer is the earliest (toi, then pair kind
//   and indices) over every pair the bounds and the normal cones keep over [0, 1], the same at any
//   thread count and equal to all_pairs' first entry. A primitive query that exhausts its box
//   budget (DeformPair::budget_exhausted: near-parallel edges, flat on-grid input) stops at a
//   time its geometry does not bound; such a pair's toi is lifted to the largest time (to within
//   time_tolerance / 2) until which the two triangles' padded boxes are apart (no contact is
//   possible before it), and dropped when they are apart over [0, 1], so pruning it never
//   changes the answer either.
// - Memory: O(n) per call, none growing with the square of the mesh: the bounds (160 bytes per
//   hierarchy node, about n / 2 nodes for leaf size 4), a copy of the leaf order (4 bytes per
//   triangle), an ownership byte per triangle and a vertex->triangle index used while it is made
//   (4 (V + 1) + 12 n bytes, freed), per task a traversal stack of at most 2 * depth + 2 items,
//   and with the normal cones one byte per hierarchy node (their signs). The cones' subtree
//   boundaries are kept with the Model (built on its first self query, kept by refit, shared with
//   self_intersections) and not counted.
//   With all_pairs, the result holds every hit pair. DeformSweepResult::scratch_bytes reports the
//   bytes held by one call (outputs excluded).
//
// Thread safety: every function here is const on its inputs; call them from any thread, also on the
// same Model at once (not while Model::refit runs on it). Parallel over the tasks (oneTBB when the
// library is built with it).
// Errors (antcd::ArgumentError naming the argument): V0 / V1 (or B0 / B1) whose size is not the
// mesh's vertex count, a non-finite coordinate or one larger than 1e150 in magnitude (named with
// its index), min_separation < 0 or not finite, time_tolerance <= 0 or not finite,
// pose_path_tolerance < 0 or not finite, a non-finite pose.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace antcd {

/// Largest coordinate magnitude deform_sweep accepts (the primitives' rounding bounds and the
/// products of differences stay finite below it).
inline constexpr Scalar kDeformMaxCoordinate = 1e150;

struct DeformSweepRequest {
  Scalar min_separation = 0;
  Scalar time_tolerance = 1e-6;
  /// Every hit primitive pair with its toi (else the earliest pair only).
  bool all_pairs = false;
  /// Rigid other only: how far B's vertices may stray from the chords the search follows (0:
  /// 1e-3 times the largest |p| of B's vertices). See the header comment.
  Scalar pose_path_tolerance = 0;
  /// Self sweeps with min_separation 0: skip the self pairs of subtrees whose continuous normal
  /// cones prove they cannot touch (see "Normal cones" above). Off: every pair the bounds keep is
  /// queried (same contacts; fewer tolerance-decided false positives may be culled when on).
  bool normal_cones = true;
  /// Box budget of each primitive query (>= 1; ccd::kMaxBoxes, 2^20, by default): a query that
  /// needs more stops with a conservative hit (DeformPair::budget_exhausted, see "Determinism").
  /// Lower it to bound the worst case of one query; the answer stays conservative.
  std::uint32_t primitive_max_boxes = 1u << 20;
};

enum class DeformPairKind : std::uint8_t { VertexFace = 0, EdgeEdge = 1 };

/// One primitive pair. VertexFace: indices = {vertex, triangle, 0, 0}. EdgeEdge: indices = {a0, a1,
/// b0, b1}, each edge's ends ascending; self: edge (a0, a1) before (b0, b1) lexicographically.
/// Against another mesh: the vertex belongs to the first model when vertex_in_first (else the
/// triangle does); edge (a0, a1) is the first model's. Indices are the meshes' own.
struct DeformPair {
  DeformPairKind kind = DeformPairKind::VertexFace;
  bool vertex_in_first = true;
  std::array<std::uint32_t, 4> indices = {0, 0, 0, 0};
  Scalar toi = 1;
  bool tolerance_decided = false;
  /// The primitive's box budget ran out (ccd.hpp); tolerance_decided is then true.
  bool budget_exhausted = false;
};

struct DeformSweepResult {
  bool hit = false;
  /// Time of impact in [0, 1] when hit (1 otherwise).
  Scalar toi = 1;
  /// The earliest pair's hit came from the tolerance, not from a proof.
  bool tolerance_decided = false;
  /// The earliest pair (valid when hit).
  DeformPair pair;
  /// all_pairs: every hit pair, sorted by (toi, kind, vertex_in_first
  /// (true first), indices). Empty otherwise.
  std::vector<DeformPair> pairs;
  std::uint64_t node_pairs = 0;         ///< node pairs whose bounds were compared
  std::uint64_t primitive_queries = 0;  ///< ccd::vertex_face / edge_edge calls
  std::size_t tasks = 0;                ///< parallel tasks the traversal was cut into
  std::uint64_t cone_tests = 0;         ///< subtrees whose normal cone was tested
  std::uint64_t cone_culled = 0;        ///< subtrees culled by it (their self pairs skipped)
  std::size_t scratch_bytes = 0;        ///< bytes one call held (see Memory above)
};

/// Self CCD of `model`'s mesh moving from V0 to V1 (one position per mesh vertex).
ANTCD_API DeformSweepResult deform_sweep(const Model& model, std::span<const Vec3> V0,
                                         std::span<const Vec3> V1,
                                         const DeformSweepRequest& request = {});

/// CCD of deforming mesh a (A0 -> A1) against deforming mesh b (B0 -> B1); pairs across the two
/// meshes only (no self pairs).
ANTCD_API DeformSweepResult deform_sweep(const Model& a, std::span<const Vec3> A0,
                                         std::span<const Vec3> A1, const Model& b,
                                         std::span<const Vec3> B0, std::span<const Vec3> B1,
                                         const DeformSweepRequest& request = {});

/// CCD of deforming mesh a (A0 -> A1, world frame) against rigid model b moving from pose_b0 to
/// pose_b1 (ccd::interpolate_pose; b's own vertices, model frame); pairs across the meshes only.
ANTCD_API DeformSweepResult deform_sweep(const Model& a, std::span<const Vec3> A0,
                                         std::span<const Vec3> A1, const Model& b,
                                         const Transform& pose_b0, const Transform& pose_b1,
                                         const DeformSweepRequest& request = {});

/// The collision-free step in IPC's terms: a step s in [0, 1] such that over [0, s] no self pair
/// (definitions above) comes closer than min_separation; s never exceeds the true largest such
/// step (s <= t*), and t* - s <= time_tolerance as for deform_sweep's toi. 1 when no pair comes
/// that close.
/// The same as deform_sweep(...).toi with that separation. Errors as deform_sweep.
ANTCD_API Scalar collision_free_step(const Model& model, std::span<const Vec3> V0,
                                     std::span<const Vec3> V1, Scalar min_separation,
                                     Scalar time_tolerance = 1e-6);

}  // namespace antcd
