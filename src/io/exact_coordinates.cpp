// OFF and PLY vertex coordinates in double precision, read along the layout assimp 5.2's OFF and
// PLY readers follow (exact_coordinates.hpp); and the OFF face-count check.
#include "io/exact_coordinates.hpp"

#include "io/ply_layout.hpp"
#include "io/polygon_soup.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <string_view>
#include <system_error>

namespace antcd::detail {
namespace {

/// A walk over an OFF file the way assimp's OFF reader walks it: `p` runs over the text and its
/// terminating NUL (assimp appends one), never past `end`.
class OffWalk {
 public:
  explicit OffWalk(const std::string& text) : p_(text.c_str()), end_(p_ + text.size() + 1) {}

  /// Blanks, line ends and '#' comment lines (assimp's NextToken).
  void next_token() {
    skip_spaces_and_line_ends();
    while (p_ < end_ && (*p_ == '#' || *p_ == '\n' || *p_ == '\r')) {
      while (*p_ != '\r' && *p_ != '\n' && *p_ != '\0') ++p_;
      while (*p_ == '\r' || *p_ == '\n') ++p_;
      skip_spaces_and_line_ends();
    }
  }
  /// assimp's strtoul10, wrapping like it.
  std::uint32_t number() {
    std::uint32_t value = 0;
    while (*p_ >= '0' && *p_ <= '9') value = value * 10 + static_cast<std::uint32_t>(*p_++ - '0');
    return value;
  }
  /// assimp's GetNextLine: a line of at most 4096 characters (a longer one goes on as the next
  /// line), then every line end after it. `line` receives the line without its ends; false at
  /// the end of the text.
  bool next_line(std::string_view& line) {
    if (*p_ == '\0') return false;
    const char* start = p_;
    for (std::size_t k = 0; k < kLineLimit && !line_end(*p_); ++k) ++p_;
    line = std::string_view(start, static_cast<std::size_t>(p_ - start));
    while (line_end(*p_) && *p_ != '\0') ++p_;
    return true;
  }
  /// True when `s` follows the cursor (within the text).
  bool at(std::string_view s) const {
    return static_cast<std::size_t>(end_ - p_) > s.size() &&
           std::memcmp(p_, s.data(), s.size()) == 0;
  }
  void advance(std::size_t n) { p_ += n; }
  bool at_digit() const { return p_ + 1 < end_ && *p_ >= '0' && *p_ <= '9'; }

  static constexpr std::size_t kLineLimit = 4096;

 private:
  static bool line_end(char c) { return c == '\r' || c == '\n' || c == '\0' || c == '\f'; }
  void skip_spaces_and_line_ends() {
    while (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n') ++p_;
  }
  const char* p_;
  const char* end_;
};

struct OffHeader {
  std::uint32_t vertices = 0;
  std::uint32_t faces = 0;
  /// "4OFF" (a w after x y z, divided out by assimp) or "nOFF" with a dimension other than 3.
  bool unusual_vertices = false;
};

/// The header as assimp reads it (keyword letters ST, C, N, 4, n then OFF, or no keyword; the
/// dimension after nOFF; the vertex, face and edge counts), leaving the walk at the first vertex
/// line. std::nullopt when assimp refuses the header.
std::optional<OffHeader> read_off_header(OffWalk& w) {
  OffHeader h;
  w.next_token();
  bool dimension_given = false;
  if (w.at("ST")) w.advance(2);
  if (w.at("C")) w.advance(1);
  if (w.at("N")) w.advance(1);
  if (w.at("4")) {
    h.unusual_vertices = true;
    w.advance(1);
  }
  if (w.at("n")) {
    dimension_given = true;
    w.advance(1);
  }
  if (w.at("OFF")) {
    w.advance(3);
    w.next_token();
  } else {
    h.unusual_vertices = false;  // assimp: without the keyword, no w (but an 'n' still counts)
    w.next_token();
    if (!w.at_digit()) return std::nullopt;  // assimp: "Header is invalid"
  }
  if (dimension_given) {
    const std::uint32_t dimension = w.number();
    if (dimension > 3) return std::nullopt;  // assimp refuses more than 3 coordinates
    if (dimension != 3) h.unusual_vertices = true;
    w.next_token();
  }
  w.next_token();
  h.vertices = w.number();
  w.next_token();
  h.faces = w.number();
  w.next_token();
  (void)w.number();  // edges
  w.next_token();
  if (h.vertices == 0 || h.faces == 0) return std::nullopt;  // assimp refuses these
  return h;
}

}  // namespace

CoordinateFormat coordinate_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c | 0x20);
  if (ext == ".off") return CoordinateFormat::Off;
  if (ext == ".ply") return CoordinateFormat::Ply;
  return CoordinateFormat::None;
}

std::optional<std::vector<Vec3>> off_coordinates(const std::string& text) {
  OffWalk w(text);
  const std::optional<OffHeader> header = read_off_header(w);
  if (!header || header->unusual_vertices) return std::nullopt;
  // A vertex line takes at least 6 bytes ("0 0 0\n"): a count beyond that gives up here, before
  // anything is allocated for it.
  if (header->vertices > text.size() / 6) return std::nullopt;
  std::vector<Vec3> out(header->vertices);
  std::string_view line;
  std::array<std::string_view, 3> tokens;
  for (Vec3& p : out) {
    // A vertex line cut at assimp's line limit, a comment line, fewer than three numbers:
    // assimp reads these differently or not at all.
    if (!w.next_line(line) || line.size() >= OffWalk::kLineLimit) return std::nullopt;
    if (split_blanks(line, tokens.data(), tokens.size()) < 3) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
      if (parse_coordinate(tokens[static_cast<std::size_t>(k)], p[k]) != std::errc{}) {
        return std::nullopt;
      }
    }
  }
  return out;
}

std::string unsafe_off_body(const std::string& text, std::uintmax_t file_size) {
  OffWalk w(text);
  const std::optional<OffHeader> header = read_off_header(w);
  if (!header) return {};  // assimp refuses it with its own message
  if (std::uint64_t{header->vertices} * 6 + std::uint64_t{header->faces} * 2 > file_size) {
    return "the OFF header announces " + std::to_string(header->vertices) + " vertices and " +
           std::to_string(header->faces) + " faces but the file has only " +
           std::to_string(file_size) + " bytes";
  }
  std::string_view line;
  for (std::uint32_t i = 0; i < header->vertices && w.next_line(line); ++i) {
  }
  std::uint64_t skipped = 0;
  for (std::uint32_t read = 0; read < header->faces;) {
    if (!w.next_line(line)) break;
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    std::uint32_t corners = 0;
    for (std::size_t k = 0; k < line.size() && line[k] >= '0' && line[k] <= '9'; ++k) {
      corners = corners * 10 + static_cast<std::uint32_t>(line[k] - '0');
    }
    if (corners == 0 || corners > 9) {
      if (++skipped > header->faces) {
        return "more face lines with 0 or over 9 corners than faces in the OFF header (" +
               std::to_string(header->faces) + ")";
      }
    } else {
      ++read;
    }
  }
  return {};
}

std::optional<std::vector<Vec3>> ply_coordinates(const std::string& text) {
  const std::string_view all(text);
  PlyHeader header;
  if (!parse_ply_header(all, header).empty()) return std::nullopt;
  const bool foreign_order = header.format == PlyFormat::BinaryBigEndian ||
                             (header.format == PlyFormat::BinaryLittleEndian &&
                              std::endian::native != std::endian::little);
  if (foreign_order) return std::nullopt;
  const bool ascii = header.format == PlyFormat::Ascii;
  const std::vector<PlyElement>& elements = header.elements;
  const std::size_t pos = header.body;
  BodyLines lines(all, pos);
  std::string_view line;

  // ---- the vertex element: one, without lists, with x, y and z ----
  std::size_t vertex_element = elements.size();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (elements[e].name != "vertex") continue;
    if (vertex_element != elements.size()) return std::nullopt;
    vertex_element = e;
  }
  if (vertex_element == elements.size()) return std::nullopt;
  const PlyElement& vertex = elements[vertex_element];
  if (vertex.has_list()) return std::nullopt;
  std::array<std::size_t, 3> column{};
  std::array<bool, 3> found{};
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (vertex.properties[i].name == std::string_view("xyz").substr(k, 1)) {
        if (found[k]) return std::nullopt;
        found[k] = true;
        column[k] = i;
      }
    }
  }
  if (!found[0] || !found[1] || !found[2]) return std::nullopt;
  // A vertex takes at least two bytes of text per property ("0 0 0\n") and 24 of binary (three
  // doubles): a count beyond that gives up before anything is allocated for it.
  const std::size_t rest = text.size() - std::min(pos, text.size());
  const std::size_t least = ascii ? 2 * vertex.properties.size() : 24;
  if (vertex.count > rest / least) return std::nullopt;
  std::vector<Vec3> out(static_cast<std::size_t>(vertex.count));

  if (ascii) {
    // One line per element instance (as assimp reads them); blank lines are not expected.
    for (std::size_t e = 0; e < vertex_element; ++e) {
      for (std::uint64_t i = 0; i < elements[e].count; ++i) {
        if (!lines.next(line)) return std::nullopt;
      }
    }
    std::vector<std::string_view> tokens(vertex.properties.size());
    for (Vec3& p : out) {
      if (!lines.next(line) || split_blanks(line, tokens.data(), tokens.size()) < tokens.size()) {
        return std::nullopt;
      }
      for (int k = 0; k < 3; ++k) {
        if (parse_coordinate(tokens[column[static_cast<std::size_t>(k)]], p[k]) != std::errc{}) {
          return std::nullopt;
        }
      }
    }
    return out;
  }

  // Binary little-endian: only doubles are worth reading (assimp's float of a float is exact),
  // and only at fixed offsets (no list before the vertices).
  std::size_t offset = pos;  // the byte after end_header's "\n"
  if (all.substr(0, pos).ends_with("\r\n")) return std::nullopt;
  for (std::size_t k = 0; k < 3; ++k) {
    if (ply_type_size(vertex.properties[column[k]].type) != 8) return std::nullopt;
  }
  for (std::size_t e = 0; e < vertex_element; ++e) {
    if (elements[e].has_list()) return std::nullopt;
    std::uint64_t stride = 0;
    for (const PlyProperty& p : elements[e].properties) stride += ply_type_size(p.type);
    if (elements[e].count > text.size() || stride * elements[e].count > text.size() - offset) {
      return std::nullopt;
    }
    offset += static_cast<std::size_t>(stride * elements[e].count);
  }
  std::size_t stride = 0;
  std::array<std::size_t, 3> at{};
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (i == column[k]) at[k] = stride;
    }
    stride += ply_type_size(vertex.properties[i].type);
  }
  if (stride * vertex.count > text.size() - offset) return std::nullopt;
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      double value = 0;
      std::memcpy(&value, text.data() + offset + i * stride + at[k], sizeof value);
      out[i][static_cast<Eigen::Index>(k)] = value;
    }
  }
  return out;
}

}  // namespace antcd::detail
