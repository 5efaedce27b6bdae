// shared/production_line/tessellation.hpp — equipment meshes as compounds of boxes, cylinders and
// spheres, each tessellated so that the compound has about a requested number of vertices
// (internal to the production-line generator).
#pragma once

#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace antcd::shared::line {

enum class Shape { Box, Cylinder, Sphere };

/// One primitive of a compound mesh. dims: box half extents; cylinder (radius, height, -) along
/// its z; sphere (radius, -, -). `place` maps the primitive into the mesh's frame.
struct Part {
  Shape shape = Shape::Box;
  Vec3 dims = Vec3::Zero();
  Transform place;
};

Part box_part(const Vec3& half, const Vec3& centre);
Part cylinder_part(Scalar radius, Scalar height, const Mat3& axis, const Vec3& centre);
Part sphere_part(Scalar radius, const Vec3& centre);

/// Tessellation of a part: k is the box subdivisions or the slices around a cylinder or sphere;
/// s is the stacks of a cylinder or sphere (unused for a box).
struct Level {
  std::uint64_t k = 1;
  std::uint64_t s = 1;
};

/// A mesh of equipment: its parts at the levels chosen for the vertex budget.
struct Equipment {
  std::string file;  ///< relative to the scene folder, set when the builder registers it
  Mesh mesh;
  std::vector<Part> parts;
  std::vector<Level> levels;
};

/// Builds the compound of `parts` with about `target` vertices. When `simple` is given (a version
/// with fewer primitives, for tiny budgets) and lands nearer the target, it is used instead.
Equipment build_equipment(const std::vector<Part>& parts, std::size_t target,
                          const std::vector<Part>& simple = {});

/// Distance from a tessellated sphere's or cylinder's centre line to its facets is at least
/// radius·(1 - sag); contacts are placed deeper than the sag.
Scalar cylinder_sag(const Equipment& e);

}  // namespace antcd::shared::line
