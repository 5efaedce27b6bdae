// Private: the model file's fixed header and its checksum (model_file.cpp; the tests and the fuzz
// target use them to build files whose checksum is right but whose contents are not). The format
// is docs/model_file.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace antcd::detail {

/// The first 8 bytes of every model file.
inline constexpr std::uint8_t kModelMagic[8] = {'A', 'N', 'T', 'C', 'D', 'M', 'D', 'L'};
/// The format version this build writes and reads (docs/model_file.md).
inline constexpr std::uint32_t kModelFormatVersion = 1;
/// magic (8), version (u32), flags (u32, 0), payload size (u64), payload checksum (u64).
inline constexpr std::size_t kModelHeaderSize = 32;
inline constexpr std::size_t kModelPayloadSizeOffset = 16;
inline constexpr std::size_t kModelChecksumOffset = 24;

/// Unsigned little-endian integer of `n` bytes at `p`.
inline std::uint64_t read_le(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int k = n - 1; k >= 0; --k) v = (v << 8) | p[k];
  return v;
}

/// Writes the low `n` bytes of `v` at `p`, little-endian.
inline void write_le(std::uint8_t* p, std::uint64_t v, int n) {
  for (int k = 0; k < n; ++k) p[k] = static_cast<std::uint8_t>(v >> (8 * k));
}

/// The payload checksum: FNV-1a (64-bit offset basis and prime) applied to 8-byte little-endian
/// words instead of single bytes (eight times fewer multiplications), then to the 0..7 tail bytes
/// one by one, then to the length. Detects accidental corruption; it is no signature.
inline std::uint64_t model_checksum(std::span<const std::uint8_t> data) {
  constexpr std::uint64_t prime = 0x100000001b3ULL;
  std::uint64_t h = 0xcbf29ce484222325ULL;
  std::size_t i = 0;
  for (; i + 8 <= data.size(); i += 8) h = (h ^ read_le(data.data() + i, 8)) * prime;
  for (; i < data.size(); ++i) h = (h ^ data[i]) * prime;
  return (h ^ data.size()) * prime;
}

}  // namespace antcd::detail
