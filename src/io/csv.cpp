// Line-based text files (antcd/csv.hpp): the bounded line reader and the points reader.
#include <antcd/csv.hpp>
#include <antcd/error.hpp>
#include <antcd/file.hpp>

#include "io/polygon_soup.hpp"

#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

namespace antcd {

std::ifstream open_regular_file(const std::filesystem::path& path, const std::string& what) {
  if (const std::string problem = file_problem(path); !problem.empty()) {
    throw Error(path.string() + ": cannot open the " + what + ": " + problem);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open " + what);
  return in;
}

CsvLines::CsvLines(std::istream& in, std::string source, std::size_t max_length)
    : in_(in), source_(std::move(source)), max_length_(max_length) {
  if (max_length == 0 || max_length > kLargestLimit) {
    throw Error("CsvLines: max_length must be 1 .. " + std::to_string(kLargestLimit));
  }
  // Room for the longest line, its line break, a '\r' and the terminating NUL of getline.
  buffer_.resize(max_length + 3);
}

bool CsvLines::next(std::string& line) {
  in_.getline(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (got == 0) {
    if (in_.bad()) throw Error(source_ + ": read failed");
    return false;  // end of the input
  }
  const auto too_long = [&] {
    return Error(source_ + ":" + std::to_string(number_ + 1) + ": line longer than " +
                 std::to_string(max_length_) + " characters");
  };
  if (in_.fail() && !in_.eof()) throw too_long();          // no line break within the buffer
  line.assign(buffer_.data(), in_.eof() ? got : got - 1);  // NUL bytes kept: they are no number
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.size() > max_length_) throw too_long();
  ++number_;
  return true;
}

std::vector<Vec3> read_points_csv(std::istream& in, const std::string& source) {
  CsvLines lines(in, source, kMaxPointsLine);
  std::vector<Vec3> points;
  std::string line;
  while (lines.next(line)) {
    std::string_view fields[3];
    std::size_t count = 0;
    bool numeric = true;
    std::size_t i = 0;
    const auto separator = [](char c) { return c == ',' || c == ';' || c == '\t' || c == ' '; };
    while (i < line.size()) {
      while (i < line.size() && separator(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !separator(line[i])) ++i;
      if (count == 3) {
        numeric = false;
        break;
      }
      fields[count++] = std::string_view(line).substr(start, i - start);
    }
    if (count == 0 || fields[0].front() == '#') continue;  // blank line or comment
    Vec3 p;
    numeric = numeric && count == 3;
    for (std::size_t k = 0; numeric && k < 3; ++k) {
      numeric = detail::parse_coordinate(fields[k], p[static_cast<Eigen::Index>(k)]) == std::errc{};
    }
    if (!numeric) {
      if (points.empty() && lines.number() == 1) continue;  // header
      throw Error(source + ":" + std::to_string(lines.number()) +
                  ": expected three finite numbers x,y,z, got '" + line + "'");
    }
    points.push_back(p);
  }
  if (points.empty()) throw Error(source + ": holds no point");
  return points;
}

std::vector<Vec3> read_points_csv(const std::filesystem::path& path) {
  std::ifstream in = open_regular_file(path, "points file");
  return read_points_csv(in, path.string());
}

}  // namespace antcd
