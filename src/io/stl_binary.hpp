// Internal to the mesh layer: binary STL read natively. The format is a fixed layout (80-byte
// header, a little-endian uint32 facet count, then 50 bytes per facet: normal, three corners as
// float32 x, y, z, and a 16-bit attribute), so it needs no parser library; assimp's reader took
// about 20 s and 3 GB for 5 million facets (a copy of every corner, then its vertex joining).
#pragma once

#include <antcd/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace antcd::detail {

/// True when the file is laid out as binary STL: at least 84 bytes and exactly 84 + 50 n of
/// them, n being the count at byte 80 (assimp's rule too, which tries it before ASCII, so a file
/// starting with "solid" of that size is binary). `head` holds the file's first bytes.
bool is_binary_stl(std::string_view head, std::uintmax_t size);

/// Reads a file for which is_binary_stl holds. Corners at bit-identical positions (-0 and +0
/// alike) become one vertex, numbered in order of first use; each facet becomes a triangle with
/// its corners in file order (the facet normal is ignored, as the other readers ignore normals).
/// Throws MeshError naming `source` when the file cannot be read, has no facet, or has a
/// non-finite coordinate (naming the facet).
Mesh read_binary_stl(const std::filesystem::path& path, const std::string& source);

}  // namespace antcd::detail
