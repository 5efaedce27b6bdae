// Internal to the mesh layer: the text-format readers (OBJ, ASCII PLY) produce a polygon
// soup of double coordinates, turned into a Mesh here the same way for every format.
#pragma once

#include <antcd/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace antcd::detail {

/// Points and polygons as a file lists them: polygon i has corner_counts[i] corners, stored one
/// after the other in `corners` (indices into `points`, possibly out of range: checked later).
struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<std::int64_t> corners;
  std::vector<std::uint32_t> corner_counts;
  /// How the file counts vertices (OBJ from 1, PLY from 0), for error messages.
  std::int64_t index_base = 0;
};

/// The text formats read in double precision; anything else goes to assimp.
enum class TextFormat { None, Obj, AsciiPly };

/// Decides by extension (.obj, .ply) and, for PLY, by the header's format line: a binary PLY is
/// left to assimp. `head` is the file's first bytes. OFF stays with assimp: CGAL's OFF reader
/// reads past its arrays on malformed colour entries (found by fuzz/fuzz_mesh_load).
TextFormat text_format(const std::filesystem::path& path, std::string_view head);

/// The readers. Each throws MeshError naming `source` when the file cannot be read.
PolygonSoup read_obj(const std::filesystem::path& path, const std::string& source);
PolygonSoup read_ascii_ply(const std::filesystem::path& path, const std::string& source,
                           std::uintmax_t file_size);

/// Triangulates the soup's polygons (triangles kept, quads split on the diagonal through a
/// reflex corner if there is one, larger polygons by ear clipping in their plane), keeps only the
/// points some triangle uses (in order of first use), joins identical positions and validates.
/// Polygons with fewer than three corners are ignored. Throws MeshError for an index out of range
/// or a soup without triangles.
Mesh soup_to_mesh(const PolygonSoup& soup, const std::string& source);

/// Joins vertices at bit-identical positions (-0 and +0 alike), renumbering the triangles.
void join_identical_positions(Mesh& mesh);

/// The file's bytes. Throws MeshError naming `source` when it cannot be opened or read.
std::string read_whole_file(const std::filesystem::path& path, const std::string& source);

/// One line, no surrounding blanks: library messages sometimes carry newlines.
std::string one_line(std::string text);

}  // namespace antcd::detail
