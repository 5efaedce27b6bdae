// The PLY header and the walk over its body that load.cpp runs before assimp (ply_layout.hpp).
#include "io/ply_layout.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstring>
#include <system_error>

namespace antcd::detail {
namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

bool parse_count(std::string_view token, std::uint64_t& value) {
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc{} && ptr == token.data() + token.size();
}

bool integer_type(std::string_view type) {
  return ply_type_size(type) != 0 && type != "float" && type != "float32" && type != "double" &&
         type != "float64";
}

bool signed_type(std::string_view type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
         type == "int32";
}

/// The next blank-separated token of `line`, removed from it; false when none is left.
bool next_token(std::string_view& line, std::string_view& token) {
  while (!line.empty() && blank(line.front())) line.remove_prefix(1);
  if (line.empty()) return false;
  std::size_t k = 0;
  while (k < line.size() && !blank(line[k])) ++k;
  token = line.substr(0, k);
  line.remove_prefix(k);
  return true;
}

/// An integer of `type` stored at `p` in the file's byte order.
std::int64_t read_integer(const char* p, std::string_view type, bool big_endian) {
  const std::size_t size = ply_type_size(type);
  std::array<unsigned char, 8> bytes{};
  std::memcpy(bytes.data(), p, size);
  if (big_endian) std::reverse(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size));
  std::uint64_t u = 0;
  for (std::size_t k = size; k-- > 0;) u = (u << 8) | bytes[k];
  if (signed_type(type) && size < 8 && (u >> (8 * size - 1)) != 0) {
    u |= ~std::uint64_t{0} << (8 * size);  // sign extension
  }
  return static_cast<std::int64_t>(u);
}

std::string element_label(const PlyElement& e, std::uint64_t instance) {
  return "element '" + std::string(e.name) + "' #" + std::to_string(instance);
}

}  // namespace

BodyLines::BodyLines(std::string_view text, std::size_t pos) : text_(text), pos_(pos) {}

bool BodyLines::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(pos_, end - pos_);
  pos_ = end + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  ++number_;
  return true;
}

bool PlyElement::has_list() const {
  return std::any_of(properties.begin(), properties.end(),
                     [](const PlyProperty& p) { return p.is_list(); });
}

std::size_t ply_type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

std::size_t split_blanks(std::string_view line, std::string_view* tokens, std::size_t max) {
  std::size_t n = 0;
  std::string_view token;
  while (next_token(line, token)) {
    if (n < max) tokens[n] = token;
    ++n;
  }
  return n;
}

std::string parse_ply_header(std::string_view text, PlyHeader& header) {
  header = PlyHeader{};
  BodyLines lines(text, 0);
  std::string_view line;
  std::array<std::string_view, 6> t;
  if (!lines.next(line) || split_blanks(line, t.data(), t.size()) != 1 ||
      (t[0] != "ply" && t[0] != "PLY")) {
    return "the first line of a PLY file must be 'ply'";
  }
  bool format_seen = false;
  while (lines.next(line)) {
    const std::size_t n = split_blanks(line, t.data(), t.size());
    // assimp passes over lines it does not know (comment, obj_info, free text such as
    // Blender 2.47's "Created by ..."); so does this reader.
    if (n == 0 ||
        (t[0] != "end_header" && t[0] != "format" && t[0] != "element" && t[0] != "property")) {
      continue;
    }
    const std::string where = "the PLY header's line " + std::to_string(lines.number());
    if (t[0] == "end_header" && n == 1) {
      if (!format_seen) return "the PLY header has no format line";
      // Nothing after end_header: no body, so no mesh. (assimp 5.2 never returned on some such
      // files, e.g. a 15-character unknown header line before an end_header that ends the file;
      // found by fuzzing.)
      if (lines.pos() > text.size()) return "the PLY file ends on its end_header line (no body)";
      header.body = lines.pos();
      return {};
    }
    if (t[0] == "format" && n == 3 && !format_seen) {
      format_seen = true;
      if (t[1] == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (t[1] == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittleEndian;
      } else if (t[1] == "binary_big_endian") {
        header.format = PlyFormat::BinaryBigEndian;
      } else {
        return where + " names an unknown format '" + std::string(t[1]) + "'";
      }
    } else if (t[0] == "element" && n == 3) {
      PlyElement e;
      e.name = t[1];
      if (!parse_count(t[2], e.count)) {
        return where + " gives element '" + std::string(t[1]) + "' the count '" +
               std::string(t[2]) + "', not a non-negative integer";
      }
      for (const PlyElement& other : header.elements) {
        if (other.name == e.name) {
          return where + " declares element '" + std::string(e.name) + "' a second time";
        }
      }
      header.elements.push_back(e);
    } else if (t[0] == "property" && !header.elements.empty() && n == 3 &&
               ply_type_size(t[1]) != 0) {
      header.elements.back().properties.push_back({t[2], t[1], {}, {}});
    } else if (t[0] == "property" && !header.elements.empty() && n == 5 && t[1] == "list" &&
               integer_type(t[2]) && ply_type_size(t[3]) != 0) {
      header.elements.back().properties.push_back({t[4], "list", t[2], t[3]});
    } else {
      return where + " ('" + std::string(line.substr(0, 80)) + "') is not understood";
    }
  }
  return "the PLY header has no end_header line";
}

std::string unsafe_ply_layout(std::string_view text) {
  PlyHeader header;
  if (std::string problem = parse_ply_header(text, header); !problem.empty()) return problem;

  std::uint64_t vertices = 0;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") vertices = e.count;
  }
  const auto is_face_index = [](const PlyElement& e, const PlyProperty& p) {
    return e.name == "face" && p.is_list() &&
           (p.name == "vertex_indices" || p.name == "vertex_index");
  };
  const auto bad_index = [&](const PlyElement& e, std::uint64_t i, std::int64_t index) {
    return element_label(e, i) + " names vertex " + std::to_string(index) + " but the file has " +
           std::to_string(vertices) + " vertices";
  };
  // assimp knows these element names; for any other it reads the count from the start of the
  // name itself (its leading digits, as a wrapping 32-bit number, so usually 0): it skips no
  // instance of such an element and misreads every element after it. "4999999999vertex 4" made
  // it allocate 17 GB (found by fuzzing). Such an element is accepted only last (or empty), where
  // assimp's 0 instances change nothing, and not walked.
  const auto known = [](std::string_view name) {
    return name == "vertex" || name == "face" || name == "tristrips" || name == "edge" ||
           name == "material";
  };
  std::vector<PlyElement> walked;
  for (std::size_t k = 0; k < header.elements.size(); ++k) {
    const PlyElement& e = header.elements[k];
    if (known(e.name)) {
      walked.push_back(e);
      continue;
    }
    if (!e.name.empty() && e.name.front() >= '0' && e.name.front() <= '9') {
      return "the PLY element name '" + std::string(e.name.substr(0, 40)) + "' starts with a digit";
    }
    for (std::size_t later = k + 1; later < header.elements.size(); ++later) {
      if (e.count > 0 && known(header.elements[later].name)) {
        return "the PLY element '" + std::string(e.name.substr(0, 40)) +
               "' comes before element '" + std::string(header.elements[later].name) +
               "': assimp reads no instance of an element it does not know (it knows vertex, "
               "face, tristrips, edge, material) and would misread the rest";
      }
    }
  }
  header.elements = std::move(walked);
  const std::size_t body_size = text.size() - std::min(header.body, text.size());
  for (const PlyElement& e : header.elements) {
    if (e.count > body_size) {
      return "the PLY header announces " + std::to_string(e.count) + " of element '" +
             std::string(e.name) + "' but the body has only " + std::to_string(body_size) +
             " bytes";
    }
  }

  if (header.format == PlyFormat::Ascii) {
    BodyLines lines(text, header.body);
    std::string_view line;
    std::string_view token;
    for (const PlyElement& e : header.elements) {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        if (!lines.next(line)) {
          return "the PLY body ends before " + element_label(e, i) + " (of " +
                 std::to_string(e.count) + ")";
        }
        const auto short_line = [&] {
          return element_label(e, i) + " has fewer values than its properties";
        };
        for (const PlyProperty& p : e.properties) {
          if (!next_token(line, token)) return short_line();
          if (!p.is_list()) continue;
          std::uint64_t items = 0;
          if (!parse_count(token, items)) {
            return element_label(e, i) + " gives list '" + std::string(p.name) + "' the length '" +
                   std::string(token.substr(0, 20)) + "', not a non-negative integer";
          }
          for (std::uint64_t k = 0; k < items; ++k) {
            if (!next_token(line, token)) return short_line();
            if (!is_face_index(e, p)) continue;
            std::int64_t index = 0;
            const auto [ptr, ec] =
                std::from_chars(token.data(), token.data() + token.size(), index);
            if (ec != std::errc{} || ptr != token.data() + token.size()) {
              return element_label(e, i) + " has the vertex index '" +
                     std::string(token.substr(0, 20)) + "', not an integer";
            }
            if (index < 0 || static_cast<std::uint64_t>(index) >= vertices) {
              return bad_index(e, i, index);
            }
          }
        }
      }
    }
    return {};
  }

  const bool big_endian = header.format == PlyFormat::BinaryBigEndian;
  std::size_t at = header.body;
  const auto take = [&](std::uint64_t bytes) {
    if (bytes > text.size() - std::min(at, text.size())) return false;
    at += static_cast<std::size_t>(bytes);
    return true;
  };
  for (const PlyElement& e : header.elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        const auto ends = [&] {
          return "the PLY body ends inside " + element_label(e, i) + " (of " +
                 std::to_string(e.count) + ")";
        };
        if (!p.is_list()) {
          if (!take(ply_type_size(p.type))) return ends();
          continue;
        }
        const std::size_t count_at = at;
        if (!take(ply_type_size(p.count_type))) return ends();
        const std::int64_t items = read_integer(text.data() + count_at, p.count_type, big_endian);
        if (items < 0) {
          return element_label(e, i) + " gives list '" + std::string(p.name) +
                 "' a negative length";
        }
        const std::size_t item_size = ply_type_size(p.item_type);
        const std::size_t items_at = at;
        if (!take(static_cast<std::uint64_t>(items) * item_size)) return ends();
        if (!is_face_index(e, p)) continue;
        if (!integer_type(p.item_type)) {
          return "the PLY face indices are of type '" + std::string(p.item_type) +
                 "', not an integer type";
        }
        for (std::int64_t k = 0; k < items; ++k) {
          const std::int64_t index =
              read_integer(text.data() + items_at + static_cast<std::size_t>(k) * item_size,
                           p.item_type, big_endian);
          if (index < 0 || static_cast<std::uint64_t>(index) >= vertices) {
            return bad_index(e, i, index);
          }
        }
      }
    }
  }
  return {};
}

}  // namespace antcd::detail
