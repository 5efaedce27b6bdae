// antcd_learned/meshes.hpp — the meshes the learned baselines train on and are judged on, split
// by mesh: a mesh held out of training never appears in a training scene, and cross-validation
// folds are sets of meshes (docs/learned-baselines.md).
//
// The default meshes are Debian's assimp test models (package assimp-testmodels), one file per
// distinct shape (the package holds several shapes in several formats: one format each here).
// No torch header here.
#pragma once

#include <antcd_learned/dataset.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace antcd::learned {

/// Where Debian installs assimp-testmodels.
inline constexpr const char* kAssimpModels = "/usr/share/assimp/models";

/// The catalogue's files under `root` that exist, in catalogue order (empty when the package is
/// not installed).
std::vector<std::filesystem::path> mesh_catalogue(
    const std::filesystem::path& root = kAssimpModels);
/// The default held-out meshes (those under `root` that exist): spider.obj, WusonOBJ.obj,
/// 3DSMaxExport.STL and regr01.obj, the unseen-mesh scene of docs/learned-baselines.md.
std::vector<std::filesystem::path> default_held_out(
    const std::filesystem::path& root = kAssimpModels);
/// `meshes` without those in `held_out` (the same file: equal weakly-canonical paths).
std::vector<std::filesystem::path> without(const std::vector<std::filesystem::path>& meshes,
                                           const std::vector<std::filesystem::path>& held_out);

/// `meshes` dealt into `k` folds (1 <= k <= meshes.size()) after a shuffle seeded by `seed`:
/// fold sizes differ by at most one. Throws std::invalid_argument for a bad k.
std::vector<std::vector<std::filesystem::path>> mesh_folds(
    const std::vector<std::filesystem::path>& meshes, std::size_t k, std::uint64_t seed);

/// `meshes` in the order that makes the generator's file mode (ProductionLineOptions::mesh_files,
/// objects in pairs k, k+1 cycling over the list) pair every mesh with both neighbours in
/// `meshes` (cyclically) when it places 2 * meshes.size() objects: the list itself for an odd
/// count, followed by itself rotated by one for an even count.
std::vector<std::filesystem::path> pairing_order(const std::vector<std::filesystem::path>& meshes);

/// Each neighbour pair of a mesh scene occurs this many times, with other motions.
inline constexpr std::size_t kMeshSceneRounds = 4;

/// Samples of a scene made only of `meshes` (antcd scene generate --mesh's layout: pairs, one
/// static, one passing through it; every mesh meets its neighbours in the list, and itself when
/// alone; 2 * kMeshSceneRounds * meshes.size() objects), `frames` frames, motions from `seed`,
/// labelled by the exact method.
Dataset mesh_scene_samples(const std::vector<std::filesystem::path>& meshes, std::size_t frames,
                           std::uint64_t seed, std::size_t window, Scalar delta);

/// Counts of a prediction against the exact labels.
struct Confusion {
  std::size_t tp = 0, fp = 0, fn = 0, tn = 0;
  [[nodiscard]] double recall() const;     ///< tp / (tp + fn); 1 when nothing collides
  [[nodiscard]] double precision() const;  ///< tp / (tp + fp); 1 when nothing is reported
  [[nodiscard]] double accuracy() const;
};
Confusion confusion(const std::vector<std::uint8_t>& predicted,
                    const std::vector<std::uint8_t>& labels);

/// The file names of `meshes`, joined by ", " (for logs and the model's record).
std::string mesh_names(const std::vector<std::filesystem::path>& meshes);

}  // namespace antcd::learned
