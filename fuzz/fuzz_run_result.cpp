// libFuzzer target: antcd::shared::parse_run_result (the `antcd run --out` format) on arbitrary
// bytes.
//
// An antcd::Error is an accepted outcome; any other exception, a crash, a sanitizer report or
// memory beyond -rss_limit_mb is a finding. A result that parses must survive the round trip
// through to_json: the written text parses again to the same frames and pairs.
#include "shared/run_result.hpp"

#include <antcd/error.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "finding.hpp"

namespace {

[[noreturn]] void finding(const char* what, const char* detail) {
  antcd::fuzz::finding("fuzz_run_result", what, detail);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  antcd::shared::RunResult result;
  try {
    result = antcd::shared::parse_run_result(text, "fuzz.json");
  } catch (const antcd::Error&) {
    return 0;  // a clear refusal: fine
  } catch (const std::exception& e) {
    finding("unexpected exception from parse_run_result", e.what());
  } catch (...) {
    finding("unexpected exception from parse_run_result", "not a std::exception");
  }
  try {
    const std::string written = antcd::shared::to_json(result);
    const antcd::shared::RunResult again = antcd::shared::parse_run_result(written, "again.json");
    if (again.method != result.method || again.frames.size() != result.frames.size()) {
      finding("round trip", "method or frame count changed");
    }
    for (std::size_t i = 0; i < result.frames.size(); ++i) {
      if (again.frames[i].frame != result.frames[i].frame ||
          again.frames[i].pairs != result.frames[i].pairs ||
          again.frames[i].candidates != result.frames[i].candidates) {
        finding("round trip", "a frame changed");
      }
    }
  } catch (const std::exception& e) {
    finding("round trip through to_json failed", e.what());
  }
  return 0;
}
