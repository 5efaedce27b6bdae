// Point queries (antcd/points.hpp): batches of points against one posed model, in parallel.
#include <antcd/points.hpp>

#include "points/point_index.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

namespace antcd {

namespace {

void check_points(std::span<const Vec3> points, const char* function) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw ArgumentError(std::string(function) + ": point " + std::to_string(i) +
                          " is not finite");
    }
  }
}

/// Runs body(i) for every point index, in parallel; each point is independent, so the results do
/// not depend on the partition.
template <typename Body>
void for_each_point(std::size_t n, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
                    });
}

}  // namespace

std::vector<std::uint8_t> contains(const Model& model, const Transform& pose,
                                   std::span<const Vec3> points) {
  if (!model.is_closed()) {
    throw ArgumentError("contains: model '" + model.source() +
                        "' is not closed and consistently oriented, so it bounds no solid");
  }
  check_points(points, "contains");
  std::vector<std::uint8_t> inside(points.size(), 0);
  if (points.empty()) return inside;
  const detail::PointIndex& index = detail::point_index(model);
  const Transform to_model = pose.inverse();
  for_each_point(points.size(), [&](std::size_t i) {
    inside[i] = detail::winding_number(model, index, to_model.apply(points[i])) != 0 ? 1 : 0;
  });
  return inside;
}

SignedDistanceResult signed_distance(const Model& model, const Transform& pose,
                                     std::span<const Vec3> points) {
  check_points(points, "signed_distance");
  SignedDistanceResult result;
  result.is_signed = model.is_closed();
  result.points.resize(points.size());
  if (points.empty()) return result;
  const detail::PointIndex* index = result.is_signed ? &detail::point_index(model) : nullptr;
  const Transform to_model = pose.inverse();
  for_each_point(points.size(), [&](std::size_t i) {
    const Vec3 p = to_model.apply(points[i]);
    const detail::ClosestPoint c = detail::closest_point(model, p);
    PointDistance& out = result.points[i];
    out.distance = std::sqrt(c.distance_squared);
    out.closest = pose.apply(c.point);
    out.triangle = model.leaf_triangles()[c.leaf_triangle];
    if (index != nullptr && out.distance > 0 && detail::inside_from_closest(model, *index, p, c)) {
      out.distance = -out.distance;
    }
  });
  return result;
}

}  // namespace antcd
