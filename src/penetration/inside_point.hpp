// Private: points inside two solids and the lower bound of the penetration depth they prove
// (inside_point.cpp). See antcd/penetration.hpp for the bound: for p inside both solids,
// PD >= dist(p, ∂A) + dist(p, ∂B).
#pragma once

#include <antcd/bvh.hpp>

#include <span>
#include <vector>

namespace antcd::detail {

/// One evaluated point, world frame.
struct DepthPoint {
  Vec3 p = Vec3::Zero();
  Vec3 closest_a = Vec3::Zero();  ///< nearest point of A's surface
  Vec3 closest_b = Vec3::Zero();
  Scalar dist_a = 0;  ///< distance to A's surface (>= 0)
  Scalar dist_b = 0;
  bool inside = false;  ///< inside both solids (winding numbers)
  /// The proven lower bound: (dist_a - allowance)+ + (dist_b - allowance)+ when inside, else 0.
  Scalar bound = 0;
};

/// The two posed closed models and the rounding allowance of their point queries.
class DepthProbe {
 public:
  DepthProbe(const Model& a, const Transform& pose_a, const Model& b, const Transform& pose_b);

  /// Evaluates every point (two batched point queries).
  [[nodiscard]] std::vector<DepthPoint> evaluate(std::span<const Vec3> points) const;
  /// tolerance::kPoint (1e-10) of the coordinates' scale: far above the rounding of a point query.
  [[nodiscard]] Scalar allowance() const { return allowance_; }
  /// Size of the scene: the coordinates' magnitude plus both models' extents.
  [[nodiscard]] Scalar scale() const { return scale_; }

  /// The best point found from seeds (vertices of each model inside the other, points just
  /// inside both from where the surfaces cross, a grid over the boxes' overlap, `extra`), refined
  /// by a local ascent of the bound. bound 0 when no point
  /// inside both was found.
  [[nodiscard]] DepthPoint best_point(std::span<const Vec3> extra) const;

 private:
  [[nodiscard]] DepthPoint ascend(DepthPoint start) const;
  void vertex_seeds(const Model& m, const Transform& pose, const Model& other,
                    const Transform& other_pose, std::vector<Vec3>& seeds) const;
  void contact_seeds(std::vector<Vec3>& seeds) const;

  const Model& a_;
  const Model& b_;
  Transform pose_a_, pose_b_;
  Scalar scale_ = 1;
  Scalar allowance_ = 0;
};

}  // namespace antcd::detail
