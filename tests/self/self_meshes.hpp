// Generated meshes for the self-collision tests: sheets (flat, bent, folded through or flat onto
// themselves), closed shapes with a patch pushed through, and small hand-made pairs.
#pragma once

#include <antcd/mesh.hpp>

#include <cmath>
#include <functional>
#include <numbers>

namespace antcd::test {

/// A grid sheet of nx x ny quads (two triangles each, consistently oriented), vertex (i, j) at
/// place(i, j).
inline Mesh grid_sheet(int nx, int ny, const std::function<Vec3(int, int)>& place) {
  Mesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) m.vertices.push_back(place(i, j));
  }
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

/// A flat sheet on integer coordinates (exact), in the z = 0 plane.
inline Mesh flat_sheet(int nx, int ny) {
  return grid_sheet(nx, ny, [](int i, int j) { return Vec3(i, j, 0); });
}

/// A sheet bent about the y axis through `angle` radians in all (a cylinder arc), touching nowhere.
inline Mesh bent_sheet(int nx, int ny, Scalar angle) {
  return grid_sheet(nx, ny, [=](int i, int j) {
    const Scalar t = angle * (Scalar(i) / nx - 0.5);
    return Vec3(std::sin(t), Scalar(j) / ny, 1 - std::cos(t));
  });
}

/// A sheet whose cross-section is the loop x = s^2 - 1, z = s (s^2 - 1), s in [-1.5, 1.5]: it
/// passes through itself along the line where s = -1 and s = 1 meet.
inline Mesh looped_sheet(int nx, int ny) {
  return grid_sheet(nx, ny, [=](int i, int j) {
    const Scalar s = -1.5 + 3.0 * i / nx;
    return Vec3(s * s - 1, Scalar(j) / ny, s * (s * s - 1));
  });
}

/// A flat integer sheet folded flat about the grid line i = fold: columns past it are mirrored
/// onto the columns before it (exactly: integer coordinates), coplanar and overlapping.
inline Mesh folded_flat_sheet(int nx, int ny, int fold) {
  return grid_sheet(nx, ny, [=](int i, int j) { return Vec3(i <= fold ? i : 2 * fold - i, j, 0); });
}

/// A sphere whose cap above z = cap * r is pushed down by `push` * r, through the sphere's far side
/// when push is large enough.
inline Mesh pushed_sphere(Scalar r, Scalar cap, Scalar push) {
  Mesh m = make_sphere(r, 24, 12);
  for (Vec3& p : m.vertices) {
    if (p.z() > cap * r) p.z() -= push * r;
  }
  return m;
}

}  // namespace antcd::test
