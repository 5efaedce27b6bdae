// libFuzzer target: antcd::read_points_csv (antcd/csv.hpp) on arbitrary bytes.
//
// An antcd::Error is an accepted outcome; any other exception, a crash or a sanitizer report is a
// finding. Points that are read must be finite, at most one per line of the input, and the error
// line of a refusal must name the source.
#include <antcd/csv.hpp>
#include <antcd/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>

#include "finding.hpp"

namespace {

[[noreturn]] void finding(const char* what, const char* detail) {
  antcd::fuzz::finding("fuzz_points_csv", what, detail);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  try {
    const std::vector<antcd::Vec3> points = antcd::read_points_csv(in, "fuzz.csv");
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    if (points.empty() || points.size() > lines) finding("point count", "not 1 .. lines");
    for (const antcd::Vec3& p : points) {
      if (!p.allFinite()) finding("point", "not finite");
    }
  } catch (const antcd::Error& e) {
    if (std::string(e.what()).rfind("fuzz.csv", 0) != 0) finding("error names no source", e.what());
  } catch (const std::exception& e) {
    finding("unexpected exception from read_points_csv", e.what());
  } catch (...) {
    finding("unexpected exception from read_points_csv", "not a std::exception");
  }
  return 0;
}
