// Tests only: exact (GMP rational) ground truth for primitive CCD queries whose relative motion is
// a translation, and a corpus of degenerate and near-miss queries built that way.
//
// Truth. Vertex–face: when the three face corners move by the same displacement w, the vertex
// moves relative to the face along the segment s = [v0, v0 + (v1 - v0) - w], and the query
// touches in [0, 1] exactly when s meets the closed face at t = 0. Edge–edge: when each edge
// moves rigidly (both ends by w_a, resp. w_b), the edges touch exactly when edge b at t = 0 meets
// the parallelogram a0 ⊕ [0, w_a - w_b]. Both are decided with exact rationals (orientation signs
// and rational intersection points), degenerate cases (coplanar, collinear, zero-area) included.
// Queries of any other structure have no truth here (std::nullopt).
#pragma once

#include <antcd/math.hpp>

#include <array>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace antcd::test {

enum class CcdKind { VertexFace, EdgeEdge };

struct CcdQuery {
  std::string name;
  CcdKind kind = CcdKind::VertexFace;
  std::array<Vec3, 4> at_t0;
  std::array<Vec3, 4> at_t1;
};

/// Exact truth (see above): does the query touch within t in [0, 1] (min_separation 0)?
std::optional<bool> ccd_truth(const CcdQuery& query);

/// Exact first time of contact for a touching query whose relative motion crosses the face (or
/// parallelogram) plane transversally (nullopt when coplanar, not touching, or no truth).
std::optional<double> ccd_first_time_upper(const CcdQuery& query);

/// The hand-made degenerate corpus: spikes through holes and cracks, wedges, cube cliff and
/// internal edges, sliding spikes and wedges, parallel and coplanar edges, contact exactly at
/// t = 0 and t = 1, zero motion; each with a drifting and a far-offset copy. Every coordinate is
/// a dyadic rational exact in double, every query has a truth.
std::vector<CcdQuery> degenerate_corpus();

/// Random queries aimed at an edge, a corner or the inside of the other primitive and nudged off
/// (or onto) it by a few 2^-40: near misses and grazing hits. Exact in double, truth available.
std::vector<CcdQuery> near_miss_queries(CcdKind kind, std::size_t count, std::uint64_t seed);

/// Writes queries in the rational CSV format of Wang et al.'s CCD benchmark (8 rows per query:
/// x_num,x_den,y_num,y_den,z_num,z_den,truth), with the exact truth.
std::string to_rational_csv(const std::vector<CcdQuery>& queries);

}  // namespace antcd::test
