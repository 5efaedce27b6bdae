#include "peers/adapters/bullet.hpp"

namespace antcd::peers {

std::string bullet_version() {
  return "Bullet " + std::to_string(BT_BULLET_VERSION / 100) + "." +
         std::to_string(BT_BULLET_VERSION % 100) +
         (sizeof(btScalar) == sizeof(double) ? " (double precision build)"
                                             : " (single precision build)");
}

btTransform to_bullet(const Transform& t) {
  const Mat3& r = t.rotation;
  const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1),
                          r(2, 2));
  return btTransform(basis, btVector3(t.translation.x(), t.translation.y(), t.translation.z()));
}

}  // namespace antcd::peers
