// OFF and ASCII PLY in double precision through CGAL's polygon-soup readers, which read every
// number with the standard library's stream extraction (correctly rounded to double).
//
// A PLY property declared "float" is read by CGAL as a float. In an ASCII file the declared type
// only tells how the writer meant the text; the text itself is what the file says. So the
// header's scalar "float"/"float32" properties are declared "double" before CGAL sees it, and
// every coordinate is the nearest double to the printed number.
#include "mesh/polygon_soup.hpp"

#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/Simple_cartesian.h>

#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>

namespace antcd::detail {
namespace {

using CgalPoint = CGAL::Simple_cartesian<double>::Point_3;
using CgalPolygons = std::vector<std::vector<std::size_t>>;

PolygonSoup to_soup(const std::vector<CgalPoint>& points, const CgalPolygons& polygons) {
  PolygonSoup soup;
  soup.points.reserve(points.size());
  for (const CgalPoint& p : points) soup.points.emplace_back(p.x(), p.y(), p.z());
  soup.corner_counts.reserve(polygons.size());
  for (const auto& polygon : polygons) {
    soup.corner_counts.push_back(static_cast<std::uint32_t>(polygon.size()));
    for (const std::size_t index : polygon) {
      // CGAL stores indices unsigned: anything past int64 is out of range anyway.
      soup.corners.push_back(index > static_cast<std::size_t>(INT64_MAX)
                                 ? -1
                                 : static_cast<std::int64_t>(index));
    }
  }
  return soup;
}

/// Walks the PLY header (up to its end_header line), declares scalar float properties double
/// and refuses element counts the file cannot hold: CGAL's reader loops over an element's count
/// even when the element has no properties, so a huge count would make it spin.
void widen_ply_header(std::string& text, std::uintmax_t file_size,
                             const std::string& source) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::size_t i = pos;
    auto skip_blanks = [&] {
      while (i < end && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
    };
    auto next_word = [&] {
      skip_blanks();
      const std::size_t start = i;
      while (i < end && text[i] != ' ' && text[i] != '\t' && text[i] != '\r') ++i;
      return std::pair<std::size_t, std::size_t>(start, i - start);
    };
    const auto [key_at, key_size] = next_word();
    const std::string_view key(text.data() + key_at, key_size);
    if (key == "end_header") return;
    if (key == "element") {
      (void)next_word();  // the element's name
      const auto [count_at, count_size] = next_word();
      std::uintmax_t count = 0;
      const auto [ptr, ec] =
          std::from_chars(text.data() + count_at, text.data() + count_at + count_size, count);
      if (ec == std::errc::result_out_of_range || (ec == std::errc{} && count > file_size)) {
        throw MeshError(source, "not a readable mesh: the PLY header announces " +
                                    std::string(text, count_at, std::min<std::size_t>(count_size, 30)) +
                                    " elements of one kind but the file has only " +
                                    std::to_string(file_size) + " bytes");
      }
    } else if (key == "property") {
      const auto [type_at, type_size] = next_word();
      const std::string_view type(text.data() + type_at, type_size);
      if (type == "float" || type == "float32") {
        text.replace(type_at, type_size, "double");
        end = end + 6 - type_size;
      }
    }
    pos = end + 1;
  }
}

}  // namespace

PolygonSoup read_off(const std::filesystem::path& path, const std::string& source) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(source, "cannot be opened: " + one_line(std::strerror(errno)));
  std::vector<CgalPoint> points;
  CgalPolygons polygons;
  if (!CGAL::IO::read_OFF(in, points, polygons, CGAL::parameters::verbose(false))) {
    throw MeshError(source,
                    "not a readable mesh: CGAL's OFF reader refused it (a header, vertex or face "
                    "line that does not follow the OFF format, or a vertex index out of range)");
  }
  return to_soup(points, polygons);
}

PolygonSoup read_ascii_ply(const std::filesystem::path& path, const std::string& source,
                           std::uintmax_t file_size) {
  std::string text = read_whole_file(path, source);
  widen_ply_header(text, file_size, source);
  std::istringstream in(std::move(text));
  std::vector<CgalPoint> points;
  CgalPolygons polygons;
  if (!CGAL::IO::read_PLY(in, points, polygons, CGAL::parameters::verbose(false))) {
    throw MeshError(source,
                    "not a readable mesh: CGAL's PLY reader refused it (a header line it does not "
                    "know, or a vertex or face that does not match the header)");
  }
  return to_soup(points, polygons);
}

}  // namespace antcd::detail
