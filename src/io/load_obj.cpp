// Wavefront OBJ in double precision through tinyobjloader (Debian's double build, whose imported
// target defines TINYOBJLOADER_USE_DOUBLE: real_t is double here and in the compiled library).
//
// tinyobjloader reads the file's structure (which lines are vertices, faces with negative and
// v/vt/vn indices, objects and groups). Two of its habits are corrected here:
// - it reads a coordinate it cannot parse ("nan", "inf", "abc") as 0 without a word, so every
//   vertex line ("v" then a blank, after optional blanks, as tinyobjloader reads them) is checked
//   for three finite coordinates first; it reads indices with atoi, so an index beyond int's range
//   wraps to another vertex: face lines are checked for that too;
// - its number parser is not correctly rounded (a coordinate can be a few units in the last place
//   off the nearest double to its text, so save_obj -> load_mesh would not reproduce a mesh), so
//   the coordinates are those std::from_chars gives for the same tokens: the nearest double. When
//   the two readings do not pair up (a different vertex count, or a value further apart than
//   rounding explains) tinyobjloader's values are kept.
#include <antcd/file.hpp>

#include "io/polygon_soup.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>
#include <type_traits>

static_assert(std::is_same_v<tinyobj::real_t, double>,
              "antcd needs tinyobjloader's double build (target tinyobjloader_double)");

namespace antcd::detail {
namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// Refuses a face line with a vertex index outside int's range (the part of each corner before
/// its first '/'); anything else about the line is left to tinyobjloader.
void check_face_line(std::string_view line, std::size_t line_number, const std::string& source) {
  while (!line.empty()) {
    while (!line.empty() && blank(line.front())) line.remove_prefix(1);
    std::size_t n = 0;
    while (n < line.size() && !blank(line[n])) ++n;
    const std::string_view corner = line.substr(0, n);
    line.remove_prefix(n);
    const std::string_view index = corner.substr(0, corner.find('/'));
    std::int64_t value = 0;
    const char* first = index.data();
    if (!index.empty() && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, index.data() + index.size(), value);
    if (ec == std::errc::result_out_of_range ||
        (ec == std::errc{} && (value > INT32_MAX || value < -INT32_MAX))) {
      throw MeshError(source, "the face on line " + std::to_string(line_number) +
                                  " has a vertex index out of range: '" +
                                  printable_line(std::string(index.substr(0, 40))) + "'");
    }
  }
}

/// The three coordinates of every vertex line, each the nearest double to its text. Throws
/// MeshError naming the vertex (counted from 1, as OBJ counts) and its line when a coordinate is
/// missing, not a number or not finite. Lines end at "\n", "\r\n" or "\r".
std::vector<Vec3> read_vertex_lines(std::string_view text, const std::string& source) {
  std::vector<Vec3> out;
  std::size_t line_number = 0;
  std::size_t vertex = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    ++line_number;
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
    if (line[0] == 'f') {
      check_face_line(line.substr(2), line_number, source);
      continue;
    }
    if (line[0] != 'v') continue;
    ++vertex;
    line.remove_prefix(2);
    Vec3& p = out.emplace_back();
    for (int k = 0; k < 3; ++k) {
      while (!line.empty() && blank(line.front())) line.remove_prefix(1);
      std::size_t n = 0;
      while (n < line.size() && !blank(line[n])) ++n;
      const std::string_view token = line.substr(0, n);
      line.remove_prefix(n);
      const std::string where =
          "vertex " + std::to_string(vertex) + " (line " + std::to_string(line_number) + ")";
      if (token.empty()) {
        throw MeshError(source, where + " has fewer than 3 coordinates");
      }
      const std::errc ec = parse_coordinate(token, p[k]);
      if (ec == std::errc::result_out_of_range) {
        throw MeshError(source, where + " has a non-finite coordinate '" +
                                    printable_line(std::string(token.substr(0, 40))) + "'");
      }
      if (ec != std::errc{}) {
        throw MeshError(source, where + " has a coordinate that is not a number: '" +
                                    printable_line(std::string(token.substr(0, 40))) + "'");
      }
    }
  }
  return out;
}

}  // namespace

PolygonSoup read_obj(const std::filesystem::path& path, const std::string& source) {
  std::string text = read_whole_file(path, source);
  std::vector<Vec3> exact = read_vertex_lines(text, source);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings;
  std::string errors;
  bool ok = false;
  {
    std::istringstream in(std::move(text));
    // No material reader: materials are not geometry, and .mtl files are not opened at all.
    // Polygons are triangulated by soup_to_mesh.
    ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &in, nullptr,
                          /*triangulate=*/false, /*default_vcols_fallback=*/false);
  }
  if (!ok) {
    std::string why = printable_line(errors);
    if (why.empty()) why = "tinyobjloader gave no reason";
    throw MeshError(source, "not a readable mesh: " + why);
  }

  PolygonSoup soup;
  soup.index_base = 1;
  const std::size_t n = attrib.vertices.size() / 3;
  bool paired = exact.size() == n;
  for (std::size_t i = 0; paired && i < n; ++i) {
    for (int k = 0; paired && k < 3; ++k) {
      const double theirs = attrib.vertices[3 * i + static_cast<std::size_t>(k)];
      paired = std::abs(exact[i][k] - theirs) <= 1e-12 * std::max(1.0, std::abs(theirs));
    }
  }
  if (paired) {
    soup.points = std::move(exact);
  } else {
    soup.points.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      soup.points.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                               attrib.vertices[3 * i + 2]);
    }
  }
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& index : shape.mesh.indices)
      soup.corners.push_back(index.vertex_index);
    for (const auto count : shape.mesh.num_face_vertices) soup.corner_counts.push_back(count);
  }
  return soup;
}

}  // namespace antcd::detail
