// The meshes of the learned baselines, split by mesh (see meshes.hpp).
#include <antcd/rng.hpp>
#include <antcd_learned/meshes.hpp>

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "shared/production_line.hpp"

namespace antcd::learned {
namespace {

namespace fs = std::filesystem;

// One file per distinct shape of assimp-testmodels (Wuson, the spider, the duck, ... exist in
// several formats there: each is listed once; files assimp cannot read whole, like PLY/pond.0.ply,
// and meshes over 10 000 triangles are left out). The first four are the default held-out set.
constexpr const char* kCatalogue[] = {
    "OBJ/spider.obj",
    "OBJ/WusonOBJ.obj",
    "STL/3DSMaxExport.STL",
    "OBJ/regr01.obj",
    "STL/sphereWithHole.stl",
    "Collada/duck_triangulate.dae",
    "Collada/teapots.DAE",
    "BLEND/Suzanne_248.blend",
    "BLEND/TorusLightsCams_250_compressed.blend",
    "MD2/faerie.md2",
    "MD2/sydney.md2",
    "X/BCN_Epileptic.X",
    "FBX/huesitos.fbx",
    "Collada/Cinema4D.dae",
    "OBJ/concave_polygon.obj",
    "Collada/earthCylindrical.DAE",
    "BLEND/HUMAN.blend",
    "FBX/animation_with_skeleton.fbx",
    "LWO/LWO2/ModoExport_vertNormals.lwo",
};
constexpr std::size_t kHeldOut = 4;

fs::path canonical_or_same(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? p : c;
}

}  // namespace

std::vector<fs::path> mesh_catalogue(const fs::path& root) {
  std::vector<fs::path> out;
  for (const char* f : kCatalogue) {
    if (fs::exists(root / f)) out.push_back(root / f);
  }
  return out;
}

std::vector<fs::path> default_held_out(const fs::path& root) {
  std::vector<fs::path> out;
  for (std::size_t k = 0; k < kHeldOut; ++k) {
    if (fs::exists(root / kCatalogue[k])) out.push_back(root / kCatalogue[k]);
  }
  return out;
}

std::vector<fs::path> without(const std::vector<fs::path>& meshes,
                              const std::vector<fs::path>& held_out) {
  std::vector<fs::path> out_set;
  std::vector<fs::path> gone;
  for (const fs::path& h : held_out) gone.push_back(canonical_or_same(h));
  for (const fs::path& m : meshes) {
    if (std::find(gone.begin(), gone.end(), canonical_or_same(m)) == gone.end()) {
      out_set.push_back(m);
    }
  }
  return out_set;
}

std::vector<std::vector<fs::path>> mesh_folds(const std::vector<fs::path>& meshes, std::size_t k,
                                              std::uint64_t seed) {
  if (k < 1 || k > meshes.size()) {
    throw std::invalid_argument("--folds must be between 1 and the number of training meshes (" +
                                std::to_string(meshes.size()) + ")");
  }
  std::vector<fs::path> order = meshes;
  std::uint64_t state = mix_seed(seed ^ 0x464F4C4453ULL);
  for (std::size_t i = order.size(); i > 1; --i) {
    state = mix_seed(state);
    std::swap(order[i - 1], order[state % i]);
  }
  std::vector<std::vector<fs::path>> folds(k);
  for (std::size_t i = 0; i < order.size(); ++i) folds[i % k].push_back(order[i]);
  return folds;
}

std::vector<fs::path> pairing_order(const std::vector<fs::path>& meshes) {
  std::vector<fs::path> out = meshes;
  if (meshes.size() % 2 == 0 && !meshes.empty()) {
    out.insert(out.end(), meshes.begin() + 1, meshes.end());
    out.push_back(meshes.front());
  }
  return out;
}

Dataset mesh_scene_samples(const std::vector<fs::path>& meshes, std::size_t frames,
                           std::uint64_t seed, std::size_t window, Scalar delta) {
  if (meshes.empty()) throw std::invalid_argument("a mesh scene needs at least one mesh");
  shared::ProductionLineOptions line;
  line.mesh_files = pairing_order(meshes);
  line.objects = 2 * kMeshSceneRounds * meshes.size();
  line.frames = frames;
  line.seed = seed;
  const Scene scene = shared::make_scene(shared::generate_production_line(line));
  return scene_samples(scene, 0, frames, window, delta);
}

double Confusion::recall() const {
  return tp + fn == 0 ? 1.0 : static_cast<double>(tp) / static_cast<double>(tp + fn);
}
double Confusion::precision() const {
  return tp + fp == 0 ? 1.0 : static_cast<double>(tp) / static_cast<double>(tp + fp);
}
double Confusion::accuracy() const {
  const std::size_t all = tp + fp + fn + tn;
  return all == 0 ? 1.0 : static_cast<double>(tp + tn) / static_cast<double>(all);
}

Confusion confusion(const std::vector<std::uint8_t>& predicted,
                    const std::vector<std::uint8_t>& labels) {
  if (predicted.size() != labels.size()) {
    throw std::invalid_argument("predictions and labels differ in number");
  }
  Confusion c;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const bool p = predicted[i] != 0;
    const bool y = labels[i] != 0;
    if (p && y) ++c.tp;
    if (p && !y) ++c.fp;
    if (!p && y) ++c.fn;
    if (!p && !y) ++c.tn;
  }
  return c;
}

std::string mesh_names(const std::vector<fs::path>& meshes) {
  std::string s;
  for (const fs::path& m : meshes) {
    if (!s.empty()) s += ", ";
    s += m.filename().string();
  }
  return s;
}

}  // namespace antcd::learned
