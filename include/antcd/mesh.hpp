// antcd/mesh.hpp — triangle meshes: loading, validation, simple generated shapes.
//
// A Mesh is plain data: vertex positions and triangles as index triples (counter-clockwise seen
// from outside when the source file says so; antcd does not rely on orientation). Coordinates are
// in the file's own units and frame.
#pragma once

#include <antcd/math.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace antcd {

using TriangleIndices = std::array<std::uint32_t, 3>;

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;

  [[nodiscard]] Aabb bounds() const;
  /// Number of triangles whose area is zero (or numerically so: twice the area no larger than
  /// 1e-12 times the squared longest edge). Such triangles are kept in the mesh but left out of
  /// the hierarchy.
  [[nodiscard]] std::size_t degenerate_triangle_count() const;
};

/// Base of every error antcd throws. what() is one line that names the input (file, object) and
/// the problem.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A mesh could not be loaded or is invalid. what() is "<source>: <problem>".
class MeshError : public Error {
 public:
  MeshError(std::string source, const std::string& problem)
      : Error(source + ": " + problem), source_(std::move(source)) {}
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::string source_;
};

/// Loads every triangle of every mesh in a file (OBJ, STL ASCII/binary, PLY, OFF, glTF/GLB and the
/// other formats assimp reads), with node transforms of the file's scene graph applied, polygons
/// triangulated and identical vertices joined. Points and lines are ignored.
/// Throws MeshError (naming the path) when the file is missing, is not a readable mesh, holds no
/// triangle, has non-finite coordinates or out-of-range indices.
Mesh load_mesh(const std::filesystem::path& path);

/// Checks a mesh built in memory: at least one triangle, finite coordinates, indices in range.
/// Throws MeshError with `source` as the name.
void validate_mesh(const Mesh& mesh, std::string_view source);

/// Writes a mesh as Wavefront OBJ (atomically: a temporary file beside it, then rename).
/// Throws Error on failure.
void save_obj(const Mesh& mesh, const std::filesystem::path& path);

// ---- Generated shapes (closed, outward-facing, centred on the origin) ----

/// Box with the given half extents, each face split into `subdivisions`² quads (2 triangles each).
Mesh make_box(const Vec3& half_extents, int subdivisions = 1);
/// UV sphere of `radius` with `slices` >= 3 around and `stacks` >= 2 from pole to pole.
Mesh make_sphere(Scalar radius, int slices = 32, int stacks = 16);
/// Closed cylinder along z of `radius` and total `height` with `slices` >= 3 around.
Mesh make_cylinder(Scalar radius, Scalar height, int slices = 32, int stacks = 1);
/// Torus in the xy-plane: `major` radius of the tube's centre line, `minor` radius of the tube.
Mesh make_torus(Scalar major, Scalar minor, int major_segments = 48, int minor_segments = 24);

/// Concatenation of meshes (indices offset), for building compound shapes.
Mesh merge(const std::vector<Mesh>& parts);
/// The mesh with every vertex mapped through `t`.
Mesh transformed(Mesh mesh, const Transform& t);

}  // namespace antcd
