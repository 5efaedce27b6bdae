// Generated shapes: box, UV sphere, capped cylinder, torus.
//
// Every shape is a closed, consistently outward-oriented triangle mesh centred on the origin, with
// each position stored once (shared edges and corners are shared vertices) and no zero-area
// triangle (poles and cap centres are single vertices with triangle fans around them).
#include <antcd/mesh.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "util/check.hpp"

namespace antcd {
namespace {

void require_length(const char* function, const char* name, Scalar value) {
  detail::require_positive(std::string("antcd::") + function, name, value);
}

void require_count(const char* function, const char* name, int value, int minimum) {
  detail::require_at_least(std::string("antcd::") + function, name, value, minimum);
}

/// Rejects tessellations whose vertex count would not fit 32-bit indices.
void require_size(const char* function, std::uint64_t vertices) {
  if (vertices > std::numeric_limits<std::uint32_t>::max()) {
    throw antcd::ArgumentError(std::string("antcd::") + function +
                               ": the tessellation would have " + std::to_string(vertices) +
                               " vertices, more than 32-bit indices can address");
  }
}

/// (cos, sin) of the angle 2πk/n. Exact at multiples of a quarter turn, and symmetric: angles
/// mirrored about an axis or a diagonal give the same magnitudes bit for bit, so generated
/// shapes are exactly symmetric and their bounds exact.
std::pair<Scalar, Scalar> unit_circle(std::uint64_t k, std::uint64_t n) {
  k %= n;
  const std::uint64_t quadrant = (4 * k) / n;
  const std::uint64_t r = 4 * k - quadrant * n;  // angle within the quadrant: (π/2)·r/n
  constexpr Scalar quarter = std::numbers::pi / 2;
  Scalar c = 0;
  Scalar s = 0;
  if (2 * r <= n) {
    const Scalar a = quarter * static_cast<Scalar>(r) / static_cast<Scalar>(n);
    c = std::cos(a);
    s = std::sin(a);
  } else {
    const Scalar a = quarter * static_cast<Scalar>(n - r) / static_cast<Scalar>(n);
    c = std::sin(a);
    s = std::cos(a);
  }
  switch (quadrant) {
    case 0:
      return {c, s};
    case 1:
      return {-s, c};
    case 2:
      return {-c, -s};
    default:
      return {s, -c};
  }
}

/// Two triangles for the quad a-b-c-d given counter-clockwise as seen from outside.
void add_quad(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

Mesh make_box(const Vec3& half_extents, int subdivisions) {
  require_length("make_box", "half_extents.x", half_extents.x());
  require_length("make_box", "half_extents.y", half_extents.y());
  require_length("make_box", "half_extents.z", half_extents.z());
  require_count("make_box", "subdivisions", subdivisions, 1);
  const auto s = static_cast<std::uint64_t>(subdivisions);
  require_size("make_box", 6 * s * s + 2);

  // Surface points of the lattice {0..s}³; a point on an edge or corner of the box belongs to
  // several faces and is stored once, found again through its lattice key.
  Mesh m;
  m.vertices.reserve(6 * s * s + 2);
  m.triangles.reserve(12 * s * s);
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  index_of.reserve(6 * s * s + 2);
  auto coordinate = [&](int axis, std::uint64_t t) {
    // -h at t = 0 and +h at t = s exactly, symmetric in between.
    return half_extents[axis] * (static_cast<Scalar>(2 * t) - static_cast<Scalar>(s)) /
           static_cast<Scalar>(s);
  };
  auto vertex = [&](const std::array<std::uint64_t, 3>& l) {
    const std::uint64_t key = (l[0] * (s + 1) + l[1]) * (s + 1) + l[2];
    const auto [it, inserted] =
        index_of.try_emplace(key, static_cast<std::uint32_t>(m.vertices.size()));
    if (inserted)
      m.vertices.emplace_back(coordinate(0, l[0]), coordinate(1, l[1]), coordinate(2, l[2]));
    return it->second;
  };

  for (int axis = 0; axis < 3; ++axis) {
    for (const bool positive : {false, true}) {
      // Tangent axes (u, v) with e_u × e_v = outward normal.
      int u = (axis + 1) % 3;
      int v = (axis + 2) % 3;
      if (!positive) std::swap(u, v);
      for (std::uint64_t i = 0; i < s; ++i) {
        for (std::uint64_t j = 0; j < s; ++j) {
          auto at = [&](std::uint64_t iu, std::uint64_t jv) {
            std::array<std::uint64_t, 3> l{};
            l[static_cast<std::size_t>(axis)] = positive ? s : 0;
            l[static_cast<std::size_t>(u)] = iu;
            l[static_cast<std::size_t>(v)] = jv;
            return vertex(l);
          };
          add_quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        }
      }
    }
  }
  return m;
}

Mesh make_sphere(Scalar radius, int slices, int stacks) {
  require_length("make_sphere", "radius", radius);
  require_count("make_sphere", "slices", slices, 3);
  require_count("make_sphere", "stacks", stacks, 2);
  const auto n = static_cast<std::uint64_t>(slices);
  const auto st = static_cast<std::uint64_t>(stacks);
  require_size("make_sphere", n * (st - 1) + 2);

  Mesh m;
  m.vertices.reserve(n * (st - 1) + 2);
  m.triangles.reserve(2 * n * (st - 1));
  // Vertex 0: north pole; then rings 1..stacks-1 from north to south; last: south pole.
  m.vertices.emplace_back(0, 0, radius);
  for (std::uint64_t i = 1; i < st; ++i) {
    const auto [cos_theta, sin_theta] = unit_circle(i, 2 * st);  // polar angle π·i/stacks
    for (std::uint64_t j = 0; j < n; ++j) {
      const auto [cos_phi, sin_phi] = unit_circle(j, n);
      m.vertices.emplace_back(radius * sin_theta * cos_phi, radius * sin_theta * sin_phi,
                              radius * cos_theta);
    }
  }
  m.vertices.emplace_back(0, 0, -radius);
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  auto ring = [&](std::uint64_t i, std::uint64_t j) {
    return static_cast<std::uint32_t>(1 + (i - 1) * n + j % n);
  };

  for (std::uint64_t j = 0; j < n; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (std::uint64_t i = 1; i + 1 < st; ++i) {
    for (std::uint64_t j = 0; j < n; ++j) {
      add_quad(m, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
  }
  for (std::uint64_t j = 0; j < n; ++j) {
    m.triangles.push_back({south, ring(st - 1, j + 1), ring(st - 1, j)});
  }
  return m;
}

Mesh make_cylinder(Scalar radius, Scalar height, int slices, int stacks) {
  require_length("make_cylinder", "radius", radius);
  require_length("make_cylinder", "height", height);
  require_count("make_cylinder", "slices", slices, 3);
  require_count("make_cylinder", "stacks", stacks, 1);
  const auto n = static_cast<std::uint64_t>(slices);
  const auto st = static_cast<std::uint64_t>(stacks);
  require_size("make_cylinder", n * (st + 1) + 2);

  Mesh m;
  m.vertices.reserve(n * (st + 1) + 2);
  m.triangles.reserve(2 * n * (st + 1));
  // Rings 0..stacks from bottom (z = -height/2) to top (z = +height/2), then the two cap centres.
  for (std::uint64_t i = 0; i <= st; ++i) {
    const Scalar z = height * (static_cast<Scalar>(2 * i) - static_cast<Scalar>(st)) /
                     static_cast<Scalar>(2 * st);
    for (std::uint64_t j = 0; j < n; ++j) {
      const auto [c, s] = unit_circle(j, n);
      m.vertices.emplace_back(radius * c, radius * s, z);
    }
  }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, -height / 2);
  const auto top = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, height / 2);
  auto ring = [&](std::uint64_t i, std::uint64_t j) {
    return static_cast<std::uint32_t>(i * n + j % n);
  };

  for (std::uint64_t i = 0; i < st; ++i) {
    for (std::uint64_t j = 0; j < n; ++j) {
      add_quad(m, ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j));
    }
  }
  for (std::uint64_t j = 0; j < n; ++j) {
    m.triangles.push_back({bottom, ring(0, j + 1), ring(0, j)});
    m.triangles.push_back({top, ring(st, j), ring(st, j + 1)});
  }
  return m;
}

Mesh make_torus(Scalar major, Scalar minor, int major_segments, int minor_segments) {
  require_length("make_torus", "major", major);
  require_length("make_torus", "minor", minor);
  if (!(minor < major)) {
    // With minor >= major the tube reaches the axis: the inner ring collapses or self-intersects.
    throw antcd::ArgumentError("antcd::make_torus: minor radius (" + number_text(minor) +
                               ") must be smaller than major radius (" + number_text(major) + ")");
  }
  require_count("make_torus", "major_segments", major_segments, 3);
  require_count("make_torus", "minor_segments", minor_segments, 3);
  const auto big = static_cast<std::uint64_t>(major_segments);
  const auto small = static_cast<std::uint64_t>(minor_segments);
  require_size("make_torus", big * small);

  Mesh m;
  m.vertices.reserve(big * small);
  m.triangles.reserve(2 * big * small);
  for (std::uint64_t i = 0; i < big; ++i) {
    const auto [cu, su] = unit_circle(i, big);
    for (std::uint64_t j = 0; j < small; ++j) {
      const auto [cv, sv] = unit_circle(j, small);
      const Scalar rho = major + minor * cv;
      m.vertices.emplace_back(rho * cu, rho * su, minor * sv);
    }
  }
  auto at = [&](std::uint64_t i, std::uint64_t j) {
    return static_cast<std::uint32_t>((i % big) * small + j % small);
  };
  // Around the major circle (+u) then around the tube (+v): e_u × e_v points away from the tube's
  // centre line.
  for (std::uint64_t i = 0; i < big; ++i) {
    for (std::uint64_t j = 0; j < small; ++j) {
      add_quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return m;
}

}  // namespace antcd
