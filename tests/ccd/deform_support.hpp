// Tests only: meshes and motions for the deforming-mesh CCD tests (deform_ccd_test.cpp,
// deform_substep_test.cpp), and the discrete exact reference they are compared with.
#pragma once

#include <antcd/geometry.hpp>
#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace antcd::test {

/// A flat nx-by-ny grid of quads (2 triangles each) in the plane z = 0, [0, sx] x [0, sy].
inline Mesh make_grid(int nx, int ny, Scalar sx, Scalar sy) {
  Mesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) m.vertices.emplace_back(sx * i / nx, sy * j / ny, 0);
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

/// Positions at t of the linear motion V0 -> V1 (as the library computes them).
inline std::vector<Vec3> lerp(const std::vector<Vec3>& v0, const std::vector<Vec3>& v1, Scalar t) {
  std::vector<Vec3> out(v0.size());
  for (std::size_t i = 0; i < v0.size(); ++i) out[i] = v0[i] + t * (v1[i] - v0[i]);
  return out;
}

inline bool share_vertex(const TriangleIndices& a, const TriangleIndices& b) {
  for (auto x : a) {
    for (auto y : b) {
      if (x == y) return true;
    }
  }
  return false;
}

/// Exact discrete self test at positions p: some two triangles sharing no vertex intersect
/// (antcd::triangles_intersect, exact predicates). Sort-and-sweep on x.
inline bool self_intersects_disjoint(const Mesh& mesh, const std::vector<Vec3>& p) {
  const std::size_t n = mesh.triangles.size();
  std::vector<Aabb> box(n);
  for (std::size_t f = 0; f < n; ++f) {
    const auto& t = mesh.triangles[f];
    box[f].min = p[t[0]].cwiseMin(p[t[1]]).cwiseMin(p[t[2]]);
    box[f].max = p[t[0]].cwiseMax(p[t[1]]).cwiseMax(p[t[2]]);
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return box[a].min.x() < box[b].min.x(); });
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t a = order[i];
    for (std::size_t j = i + 1; j < n && box[order[j]].min.x() <= box[a].max.x(); ++j) {
      const std::uint32_t b = order[j];
      if ((box[a].min.array() > box[b].max.array()).any() ||
          (box[b].min.array() > box[a].max.array()).any()) {
        continue;
      }
      const auto& ta = mesh.triangles[a];
      const auto& tb = mesh.triangles[b];
      if (share_vertex(ta, tb)) continue;
      if (geometry::triangles_intersect(p[ta[0]], p[ta[1]], p[ta[2]], p[tb[0]], p[tb[1]],
                                        p[tb[2]])) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace antcd::test
