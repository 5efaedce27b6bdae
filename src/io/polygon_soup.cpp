// From a polygon soup read in double precision to a Mesh: format dispatch, triangulation, the
// used points in order of first use, identical positions joined.
#include <antcd/file.hpp>

#include "io/polygon_soup.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace antcd::detail {
namespace {

/// A corner list is a polygon of the soup; `tri` receives its triangles as corner positions
/// (0 .. n-1) in the polygon's own winding.
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

Vec3 newell_normal(const std::vector<Vec3>& p) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    n.x() += (p[j].y() - p[i].y()) * (p[j].z() + p[i].z());
    n.y() += (p[j].z() - p[i].z()) * (p[j].x() + p[i].x());
    n.z() += (p[j].x() - p[i].x()) * (p[j].y() + p[i].y());
  }
  return n;
}

/// Polygons above this many corners are split as a fan from their first corner: ear clipping is
/// quadratic to cubic in the corner count, and such polygons are rare in mesh files.
constexpr std::size_t kEarClippingLimit = 256;

void triangulate(const std::vector<Vec3>& p, Triangles& tri) {
  const std::size_t n = p.size();
  tri.clear();
  if (n == 3) {
    tri.push_back({0, 1, 2});
    return;
  }
  const Vec3 normal = newell_normal(p);
  auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
    return (p[b] - p[a]).cross(p[c] - p[b]).dot(normal);
  };
  if (n == 4) {
    // The diagonal must run through a reflex corner; for a convex quad, corners 0 and 2.
    if (turn(0, 1, 2) < 0 || turn(2, 3, 0) < 0) {
      tri.push_back({0, 1, 3});
      tri.push_back({1, 2, 3});
    } else {
      tri.push_back({0, 1, 2});
      tri.push_back({0, 2, 3});
    }
    return;
  }
  if (n > kEarClippingLimit) {
    for (std::uint32_t i = 1; i + 1 < n; ++i) tri.push_back({0, i, i + 1});
    return;
  }
  // Ear clipping in the plane perpendicular to the normal's largest component, oriented so
  // that the polygon turns counter-clockwise there.
  int drop = 0;
  normal.cwiseAbs().maxCoeff(&drop);
  const int u = (drop + 1) % 3;
  const int v = (drop + 2) % 3;
  const Scalar sign = normal[drop] < 0 ? -1 : 1;
  auto cross2 = [&](std::size_t a, std::size_t b, std::size_t c) {
    return sign *
           ((p[b][u] - p[a][u]) * (p[c][v] - p[a][v]) - (p[b][v] - p[a][v]) * (p[c][u] - p[a][u]));
  };
  std::vector<std::uint32_t> ring(n);
  for (std::uint32_t i = 0; i < n; ++i) ring[i] = i;
  std::size_t i = 0;
  std::size_t failures = 0;
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    const std::uint32_t a = ring[(i + m - 1) % m];
    const std::uint32_t b = ring[i % m];
    const std::uint32_t c = ring[(i + 1) % m];
    bool ear = cross2(a, b, c) > 0;
    for (std::size_t k = 0; ear && k < m; ++k) {
      const std::uint32_t q = ring[k];
      if (q == a || q == b || q == c) continue;
      ear = !(cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0);
    }
    // After a full round without an ear (degenerate or self-intersecting polygon) the corner is
    // clipped anyway, so the loop always ends with n - 2 triangles.
    if (ear || failures >= m) {
      tri.push_back({a, b, c});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i % m));
      i = (i % m) % ring.size();
      failures = 0;
    } else {
      i = (i + 1) % m;
      ++failures;
    }
  }
  tri.push_back({ring[0], ring[1], ring[2]});
}

struct PositionHash {
  std::size_t operator()(const Vec3& p) const { return position_hash(p); }
};

}  // namespace

std::size_t position_hash(const Vec3& p) {
  // Each coordinate's bits folded in through MurmurHash3's 64-bit finaliser: round coordinates
  // (integers, halves) differ only in their high bits, and every output bit must depend on them.
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (int k = 0; k < 3; ++k) {
    const double x = p[k] == 0 ? 0.0 : p[k];  // -0 and +0 are the same position
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof bits);
    h ^= bits;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDULL;
    h ^= h >> 33;
    h *= 0xC4CEB9FE1A85EC53ULL;
    h ^= h >> 33;
  }
  return static_cast<std::size_t>(h);
}

std::errc parse_coordinate(std::string_view token, double& value) {
  const char* first = token.data();
  const char* const last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range || (ec == std::errc{} && !std::isfinite(value))) {
    return std::errc::result_out_of_range;
  }
  if (ec != std::errc{} || ptr != last) return std::errc::invalid_argument;
  return {};
}

std::string read_whole_file(const std::filesystem::path& path, const std::string& source) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(source, "cannot be opened: " + printable_line(std::strerror(errno)));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw MeshError(source, "cannot be read");
  return std::move(buffer).str();
}

TextFormat text_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(c | 0x20);
  return ext == ".obj" ? TextFormat::Obj : TextFormat::None;
}

void join_identical_positions(Mesh& mesh) {
  std::unordered_map<Vec3, std::uint32_t, PositionHash> first;
  first.reserve(mesh.vertices.size());
  std::vector<std::uint32_t> remap(mesh.vertices.size());
  std::vector<Vec3> unique;
  unique.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto [it, inserted] =
        first.try_emplace(mesh.vertices[i], static_cast<std::uint32_t>(unique.size()));
    if (inserted) unique.push_back(mesh.vertices[i]);
    remap[i] = it->second;
  }
  if (unique.size() == mesh.vertices.size()) return;
  for (TriangleIndices& t : mesh.triangles) {
    for (std::uint32_t& v : t) v = remap[v];
  }
  mesh.vertices = std::move(unique);
}

Mesh soup_to_mesh(const PolygonSoup& soup, const std::string& source) {
  constexpr std::uint32_t unset = std::numeric_limits<std::uint32_t>::max();
  const auto point_count = static_cast<std::int64_t>(soup.points.size());
  if (soup.points.size() >= unset) {
    throw MeshError(source, "has more vertices than 32-bit indices can address");
  }
  std::size_t triangle_count = 0;
  for (const std::uint32_t n : soup.corner_counts) triangle_count += n >= 3 ? n - 2 : 0;
  if (triangle_count == 0) throw MeshError(source, "contains no triangles");

  Mesh mesh;
  mesh.triangles.reserve(triangle_count);
  std::vector<std::uint32_t> remap(soup.points.size(), unset);
  std::vector<Vec3> corners;
  std::vector<std::uint32_t> ids;
  Triangles tri;
  std::size_t offset = 0;
  for (std::size_t f = 0; f < soup.corner_counts.size(); ++f) {
    const std::uint32_t n = soup.corner_counts[f];
    const std::size_t begin = offset;
    offset += n;
    if (n < 3) continue;  // points and lines are not collision geometry
    corners.clear();
    ids.clear();
    for (std::size_t k = begin; k < begin + n; ++k) {
      const std::int64_t index = soup.corners[k];
      if (index < 0 || index >= point_count) {
        const std::string face = "face " + std::to_string(f + soup.index_base);
        if (index < 0) throw MeshError(source, face + " references a vertex before the first one");
        throw MeshError(source, face + " references vertex " +
                                    std::to_string(index + soup.index_base) + " but the file has " +
                                    std::to_string(point_count) + " vertices (counted from " +
                                    std::to_string(soup.index_base) + ")");
      }
      const auto v = static_cast<std::size_t>(index);
      if (remap[v] == unset) {
        remap[v] = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.push_back(soup.points[v]);
      }
      ids.push_back(remap[v]);
      corners.push_back(soup.points[v]);
    }
    triangulate(corners, tri);
    for (const auto& t : tri) mesh.triangles.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
  }
  join_identical_positions(mesh);
  validate_mesh(mesh, source);
  return mesh;
}

}  // namespace antcd::detail
