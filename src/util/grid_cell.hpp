// Private: a coordinate's cell index in a grid or along a space-filling curve, converted without
// undefined behaviour. Converting a double that is NaN or outside an integer type's range is
// undefined (UBSan's float-cast-overflow): coordinates near the ends of the double range, a box
// wider than that range or coincident points make such values in a grid's arithmetic.
#pragma once

namespace antcd::detail {

/// `x` truncated toward zero and clamped to [lo, hi] (lo <= hi, both exactly representable as
/// doubles), clamped as a double before the conversion; a NaN gives lo.
template <class Int>
[[nodiscard]] constexpr Int clamped_cell(double x, Int lo, Int hi) {
  if (!(x >= static_cast<double>(lo))) return lo;
  return x < static_cast<double>(hi) ? static_cast<Int>(x) : hi;
}

}  // namespace antcd::detail
