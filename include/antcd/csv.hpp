// antcd/csv.hpp — reading line-based text files (CSV) that may be hostile: point lists
// (read_points_csv, `antcd points`), and the bounded line reader the tools' other CSV formats use.
// Part of the antcd::io library (link antcd::io).
//
// Guarantees, for any bytes: a file is read only if it is a regular file (a FIFO could block
// forever, a device read without end); a line is refused before it is held in memory when it is
// longer than the reader's limit (a binary file, a file without line breaks), so memory is that of
// the valid answer plus one line; time is linear in the input. Every refusal is an antcd::Error
// whose what() is one line "<source>[:<line>]: <problem>" (pass it through antcd::printable_line
// before printing: a quoted line may hold control bytes).
// Thread safety: the functions may be called from several threads at once; one CsvLines object
// belongs to one thread.
#pragma once

#include <antcd/io_export.hpp>
#include <antcd/math.hpp>

#include <filesystem>
#include <fstream>
#include <istream>
#include <string>
#include <vector>

namespace antcd {

/// Opens `path` for reading, binary. Throws antcd::Error "<path>: <what> ..." when it is missing,
/// not a regular file (a directory, device, FIFO or socket) or cannot be opened.
ANTCD_IO_API std::ifstream open_regular_file(const std::filesystem::path& path,
                                             const std::string& what);

/// The lines of a stream, each at most `max_length` bytes (without its line break). A trailing
/// '\r' is dropped; NUL and other bytes are kept as they are.
class ANTCD_IO_API CsvLines {
 public:
  /// Longest line limit a reader may ask for (the buffer is allocated once, this size).
  static constexpr std::size_t kLargestLimit = 1 << 16;

  /// `source` names the input in errors. Throws antcd::Error if max_length is 0 or above
  /// kLargestLimit.
  CsvLines(std::istream& in, std::string source, std::size_t max_length);

  /// The next line into `line`; false at the end of the input. Throws antcd::Error
  /// "<source>:<n>: line longer than <max_length> characters", or "<source>: read failed".
  bool next(std::string& line);
  /// 1-based number of the line `next` returned last (0 before the first).
  [[nodiscard]] std::size_t number() const { return number_; }
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::istream& in_;
  std::string source_;
  std::size_t max_length_;
  std::size_t number_ = 0;
  std::vector<char> buffer_;
};

/// Longest line of a points file: three doubles in full need far less.
inline constexpr std::size_t kMaxPointsLine = 1024;

/// Reads points, one "x,y,z" per line (commas, semicolons, tabs and/or blanks between the three
/// numbers, each finite); blank lines and lines starting with '#' are skipped, and so is a first
/// line that holds no number (a header). Throws antcd::Error naming `source` and the line: a line
/// that is not three finite numbers, a line longer than kMaxPointsLine, no point at all.
ANTCD_IO_API std::vector<Vec3> read_points_csv(std::istream& in, const std::string& source);
/// The same from a file (a regular file only, see open_regular_file); errors name `path`.
ANTCD_IO_API std::vector<Vec3> read_points_csv(const std::filesystem::path& path);

}  // namespace antcd
