// Private: ray casts against one posed model, shared by the free functions and the World.
#pragma once

#include <antcd/world.hpp>

#include <optional>
#include <vector>

namespace antcd::detail {

/// Validates a ray (throws ArgumentError naming `function` and the field); returns the
/// unit direction.
Vec3 checked_ray_direction(const Ray& ray, const char* function);

/// Appends every hit of the ray on the model (object left default), sorted by (distance,
/// triangle).
void model_ray_hits(const Model& model, const Transform& pose, const Ray& ray, const Vec3& unit_dir,
                    std::vector<RayHit>& out);

/// The nearest hit within min(ray.max_distance, s_max), ties to the smallest triangle index.
std::optional<RayHit> model_ray_first(const Model& model, const Transform& pose, const Ray& ray,
                                      const Vec3& unit_dir, Scalar s_max);

}  // namespace antcd::detail
