// The test suite's mesh-file writers: binary and ASCII STL built byte by byte, so that tests can
// write exactly the file they mean (lying headers, truncations, bad numbers) without an exporter.
#pragma once

#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

namespace antcd::test {

/// Appends a little-endian float (binary STL is little-endian, like every platform antcd targets).
void append_f32(std::string& out, float x);
/// Appends a little-endian 32-bit unsigned integer.
void append_u32(std::string& out, std::uint32_t x);
/// Appends one binary STL facet record: the normal (zero for a degenerate triangle), the three
/// corners as floats and a zero attribute byte count.
void append_stl_facet(std::string& out, const std::array<Vec3, 3>& corners);

/// A binary STL of `m`: `header` padded with zero bytes to 80, then the triangle count (`count`
/// when >= 0, a lie on purpose; the true count otherwise), then one facet per triangle.
std::string binary_stl(const Mesh& m, std::string header = {}, std::int64_t count = -1);

/// An ASCII STL of `m` ("solid cube" … "endsolid cube"), nine significant digits.
std::string ascii_stl(const Mesh& m);

/// Vertices and triangles of a triangle-only OBJ file ("v" and "f" lines, corners "a/b/c" or "a",
/// 1-based), coordinates parsed with strtod: the test's own reading of a file's exact numbers,
/// independent of the library's loaders. Throws std::runtime_error on a face that is not a
/// triangle.
Mesh parse_obj_reference(const std::filesystem::path& path);

}  // namespace antcd::test
