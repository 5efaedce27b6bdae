// ASCII PLY in double precision through CGAL's polygon-soup reader, which reads every number with
// the standard library's stream extraction (correctly rounded to double).
//
// A PLY property declared "float" is read by CGAL as a float. In an ASCII file the declared type
// only tells how the writer meant the text; the text itself is what the file says. So the
// header's scalar "float"/"float32" properties are declared "double" before CGAL sees it, and
// every coordinate is the nearest double to the printed number.
#include "mesh/polygon_soup.hpp"

#include <CGAL/IO/PLY.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace antcd::detail {
namespace {

using CgalPoint = CGAL::Simple_cartesian<double>::Point_3;

/// The most elements one allocation of a Bounded container may hold, on this thread (0: none).
thread_local std::size_t allocation_limit = 0;

/// CGAL's readers size arrays by counts read from the file before reading what they count. The
/// arrays handed to them use this allocator, which refuses (std::length_error) more elements than
/// the file could describe.
template <class T>
struct Bounded {
  using value_type = T;
  Bounded() = default;
  template <class U>
  explicit Bounded(const Bounded<U>& /*other*/) {}
  T* allocate(std::size_t n) {
    if (n > allocation_limit) throw std::length_error("more elements than the file can hold");
    return std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n) { std::allocator<T>().deallocate(p, n); }
  friend bool operator==(const Bounded&, const Bounded&) { return true; }
};

/// Sets allocation_limit for one read.
class AllocationLimit {
 public:
  explicit AllocationLimit(std::size_t limit) { allocation_limit = limit; }
  ~AllocationLimit() { allocation_limit = 0; }
  AllocationLimit(const AllocationLimit&) = delete;
  AllocationLimit& operator=(const AllocationLimit&) = delete;
};

template <class T>
using BoundedVector = std::vector<T, Bounded<T>>;
using CgalPoints = BoundedVector<CgalPoint>;
using CgalPolygons = BoundedVector<BoundedVector<std::size_t>>;

PolygonSoup to_soup(const CgalPoints& points, const CgalPolygons& polygons) {
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

/// What the PLY header says of one element: its count and, per property, whether it is a list
/// and whether the list's size type is wider than 8 bits.
struct PlyElement {
  std::uintmax_t count = 0;
  enum class Kind { Scalar, ShortList, LongList };
  std::vector<Kind> properties;
};

/// Walks the PLY header (up to its end_header line), declares scalar float properties double
/// and refuses element counts the file cannot hold: CGAL's reader loops over an element's count
/// even when the element has no properties, so a huge count would make it spin. Returns the
/// elements and sets `body` to the offset after the header.
std::vector<PlyElement> widen_ply_header(std::string& text, std::uintmax_t file_size,
                                         const std::string& source, std::size_t& body) {
  std::vector<PlyElement> elements;
  std::size_t pos = 0;
  body = text.size();
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::size_t i = pos;
    auto next_word = [&] {
      while (i < end && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
      const std::size_t start = i;
      while (i < end && text[i] != ' ' && text[i] != '\t' && text[i] != '\r') ++i;
      return std::string_view(text.data() + start, i - start);
    };
    const std::string_view key = next_word();
    if (key == "end_header") {
      body = std::min(end + 1, text.size());
      return elements;
    }
    if (key == "element") {
      (void)next_word();  // the element's name
      const std::string_view count_text = next_word();
      std::uintmax_t count = 0;
      const auto [ptr, ec] =
          std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
      if (ec == std::errc::result_out_of_range || (ec == std::errc{} && count > file_size)) {
        throw MeshError(source, "not a readable mesh: the PLY header announces " +
                                    std::string(count_text.substr(0, 30)) +
                                    " elements of one kind, more than the file's " +
                                    std::to_string(file_size) + " bytes can hold");
      }
      elements.push_back({count, {}});
    } else if (key == "property") {
      const std::string_view type = next_word();
      PlyElement::Kind kind = PlyElement::Kind::Scalar;
      if (type == "list") {
        const std::string_view size_type = next_word();
        const bool narrow = size_type == "uchar" || size_type == "uint8" || size_type == "char" ||
                            size_type == "int8";
        kind = narrow ? PlyElement::Kind::ShortList : PlyElement::Kind::LongList;
      } else if (type == "float" || type == "float32") {
        const auto at = static_cast<std::size_t>(type.data() - text.data());
        const std::size_t size = type.size();
        text.replace(at, size, "double");
        end = end + 6 - size;
      }
      if (!elements.empty()) elements.back().properties.push_back(kind);
    }
    pos = end + 1;
  }
  return elements;
}

/// CGAL's PLY reader sizes a list by the count it reads before the list's items. With an 8-bit
/// size type that is at most 255; with a wider one, the body is walked (element by element, as
/// the header describes it) and a list announcing more items than the rest of the file can hold
/// (2 bytes an item) is refused. The walk stops where the body stops following the header:
/// CGAL then refuses the file.
void check_ply_list_sizes(std::string_view body, const std::vector<PlyElement>& elements,
                          const std::string& source) {
  bool any_long = false;
  for (const PlyElement& e : elements) {
    for (const auto kind : e.properties) any_long = any_long || kind == PlyElement::Kind::LongList;
  }
  if (!any_long) return;
  std::size_t i = 0;
  auto next_token = [&] {
    while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i])) != 0) ++i;
    const std::size_t start = i;
    while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i])) == 0) ++i;
    return body.substr(start, i - start);
  };
  for (const PlyElement& e : elements) {
    for (std::uintmax_t item = 0; item < e.count; ++item) {
      for (const auto kind : e.properties) {
        const std::string_view token = next_token();
        if (token.empty()) return;
        if (kind == PlyElement::Kind::Scalar) continue;
        std::uintmax_t n = 0;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
        if (ec != std::errc{}) return;
        if (n > (body.size() - i) / 2) {
          throw MeshError(source, "not a readable mesh: a PLY list announces " +
                                      std::string(token.substr(0, 30)) +
                                      " items, more than the " + std::to_string(body.size() - i) +
                                      " bytes left can hold");
        }
        for (std::uintmax_t k = 0; k < n; ++k) {
          if (next_token().empty()) return;
        }
      }
    }
  }
}

}  // namespace

PolygonSoup read_ascii_ply(const std::filesystem::path& path, const std::string& source,
                           std::uintmax_t file_size) {
  std::string text = read_whole_file(path, source);
  std::size_t body = 0;
  const std::vector<PlyElement> elements = widen_ply_header(text, file_size, source, body);
  check_ply_list_sizes(std::string_view(text).substr(body), elements, source);
  std::istringstream in(std::move(text));
  CgalPoints points;
  CgalPolygons polygons;
  bool ok = false;
  try {
    // Read item by item: no array grows past about twice what the file holds.
    const AllocationLimit limit(static_cast<std::size_t>(file_size) + 64);
    ok = CGAL::IO::read_PLY(in, points, polygons, CGAL::parameters::verbose(false));
  } catch (const std::length_error&) {
    throw MeshError(source, "not a readable mesh: the PLY file announces more items than its " +
                                std::to_string(file_size) + " bytes can hold");
  }
  if (!ok) {
    throw MeshError(source,
                    "not a readable mesh: CGAL's PLY reader refused it (a header line it does not "
                    "know, or a vertex or face that does not match the header)");
  }
  return to_soup(points, polygons);
}

}  // namespace antcd::detail
