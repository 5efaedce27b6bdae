// The fuzz targets' reader of their input bytes, front to back; past the end every read gives 0
// (so every input, however short, is a complete case).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace antcd::fuzz {

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  /// raw: the next 8 bytes as a double (any bits: NaN, infinity, subnormals); else a small integer
  /// in [-4, 4] from one byte, so that coplanar, collinear and coincident geometry is common.
  double coordinate(bool raw) {
    if (!raw) return static_cast<double>(static_cast<std::int8_t>(byte()) % 5);
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) bits |= std::uint64_t{byte()} << (8 * k);
    double x = 0;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  }
};

}  // namespace antcd::fuzz
