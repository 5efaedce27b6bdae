// The flexible veneer sheets (flexible.hpp): the grid, its sag, droop and fold.
#include "shared/production_line/flexible.hpp"

#include "shared/production_line.hpp"
#include "shared/production_line/poses.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace antcd::shared {

Mesh flexible_sheet_mesh(std::size_t columns, std::size_t rows, Scalar half_x, Scalar half_y) {
  columns = std::max<std::size_t>(columns, 2);
  rows = std::max<std::size_t>(rows, 2);
  // Vertex (i, j) is numbered when a triangle first uses it, triangles row by row: the order an
  // OBJ of this mesh loads back in (load_mesh keeps vertices in order of first use), which a
  // side file of vertex frames indexes.
  constexpr std::uint32_t unset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> number(columns * rows, unset);
  Mesh m;
  const auto id = [&](std::size_t i, std::size_t j) {
    std::uint32_t& n = number[j * columns + i];
    if (n == unset) {
      n = static_cast<std::uint32_t>(m.vertices.size());
      const Scalar x = -half_x + 2 * half_x * static_cast<Scalar>(i) / (columns - 1);
      const Scalar y = -half_y + 2 * half_y * static_cast<Scalar>(j) / (rows - 1);
      m.vertices.emplace_back(x, y, 0);
    }
    return n;
  };
  for (std::size_t j = 0; j + 1 < rows; ++j) {
    for (std::size_t i = 0; i + 1 < columns; ++i) {
      const std::uint32_t a = id(i, j);
      const std::uint32_t b = id(i + 1, j);
      const std::uint32_t c = id(i + 1, j + 1);
      const std::uint32_t d = id(i, j + 1);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  }
  return m;
}

}  // namespace antcd::shared

namespace antcd::shared::line {

Scalar RollerSupport::offset(Scalar x) const {
  const Scalar last_axis = first_axis + pitch * static_cast<Scalar>(rollers - 1);
  const Scalar low = first_axis - radius;
  const Scalar high = last_axis + radius;
  if (x < low) return -kDroopRate * (low - x) * (low - x);
  if (x > high) return -kDroopRate * (x - high) * (x - high);
  const Scalar k =
      std::clamp(std::round((x - first_axis) / pitch), Scalar{0}, static_cast<Scalar>(rollers - 1));
  const Scalar d = std::abs(x - (first_axis + pitch * k));
  if (d <= radius) return 0;
  const Scalar t = std::min(Scalar{1}, (d - radius) / (pitch / 2 - radius));
  const Scalar s = std::sin(kPi / 2 * t);
  return -kSagDepth * s * s;
}

Fold fold_at(Scalar u) {
  const Scalar straight = kFlapLength - kPi * kFoldRadius;
  const Scalar tilt = std::asin((2 * kFoldRadius + kFoldPress) / straight);
  if (u < 0.4) return {kPi * smoothstep(u / 0.4), 0};
  if (u < 0.6) return {kPi, tilt * smoothstep((u - 0.4) / 0.2)};
  if (u < 0.7) return {kPi, tilt};
  if (u < 0.8) return {kPi, tilt * (1 - smoothstep((u - 0.7) / 0.1))};
  return {kPi * (1 - smoothstep((u - 0.8) / 0.2)), 0};
}

std::vector<Vec3> sheet_frame(const Mesh& rest, const RollerSupport& support, Scalar world_x,
                              const Fold& fold) {
  Scalar min_x = std::numeric_limits<Scalar>::infinity();
  for (const Vec3& v : rest.vertices) min_x = std::min(min_x, v.x());
  const Scalar fold_x = min_x + kFlapLength;  // the flap is the trailing part, x < fold_x
  const Scalar r = kFoldRadius;
  std::vector<Vec3> out;
  out.reserve(rest.vertices.size());
  for (const Vec3& v : rest.vertices) {
    Scalar x = v.x();
    Scalar z = 0;
    if (fold.curl > 0 && x < fold_x) {
      const Scalar s = fold_x - x;  // arc length from the fold line
      if (s <= fold.curl * r) {
        const Scalar phi = s / r;
        x = fold_x - r * std::sin(phi);
        z = r * (1 - std::cos(phi));
      } else {
        const Scalar psi = fold.curl + fold.tilt;
        const Scalar rest_length = s - fold.curl * r;
        x = fold_x - r * std::sin(fold.curl) - rest_length * std::cos(psi);
        z = r * (1 - std::cos(fold.curl)) + rest_length * std::sin(psi);
      }
    }
    z += support.offset(world_x + x);
    out.emplace_back(x, v.y(), z);
  }
  return out;
}

}  // namespace antcd::shared::line
