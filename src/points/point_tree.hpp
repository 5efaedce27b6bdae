// Private: the compact axis-aligned tree that point-distance queries descend (model frame),
// and the batch order that makes consecutive queries coherent.
#pragma once

#include <antcd/bvh.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace antcd::detail {

/// The model's hierarchy (same topology, same leaves) re-expressed for point distance: each
/// internal node holds the axis-aligned boxes of its two children side by side, so one fetch of
/// 112 bytes gives both children's lower bounds (computed two at a time). An axis-aligned box
/// bounds a point's distance from below as tightly as the hierarchy's oriented boxes near the
/// surface and costs a third as much to evaluate.
struct PointTree {
  struct Node {
    /// Boxes of the two children, coordinate-major: lo[axis][child].
    alignas(16) Scalar lo[3][2];
    alignas(16) Scalar hi[3][2];
    /// Internal child: its Node index; leaf child: its first leaf-order triangle.
    std::uint32_t ref[2];
    /// Leaf child: its triangle count; internal child: 0.
    std::uint32_t count[2];
  };
  std::vector<Node> nodes;  ///< nodes[0] is the root, when the root is not itself a leaf
  /// Per leaf-order triangle: its unit normal n and the inward unit normals m[i] of its edges
  /// within its plane, each with its offset (n.p - nd is p's height over the plane, m[i].p - md[i]
  /// its signed distance inside edge i's line). They give a lower bound of p's distance to the
  /// triangle, exact in the face and edge regions, for a dozen multiplications: sqrt(height^2 +
  /// max(0, -m[i].p + md[i])^2). Slivers (whose normal rounding could tilt the bound) get zeros,
  /// i.e. the bound 0.
  struct Triangle {
    Vec3 n;
    Scalar nd;
    Vec3 m[3];
    Scalar md[3];
  };
  std::vector<Triangle> triangles;
  /// Largest absolute vertex coordinate: the scale of the rounding of every bound.
  Scalar coordinate_scale = 0;
  std::uint32_t root_leaf_count = 0;  ///< the root is a leaf of this many triangles (else 0)
  std::size_t max_depth = 0;          ///< longest root-to-leaf path, in nodes
};

/// Stack of a depth-first descent that pushes two children and pops one per internal node: it
/// never holds more than depth + 1 entries. On the call stack unless the tree is unusually deep.
template <typename T>
class DescentStack {
 public:
  explicit DescentStack(std::size_t depth) {
    if (depth + 2 > kLocal) heap_.resize(depth + 2);
  }
  T* data() { return heap_.empty() ? local_ : heap_.data(); }

 private:
  static constexpr std::size_t kLocal = 96;
  T local_[kLocal];
  std::vector<T> heap_;
};

/// Builds the tree from the model's hierarchy. O(n).
PointTree build_point_tree(const Model& model);

/// The model's tree, built on first use (once, thread-safe) and kept by the model.
const PointTree& point_tree(const Model& model);

/// Closest point of the model's surface to p (model frame): squared distance, the point, and
/// the leaf-order triangle index.
struct ClosestPoint {
  Scalar distance_squared = 0;
  Vec3 point = Vec3::Zero();
  std::uint32_t leaf_triangle = 0;
};

inline constexpr std::uint32_t kNoHint = std::numeric_limits<std::uint32_t>::max();

/// Branch-and-bound descent, nearer child first. `hint` (a leaf-order triangle, or kNoHint) seeds
/// the bound: its distance is computed first, so a good guess (the previous point's answer in a
/// coherent batch) prunes most of the tree. Among triangles at the same computed distance the one
/// with the smallest leaf-order index wins, so the answer does not depend on the hint.
ClosestPoint closest_point(const Model& model, const PointTree& tree, const Vec3& p,
                           std::uint32_t hint = kNoHint);

/// A permutation of the points that follows a Morton (Z-order) curve through their bounding box,
/// so that consecutive points are near one another. Deterministic (ties by index).
std::vector<std::size_t> coherent_order(std::span<const Vec3> points);

}  // namespace antcd::detail
