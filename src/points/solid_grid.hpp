// Private: a voxel grid over a closed model that answers inside/outside at once for points in
// cells the surface does not reach (model frame).
#pragma once

#include <antcd/bvh.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace antcd::detail {

/// Cells of a regular grid over the surface's bounding box (one cell of margin around it). A
/// cell is marked "surface" when the box of some triangle, grown by a margin far above rounding,
/// meets the closed cell. The unmarked cells fall into face-connected components; the surface
/// meets no component's closed union, so the winding number is constant on it, and is computed
/// once at a cell centre (for at most about 1000 + n/16 components; any further ones are left
/// undecided, like surface cells). A point in an unmarked cell (or outside the grid, where the
/// winding number is 0) gets its answer from the cell; one in a surface cell needs a point query.
class SolidGrid {
 public:
  enum : std::uint8_t { kSurface = 0, kOutside = 1, kInside = 2 };

  SolidGrid() = default;
  /// `winding(p)` returns the winding number at p (exact away from the surface).
  SolidGrid(const Model& model, const std::function<int(const Vec3&)>& winding);

  /// kOutside, kInside, or kSurface (not decided here).
  [[nodiscard]] std::uint8_t classify(const Vec3& p) const {
    if (cells_.empty()) return kSurface;
    const Vec3 q = (p - origin_) * inverse_cell_;
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a) {
      if (!(q[a] >= 0 && q[a] < static_cast<Scalar>(dims_[a]))) return kOutside;
      c[a] = static_cast<std::int64_t>(q[a]);
    }
    return cells_[static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0])];
  }

 private:
  Vec3 origin_ = Vec3::Zero();
  Scalar inverse_cell_ = 0;
  std::array<std::int64_t, 3> dims_{0, 0, 0};
  std::vector<std::uint8_t> cells_;
};

}  // namespace antcd::detail
