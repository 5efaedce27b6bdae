// Private: the model file's fixed header and its checksum (model_file.cpp; the tests and the fuzz
// target use them to build files whose checksum is right but whose contents are not). The format
// is docs/model_file.md.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
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

/// Unsigned little-endian integer of `n` (1..8) bytes at `p`.
inline std::uint64_t read_le(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int k = n - 1; k >= 0; --k) v = (v << 8) | p[k];
  return v;
}

/// The little-endian u64 at `p` (one load on a little-endian host).
inline std::uint64_t read_le64(const std::uint8_t* p) {
  if constexpr (std::endian::native == std::endian::little) {
    std::uint64_t v = 0;
    std::memcpy(&v, p, 8);
    return v;
  } else {
    return read_le(p, 8);
  }
}

/// The little-endian u32 at `p`.
inline std::uint32_t read_le32(const std::uint8_t* p) {
  if constexpr (std::endian::native == std::endian::little) {
    std::uint32_t v = 0;
    std::memcpy(&v, p, 4);
    return v;
  } else {
    return static_cast<std::uint32_t>(read_le(p, 4));
  }
}

/// Writes the low `n` bytes of `v` at `p`, little-endian.
inline void write_le(std::uint8_t* p, std::uint64_t v, int n) {
  for (int k = 0; k < n; ++k) p[k] = static_cast<std::uint8_t>(v >> (8 * k));
}

/// The payload checksum: FNV-1a (64-bit offset basis and prime) in four lanes, lane j taking the
/// 8-byte little-endian words j, j + 4, j + 8, ... (words, not bytes, and four independent chains:
/// it runs at memory speed); then the lanes are folded into lane 0 in order, then the 0..31 tail
/// bytes one by one, then the length. Detects accidental corruption; it is no signature.
inline std::uint64_t model_checksum(std::span<const std::uint8_t> data) {
  constexpr std::uint64_t prime = 0x100000001b3ULL;
  constexpr std::uint64_t basis = 0xcbf29ce484222325ULL;
  std::uint64_t lane[4] = {basis, basis, basis, basis};
  std::size_t i = 0;
  for (; i + 32 <= data.size(); i += 32) {
    for (std::size_t j = 0; j < 4; ++j)
      lane[j] = (lane[j] ^ read_le64(data.data() + i + 8 * j)) * prime;
  }
  std::uint64_t h = lane[0];
  for (std::size_t j = 1; j < 4; ++j) h = (h ^ lane[j]) * prime;
  for (; i < data.size(); ++i) h = (h ^ data[i]) * prime;
  return (h ^ data.size()) * prime;
}

}  // namespace antcd::detail
