#include "support/test_support.hpp"

#include <antcd/geometry.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace antcd::test {

std::filesystem::path assimp_model(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(ANTCD_ASSIMP_MODELS) / relative;
  if (!std::filesystem::exists(path)) {
    ADD_FAILURE() << "missing test model " << path
                  << " (install the Debian package assimp-testmodels)";
  }
  return path;
}

std::filesystem::path fresh_temp_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(ANTCD_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

Mesh unit_size(Mesh m) {
  const Aabb box = m.bounds();
  const Vec3 centre = 0.5 * (box.min + box.max);
  const Scalar scale = 1 / box.extent().maxCoeff();
  for (Vec3& v : m.vertices) v = (v - centre) * scale;
  return m;
}

Transform random_pose(std::mt19937_64& rng, Scalar extent) {
  std::normal_distribution<Scalar> gauss(0.0, 1.0);
  std::uniform_real_distribution<Scalar> uni(-extent, extent);
  Quat q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  Transform t;
  t.rotation = q.normalized().toRotationMatrix();
  t.translation = Vec3(uni(rng), uni(rng), uni(rng));
  return t;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> brute_force_pairs(
    const Mesh& a, const Transform& pa, const Mesh& b, const Transform& pb, Scalar delta) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  std::vector<Vec3> va, vb;
  for (const Vec3& v : a.vertices) va.push_back(pa.apply(v));
  for (const Vec3& v : b.vertices) vb.push_back(pb.apply(v));
  for (std::uint32_t i = 0; i < a.triangles.size(); ++i) {
    const auto& ta = a.triangles[i];
    if (geometry::is_degenerate_triangle(a.vertices[ta[0]], a.vertices[ta[1]], a.vertices[ta[2]]))
      continue;
    for (std::uint32_t j = 0; j < b.triangles.size(); ++j) {
      const auto& tb = b.triangles[j];
      if (geometry::is_degenerate_triangle(b.vertices[tb[0]], b.vertices[tb[1]], b.vertices[tb[2]]))
        continue;
      if (geometry::triangles_within(va[ta[0]], va[ta[1]], va[ta[2]], vb[tb[0]], vb[tb[1]],
                                     vb[tb[2]], delta)) {
        out.emplace_back(i, j);
      }
    }
  }
  return out;
}

}  // namespace antcd::test
