#include "support/mesh_files.hpp"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace antcd::test {

void append_f32(std::string& out, float x) {
  char bytes[4];
  std::memcpy(bytes, &x, 4);
  out.append(bytes, 4);
}

void append_u32(std::string& out, std::uint32_t x) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((x >> (8 * k)) & 0xFF));
}

namespace {

Vec3 facet_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const Scalar length = n.norm();
  return length > 0 ? Vec3(n / length) : Vec3(Vec3::Zero());
}

}  // namespace

void append_stl_facet(std::string& out, const std::array<Vec3, 3>& corners) {
  const Vec3 n = facet_normal(corners[0], corners[1], corners[2]);
  for (int k = 0; k < 3; ++k) append_f32(out, static_cast<float>(n[k]));
  for (const Vec3& c : corners) {
    for (int k = 0; k < 3; ++k) append_f32(out, static_cast<float>(c[k]));
  }
  out.append(2, '\0');
}

std::string binary_stl(const Mesh& m, std::string header, std::int64_t count) {
  header.resize(80, '\0');
  std::string out = header;
  append_u32(out, static_cast<std::uint32_t>(count < 0 ? std::int64_t(m.triangles.size()) : count));
  for (const auto& t : m.triangles) {
    append_stl_facet(out, {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  }
  return out;
}

std::string ascii_stl(const Mesh& m) {
  std::ostringstream out;
  out.precision(9);
  out << "solid cube\n";
  for (const auto& t : m.triangles) {
    const Vec3 n = facet_normal(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]);
    out << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n    outer loop\n";
    for (const auto i : t) {
      out << "      vertex " << m.vertices[i].x() << ' ' << m.vertices[i].y() << ' '
          << m.vertices[i].z() << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid cube\n";
  return out.str();
}

Mesh parse_obj_reference(const std::filesystem::path& path) {
  std::ifstream in(path);
  Mesh m;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      std::string x, y, z;
      fields >> x >> y >> z;
      m.vertices.emplace_back(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                              std::strtod(z.c_str(), nullptr));
    } else if (tag == "f") {
      std::vector<std::uint32_t> f;
      std::string corner;
      while (fields >> corner) f.push_back(static_cast<std::uint32_t>(std::stoul(corner)) - 1);
      if (f.size() != 3)
        throw std::runtime_error(path.string() + ": a face that is not a triangle");
      m.triangles.push_back({f[0], f[1], f[2]});
    }
  }
  return m;
}

}  // namespace antcd::test
