// antcd/mesh.hpp — triangle meshes: validation, simple generated shapes, OBJ output. Loading mesh
// files is antcd/load.hpp (the antcd::io target).
//
// A Mesh is plain data: vertex positions and triangles as index triples (counter-clockwise seen
// from outside when the source file says so; antcd does not rely on orientation). Coordinates are
// in the file's own units and frame.
#pragma once

#include <antcd/error.hpp>
#include <antcd/export.hpp>
#include <antcd/math.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace antcd {

using TriangleIndices = std::array<std::uint32_t, 3>;

struct ANTCD_API Mesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;

  [[nodiscard]] Aabb bounds() const;
  /// Number of triangles whose area is zero (or numerically so: twice the area no larger than
  /// 1e-12 times the squared longest edge). Such triangles are kept in the mesh but left out of
  /// the hierarchy.
  [[nodiscard]] std::size_t degenerate_triangle_count() const;
};

/// Checks a mesh built in memory: at least one triangle, finite coordinates, indices in range.
/// Throws MeshError with `source` as the name.
ANTCD_API void validate_mesh(const Mesh& mesh, std::string_view source);

/// True when the mesh bounds a solid: closed (every edge of a triangle with three distinct vertex
/// indices is shared with exactly one other triangle) and consistently oriented (the two triangles
/// traverse their common edge in opposite directions). Triangles with a repeated index are ignored.
/// Topology only: vertices are compared by index, so duplicated vertices make the mesh open.
ANTCD_API bool is_closed(const Mesh& mesh);

/// Writes a mesh as Wavefront OBJ (atomically: a temporary file beside it, then rename).
/// Throws Error on failure.
ANTCD_API void save_obj(const Mesh& mesh, const std::filesystem::path& path);

// ---- Generated shapes (closed, outward-facing, centred on the origin) ----
// Each throws ArgumentError for a size that is not finite and > 0 or a segment count out of range.

/// Box with the given half extents, each face split into `subdivisions`² quads (2 triangles each).
ANTCD_API Mesh make_box(const Vec3& half_extents, int subdivisions = 1);
/// UV sphere of `radius` with `slices` >= 3 around and `stacks` >= 2 from pole to pole.
ANTCD_API Mesh make_sphere(Scalar radius, int slices = 32, int stacks = 16);
/// Closed cylinder along z of `radius` and total `height` with `slices` >= 3 around.
ANTCD_API Mesh make_cylinder(Scalar radius, Scalar height, int slices = 32, int stacks = 1);
/// Torus in the xy-plane: `major` radius of the tube's centre line, `minor` radius of the tube.
ANTCD_API Mesh make_torus(Scalar major, Scalar minor, int major_segments = 48,
                          int minor_segments = 24);

/// Concatenation of meshes (indices offset), for building compound shapes. Throws ArgumentError
/// for a part with an out-of-range index or a result too large for 32-bit indices.
ANTCD_API Mesh merge(const std::vector<Mesh>& parts);
/// The mesh with every vertex mapped through `t`.
ANTCD_API Mesh transformed(Mesh mesh, const Transform& t);

}  // namespace antcd
