// The generator's entry points: option checks, the choice of mode, summary numbers.
#include "shared/production_line.hpp"

#include "shared/production_line/modes.hpp"

#include <antcd/error.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace antcd::shared {

void validate_options(const ProductionLineOptions& options) {
  if (options.objects < kMinObjects || options.objects > kMaxObjects) {
    throw antcd::ArgumentError("--objects must be between " + std::to_string(kMinObjects) +
                               " and " + std::to_string(kMaxObjects) + ", got " +
                               std::to_string(options.objects));
  }
  if (options.vertices < kMinVertices || options.vertices > kMaxVertices) {
    throw antcd::ArgumentError(
        "--vertices must be between " + std::to_string(kMinVertices) +
        " (a box's 8 corners: the coarsest closed solid the equipment is built from) and " +
        std::to_string(kMaxVertices) + ", got " + std::to_string(options.vertices));
  }
  if (options.frames < 1 || options.frames > kMaxFrames) {
    throw antcd::ArgumentError("--frames must be between 1 and " + std::to_string(kMaxFrames) +
                               ", got " + std::to_string(options.frames));
  }
  if (options.objects * options.frames > kMaxPoses) {
    throw antcd::ArgumentError("--objects × --frames must be at most " + std::to_string(kMaxPoses) +
                               " (one pose per moving object and " +
                               "frame is kept in memory), got " +
                               std::to_string(options.objects * options.frames));
  }
  if (options.flexible && !options.mesh_files.empty()) {
    throw antcd::ArgumentError(
        "--flexible makes the generated veneer sheets flexible: not with --mesh");
  }
  if (options.flexible && options.vertices / 2 * options.frames > kMaxSheetPositions) {
    throw antcd::ArgumentError(
        "--flexible: --vertices / 2 × --frames must be at most " +
        std::to_string(kMaxSheetPositions) +
        " (a sheet's positions of every frame are kept in memory and written), got " +
        std::to_string(options.vertices / 2 * options.frames));
  }
  for (const std::filesystem::path& p : options.mesh_files) {
    if (p.empty()) throw antcd::ArgumentError("--mesh: an empty file name was given");
  }
}

GeneratedScene generate_production_line(const ProductionLineOptions& options) {
  validate_options(options);
  return options.mesh_files.empty() ? line::generate_equipment(options)
                                    : line::generate_from_files(options);
}

SceneStats scene_stats(const GeneratedScene& generated) {
  SceneStats s;
  s.objects = generated.scene.objects.size();
  s.meshes = generated.meshes.size();
  std::map<std::string, std::size_t> vertices_of;
  s.min_vertices = std::numeric_limits<std::size_t>::max();
  for (const auto& [name, mesh] : generated.meshes) {
    vertices_of[name] = mesh.vertices.size();
    s.min_vertices = std::min(s.min_vertices, mesh.vertices.size());
    s.max_vertices = std::max(s.max_vertices, mesh.vertices.size());
  }
  if (generated.meshes.empty()) s.min_vertices = 0;
  double sum = 0;
  for (const SceneObject& o : generated.scene.objects) {
    if (generated.scene.frames > 1 && o.poses.size() == generated.scene.frames) ++s.moving_objects;
    const auto it = vertices_of.find(o.mesh_text);
    if (it != vertices_of.end()) sum += static_cast<double>(it->second);
  }
  if (s.objects > 0) s.average_vertices = sum / static_cast<double>(s.objects);
  return s;
}

Scene make_scene(const GeneratedScene& generated, const BuildOptions& options) {
  return Scene(
      generated.scene,
      [&generated](const SceneObject& o) {
        const std::string name = o.mesh.lexically_normal().generic_string();
        for (const auto& [file, mesh] : generated.meshes) {
          if (std::filesystem::path(file).lexically_normal().generic_string() == name) return mesh;
        }
        throw MeshError(name, "not among the generated meshes");
      },
      options);
}

}  // namespace antcd::shared
