// The fuzz targets' one way to report a finding: a line naming the target and what broke, then
// abort(), which libFuzzer records as a crash with the input that caused it.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace antcd::fuzz {

[[noreturn]] inline void finding(const char* target, const char* what, const char* detail) {
  std::fprintf(stderr, "antcd %s: %s: %s\n", target, what, detail);
  std::abort();
}

}  // namespace antcd::fuzz
