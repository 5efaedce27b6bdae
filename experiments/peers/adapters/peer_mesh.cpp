#include "peers/adapters/peer_mesh.hpp"

#include <antcd/geometry.hpp>

#include <cmath>

namespace antcd::peers {

PeerMesh peer_mesh(const Mesh& mesh) {
  PeerMesh out;
  out.vertices = mesh.vertices;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (geometry::is_degenerate_triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                         mesh.vertices[tri[2]])) {
      continue;
    }
    out.triangles.push_back(tri);
    out.mesh_index.push_back(t);
  }
  return out;
}

int tessellation_for(std::size_t nominal) {
  switch (nominal) {
    case 1'000:
      return 16;
    case 10'000:
      return 50;
    case 100'000:
      return 158;
    case 1'000'000:
      return 500;
    default:
      return static_cast<int>(std::lround(std::sqrt(static_cast<double>(nominal) / 4.0)));
  }
}

Mesh benchmark_torus(std::size_t nominal) {
  const int k = tessellation_for(nominal);
  return make_torus(1.0, 0.4, 2 * k, k);
}

}  // namespace antcd::peers
