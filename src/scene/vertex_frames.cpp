// The vertex-frames side file of deforming scene objects (antcd/scene.hpp, docs/cli.md): its
// bytes, read with every size checked against the file's real size before anything is allocated.
#include <antcd/file.hpp>
#include <antcd/scene.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>

#include "bvh/model_file.hpp"  // read_le32 / read_le64 / write_le: one copy of the byte helpers

namespace antcd {

namespace {

constexpr std::uint64_t kVertexFramesHeaderSize = 24;
constexpr std::uint64_t kBytesPerVertex = 24;  // x, y, z as float64

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw SceneError(printable_line(source + ": " + problem));
}

struct Header {
  std::uint32_t vertex_count = 0;
  std::uint64_t frames = 0;
  std::uint64_t payload = 0;  ///< bytes after the header the counts call for
};

/// Checks the header's magic, version and counts; `size` is the whole file's size in bytes.
Header check_header(const std::uint8_t* p, std::uint64_t size, const std::string& source) {
  if (size < kVertexFramesHeaderSize) {
    fail(source, "truncated: " + std::to_string(size) + " bytes, shorter than the " +
                     std::to_string(kVertexFramesHeaderSize) + "-byte vertex-frames header");
  }
  if (std::memcmp(p, kVertexFramesMagic, sizeof kVertexFramesMagic) != 0) {
    fail(source, "not a vertex-frames file (wrong magic; expected \"ANTCDVFR\")");
  }
  const std::uint32_t version = detail::read_le32(p + 8);
  if (version != kVertexFramesVersion) {
    fail(source, "vertex-frames format version " + std::to_string(version) +
                     " is not supported (this build reads version " +
                     std::to_string(kVertexFramesVersion) + ")");
  }
  Header h;
  h.vertex_count = detail::read_le32(p + 12);
  h.frames = detail::read_le64(p + 16);
  if (h.vertex_count == 0) fail(source, "vertex count is 0");
  if (h.frames == 0) fail(source, "frame count is 0");
  // 24 n F must not overflow: n < 2^32, so F <= (2^64 - 1) / (24 n) bounds it.
  const std::uint64_t per_frame = kBytesPerVertex * h.vertex_count;
  if (h.frames >
      (std::numeric_limits<std::uint64_t>::max() - kVertexFramesHeaderSize) / per_frame) {
    fail(source, "frame count " + std::to_string(h.frames) + " times " +
                     std::to_string(h.vertex_count) + " vertices does not fit any file");
  }
  h.payload = per_frame * h.frames;
  const std::uint64_t expected = kVertexFramesHeaderSize + h.payload;
  if (size != expected) {
    fail(source, std::string(size < expected ? "truncated" : "has trailing bytes") + ": " +
                     std::to_string(size) + " bytes, expected " + std::to_string(expected) +
                     " for " + std::to_string(h.vertex_count) + " vertices x " +
                     std::to_string(h.frames) + " frames");
  }
  return h;
}

/// The positions of `h` from `p` (the payload), each checked finite.
VertexFrames decode(const Header& h, const std::uint8_t* p, const std::string& source) {
  VertexFrames out;
  out.vertex_count = h.vertex_count;
  out.frames = static_cast<std::size_t>(h.frames);
  const std::uint64_t count = h.payload / kBytesPerVertex;
  out.positions.resize(static_cast<std::size_t>(count));
  for (std::uint64_t k = 0; k < count; ++k) {
    Vec3& v = out.positions[static_cast<std::size_t>(k)];
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t bits = detail::read_le64(p + kBytesPerVertex * k + 8 * c);
      double x = 0;
      std::memcpy(&x, &bits, 8);
      if (!std::isfinite(x)) {
        fail(source, "frame " + std::to_string(k / h.vertex_count) + ", vertex " +
                         std::to_string(k % h.vertex_count) + ": coordinate " +
                         std::string(1, "xyz"[c]) + " is not finite");
      }
      v[c] = x;
    }
  }
  return out;
}

}  // namespace

VertexFrames parse_vertex_frames(std::span<const std::uint8_t> bytes, const std::string& source) {
  const Header h = check_header(bytes.data(), bytes.size(), source);
  return decode(h, bytes.data() + kVertexFramesHeaderSize, source);
}

VertexFrames read_vertex_frames(const std::filesystem::path& path) {
  const std::string source = path.string();
  if (const std::string problem = file_problem(path); !problem.empty()) fail(source, problem);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(source, "cannot be accessed: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(source, "cannot be opened");
  std::uint8_t header[kVertexFramesHeaderSize] = {};
  in.read(reinterpret_cast<char*>(header),
          static_cast<std::streamsize>(std::min<std::uintmax_t>(size, sizeof header)));
  if (!in) fail(source, "cannot be read");
  // The counts are checked against the size before the payload is allocated: the memory taken is
  // the file's real size, whatever its header claims.
  const Header h = check_header(header, size, source);
  std::vector<std::uint8_t> payload(static_cast<std::size_t>(h.payload));
  in.read(reinterpret_cast<char*>(payload.data()), static_cast<std::streamsize>(payload.size()));
  if (static_cast<std::uint64_t>(in.gcount()) != h.payload) {
    fail(source, "truncated while reading (the file shrank?)");
  }
  return decode(h, payload.data(), source);
}

std::string vertex_frames_bytes(const VertexFrames& frames) {
  if (frames.vertex_count == 0 || frames.frames == 0 ||
      frames.positions.size() != std::size_t{frames.vertex_count} * frames.frames) {
    throw ArgumentError("vertex_frames_bytes: positions must hold vertex_count x frames (" +
                        std::to_string(frames.vertex_count) + " x " +
                        std::to_string(frames.frames) + ") positions, got " +
                        std::to_string(frames.positions.size()));
  }
  std::string out(kVertexFramesHeaderSize + kBytesPerVertex * frames.positions.size(), '\0');
  auto* p = reinterpret_cast<std::uint8_t*>(out.data());
  std::memcpy(p, kVertexFramesMagic, sizeof kVertexFramesMagic);
  detail::write_le(p + 8, kVertexFramesVersion, 4);
  detail::write_le(p + 12, frames.vertex_count, 4);
  detail::write_le(p + 16, frames.frames, 8);
  p += kVertexFramesHeaderSize;
  for (const Vec3& v : frames.positions) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(v[c])) {
        throw ArgumentError("vertex_frames_bytes: a position is not finite");
      }
      std::uint64_t bits = 0;
      const double x = v[c];
      std::memcpy(&bits, &x, 8);
      detail::write_le(p, bits, 8);
      p += 8;
    }
  }
  return out;
}

void save_vertex_frames(const VertexFrames& frames, const std::filesystem::path& path) {
  write_file_atomic(path, vertex_frames_bytes(frames));
}

void load_vertex_frames(SceneDescription& scene, const std::string& source) {
  for (SceneObject& o : scene.objects) {
    if (o.vertex_file_text.empty() || o.vertex_frames) continue;
    VertexFrames frames;
    try {
      frames = read_vertex_frames(o.vertex_file);
    } catch (const SceneError& e) {
      throw SceneError(printable_line(source + ": object '" + o.name + "': " + e.what()));
    }
    if (frames.frames != scene.frames) {
      throw SceneError(printable_line(source + ": object '" + o.name +
                                      "': " + o.vertex_file.string() + ": holds " +
                                      std::to_string(frames.frames) + " frames; the scene has " +
                                      std::to_string(scene.frames)));
    }
    o.vertex_frames = std::make_shared<const VertexFrames>(std::move(frames));
  }
}

}  // namespace antcd
