// The generator's file mode: given meshes placed in pairs, one static and one passing through it.
#include <antcd/load.hpp>

#include "shared/production_line/modes.hpp"

#include "shared/production_line/poses.hpp"
#include "shared/rng.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared::line {
namespace {

using Rng = SplitMix64;

std::string sanitized_stem(const std::filesystem::path& path) {
  std::string stem = path.stem().string();
  for (char& c : stem) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) c = '_';
  }
  return stem.empty() ? std::string("mesh") : stem;
}

std::string padded(std::size_t value, std::size_t width) {
  std::string s = std::to_string(value);
  if (s.size() < width) s.insert(0, width - s.size(), '0');
  return s;
}

}  // namespace

/// Objects in pairs along x: one static, one that spins and moves from well apart (bounding
/// spheres disjoint) to the other's centre and back.
GeneratedScene generate_from_files(const ProductionLineOptions& options) {
  GeneratedScene out;
  out.scene.frames = options.frames;
  // Files beyond the object count would not be used: they are not loaded.
  const std::size_t files = std::min(options.mesh_files.size(), options.objects);
  const std::size_t width = std::max<std::size_t>(2, std::to_string(options.objects - 1).size());
  std::vector<std::string> names;
  std::vector<std::string> stems;
  std::vector<Scalar> radius;
  for (std::size_t k = 0; k < files; ++k) {
    Mesh mesh = load_mesh(options.mesh_files[k]);
    const Aabb box = mesh.bounds();
    const Vec3 centre = (box.min + box.max) / 2;
    for (Vec3& v : mesh.vertices) v -= centre;
    const Scalar r = box.extent().norm() / 2;
    radius.push_back(r > 0 ? r : 1);
    stems.push_back(sanitized_stem(options.mesh_files[k]));
    names.push_back("meshes/" + padded(k, 2) + "_" + stems.back() + ".obj");
    out.meshes.emplace_back(names.back(), std::move(mesh));
  }
  const Scalar largest = *std::max_element(radius.begin(), radius.end());
  const Scalar pitch = 6 * largest;
  for (std::size_t i = 0; i < options.objects; ++i) {
    Rng rng(options.seed, i);
    const std::size_t k = i % files;
    SceneObject o;
    o.name = stems[k] + "_" + padded(i, width);
    o.mesh_text = names[k];
    o.mesh = names[k];
    const Vec3 home(pitch * static_cast<Scalar>(i / 2), 0, 0);
    const Vec3 tilt(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Mat3 start = rot(tilt.norm() > 1e-3 ? tilt : Vec3::UnitZ(), rng.uniform(0, 2 * kPi));
    const bool mover = i % 2 == 1;
    if (!mover) {
      o.poses.push_back(pose(start, home));
    } else {
      const Scalar far = 1.05 * (radius[k] + radius[(i - 1) % files]);
      const Scalar period = std::round(rng.uniform(60, 120));
      const Scalar phase = rng.uniform(0, 1);
      const Scalar spin = rng.uniform(0.01, 0.05);
      const Vec3 axis(rng.uniform(-1, 1), rng.uniform(-1, 1), 1);
      o.poses.reserve(options.frames);
      for (std::size_t f = 0; f < options.frames; ++f) {
        const Scalar u = phase + static_cast<Scalar>(f) / period;
        const Scalar d = far * (0.5 + 0.5 * std::cos(2 * kPi * u));
        const Scalar angle = std::fmod(spin * static_cast<Scalar>(f), 2 * kPi);
        o.poses.push_back(pose(rot(axis, angle) * start, home + Vec3(d, 0, 0)));
      }
    }
    out.scene.objects.push_back(std::move(o));
  }
  return out;
}

}  // namespace antcd::shared::line
