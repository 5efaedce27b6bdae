// Model files (docs/model_file.md): Model::save / load / to_bytes / from_bytes. Every value is
// written and read by explicit code, one field at a time, little-endian whatever the host, so a
// change of BvhNode's members is a compile error here (the static_assert) and an edit of
// write_node / read_node with a new format version, never a silent change of the file.
//
// Reading trusts nothing: the header's payload size must be the file's, the checksum must match,
// every count is checked against the bytes left before anything is allocated for it (so a hostile
// file never allocates more than a few times its own size), and the contents are validated
// (finite coordinates, indices in range, the tree's depth-first shape, leaves covering the leaf
// order, only degenerate triangles left out, volumes that hold their subtrees) before the Model
// exists; the proofs about the tree and its volumes are bvh/model_check.cpp's.
//
// One piece on purpose: the writer and the reader of one format, field by field, side by side, so
// that a field changed in one is seen to change in the other; the shared byte layout and checksum
// are bvh/model_file.hpp's.
#include <antcd/bvh.hpp>
#include <antcd/file.hpp>

#include "bvh/model_cache.hpp"
#include "bvh/model_check.hpp"
#include "bvh/model_file.hpp"
#include "util/huge_pages.hpp"
#include "util/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace antcd {

namespace detail {
namespace {

// The bytes of one node, field by field (write_node / read_node).
static_assert(sizeof(BvhNode) == 96,
              "BvhNode changed: update write_node/read_node and kModelFormatVersion");
constexpr std::size_t kNodeBytes = 3 * 8 + 4 + 4 + 4 + 3 * 4 + 3 * 8 + 3 * 8;
constexpr std::size_t kVertexBytes = 3 * 8;
constexpr std::size_t kTriangleBytes = 3 * 4;
// leaf_size, covariance, closed, reserved (u32 each), build_ms (f64).
constexpr std::size_t kSettingsBytes = 4 * 4 + 8;
// Models larger than this fail the build's 32-bit node and triangle indices anyway.
constexpr std::uint64_t kMaxCount = 0xFFFFFFFFULL;

/// The bits of `from` as a To (std::bit_cast, which the WebAssembly build's libc++ lacks).
template <class To, class From>
To same_bits(const From& from) {
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

float f32_at(const std::uint8_t* p) { return same_bits<float>(read_le32(p)); }
double f64_at(const std::uint8_t* p) { return same_bits<double>(read_le64(p)); }
std::uint32_t u32_at(const std::uint8_t* p) { return read_le32(p); }
Vec3 vec3_at(const std::uint8_t* p) { return {f64_at(p), f64_at(p + 8), f64_at(p + 16)}; }

/// body(i) for i in [0, n): in parallel blocks for a large model.
template <class Body>
void blocks(std::size_t n, const Body& body) {
  const auto range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) body(i);
  };
  if (n < kParallelCheck) {
    range(0, n);
  } else {
    parallel::for_ranges(0, n, 8192, range);
  }
}

/// `v` resized to n elements, on huge pages when large (their first writes are most of a large
/// model's load otherwise, as of its build: util/huge_pages.hpp).
template <class T>
void sized(std::vector<T>& v, std::size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity());
  v.resize(n);
}

class Writer {
 public:
  explicit Writer(std::uint8_t* p) : p_(p) {}
  void u32(std::uint32_t v) { put(v, 4); }
  void u64(std::uint64_t v) { put(v, 8); }
  void f32(float v) { put(same_bits<std::uint32_t>(v), 4); }
  void f64(double v) { put(same_bits<std::uint64_t>(v), 8); }
  void vec3(const Vec3& v) {
    for (int k = 0; k < 3; ++k) f64(v[k]);
  }
  void text(const std::string& s) {
    u64(s.size());
    if (!s.empty()) std::memcpy(p_, s.data(), s.size());
    p_ += s.size();
  }
  [[nodiscard]] const std::uint8_t* position() const { return p_; }

 private:
  void put(std::uint64_t v, int n) {
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(p_, &v, static_cast<std::size_t>(n));  // the low n bytes come first
    } else {
      write_le(p_, v, n);
    }
    p_ += n;
  }
  std::uint8_t* p_;
};

void write_node(Writer& w, const BvhNode& node) {
  w.vec3(node.center);
  w.f32(node.radius);
  w.u32(node.count);
  w.u32(node.first_or_right);
  for (const float h : node.half) w.f32(h);
  w.vec3(node.axis0);
  w.vec3(node.axis1);
}

BvhNode read_node(const std::uint8_t* p) {
  BvhNode node;
  node.center = vec3_at(p);
  node.radius = f32_at(p + 24);
  node.count = u32_at(p + 28);
  node.first_or_right = u32_at(p + 32);
  for (std::size_t k = 0; k < 3; ++k) node.half[k] = f32_at(p + 36 + 4 * k);
  node.axis0 = vec3_at(p + 48);
  node.axis1 = vec3_at(p + 72);
  return node;
}

/// The payload, read front to back; every problem is a MeshError naming the input.
class Reader {
 public:
  Reader(std::span<const std::uint8_t> data, std::string name)
      : data_(data), name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& problem) const { throw MeshError(name_, problem); }
  [[nodiscard]] const std::string& name() const { return name_; }

  /// The next `n` bytes (`what` names them in the error when fewer remain).
  const std::uint8_t* take(std::size_t n, const char* what) {
    if (n > data_.size() - pos_) {
      fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
           std::to_string(data_.size() - pos_) + " remain");
    }
    const std::uint8_t* p = data_.data() + pos_;
    pos_ += n;
    return p;
  }
  std::uint32_t u32(const char* what) { return u32_at(take(4, what)); }
  std::uint64_t u64(const char* what) { return read_le64(take(8, what)); }

  /// A count of records of `record_bytes` each, checked against the bytes that remain before
  /// anything is allocated for them. Returns the count and sets `records` to their bytes.
  std::size_t records(std::size_t record_bytes, const char* what, const std::uint8_t*& records) {
    const std::uint64_t n = u64(what);
    const std::size_t left = data_.size() - pos_;
    if (n > kMaxCount) {
      fail(std::string(what) + ": " + std::to_string(n) + " is more than 32-bit indices address");
    }
    if (n > left / record_bytes) {
      fail(std::string("truncated: ") + std::to_string(n) + " " + what + " of " +
           std::to_string(record_bytes) + " bytes need more than the " + std::to_string(left) +
           " bytes that remain");
    }
    const auto count = static_cast<std::size_t>(n);  // <= 2^32 - 1 and <= the bytes left
    records = take(count * record_bytes, what);
    return count;
  }

  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }

 private:
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::string name_;
};

/// Below this magnitude of every vertex coordinate, the build's volumes are finite floats: a box
/// fitted to points in [-M, M]^3 has half extents of at most sqrt(3) M and its centre is within
/// 3 M of the origin (sqrt(3) M along each axis), so a sphere about it holding the points has a
/// radius of at most (3 + sqrt(3)) M, below FLT_MAX (3.4e38) for M <= FLT_MAX / 8. Beyond it a
/// build may round a radius or an extent up to +inf (node_store.hpp's float_at_least), so a file
/// may too.
constexpr Scalar kFiniteVolumeCoordinate = 3.4e38 / 8;

}  // namespace

struct ModelFile {
  static std::vector<std::uint8_t> write(const Model& m) {
    const std::size_t payload = kSettingsBytes + 8 + m.source_.size() + 8 +
                                m.mesh_.vertices.size() * kVertexBytes + 8 +
                                m.mesh_.triangles.size() * kTriangleBytes + 8 +
                                m.nodes_.size() * kNodeBytes + 8 + m.leaf_triangles_.size() * 4;
    std::vector<std::uint8_t> out(kModelHeaderSize + payload);
    Writer w(out.data() + kModelHeaderSize);
    w.u32(m.options_.leaf_size);
    w.u32(static_cast<std::uint32_t>(m.options_.covariance));
    w.u32(m.closed_ ? 1 : 0);
    w.u32(0);
    w.f64(m.stats_.build_ms);
    w.text(m.source_);
    w.u64(m.mesh_.vertices.size());
    for (const Vec3& v : m.mesh_.vertices) w.vec3(v);
    w.u64(m.mesh_.triangles.size());
    for (const TriangleIndices& t : m.mesh_.triangles) {
      for (const std::uint32_t v : t) w.u32(v);
    }
    w.u64(m.nodes_.size());
    for (const BvhNode& node : m.nodes_) write_node(w, node);
    w.u64(m.leaf_triangles_.size());
    for (const std::uint32_t t : m.leaf_triangles_) w.u32(t);
    if (w.position() != out.data() + out.size()) {
      throw std::logic_error("model file: the payload's size differs from its computed size");
    }
    std::copy(std::begin(kModelMagic), std::end(kModelMagic), out.begin());
    Writer header(out.data() + sizeof kModelMagic);
    header.u32(kModelFormatVersion);
    header.u32(0);
    header.u64(payload);
    header.u64(model_checksum(std::span(out).subspan(kModelHeaderSize)));
    return out;
  }

  /// The payload of a model file named `name`, after the header's checks.
  static std::span<const std::uint8_t> payload(std::span<const std::uint8_t> bytes,
                                               const std::string& name) {
    if (bytes.size() < sizeof kModelMagic ||
        !std::equal(std::begin(kModelMagic), std::end(kModelMagic), bytes.begin())) {
      throw MeshError(name, "not an antcd model file (it does not start with \"ANTCDMDL\")");
    }
    if (bytes.size() < kModelHeaderSize) {
      throw MeshError(name, "truncated: " + std::to_string(bytes.size()) +
                                " bytes, the header alone has " + std::to_string(kModelHeaderSize));
    }
    const std::uint64_t version = read_le(bytes.data() + 8, 4);
    if (version != kModelFormatVersion) {
      throw MeshError(name, "model format version " + std::to_string(version) +
                                " is not supported (this build reads version " +
                                std::to_string(kModelFormatVersion) + ")");
    }
    if (read_le(bytes.data() + 12, 4) != 0) {
      throw MeshError(name, "unknown header flags (this build reads none)");
    }
    const std::uint64_t size = read_le(bytes.data() + kModelPayloadSizeOffset, 8);
    const std::size_t actual = bytes.size() - kModelHeaderSize;
    if (size != actual) {
      throw MeshError(name, std::string(size > actual ? "truncated" : "trailing bytes") +
                                ": the header announces " + std::to_string(size) +
                                " payload bytes, there are " + std::to_string(actual));
    }
    const std::span<const std::uint8_t> data = bytes.subspan(kModelHeaderSize);
    if (model_checksum(data) != read_le(bytes.data() + kModelChecksumOffset, 8)) {
      throw MeshError(name, "corrupted: the payload's checksum differs from the header's");
    }
    return data;
  }

  static Model read(std::span<const std::uint8_t> bytes, const std::string& name) {
    Reader in(payload(bytes, name), name);
    Model m;
    m.options_.leaf_size = in.u32("the leaf size");
    const std::uint32_t covariance = in.u32("the covariance method");
    const std::uint32_t closed = in.u32("the closed flag");
    const std::uint32_t reserved = in.u32("a reserved field");
    m.stats_.build_ms = f64_at(in.take(8, "the build time"));
    if (m.options_.leaf_size == 0 || covariance > 1 || closed > 1 || reserved != 0) {
      in.fail("bad settings (leaf size " + std::to_string(m.options_.leaf_size) + ", covariance " +
              std::to_string(covariance) + ", closed " + std::to_string(closed) + ")");
    }
    m.options_.covariance = static_cast<CovarianceMethod>(covariance);

    const std::uint8_t* p = nullptr;
    const std::size_t source_size = in.records(1, "source name bytes", p);
    m.source_.assign(reinterpret_cast<const char*>(p), source_size);
    // Every section's size is checked against the payload before anything is allocated.
    const std::uint8_t* pv = nullptr;
    const std::uint8_t* pt = nullptr;
    const std::uint8_t* pn = nullptr;
    const std::uint8_t* pl = nullptr;
    const std::size_t nv = in.records(kVertexBytes, "vertices", pv);
    const std::size_t nt = in.records(kTriangleBytes, "triangles", pt);
    const std::size_t nn = in.records(kNodeBytes, "nodes", pn);
    const std::size_t nl = in.records(4, "leaf triangles", pl);
    if (nn == 0) in.fail("the tree has no node");
    if (nl == 0 || nl > nt) {
      in.fail(std::to_string(nl) + " leaf triangles for " + std::to_string(nt) + " triangles");
    }
    if (in.remaining() != 0) {
      in.fail(std::to_string(in.remaining()) + " bytes after the last section");
    }

    sized(m.mesh_.vertices, nv);
    sized(m.mesh_.triangles, nt);
    blocks(nv, [&](std::size_t i) { m.mesh_.vertices[i] = vec3_at(pv + i * kVertexBytes); });
    blocks(nt, [&](std::size_t i) {
      for (std::size_t c = 0; c < 3; ++c) {
        m.mesh_.triangles[i][c] = u32_at(pt + i * kTriangleBytes + 4 * c);
      }
    });
    validate_mesh(m.mesh_, name);
    bool finite_volumes = true;
    for (const Vec3& v : m.mesh_.vertices) {
      finite_volumes = finite_volumes && v.cwiseAbs().maxCoeff() <= kFiniteVolumeCoordinate;
    }

    // The closedness recomputed (volume queries rely on it) while the tree is read and checked.
    bool is_closed_now = false;
    const auto closedness = [&] { is_closed_now = antcd::is_closed(m.mesh_); };
    std::vector<bool> seen(nt, false);  // which triangles the tree holds
    const auto tree = [&] {
      sized(m.nodes_, nn);
      blocks(nn, [&](std::size_t i) { m.nodes_[i] = read_node(pn + i * kNodeBytes); });
      sized(m.leaf_triangles_, nl);
      for (std::size_t i = 0; i < nl; ++i) {
        const std::uint32_t t = u32_at(pl + 4 * i);
        if (t >= nt || seen[t]) {
          in.fail("leaf triangle " + std::to_string(i) + " is mesh triangle " + std::to_string(t) +
                  (t >= nt ? ", out of range" : ", which occurs twice"));
        }
        seen[t] = true;
        m.leaf_triangles_[i] = t;
      }
      m.stats_.depth = check_tree(m.nodes_, nl, m.options_.leaf_size, finite_volumes, name);
    };
    if (nt >= kParallelCheck) {
      parallel::invoke(closedness, tree);
    } else {
      closedness();
      tree();
    }
    if (is_closed_now != (closed == 1)) {
      in.fail("the closed flag disagrees with the mesh's topology");
    }
    m.closed_ = is_closed_now;
    check_volumes(m, seen, name);
    m.stats_.degenerate_triangles = nt - nl;
    m.count_stats();
    return m;
  }
};

}  // namespace detail

Model::Model() : cache_(std::make_shared<detail::ModelCache>()) {}

std::vector<std::uint8_t> Model::to_bytes() const { return detail::ModelFile::write(*this); }

void Model::save(const std::filesystem::path& path) const {
  const std::vector<std::uint8_t> bytes = to_bytes();
  write_file_atomic(path,
                    std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Model Model::from_bytes(std::span<const std::uint8_t> bytes, std::string_view name) {
  return detail::ModelFile::read(bytes, std::string(name));
}

namespace {

/// A whole file's bytes, in a buffer that was not zeroed first.
struct FileBytes {
  std::unique_ptr<std::uint8_t[]> data;
  std::size_t size = 0;
};

/// The bytes of the regular file at `path`, read in one piece into a buffer that is not zeroed
/// first (read_file's string is: one more pass over a large model file, 8 % of a 5-million-
/// triangle load's instructions). No data when anything is unusual (not a regular file, cannot
/// open, empty, a size that changes while it is read): the caller reads the file with read_file
/// then, which reads it all the same or names the problem.
FileBytes read_whole(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || ec) return {};
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size == 0 ||
      size >= static_cast<std::uintmax_t>(std::numeric_limits<std::streamsize>::max())) {
    return {};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  FileBytes bytes;
  bytes.size = static_cast<std::size_t>(size);
  bytes.data.reset(new std::uint8_t[bytes.size]);  // not value-initialised: the read writes it
  detail::advise_huge_pages(bytes.data.get(), bytes.size);
  in.read(reinterpret_cast<char*>(bytes.data.get()), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size ||
      in.peek() != std::ifstream::traits_type::eof()) {
    return {};  // shorter or longer than its size said: changing
  }
  return bytes;
}

}  // namespace

Model Model::load(const std::filesystem::path& path) {
  const FileBytes whole = read_whole(path);
  std::string text;  // read_file's copy, when the fast read gave up
  std::span<const std::uint8_t> bytes(whole.data.get(), whole.size);
  if (whole.data == nullptr) {
    text = read_file(path);
    bytes = std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  }
  Model m = detail::ModelFile::read(bytes, path.string());
  m.source_ = path.string();
  return m;
}

bool is_model_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".antcd";
}

}  // namespace antcd
