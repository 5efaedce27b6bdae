// Internal to the mesh layer: a PLY file's header (format, elements, properties) and a walk over
// its body that checks the body holds what the header announces, before assimp reads the file.
//
// assimp 5.2's PLY reader trusts the header: a binary body shorter than the header announces, or
// an ASCII line with fewer values than its element's properties, makes it read past its buffers
// and corrupt the heap (found by fuzzing: a 355-byte binary file announcing 4 vertices of 28
// bytes, then two "face" elements); a count of billions of instances makes it allocate for all of
// them first. load.cpp therefore refuses, with the reason, a PLY file whose layout this walk
// cannot follow to the end. The walk follows the PLY format (one line per element instance in
// ASCII; lists as a count then that many items), which is also how assimp reads it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace antcd::detail {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string_view name;
  std::string_view type;        ///< the scalar type, or "list"
  std::string_view count_type;  ///< a list's count type (empty for a scalar)
  std::string_view item_type;   ///< a list's item type (empty for a scalar)
  [[nodiscard]] bool is_list() const { return type == "list"; }
};

struct PlyElement {
  std::string_view name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  [[nodiscard]] bool has_list() const;
};

/// The lines of a text from an offset on: each without its '\n' and without a CR before it.
class BodyLines {
 public:
  BodyLines(std::string_view text, std::size_t pos);
  /// The next line; false at the end of the text.
  bool next(std::string_view& line);
  /// The offset of the next line's first byte.
  [[nodiscard]] std::size_t pos() const { return pos_; }
  /// 1-based number of the last line read (counted from `pos` given to the constructor).
  [[nodiscard]] std::size_t number() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_;
  std::size_t number_ = 0;
};

/// A parsed header; its views point into the text it was parsed from.
struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  ///< offset of the first byte after the end_header line's '\n'
};

/// The byte size of a PLY scalar type name (char .. double, int8 .. float64), 0 for an unknown one.
std::size_t ply_type_size(std::string_view type);

/// Splits `line` at blanks (space, tab, a CR before the line end) into at most `max` tokens;
/// returns how many there were (counting on past `max`).
std::size_t split_blanks(std::string_view line, std::string_view* tokens, std::size_t max);

/// Parses the header of `text` (a whole file starting with "ply"). Lines other than format,
/// element, property and end_header (comment, obj_info, free text) are passed over, as assimp
/// does. Returns the problem ("the PLY header ..."), or an empty string with `header` filled.
std::string parse_ply_header(std::string_view text, PlyHeader& header);

/// Checks that the file `text` is a PLY file whose body holds every instance of every element the
/// header announces: in ASCII one line per instance with a value per scalar property and, per
/// list, a count (a non-negative integer) followed by that many values; in binary the bytes of
/// the same (list counts read in the file's byte order). Also checks that no element name appears
/// twice and that every face's vertex indices ("vertex_indices" or "vertex_index" in "face") name
/// a vertex of the "vertex" element. Work is bounded by the file's size. Returns the problem, or
/// an empty string.
std::string unsafe_ply_layout(std::string_view text);

}  // namespace antcd::detail
