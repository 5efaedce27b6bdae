#include "model_archive.hpp"

#include <zlib.h>

#include <array>
#include <cstdint>

namespace antcd::learned::detail {

namespace {

/// Little-endian reads inside `bytes`; `ok` turns false (and stays) on a read past the end.
struct Reader {
  std::string_view bytes;
  bool ok = true;

  std::uint32_t u(std::size_t at, std::size_t width) {
    if (at > bytes.size() || bytes.size() - at < width) {
      ok = false;
      return 0;
    }
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < width; ++i) {
      v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
    }
    return v;
  }
  std::uint32_t u16(std::size_t at) { return u(at, 2); }
  std::uint32_t u32(std::size_t at) { return u(at, 4); }
};

constexpr std::uint32_t kEndRecord = 0x06054B50;     // "PK\5\6"
constexpr std::uint32_t kCentralEntry = 0x02014B50;  // "PK\1\2"
constexpr std::uint32_t kLocalHeader = 0x04034B50;   // "PK\3\4"
constexpr std::size_t kEndRecordSize = 22;
constexpr std::size_t kCentralEntrySize = 46;
constexpr std::size_t kLocalHeaderSize = 30;

/// CRC-32 of a deflated entry, inflated in bounded chunks (nothing kept); false when the data is
/// not valid deflate, unpacks to another size than `size`, or does not end inside `data`.
bool inflated_crc(std::string_view data, std::uint32_t size, std::uint32_t& crc) {
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;  // raw deflate, as zip stores it
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  std::array<unsigned char, 16384> chunk{};
  uLong c = crc32(0L, Z_NULL, 0);
  std::uint64_t total = 0;
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = chunk.data();
    z.avail_out = static_cast<uInt>(chunk.size());
    status = inflate(&z, Z_NO_FLUSH);
    const std::size_t got = chunk.size() - z.avail_out;
    total += got;
    if (total > size) break;
    c = crc32(c, chunk.data(), static_cast<uInt>(got));
    if (status == Z_OK && got == 0 && z.avail_in == 0) break;  // input ended early
  }
  inflateEnd(&z);
  crc = static_cast<std::uint32_t>(c);
  return status == Z_STREAM_END && total == size;
}

}  // namespace

std::string model_archive_problem(std::string_view bytes) {
  if (bytes.size() > kMaxModelBytes) {
    return "larger than " + std::to_string(kMaxModelBytes >> 20) + " MB";
  }
  Reader r{bytes};
  if (bytes.size() < kEndRecordSize || r.u32(0) != kLocalHeader) {
    return "not an antcd learned model (not a zip archive)";
  }
  // The end record: the last "PK\5\6" whose comment reaches exactly to the end of the file.
  std::size_t end = std::string_view::npos;
  const std::size_t lowest =
      bytes.size() > kEndRecordSize + 0xFFFF ? bytes.size() - kEndRecordSize - 0xFFFF : 0;
  for (std::size_t at = bytes.size() - kEndRecordSize + 1; at-- > lowest;) {
    if (r.u32(at) == kEndRecord && at + kEndRecordSize + r.u16(at + 20) == bytes.size()) {
      end = at;
      break;
    }
  }
  if (end == std::string_view::npos) return "truncated zip archive (no end record)";
  const std::uint32_t entries = r.u16(end + 10);
  const std::uint32_t directory_size = r.u32(end + 12);
  const std::uint32_t directory_at = r.u32(end + 16);
  if (r.u16(end + 4) != 0 || r.u16(end + 6) != 0 || r.u16(end + 8) != entries) {
    return "a multi-part zip archive";
  }
  if (entries == 0xFFFF || directory_size == 0xFFFFFFFF || directory_at == 0xFFFFFFFF) {
    return "a zip64 archive (a model file is far smaller)";
  }
  if (entries == 0) return "an empty zip archive";
  if (static_cast<std::uint64_t>(directory_at) + directory_size > end) {
    return "damaged zip archive (central directory outside the file)";
  }
  std::uint64_t unpacked = 0;
  std::size_t at = directory_at;
  for (std::uint32_t k = 0; k < entries; ++k) {
    const std::string entry = "zip entry " + std::to_string(k + 1);
    if (r.u32(at) != kCentralEntry || !r.ok) {
      return "damaged zip archive (" + entry + ": no central directory record)";
    }
    const std::uint32_t flags = r.u16(at + 8);
    const std::uint32_t method = r.u16(at + 10);
    const std::uint32_t crc = r.u32(at + 16);
    const std::uint32_t packed = r.u32(at + 20);
    const std::uint32_t size = r.u32(at + 24);
    const std::size_t next =
        at + kCentralEntrySize + r.u16(at + 28) + r.u16(at + 30) + r.u16(at + 32);
    const std::uint32_t local = r.u32(at + 42);
    if (!r.ok || next > static_cast<std::size_t>(directory_at) + directory_size) {
      return "damaged zip archive (" + entry + ": record outside the central directory)";
    }
    if ((flags & 1U) != 0) return "an encrypted zip archive";
    if (method != 0 && method != 8) {
      return "zip " + entry + " uses compression method " + std::to_string(method);
    }
    if (packed == 0xFFFFFFFF || size == 0xFFFFFFFF || local == 0xFFFFFFFF) {
      return "a zip64 archive (a model file is far smaller)";
    }
    unpacked += size;
    if (unpacked > kMaxModelBytes) {
      return "unpacks to more than " + std::to_string(kMaxModelBytes >> 20) + " MB";
    }
    if (r.u32(local) != kLocalHeader || !r.ok) {
      return "damaged zip archive (" + entry + ": no local header)";
    }
    const std::uint64_t data_at = static_cast<std::uint64_t>(local) + kLocalHeaderSize +
                                  r.u16(local + 26) + r.u16(local + 28);
    if (!r.ok || data_at + packed > directory_at) {
      return "damaged zip archive (" + entry + ": data outside the file)";
    }
    const std::string_view data = bytes.substr(static_cast<std::size_t>(data_at), packed);
    std::uint32_t actual = 0;
    if (method == 0) {
      if (packed != size) return "damaged zip archive (" + entry + ": sizes differ)";
      actual = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0),
                                                reinterpret_cast<const Bytef*>(data.data()),
                                                static_cast<uInt>(data.size())));
    } else if (!inflated_crc(data, size, actual)) {
      return "damaged zip archive (" + entry + ": its data does not unpack)";
    }
    if (actual != crc) return "corrupt model file (" + entry + ": CRC-32 mismatch)";
    at = next;
  }
  return {};
}

}  // namespace antcd::learned::detail
