// Private: doubles rounded outward to floats, for boxes kept in single precision (the World's
// broad-phase tree, the self test's boxes). A box of floats below and above the exact bounds holds
// the exact box, so boxes found apart in floats are apart exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace antcd::detail {

/// A float <= x at most two units in the last place away; finite x only. The nearest float moved
/// down by at least one unit in the last place (|f| 2^-23 is one or two of them) plus the smallest
/// normal float (for f = 0; still a step under flush-to-zero): no branch on which way the
/// conversion rounded, which is a coin toss (and was mispredicted for every leaf box of a moving
/// world). Beyond the float range: -infinity, or the largest float.
inline float float_below(double x) {
  constexpr double kMax = std::numeric_limits<float>::max();
  const auto f = static_cast<float>(std::min(std::max(x, -kMax), kMax));
  return f - (std::abs(f) * 0x1p-23F + std::numeric_limits<float>::min());
}

/// A float >= x, as float_below mirrored: +infinity or minus the largest float beyond the range.
inline float float_above(double x) { return -float_below(-x); }

}  // namespace antcd::detail
