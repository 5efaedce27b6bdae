// experiments/peers/adapters/peer_mesh.hpp — meshes as the peer engines (FCL, Bullet) get them,
// and the test meshes the benchmarks share. No peer headers here.
#pragma once

#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace antcd::peers {

/// Colliding object pairs (i < j), sorted.
using ObjectPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// The triangles antcd keeps (non-degenerate), in mesh order, with the way back to the mesh.
struct PeerMesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;
  std::vector<std::uint32_t> mesh_index;  ///< peer triangle → mesh triangle
};

PeerMesh peer_mesh(const Mesh& mesh);

/// Tessellation parameter k for a nominal triangle count: a torus with 2k × k segments has 4k²
/// triangles, a sphere with 2k slices and k stacks 4k(k - 1) (torus 1 024 / 10 000 / 99 856 /
/// 1 000 000 and sphere 960 / 9 800 / 99 224 / 998 000 for the nominal 1k, 10k, 100k and 1M).
int tessellation_for(std::size_t nominal);

/// The benchmarks' torus: make_torus(1, 0.4, 2k, k) with k = tessellation_for(nominal).
Mesh benchmark_torus(std::size_t nominal);

}  // namespace antcd::peers
