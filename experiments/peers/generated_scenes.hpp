// experiments/peers/generated_scenes.hpp — the generated scenes of the protocols: a work folder,
// the dense variant of the production line, and loading a generated scene back through files
// (as any scene file is loaded).
#pragma once

#include "shared/production_line.hpp"

#include <antcd/scene.hpp>

#include <filesystem>
#include <memory>

namespace antcd::experiments::peers_bench {

/// A folder removed when it goes out of scope (only when we created it).
class WorkDir {
 public:
  /// `requested`, created; or, when empty, a fresh folder under the system temporary folder.
  explicit WorkDir(const std::filesystem::path& requested);
  ~WorkDir();
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  bool owned_ = false;
};

/// The dense variant: every translation's x (the line's direction) multiplied by `x_scale`, about
/// x = 0. Objects keep their size and motion, so neighbouring stations slide into each other.
void pack_along_line(shared::GeneratedScene& g, Scalar x_scale);

/// Writes `g` into `dir` and loads it back.
std::unique_ptr<Scene> load_generated(const shared::GeneratedScene& g,
                                      const std::filesystem::path& dir);

}  // namespace antcd::experiments::peers_bench
