// The voxel grid of a closed model: surface cells marked from triangle boxes, the other cells
// classified per face-connected component by one winding number each.
#include "points/solid_grid.hpp"
#include "util/grid_cell.hpp"

#include <antcd/tolerances.hpp>

#include <algorithm>
#include <cmath>

namespace antcd::detail {

namespace {

/// About this many cells per triangle (bounded below and above): surface cells are then a small
/// fraction of the box for a fine mesh, and the grid costs about a byte per cell.
constexpr Scalar kCellsPerTriangle = 8;
constexpr Scalar kMinCells = 4096;
constexpr Scalar kMaxCells = 1 << 24;

}  // namespace

SolidGrid::SolidGrid(const Model& model, const std::function<int(const Vec3&)>& winding) {
  const LeafCorners lv = model.leaf_corners();
  Aabb box;
  for (std::size_t k = 0; k < lv.size(); ++k) {
    for (int c = 0; c < 3; ++c) box.extend(lv(k, c));
  }
  const Vec3 extent = box.extent();
  const Scalar largest = extent.maxCoeff();
  if (!(largest > 0)) return;
  const Scalar target =
      std::clamp(kCellsPerTriangle * static_cast<Scalar>(lv.size()), kMinCells, kMaxCells);
  // Flat axes count as 1/256 of the largest one, so that a thin solid still gets cells.
  const Vec3 sized = extent.cwiseMax(largest / 256);
  const Scalar cell = std::cbrt(sized.prod() / target);
  // Coordinates near the ends of the double range overflow (or underflow) the cell arithmetic:
  // no grid then (every point goes to the exact query), never a NaN cast to an index.
  if (!std::isfinite(largest) || !(cell > 0) || !std::isfinite(cell) || !std::isfinite(1 / cell)) {
    return;
  }
  for (int a = 0; a < 3; ++a) {
    dims_[a] = static_cast<std::int64_t>(std::ceil(extent[a] / cell)) + 2;  // one cell of margin
  }
  origin_ = box.min - Vec3::Constant(cell);
  inverse_cell_ = 1 / cell;
  // Far above the rounding of the coordinates and of the cell arithmetic.
  const Scalar eps =
      tolerance::kVolume * (box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff() + largest);
  const std::size_t total = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  cells_.assign(total, kOutside);

  auto cell_of = [&](Scalar x, int a) {
    return clamped_cell<std::int64_t>(std::floor((x - origin_[a]) * inverse_cell_), 0,
                                      dims_[a] - 1);
  };
  auto index_of = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::size_t>((z * dims_[1] + y) * dims_[0] + x);
  };
  // A triangle whose box spans more than two cells is split into four at its edge midpoints
  // (the pieces cover it up to rounding, which eps absorbs), so a large tilted triangle marks
  // the cells along it rather than its whole box.
  auto mark = [&](auto&& self, const Vec3& a, const Vec3& b, const Vec3& c, int depth) -> void {
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(eps);
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(eps);
    std::array<std::int64_t, 3> first{}, last{};
    bool split = false;
    for (int k = 0; k < 3; ++k) {
      first[k] = cell_of(lo[k], k);
      last[k] = cell_of(hi[k], k);
      split = split || last[k] - first[k] > 2;
    }
    if (split && depth < 16) {
      const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
      self(self, a, ab, ca, depth + 1);
      self(self, ab, b, bc, depth + 1);
      self(self, ca, bc, c, depth + 1);
      self(self, ab, bc, ca, depth + 1);
      return;
    }
    for (std::int64_t z = first[2]; z <= last[2]; ++z) {
      for (std::int64_t y = first[1]; y <= last[1]; ++y) {
        for (std::int64_t x = first[0]; x <= last[0]; ++x) cells_[index_of(x, y, z)] = kSurface;
      }
    }
  };
  for (std::size_t k = 0; k < lv.size(); ++k) mark(mark, lv(k, 0), lv(k, 1), lv(k, 2), 0);

  // Face-connected components of the free cells, each classified at its first cell's centre
  // (at least half a cell from the surface, so its winding number is exact).
  std::vector<bool> seen(total, false);
  std::vector<std::size_t> queue;
  std::vector<std::size_t> component;
  const std::int64_t stride[3] = {1, dims_[0], dims_[0] * dims_[1]};
  // Each component costs one winding number; a surface that encloses very many small free
  // regions (thousands of tiny shells) would make that the bulk of the build, so past a budget
  // the remaining components are left to the point queries (marked as surface cells).
  std::size_t budget = 1024 + lv.size() / 16;
  for (std::size_t start = 0; start < total; ++start) {
    if (cells_[start] == kSurface || seen[start]) continue;
    component.clear();
    queue.assign(1, start);
    seen[start] = true;
    while (!queue.empty()) {
      const std::size_t i = queue.back();
      queue.pop_back();
      component.push_back(i);
      const auto si = static_cast<std::int64_t>(i);
      const std::int64_t at[3] = {si % dims_[0], (si / dims_[0]) % dims_[1],
                                  si / (dims_[0] * dims_[1])};
      for (int a = 0; a < 3; ++a) {
        for (const std::int64_t step : {std::int64_t{-1}, std::int64_t{1}}) {
          if (at[a] + step < 0 || at[a] + step >= dims_[a]) continue;
          const auto j = static_cast<std::size_t>(si + step * stride[a]);
          if (cells_[j] == kSurface || seen[j]) continue;
          seen[j] = true;
          queue.push_back(j);
        }
      }
    }
    const auto s0 = static_cast<std::int64_t>(start);
    const Vec3 centre =
        origin_ + cell * Vec3(static_cast<Scalar>(s0 % dims_[0]) + 0.5,
                              static_cast<Scalar>((s0 / dims_[0]) % dims_[1]) + 0.5,
                              static_cast<Scalar>(s0 / (dims_[0] * dims_[1])) + 0.5);
    std::uint8_t state = kSurface;
    if (budget > 0) {
      --budget;
      state = winding(centre) != 0 ? kInside : kOutside;
    }
    for (const std::size_t i : component) cells_[i] = state;
  }
}

}  // namespace antcd::detail
