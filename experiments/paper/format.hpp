// experiments/paper/format.hpp — how numbers are printed in the CSV files, tables and report.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace antcd::experiments::paper {

/// Fixed-point text; empty for NaN or infinity (a missing CSV field).
inline std::string num(double v, int digits) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// Like num, but "n/r" (not reached) for infinity and "-" for NaN: for Markdown tables.
inline std::string cell(double v, int digits) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return "n/r";
  return num(v, digits);
}

inline std::string pct(double fraction, int digits = 1) {
  if (std::isnan(fraction)) return "-";
  return num(100 * fraction, digits);
}

inline std::string squared(std::uint32_t n) { return std::to_string(n) + "²"; }

inline std::string ratio_text(std::size_t a, std::size_t b) {
  return std::to_string(a) + "/" + std::to_string(b);
}

}  // namespace antcd::experiments::paper
