// experiments/peers/adapters/bullet.hpp — Bullet 3.24 as a peer: GImpact mesh shapes over the
// triangles antcd keeps, in a btCollisionWorld with a btDbvtBroadphase.
#pragma once

#include "peers/adapters/peer_mesh.hpp"
#include "peers/adapters/scene_objects.hpp"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace antcd::peers {

/// "Bullet 3.24 (double precision build)".
std::string bullet_version();

btTransform to_bullet(const Transform& t);

/// One GImpact mesh shape over a peer mesh (the arrays must outlive the shape).
struct BulletMesh {
  std::vector<int> indices;
  std::vector<btScalar> coords;
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::unique_ptr<btGImpactMeshShape> shape;

  explicit BulletMesh(const PeerMesh& m) {
    for (const auto& t : m.triangles) {
      for (int k = 0; k < 3; ++k) indices.push_back(static_cast<int>(t[k]));
    }
    for (const Vec3& v : m.vertices) {
      coords.push_back(v.x());
      coords.push_back(v.y());
      coords.push_back(v.z());
    }
    btIndexedMesh part;
    part.m_numTriangles = static_cast<int>(m.triangles.size());
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices.data());
    part.m_triangleIndexStride = 3 * static_cast<int>(sizeof(int));
    part.m_numVertices = static_cast<int>(m.vertices.size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(coords.data());
    part.m_vertexStride = 3 * static_cast<int>(sizeof(btScalar));
    part.m_indexType = PHY_INTEGER;
    part.m_vertexType = sizeof(btScalar) == sizeof(double) ? PHY_DOUBLE : PHY_FLOAT;
    array = std::make_unique<btTriangleIndexVertexArray>();
    array->addIndexedMesh(part, PHY_INTEGER);
    shape = std::make_unique<btGImpactMeshShape>(array.get());
    // GImpact grows every triangle (its box and its clipping) by the margin; 0 makes the contact
    // test the closed triangles themselves, like antcd and FCL.
    shape->setMargin(0);
    shape->updateBound();
  }
};

/// The scene's objects in Bullet; a pair collides when its manifold has a point at distance <= 0.
class BulletScene {
 public:
  explicit BulletScene(const SceneObjects& objects) : objects_(objects) {
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    for (const PeerMesh& m : objects.meshes) meshes_.push_back(std::make_unique<BulletMesh>(m));
    for (std::size_t i = 0; i < objects.model_of.size(); ++i) {
      auto o = std::make_unique<btCollisionObject>();
      o->setCollisionShape(meshes_[objects.model_of[i]]->shape.get());
      o->setWorldTransform(to_bullet(objects.pose(i, 0)));
      o->setUserIndex(static_cast<int>(i));
      bodies_.push_back(std::move(o));
    }
    world_ =
        std::make_unique<btCollisionWorld>(dispatcher_.get(), broadphase_.get(), config_.get());
    for (auto& o : bodies_) world_->addCollisionObject(o.get());
  }
  ~BulletScene() {
    for (auto& o : bodies_) world_->removeCollisionObject(o.get());
  }
  BulletScene(const BulletScene&) = delete;
  BulletScene& operator=(const BulletScene&) = delete;

  /// One frame; returns the broad phase's overlapping pairs.
  std::size_t run(std::size_t frame, ObjectPairs& pairs) {
    pairs.clear();
    for (const std::uint32_t i : objects_.moving) {
      bodies_[i]->setWorldTransform(to_bullet(objects_.pose(i, frame)));
    }
    world_->performDiscreteCollisionDetection();
    const int manifolds = dispatcher_->getNumManifolds();
    for (int k = 0; k < manifolds; ++k) {
      const btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(k);
      bool touching = false;
      for (int c = 0; c < m->getNumContacts() && !touching; ++c) {
        touching = m->getContactPoint(c).getDistance() <= 0;
      }
      if (!touching) continue;
      auto i = static_cast<std::uint32_t>(m->getBody0()->getUserIndex());
      auto j = static_cast<std::uint32_t>(m->getBody1()->getUserIndex());
      if (i > j) std::swap(i, j);
      pairs.emplace_back(i, j);
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return static_cast<std::size_t>(world_->getPairCache()->getNumOverlappingPairs());
  }

 private:
  const SceneObjects& objects_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::vector<std::unique_ptr<BulletMesh>> meshes_;
  std::vector<std::unique_ptr<btCollisionObject>> bodies_;
  std::unique_ptr<btCollisionWorld> world_;
};

}  // namespace antcd::peers
