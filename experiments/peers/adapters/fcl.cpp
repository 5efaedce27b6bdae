#include "peers/adapters/fcl.hpp"

#include <fcl/config.h>

namespace antcd::peers {

std::string fcl_version() { return std::string("FCL ") + FCL_VERSION; }

FclInput fcl_input(const PeerMesh& m) {
  FclInput in;
  in.vertices.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices) in.vertices.emplace_back(v.x(), v.y(), v.z());
  in.triangles.reserve(m.triangles.size());
  for (const auto& t : m.triangles) in.triangles.emplace_back(t[0], t[1], t[2]);
  return in;
}

fcl::Transform3d to_fcl(const Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

}  // namespace antcd::peers
