// Whether a mesh bounds a solid: closed (every edge shared by exactly two triangles) and
// consistently oriented (the two traverse it in opposite directions).
#include <antcd/mesh.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace antcd {

bool is_closed(const Mesh& mesh) {
  // Every directed edge (u, v) of a triangle with three distinct vertices, as one 64-bit key. The
  // mesh is closed and consistently oriented exactly when each directed edge occurs once and its
  // reverse occurs once too: then each undirected edge has two triangles, traversing it in
  // opposite directions. Triangles with a repeated vertex index have no area and no edge.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  const std::size_t n = mesh.vertices.size();
  for (const TriangleIndices& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) return false;
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    for (int k = 0; k < 3; ++k) {
      edges.push_back((std::uint64_t{t[k]} << 32) | t[(k + 1) % 3]);
    }
  }
  if (edges.empty()) return false;
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;  // used twice
  // Every edge's reverse is an edge exactly when the reversed edges, sorted, are the same list
  // (both lists are free of repeats): two sorts instead of a binary search per edge, which on a
  // multi-million-triangle mesh missed the cache at every step.
  std::vector<std::uint64_t> reversed(edges.size());
  std::transform(edges.begin(), edges.end(), reversed.begin(),
                 [](std::uint64_t e) { return (e << 32) | (e >> 32); });
  std::sort(reversed.begin(), reversed.end());
  return reversed == edges;
}

}  // namespace antcd
