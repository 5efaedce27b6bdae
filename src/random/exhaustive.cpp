// Exhaustive enumeration of the feature grid, row by row: the reference every heuristic search is
// measured against (it finds every colliding pair, in na * nb evaluations).
#include "random/engines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace antcd::detail {
namespace {

/// Smallest squared distance from (ax, ay, az) to B's features [0, count). Branch-free so the
/// compiler can vectorise it.
Scalar row_minimum(const FeatureSide& b, std::uint32_t count, Scalar ax, Scalar ay, Scalar az) {
  const Scalar* bx = b.x.data();
  const Scalar* by = b.y.data();
  const Scalar* bz = b.z.data();
  Scalar m = std::numeric_limits<Scalar>::infinity();
  for (std::uint32_t j = 0; j < count; ++j) {
    const Scalar dx = ax - bx[j];
    const Scalar dy = ay - by[j];
    const Scalar dz = az - bz[j];
    const Scalar d2 = dx * dx + dy * dy + dz * dz;
    m = d2 < m ? d2 : m;
  }
  return m;
}

}  // namespace

void run_exhaustive(const FeatureSpace& space, Recorder& rec) {
  const std::uint32_t na = space.a.size();
  const std::uint32_t nb = space.b.size();
  const Scalar delta2 = rec.delta_squared();
  Scalar best2 = std::numeric_limits<Scalar>::infinity();
  for (std::uint32_t i = 0; i < na; ++i) {
    if (!rec.begin_iteration(i + 1)) return;
    std::uint32_t count = nb;
    if (rec.max_evaluations() != 0) {
      count = static_cast<std::uint32_t>(
          std::min<std::uint64_t>(nb, rec.max_evaluations() - rec.evaluations()));
    }
    const Scalar ax = space.a.x[i], ay = space.a.y[i], az = space.a.z[i];
    // Fast pass; the exact per-cell pass runs only on rows that hold a hit or a new best.
    const Scalar m = row_minimum(space.b, count, ax, ay, az);
    std::uint32_t counted = 0;  // evaluations of this row already added to the recorder
    if (m <= delta2 || m < best2) {
      for (std::uint32_t j = 0; j < count; ++j) {
        const Scalar dx = ax - space.b.x[j];
        const Scalar dy = ay - space.b.y[j];
        const Scalar dz = az - space.b.z[j];
        const Scalar d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < best2) {
          best2 = d2;
          rec.offer_best(i, j, std::sqrt(d2));
        }
        if (d2 <= delta2) {
          // Bring the count up to this cell first, so the hit sees the right evaluation count.
          rec.add_evaluations(j + 1 - counted);
          counted = j + 1;
          rec.add_unique_hit(i, j, std::sqrt(d2));
          if (rec.stopped()) return;  // first hit or target: the row ends here
        }
      }
    }
    rec.add_evaluations(count - counted);
    rec.check_budget();
    if (rec.stopped()) return;
  }
}

}  // namespace antcd::detail

namespace antcd {

std::uint64_t count_colliding(const FeatureSpace& space, Scalar delta) {
  if (std::isnan(delta)) throw antcd::ArgumentError("count_colliding: delta is NaN");
  const Scalar d = delta < 0 ? space.delta : delta;
  const Scalar delta2 = d * d;
  std::uint64_t total = 0;
  const std::uint32_t nb = space.b.size();
  const Scalar* bx = space.b.x.data();
  const Scalar* by = space.b.y.data();
  const Scalar* bz = space.b.z.data();
  for (std::uint32_t i = 0; i < space.a.size(); ++i) {
    const Scalar ax = space.a.x[i], ay = space.a.y[i], az = space.a.z[i];
    std::uint64_t row = 0;
    for (std::uint32_t j = 0; j < nb; ++j) {
      const Scalar dx = ax - bx[j];
      const Scalar dy = ay - by[j];
      const Scalar dz = az - bz[j];
      row += (dx * dx + dy * dy + dz * dz) <= delta2 ? 1 : 0;
    }
    total += row;
  }
  return total;
}

}  // namespace antcd
