// Top-down construction of the hybrid Sphere-OBB hierarchy (paper, section 2): each node gets
// the OBB of its triangles (geometry/obb_fit.cpp, Eqs. 1–3) and a sphere about the box centre,
// then its triangles are cut in two (split.cpp) until at most leaf_size remain.
#include <antcd/bvh.hpp>

#include "bvh/model_cache.hpp"
#include "bvh/split.hpp"
#include "geometry/obb_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <stdexcept>

namespace antcd {

namespace {

using BuildTriangle = geometry::detail::FitTriangle;

class Builder {
 public:
  Builder(std::vector<BuildTriangle>& tris, const BuildOptions& options,
          std::vector<BvhNode>& nodes)
      : tris_(tris), options_(options), nodes_(nodes) {}

  std::size_t build(std::size_t begin, std::size_t end, std::size_t depth) {
    const std::size_t index = nodes_.size();
    nodes_.emplace_back();
    BvhNode node = fit_node(begin, end);
    std::size_t height = 1;
    if (end - begin <= options_.leaf_size) {
      node.first_or_right = static_cast<std::uint32_t>(begin);
      node.count = static_cast<std::uint32_t>(end - begin);
    } else {
      const std::size_t mid = begin + detail::split_triangles(range(begin, end), depth);
      const std::size_t left_height = build(begin, mid, depth + 1);
      node.first_or_right = static_cast<std::uint32_t>(nodes_.size());
      const std::size_t right_height = build(mid, end, depth + 1);
      height += std::max(left_height, right_height);
    }
    nodes_[index] = node;
    return height;
  }

 private:
  std::span<BuildTriangle> range(std::size_t begin, std::size_t end) const {
    return std::span<BuildTriangle>(tris_).subspan(begin, end - begin);
  }

  BvhNode fit_node(std::size_t begin, std::size_t end) const {
    const std::span<const BuildTriangle> tris = range(begin, end);
    BvhNode node;
    node.obb =
        geometry::detail::fit_obb(tris, geometry::detail::fit_obb_axes(tris, options_.covariance));
    // Sphere about the box centre through the farthest vertex: never larger than the box's
    // circumscribed sphere, and a cheap first reject in the traversal.
    Scalar r2 = 0;
    for (const BuildTriangle& t : tris) {
      for (const Vec3& v : t.v) r2 = std::max(r2, (v - node.obb.center).squaredNorm());
    }
    node.sphere.center = node.obb.center;
    node.sphere.radius = std::sqrt(r2);
    return node;
  }

  std::vector<BuildTriangle>& tris_;
  const BuildOptions& options_;
  std::vector<BvhNode>& nodes_;
};

}  // namespace

Model::Model(Mesh mesh, const BuildOptions& options, std::string source)
    : mesh_(std::move(mesh)),
      source_(std::move(source)),
      options_(options),
      cache_(std::make_shared<detail::ModelCache>()) {
  const auto start = std::chrono::steady_clock::now();
  if (options_.leaf_size == 0) {
    throw antcd::ArgumentError(source_ + ": leaf size must be at least 1");
  }
  validate_mesh(mesh_, source_);
  closed_ = antcd::is_closed(mesh_);

  std::vector<BuildTriangle> tris;
  tris.reserve(mesh_.triangles.size());
  for (std::uint32_t i = 0; i < mesh_.triangles.size(); ++i) {
    const auto& t = mesh_.triangles[i];
    BuildTriangle bt{
        i, {mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]}, Vec3::Zero(), 0};
    if (geometry::is_degenerate_triangle(bt.v[0], bt.v[1], bt.v[2])) {
      ++stats_.degenerate_triangles;
      continue;
    }
    // The centroid of a triangle (its static moments over its area) is its vertex mean.
    bt.centroid = (bt.v[0] + bt.v[1] + bt.v[2]) / 3.0;
    bt.area = 0.5 * (bt.v[1] - bt.v[0]).cross(bt.v[2] - bt.v[0]).norm();
    tris.push_back(bt);
  }
  if (tris.empty()) {
    throw MeshError(source_, "has no triangle of non-zero area");
  }

  nodes_.reserve(2 * (tris.size() / options_.leaf_size + 1));
  Builder builder(tris, options_, nodes_);
  stats_.depth = builder.build(0, tris.size(), 0);
  nodes_.shrink_to_fit();

  leaf_triangles_.resize(tris.size());
  leaf_vertices_.resize(3 * tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    leaf_triangles_[i] = tris[i].index;
    for (int k = 0; k < 3; ++k) leaf_vertices_[3 * i + k] = tris[i].v[k];
  }

  stats_.triangles = mesh_.triangles.size();
  stats_.nodes = nodes_.size();
  for (const BvhNode& node : nodes_) {
    stats_.obb_volume_sum += node.obb.volume();
    if (node.is_leaf()) {
      ++stats_.leaves;
      stats_.max_leaf_size = std::max<std::size_t>(stats_.max_leaf_size, node.count);
    }
  }
  stats_.memory_bytes =
      mesh_.vertices.capacity() * sizeof(Vec3) +
      mesh_.triangles.capacity() * sizeof(TriangleIndices) + nodes_.capacity() * sizeof(BvhNode) +
      leaf_triangles_.capacity() * sizeof(std::uint32_t) + leaf_vertices_.capacity() * sizeof(Vec3);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace antcd
