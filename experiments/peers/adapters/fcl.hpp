// experiments/peers/adapters/fcl.hpp — FCL 0.7 as a peer: models built from the same triangles
// antcd keeps, poses, a memory estimate, and a scene behind FCL's dynamic AABB tree manager.
#pragma once

#include "peers/adapters/peer_mesh.hpp"
#include "peers/adapters/scene_objects.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace antcd::peers {

/// num_max_contacts of an all-contacts query: every colliding triangle pair.
inline constexpr std::size_t kFclAllContacts = 10'000'000;

/// "FCL 0.7.0".
std::string fcl_version();

/// A mesh in FCL's input form: the peer mesh's vertices and triangles, in order (so FCL's
/// primitive ids index PeerMesh::triangles).
struct FclInput {
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
};

FclInput fcl_input(const PeerMesh& m);

/// An FCL hierarchy (default splitter) over `in`: what is timed as FCL's build.
template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> build_fcl(const FclInput& in) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(static_cast<int>(in.triangles.size()), static_cast<int>(in.vertices.size()));
  model->addSubModel(in.vertices, in.triangles);
  model->endModel();
  return model;
}

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> build_fcl(const PeerMesh& m) {
  return build_fcl<BV>(fcl_input(m));
}

/// Memory estimate: the BV node array, the vertices and the triangles (the permutation array
/// primitive_indices, one int per triangle, is left out).
template <class BV>
double fcl_bytes(const fcl::BVHModel<BV>& model) {
  return static_cast<double>(model.getNumBVs()) * sizeof(fcl::BVNode<BV>) +
         static_cast<double>(model.num_vertices) * sizeof(fcl::Vector3d) +
         static_cast<double>(model.num_tris) * sizeof(fcl::Triangle);
}

fcl::Transform3d to_fcl(const Transform& t);

namespace fcl_detail {

struct FclCallbackData {
  const SceneObjects* objects = nullptr;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  ObjectPairs* pairs = nullptr;
  std::vector<TriContact>* contacts = nullptr;
  std::size_t candidates = 0;
};

inline std::uint32_t object_index(const fcl::CollisionObjectd* o) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o->getUserData()));
}

inline bool fcl_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto& d = *static_cast<FclCallbackData*>(data);
  ++d.candidates;
  d.result.clear();
  fcl::collide(o1, o2, d.request, d.result);
  if (!d.result.isCollision()) return false;
  std::uint32_t i = object_index(o1);
  std::uint32_t j = object_index(o2);
  const bool swapped = i > j;
  if (swapped) std::swap(i, j);
  d.pairs->emplace_back(i, j);
  if (d.contacts != nullptr) {
    const auto& map_i = d.objects->meshes[d.objects->model_of[i]].mesh_index;
    const auto& map_j = d.objects->meshes[d.objects->model_of[j]].mesh_index;
    for (std::size_t k = 0; k < d.result.numContacts(); ++k) {
      const auto& c = d.result.getContact(k);
      auto b1 = static_cast<std::uint32_t>(c.b1);
      auto b2 = static_cast<std::uint32_t>(c.b2);
      if (swapped) std::swap(b1, b2);
      d.contacts->push_back({i, j, map_i[b1], map_j[b2]});
    }
  }
  return false;  // never stop: every pair is wanted
}

}  // namespace fcl_detail

/// The scene's objects in FCL: one BVHModel<BV> per distinct mesh, one CollisionObject per object,
/// all behind a DynamicAABBTreeCollisionManager.
template <class BV>
class FclScene {
 public:
  explicit FclScene(const SceneObjects& objects) : objects_(objects) {
    for (const PeerMesh& m : objects.meshes) models_.push_back(build_fcl<BV>(m));
    std::vector<fcl::CollisionObjectd*> all;
    for (std::size_t i = 0; i < objects.model_of.size(); ++i) {
      auto o = std::make_unique<fcl::CollisionObjectd>(models_[objects.model_of[i]],
                                                       to_fcl(objects.pose(i, 0)));
      o->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
      o->computeAABB();
      all.push_back(o.get());
      objects_list_.push_back(std::move(o));
    }
    for (const std::uint32_t i : objects.moving) moving_.push_back(objects_list_[i].get());
    manager_.registerObjects(all);
    manager_.setup();
  }

  /// One frame: moves the moving objects, refits the broad phase, tests every overlapping pair.
  /// Returns the broad-phase pairs tested.
  std::size_t run(std::size_t frame, bool all_contacts, ObjectPairs& pairs,
                  std::vector<TriContact>* contacts) {
    pairs.clear();
    if (contacts != nullptr) contacts->clear();
    for (const std::uint32_t i : objects_.moving) {
      objects_list_[i]->setTransform(to_fcl(objects_.pose(i, frame)));
      objects_list_[i]->computeAABB();
    }
    manager_.update(moving_);
    fcl_detail::FclCallbackData data;
    data.objects = &objects_;
    data.request = all_contacts ? fcl::CollisionRequestd(kFclAllContacts, false)
                                : fcl::CollisionRequestd(1, false);
    data.pairs = &pairs;
    data.contacts = contacts;
    manager_.collide(&data, fcl_detail::fcl_callback);
    std::sort(pairs.begin(), pairs.end());
    if (contacts != nullptr) std::sort(contacts->begin(), contacts->end());
    return data.candidates;
  }

 private:
  const SceneObjects& objects_;
  std::vector<std::shared_ptr<fcl::BVHModel<BV>>> models_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_list_;
  std::vector<fcl::CollisionObjectd*> moving_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
};

}  // namespace antcd::peers
