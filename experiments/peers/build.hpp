// experiments/peers/build.hpp — hierarchy build time and memory per triangle, antcd Model against
// FCL BVHModel (OBBRSS and OBB), on the same mesh.
#pragma once

#include <antcd/mesh.hpp>

#include <cstddef>

namespace antcd::experiments::peers_bench {

struct BuildRow {
  std::size_t size = 0;
  std::size_t triangles = 0;
  double antcd_ms = 0;
  double fcl_obbrss_ms = 0;
  double fcl_obb_ms = 0;
  double antcd_bytes_per_tri = 0;
  double fcl_obbrss_bytes_per_tri = 0;
  double fcl_obb_bytes_per_tri = 0;
  std::size_t antcd_nodes = 0;
  int fcl_bvs = 0;
};

/// Median build time over `reps` constructions of each hierarchy over `mesh`, and its memory.
BuildRow measure_build(std::size_t size, const Mesh& mesh, int reps);

}  // namespace antcd::experiments::peers_bench
