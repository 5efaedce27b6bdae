#include "peers/generated_scenes.hpp"

#include <antcd/file.hpp>

#include <unistd.h>

#include <chrono>
#include <string>
#include <system_error>

namespace antcd::experiments::peers_bench {

namespace fs = std::filesystem;

WorkDir::WorkDir(const fs::path& requested) {
  if (!requested.empty()) {
    path_ = requested;
    create_folders(path_);
    return;
  }
  path_ = fs::temp_directory_path() /
          ("antcd-peers-" + std::to_string(::getpid()) + "-" +
           std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  create_folders(path_);
  owned_ = true;
}

WorkDir::~WorkDir() {
  if (owned_) {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
}

void pack_along_line(shared::GeneratedScene& g, Scalar x_scale) {
  for (SceneObject& o : g.scene.objects) {
    for (Transform& t : o.poses) t.translation.x() *= x_scale;
  }
}

std::unique_ptr<Scene> load_generated(const shared::GeneratedScene& g, const fs::path& dir) {
  const fs::path file = shared::write_scene(g, dir);
  return std::make_unique<Scene>(load_scene(file));
}

}  // namespace antcd::experiments::peers_bench
