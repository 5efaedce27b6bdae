// Tests only: small deforming sheets and their vertex frames for the deforming-scene tests.
#pragma once

#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <cmath>
#include <cstddef>

#include "shared/production_line.hpp"

namespace antcd::test {

/// The generator's flat sheet: columns x rows vertices over [-0.5, 0.5] x [-0.4, 0.4], vertices in
/// order of first use (so an OBJ of it loads back in this order).
inline Mesh grid_mesh(std::size_t columns, std::size_t rows) {
  return shared::flexible_sheet_mesh(columns, rows, 0.5, 0.4);
}

/// `frames` frames of `mesh` waving: z = 0.05 sin(3 x + f) at frame f.
inline VertexFrames wave_frames(const Mesh& mesh, std::size_t frames) {
  VertexFrames v;
  v.vertex_count = static_cast<std::uint32_t>(mesh.vertices.size());
  v.frames = frames;
  for (std::size_t f = 0; f < frames; ++f) {
    for (const Vec3& p : mesh.vertices) {
      v.positions.emplace_back(p.x(), p.y(), 0.05 * std::sin(3 * p.x() + static_cast<double>(f)));
    }
  }
  return v;
}

}  // namespace antcd::test
