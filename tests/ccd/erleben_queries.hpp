// Tests and benchmarks only: primitive CCD queries in the rational CSV format of Wang et al.'s
// CCD benchmark, and the part of its Erleben scenes stored in tests/ccd/data/erleben (its README
// names the source, the commit, the licence and which part is stored).
//
// Format: 8 rows per query, each "x_num,x_den,y_num,y_den,z_num,z_den,truth" (decimal integers
// of any size, truth 0 or 1 and the same on all 8 rows). Vertex–face: the vertex, then the
// face's 3 corners at t = 0, then the same 4 points at t = 1. Edge–edge: edge a's 2 ends, edge
// b's 2 ends at t = 0, then the same at t = 1 (the order of ccd::vertex_face / edge_edge).
#pragma once

#include <string>
#include <vector>

#include "exact_truth.hpp"

namespace antcd::test {

struct RationalQuery {
  CcdQuery query;
  /// The file's truth column: the exact rational query touches within [0, 1].
  bool truth = false;
  /// Every coordinate is exactly a double (so `query` is the file's query, not a rounding of it).
  bool exact = true;
};

/// Reads a rational CSV file; each coordinate is rounded to the nearest double (ties to even).
/// Throws std::runtime_error naming the file and the row on any malformed row, a zero
/// denominator, a coordinate out of the double range or an incomplete last query.
std::vector<RationalQuery> read_rational_csv(const std::string& path, CcdKind kind,
                                             const std::string& name_prefix);

struct ErlebenFile {
  std::string scene;  ///< e.g. "spikes" (the directory is "erleben-spikes")
  CcdKind kind = CcdKind::VertexFace;
  std::vector<RationalQuery> queries;
};

/// The ten Erleben scenes' stored files under `dir` (tests/ccd/data/erleben), vertex–face then
/// edge–edge per scene, scenes in alphabetical order.
std::vector<ErlebenFile> load_erleben(const std::string& dir);

}  // namespace antcd::test
