// Internal to the mesh layer: OFF and PLY vertex coordinates re-read from the file's bytes in
// double precision, and the OFF check assimp's OFF reader needs before it may run (load.cpp).
//
// assimp (built for float here) stays the reader of these formats' structure: which faces, their
// corners, how many vertices. These readers follow the same layout only as far as needed to find
// each vertex's x, y and z: OFF's header then one line per vertex, PLY's header (element order,
// the vertex element's properties; parsed by ply_layout.hpp) then its body. They give up
// (std::nullopt) on any layout they do not follow exactly, and load.cpp uses their values only
// when every one of them agrees with the float assimp read for the same vertex (see load.cpp).
#pragma once

#include <antcd/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace antcd::detail {

/// The formats whose coordinates are re-read, decided by extension as assimp picks its reader.
enum class CoordinateFormat { None, Off, Ply };
CoordinateFormat coordinate_format(const std::filesystem::path& path);

/// The vertices of an OFF file, in file order, each coordinate the nearest double to its text.
/// `text` is the whole file; its terminating NUL is read as assimp reads the NUL it appends.
/// std::nullopt for a homogeneous ("4OFF") or n-dimensional header, a vertex line that is not
/// three numbers followed by blanks and other fields, or too few vertex lines.
std::optional<std::vector<Vec3>> off_coordinates(const std::string& text);

/// The vertices of a PLY file, in file order: in ASCII each coordinate the nearest double to its
/// text; in binary little-endian only when x, y and z are stored as double (a float is already
/// exact in assimp's float). std::nullopt for anything else: big-endian, list properties in the
/// vertex element or in an element before it (binary), a missing x/y/z, a malformed element or
/// property line, a body line that does not hold the vertex's properties, a short file.
std::optional<std::vector<Vec3>> ply_coordinates(const std::string& text);

/// assimp 5.2's OFF reader drops a face line whose corner count is 0 or above 9 by decrementing
/// the mesh's face count, without bound: with more such lines than the header has faces the count
/// wraps around to about 4 billion and assimp reads far past its face array (a crash found by
/// fuzzing: "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n0\n3 0 1 2\n"). Its counts are also read from
/// files without the OFF keyword. This walks `text` (the whole file) the way that reader does:
/// its header tokens, then one line per vertex, then face lines until the header's count of faces
/// is read. Returns the problem, or an empty string.
std::string unsafe_off_body(const std::string& text, std::uintmax_t file_size);

}  // namespace antcd::detail
