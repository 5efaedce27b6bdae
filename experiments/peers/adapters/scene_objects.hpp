// experiments/peers/adapters/scene_objects.hpp — an antcd Scene as every peer engine sees it:
// its distinct meshes (as PeerMesh), which object uses which, which objects move.
#pragma once

#include "peers/adapters/peer_mesh.hpp"

#include <antcd/scene.hpp>

#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace antcd::peers {

/// A colliding triangle pair between two objects (object i < object j; triangle indices in their
/// meshes).
struct TriContact {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  std::uint32_t ta = 0;
  std::uint32_t tb = 0;
  auto operator<=>(const TriContact&) const = default;
};

struct SceneObjects {
  const Scene* scene = nullptr;
  std::vector<const Model*> models;  ///< distinct
  std::vector<std::size_t> model_of;
  std::vector<PeerMesh> meshes;  ///< per distinct model
  std::vector<std::uint32_t> moving;
  std::size_t triangles = 0;  ///< summed over objects

  explicit SceneObjects(const Scene& s) : scene(&s) {
    std::map<const Model*, std::size_t> index;
    for (std::size_t i = 0; i < s.object_count(); ++i) {
      const Model* m = &s.model_of(i);
      auto it = index.find(m);
      if (it == index.end()) {
        it = index.emplace(m, models.size()).first;
        models.push_back(m);
        meshes.push_back(peer_mesh(m->mesh()));
      }
      model_of.push_back(it->second);
      triangles += meshes[it->second].triangles.size();
      if (s.description().objects[i].poses.size() > 1) {
        moving.push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  [[nodiscard]] const Transform& pose(std::size_t object, std::size_t frame) const {
    return scene->description().objects[object].pose(frame);
  }
};

}  // namespace antcd::peers
