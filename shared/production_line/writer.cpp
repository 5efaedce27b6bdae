// Writing a generated scene: the mesh files, then scene.json, each atomically.
#include "shared/production_line.hpp"

#include <antcd/error.hpp>
#include <antcd/file.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace antcd::shared {

std::filesystem::path write_scene(const GeneratedScene& generated,
                                  const std::filesystem::path& dir) {
  // Check every name before writing anything.
  const auto check_name = [](const std::string& name, const char* what) {
    const std::filesystem::path rel = std::filesystem::path(name).lexically_normal();
    if (name.empty() || rel.is_absolute() || rel.has_root_path() || rel.empty() ||
        *rel.begin() == "..") {
      throw antcd::ArgumentError(std::string("write_scene: ") + what + " file name '" + name +
                                 "' must be relative and stay inside the scene folder");
    }
  };
  for (const SceneObject& o : generated.scene.objects) {
    if (!o.vertex_frames) continue;
    check_name(o.vertex_file_text, "vertex-frames");
  }
  for (const auto& [name, mesh] : generated.meshes) check_name(name, "mesh");
  create_folders(dir);
  for (const auto& [name, mesh] : generated.meshes) {
    const std::filesystem::path path = dir / std::filesystem::path(name);
    create_folders(path.parent_path());
    save_obj(mesh, path);
  }
  for (const SceneObject& o : generated.scene.objects) {
    if (!o.vertex_frames) continue;
    const std::filesystem::path path = dir / std::filesystem::path(o.vertex_file_text);
    create_folders(path.parent_path());
    save_vertex_frames(*o.vertex_frames, path);
  }
  const std::filesystem::path scene_path = dir / "scene.json";
  save_scene(generated.scene, scene_path);
  return scene_path;
}

}  // namespace antcd::shared
