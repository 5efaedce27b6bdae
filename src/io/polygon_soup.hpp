// Internal to the mesh layer: the double-precision readers (OBJ; OFF and PLY through assimp with
// their coordinates re-read) produce a polygon soup of double coordinates, turned into a Mesh
// here the same way for every format.
#pragma once

#include <antcd/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace antcd::detail {

/// Points and polygons as a file lists them: polygon i has corner_counts[i] corners, stored one
/// after the other in `corners` (indices into `points`, possibly out of range: checked later).
struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<std::int64_t> corners;
  std::vector<std::uint32_t> corner_counts;
  /// How the file counts vertices (OBJ from 1), for error messages.
  std::int64_t index_base = 0;
};

/// The formats read in double precision; anything else goes to assimp.
enum class TextFormat { None, Obj };

/// Decides by extension (.obj). OFF and PLY stay with assimp for their structure, their
/// coordinates are re-read (exact_coordinates.hpp): CGAL's OFF and PLY readers were tried and
/// read past their arrays or call through null pointers on malformed files (found by
/// fuzz/fuzz_mesh_load).
TextFormat text_format(const std::filesystem::path& path);

/// The reader. Throws MeshError naming `source` when the file cannot be read.
PolygonSoup read_obj(const std::filesystem::path& path, const std::string& source);

/// Triangulates the soup's polygons (triangles kept, quads split on the diagonal through a
/// reflex corner if there is one, larger polygons by ear clipping in their plane), keeps only the
/// points some triangle uses (in order of first use), joins identical positions and validates.
/// Polygons with fewer than three corners are ignored. Throws MeshError for an index out of range
/// or a soup without triangles.
Mesh soup_to_mesh(const PolygonSoup& soup, const std::string& source);

/// A hash of a position that gives -0 and +0 the same value (equal positions, equal hashes).
std::size_t position_hash(const Vec3& p);

/// Joins vertices at bit-identical positions (-0 and +0 alike), renumbering the triangles.
void join_identical_positions(Mesh& mesh);

/// The file's bytes. Throws MeshError naming `source` when it cannot be opened or read.
std::string read_whole_file(const std::filesystem::path& path, const std::string& source);

/// Reads one coordinate token in full: an optional '+' (which std::from_chars does not take),
/// then a number as std::from_chars reads it, the nearest double to the text. Returns std::errc{}
/// on success, std::errc::result_out_of_range when the value is not finite ("inf", "nan",
/// "1e999"), std::errc::invalid_argument when the token is empty, not a number or has characters
/// after it. Shared by every text reader, so all of them round the same way.
std::errc parse_coordinate(std::string_view token, double& value);

}  // namespace antcd::detail
