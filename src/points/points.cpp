// Point queries (antcd/points.hpp): batches of points against one posed model, in parallel.
#include <antcd/points.hpp>

#include "points/point_index.hpp"
#include "points/point_tree.hpp"
#include "util/parallel.hpp"

#include <algorithm>
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

/// Points per block of the coherent order: each block is searched by one thread, each point
/// seeded with the previous point's closest triangle. The answers do not depend on the seed
/// (closest_point); fixed blocks keep even the work per point independent of the thread count.
constexpr std::size_t kBlock = 64;

/// Runs body(i, hint) for every point index i, in parallel, blocks of kBlock points along a
/// Morton curve through the (model-frame) points; `hint` is the leaf-order closest triangle of the
/// previous point of the block (detail::kNoHint for its first), and body returns point i's.
template <typename Body>
void for_each_point(std::span<const Vec3> local, const Body& body) {
  const std::vector<std::size_t> order = detail::coherent_order(local);
  const std::size_t blocks = (local.size() + kBlock - 1) / kBlock;
  parallel::for_ranges(0, blocks, 4, [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b != last; ++b) {
      std::uint32_t hint = detail::kNoHint;
      const std::size_t end = std::min(local.size(), (b + 1) * kBlock);
      for (std::size_t j = b * kBlock; j < end; ++j) hint = body(order[j], hint);
    }
  });
}

/// The points in the model's frame.
std::vector<Vec3> to_model_frame(const Transform& pose, std::span<const Vec3> points) {
  const Transform to_model = pose.inverse();
  std::vector<Vec3> local(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) local[i] = to_model.apply(points[i]);
  return local;
}

// contains()'s answer for one point p (model frame) into `inside`; returns the descent's hint for
// the next point (its closest leaf triangle, or `hint` when the grid decided).
std::uint32_t inside_at(const Model& model, const detail::PointIndex& index,
                        const detail::PointTree& tree, const Vec3& p, std::uint32_t hint,
                        bool& inside) {
  const std::uint8_t state = detail::solid_state(index, p);
  if (state != detail::SolidGrid::kSurface) {
    inside = state == detail::SolidGrid::kInside;
    return hint;
  }
  const detail::ClosestPoint c = detail::closest_point(model, tree, p, hint);
  inside = c.distance_squared > 0 && detail::inside_from_closest(model, index, p, c);
  return c.leaf_triangle;
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
  const detail::PointTree& tree = detail::point_tree(model);
  const std::vector<Vec3> local = to_model_frame(pose, points);
  for_each_point(local, [&](std::size_t i, std::uint32_t hint) {
    bool in = false;
    hint = inside_at(model, index, tree, local[i], hint, in);
    inside[i] = in ? 1 : 0;
    return hint;
  });
  return inside;
}

bool detail::inside_solid(const Model& model, const Vec3& p) {
  bool in = false;
  inside_at(model, point_index(model), point_tree(model), p, 0, in);
  return in;
}

SignedDistanceResult signed_distance(const Model& model, const Transform& pose,
                                     std::span<const Vec3> points) {
  check_points(points, "signed_distance");
  SignedDistanceResult result;
  result.is_signed = model.is_closed();
  result.points.resize(points.size());
  if (points.empty()) return result;
  const detail::PointIndex* index = result.is_signed ? &detail::point_index(model) : nullptr;
  const detail::PointTree& tree = detail::point_tree(model);
  const std::vector<Vec3> local = to_model_frame(pose, points);
  for_each_point(local, [&](std::size_t i, std::uint32_t hint) {
    const Vec3& p = local[i];
    const detail::ClosestPoint c = detail::closest_point(model, tree, p, hint);
    PointDistance& out = result.points[i];
    out.distance = std::sqrt(c.distance_squared);
    out.closest = pose.apply(c.point);
    out.triangle = model.leaf_triangles()[c.leaf_triangle];
    if (index != nullptr && out.distance > 0) {
      const std::uint8_t state = detail::solid_state(*index, p);
      const bool in = state == detail::SolidGrid::kSurface
                          ? detail::inside_from_closest(model, *index, p, c)
                          : state == detail::SolidGrid::kInside;
      if (in) out.distance = -out.distance;
    }
    return c.leaf_triangle;
  });
  return result;
}

}  // namespace antcd
