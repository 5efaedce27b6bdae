// Binary STL read natively (stl_binary.hpp). Facets are read in blocks and their corners joined
// on the fly through an open-addressing table of vertex indices, so the peak memory is the mesh
// plus 4 to 8 bytes per vertex for the table, and one block of the file.
#include "io/stl_binary.hpp"

#include "io/polygon_soup.hpp"
#include "util/huge_pages.hpp"

#include <antcd/error.hpp>
#include <antcd/file.hpp>

#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

namespace antcd::detail {

namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kFacetBytes = 50;
constexpr std::size_t kFacetsPerBlock = 1 << 16;

std::uint32_t read_u32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

float read_f32(const unsigned char* p) { return std::bit_cast<float>(read_u32(p)); }

/// Vertex indices by position: open addressing with linear probing, at most half full.
class VertexTable {
 public:
  explicit VertexTable(std::size_t expected) { resize(std::max<std::size_t>(expected, 1024)); }

  /// The index of `p` in `vertices`, appended there if new.
  std::uint32_t find_or_add(const Vec3& p, std::vector<Vec3>& vertices, const std::string& source) {
    std::size_t slot = slot_of(p);
    while (true) {
      const std::uint32_t id = slots_[slot];
      if (id == kEmpty) break;
      if (vertices[id] == p) return id;
      slot = (slot + 1) & mask_;
    }
    if (vertices.size() >= kEmpty) {
      throw MeshError(source, "has more vertices than 32-bit indices can address");
    }
    const auto id = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(p);
    slots_[slot] = id;
    if (2 * vertices.size() > slots_.size()) {
      resize(2 * slots_.size());
      for (std::uint32_t v = 0; v < vertices.size(); ++v) place(v, vertices[v]);
    }
    return id;
  }

 private:
  static constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();

  // position_hash leaves the low bits of round coordinates alike: the slot is taken from the
  // high bits of a multiplicative (Fibonacci) mix, which depend on all of them.
  [[nodiscard]] std::size_t slot_of(const Vec3& p) const {
    const std::uint64_t x = static_cast<std::uint64_t>(position_hash(p)) * 0x9E3779B97F4A7C15ULL;
    return static_cast<std::size_t>(x >> shift_);
  }

  void resize(std::size_t at_least) {
    std::size_t n = 1;
    int bits = 0;
    while (n < 2 * at_least) {
      n <<= 1;
      ++bits;
    }
    slots_.assign(n, kEmpty);
    mask_ = n - 1;
    shift_ = 64 - bits;
  }

  void place(std::uint32_t id, const Vec3& p) {
    std::size_t slot = slot_of(p);
    while (slots_[slot] != kEmpty) slot = (slot + 1) & mask_;
    slots_[slot] = id;
  }

  std::vector<std::uint32_t> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

bool is_binary_stl(std::string_view head, std::uintmax_t size) {
  if (size < kHeaderBytes || head.size() < kHeaderBytes) return false;
  const auto facets =
      read_u32(reinterpret_cast<const unsigned char*>(head.data()) + kHeaderBytes - 4);
  return size == kHeaderBytes + std::uintmax_t{kFacetBytes} * facets;
}

Mesh read_binary_stl(const std::filesystem::path& path, const std::string& source) {
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw MeshError(source, "cannot be opened: " + printable_line(std::strerror(errno)));
  std::array<unsigned char, kHeaderBytes> header{};
  if (std::fread(header.data(), 1, header.size(), file.get()) != header.size()) {
    throw MeshError(source, "cannot be read: the binary STL header is cut short");
  }
  const std::uint32_t facets = read_u32(header.data() + kHeaderBytes - 4);
  if (facets == 0) throw MeshError(source, "contains no triangles");

  Mesh mesh;
  mesh.triangles.reserve(facets);
  // A closed surface has about half as many vertices as triangles.
  mesh.vertices.reserve(facets / 2 + 3);
  advise_huge_pages(mesh.triangles.data(), mesh.triangles.capacity());
  advise_huge_pages(mesh.vertices.data(), mesh.vertices.capacity());
  VertexTable table(facets / 2 + 3);
  std::vector<unsigned char> block(kFacetsPerBlock * kFacetBytes);
  std::uint32_t done = 0;
  while (done < facets) {
    const std::size_t count = std::min<std::size_t>(kFacetsPerBlock, facets - done);
    if (std::fread(block.data(), kFacetBytes, count, file.get()) != count) {
      throw MeshError(source,
                      "cannot be read: the file ended or failed at facet " + std::to_string(done));
    }
    for (std::size_t f = 0; f < count; ++f) {
      const unsigned char* corner = block.data() + f * kFacetBytes + 12;  // after the normal
      TriangleIndices tri{};
      for (int k = 0; k < 3; ++k, corner += 12) {
        const Vec3 p(read_f32(corner), read_f32(corner + 4), read_f32(corner + 8));
        if (!p.allFinite()) {
          throw MeshError(source,
                          "facet " + std::to_string(done + f) + " has a non-finite coordinate");
        }
        tri[k] = table.find_or_add(p, mesh.vertices, source);
      }
      mesh.triangles.push_back(tri);
    }
    done += static_cast<std::uint32_t>(count);
  }
  mesh.vertices.shrink_to_fit();
  validate_mesh(mesh, source);
  return mesh;
}

}  // namespace antcd::detail
