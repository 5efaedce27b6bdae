// The README's C++ example: two meshes, a collision query with every contact, a distance query.
// Built and run by ctest (example_cpp_quickstart); links the core alone (antcd::antcd).
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/mesh.hpp>

#include <cstdio>

int main() {
  const antcd::Model torus(antcd::make_torus(1.0, 0.25));  // builds the Sphere-OBB hierarchy once
  const antcd::Model ball(antcd::make_sphere(0.5));
  // A pose: rotation (axis, angle) then translation; {} is the identity.
  const antcd::Transform on_ring = antcd::Transform::from_axis_angle({0, 0, 1}, 0.3, {1, 0, 0});

  const antcd::CollisionResult hit =
      antcd::collide(torus, {}, ball, on_ring, {.delta = 0.0, .all_contacts = true});
  std::printf("colliding: %s, %zu triangle pairs\n", hit.colliding ? "yes" : "no",
              hit.contacts.size());

  antcd::Transform apart;
  apart.translation = antcd::Vec3(3, 0, 0);
  const antcd::DistanceResult d = antcd::distance(torus, {}, ball, apart);
  std::printf("distance at x = 3: %.6f (torus triangle %u, ball triangle %u)\n", d.distance,
              d.triangle_a, d.triangle_b);
  return hit.colliding && d.distance > 1.0 ? 0 : 1;
}
