// The benchmarks' mesh normalisation: a mesh centred and scaled to a given bounding radius.
#pragma once

#include <antcd/mesh.hpp>

#include <algorithm>

namespace antcd::bench {

/// The mesh moved to its bounding-box centre and scaled about it to bounding radius `radius`.
inline Mesh scaled(Mesh m, Scalar radius) {
  const Aabb b = m.bounds();
  const Vec3 c = 0.5 * (b.min + b.max);
  Scalar r = 0;
  for (const Vec3& v : m.vertices) r = std::max(r, (v - c).norm());
  for (Vec3& v : m.vertices) v = (v - c) * (radius / r);
  return m;
}

}  // namespace antcd::bench
