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
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (i + 1 < edges.size() && edges[i + 1] == edges[i]) return false;  // edge used twice
    const std::uint64_t reverse = (edges[i] << 32) | (edges[i] >> 32);
    if (!std::binary_search(edges.begin(), edges.end(), reverse)) return false;  // open edge
  }
  return true;
}

}  // namespace antcd
