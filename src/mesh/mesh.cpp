// Mesh basics: bounds, degenerate-triangle count, validation, OBJ output, merge and transform.
#include <antcd/file.hpp>
#include <antcd/geometry.hpp>
#include <antcd/mesh.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <system_error>

namespace antcd {

Aabb Mesh::bounds() const {
  // Written out by component so that a NaN coordinate is skipped (every comparison with NaN is
  // false) instead of poisoning the box; infinities do extend it. An empty mesh gives an empty box.
  Aabb box;
  for (const Vec3& v : vertices) {
    for (int k = 0; k < 3; ++k) {
      if (v[k] < box.min[k]) box.min[k] = v[k];
      if (v[k] > box.max[k]) box.max[k] = v[k];
    }
  }
  return box;
}

std::size_t Mesh::degenerate_triangle_count() const {
  std::size_t count = 0;
  const std::size_t n = vertices.size();
  for (const TriangleIndices& t : triangles) {
    // A triangle with an out-of-range index has no geometry: it is counted as degenerate rather
    // than read out of bounds (validate_mesh reports it properly).
    if (t[0] >= n || t[1] >= n || t[2] >= n ||
        geometry::is_degenerate_triangle(vertices[t[0]], vertices[t[1]], vertices[t[2]])) {
      ++count;
    }
  }
  return count;
}

void validate_mesh(const Mesh& mesh, std::string_view source) {
  if (mesh.triangles.empty()) throw MeshError(std::string(source), "contains no triangles");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw MeshError(std::string(source),
                      "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  const std::size_t n = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) {
      if (v >= n) {
        throw MeshError(std::string(source), "triangle " + std::to_string(t) +
                                                 " references vertex " + std::to_string(v) +
                                                 " but the mesh has " + std::to_string(n) +
                                                 " vertices");
      }
    }
  }
}

namespace {

void append_index(std::string& out, std::uint64_t i) {
  std::array<char, 24> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), i);
  out.append(buf.data(), ec == std::errc{} ? end : buf.data());
}

}  // namespace

void save_obj(const Mesh& mesh, const std::filesystem::path& path) {
  // An invalid mesh would be written as an OBJ that no reader accepts: refuse it up front.
  validate_mesh(mesh, path.string());
  std::string text;
  text.reserve(40 * mesh.vertices.size() + 24 * mesh.triangles.size() + 64);
  text += "# antcd mesh: ";
  append_index(text, mesh.vertices.size());
  text += " vertices, ";
  append_index(text, mesh.triangles.size());
  text += " triangles\n";
  for (const Vec3& v : mesh.vertices) {
    text += "v ";
    append_number_text(text, v.x());
    text += ' ';
    append_number_text(text, v.y());
    text += ' ';
    append_number_text(text, v.z());
    text += '\n';
  }
  for (const TriangleIndices& t : mesh.triangles) {
    text += 'f';
    for (const std::uint32_t i : t) {
      text += ' ';
      append_index(text, std::uint64_t{i} + 1);  // OBJ indices are 1-based
    }
    text += '\n';
  }
  try {
    write_file_atomic(path, text);
  } catch (const Error& e) {
    // write_file_atomic's message already names the path: keep it, say what was being saved.
    throw Error(std::string(e.what()) + " (saving OBJ)");
  }
}

Mesh merge(const std::vector<Mesh>& parts) {
  std::size_t total_vertices = 0;
  std::size_t total_triangles = 0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::size_t n = parts[p].vertices.size();
    for (std::size_t t = 0; t < parts[p].triangles.size(); ++t) {
      for (const std::uint32_t v : parts[p].triangles[t]) {
        // Offsetting an out-of-range index could silently make it point into the next part.
        if (v >= n) {
          throw antcd::ArgumentError("antcd::merge: part " + std::to_string(p) + " triangle " +
                                     std::to_string(t) + " references vertex " + std::to_string(v) +
                                     " but the part has " + std::to_string(n) + " vertices");
        }
      }
    }
    total_vertices += n;
    total_triangles += parts[p].triangles.size();
  }
  if (total_vertices > std::numeric_limits<std::uint32_t>::max()) {
    throw antcd::ArgumentError("antcd::merge: the merged mesh would have " +
                               std::to_string(total_vertices) +
                               " vertices, more than 32-bit indices can address");
  }

  Mesh out;
  out.vertices.reserve(total_vertices);
  out.triangles.reserve(total_triangles);
  for (const Mesh& part : parts) {
    const auto offset = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const TriangleIndices& t : part.triangles) {
      out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  }
  return out;
}

Mesh transformed(Mesh mesh, const Transform& t) {
  for (Vec3& v : mesh.vertices) v = t.apply(v);
  return mesh;
}

}  // namespace antcd
