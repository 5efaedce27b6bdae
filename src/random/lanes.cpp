// The lane arithmetic of a colony step (Recorder::evaluate_batch): 16 candidates' centroids
// gathered, their distances and reaches in fixed-length, branch-free loops the compiler vectorises (baseline and
// AVX2 clones, same arithmetic: fast_math.hpp).
#include "random/fast_math.hpp"
#include "random/recorder.hpp"

#include <bit>
#include <cmath>
#include <limits>

namespace antcd::detail {

ANTCD_VECTOR_CLONES Recorder::LaneSummary Recorder::compute_lanes(
    Lanes& lanes, const FeatureSpace& space, const std::uint32_t* ci, const std::uint32_t* cj,
    std::uint32_t count, bool witness, float delta, float centroid) {
  const float* const ax = space.a.x.data();
  const float* const ay = space.a.y.data();
  const float* const az = space.a.z.data();
  const float* const bx = space.b.x.data();
  const float* const by = space.b.y.data();
  const float* const bz = space.b.z.data();
  for (std::uint32_t k = 0; k < kLanes; ++k) {
    lanes.ax[k] = ax[ci[k]];
    lanes.ay[k] = ay[ci[k]];
    lanes.az[k] = az[ci[k]];
    lanes.bx[k] = bx[cj[k]];
    lanes.by[k] = by[cj[k]];
    lanes.bz[k] = bz[cj[k]];
  }
  if (witness) {
    const float* const ra = space.a.radius.data();
    const float* const rb = space.b.radius.data();
    for (std::uint32_t k = 0; k < kLanes; ++k) {
      lanes.ra[k] = ra[ci[k]];
      lanes.rb[k] = rb[cj[k]];
    }
    for (std::uint32_t k = 0; k < kLanes; ++k) {
      lanes.reach[k] = lanes.ra[k] + lanes.rb[k] + delta;
    }
  } else {
    for (std::uint32_t k = 0; k < kLanes; ++k) lanes.reach[k] = centroid;
  }
  for (std::uint32_t k = 0; k < kLanes; ++k) {
    const float dx = lanes.ax[k] - lanes.bx[k];
    const float dy = lanes.ay[k] - lanes.by[k];
    const float dz = lanes.az[k] - lanes.bz[k];
    const float d2 = dx * dx + dy * dy + dz * dz;
    lanes.d2[k] = d2;
    lanes.d[k] = std::sqrt(d2);
    lanes.within[k] = d2 <= lanes.reach[k] * lanes.reach[k] ? 1U : 0U;
  }
  // Reductions over the real lanes only, in fixed-length loops.
  LaneSummary summary;
  summary.min_d2_bits = std::bit_cast<std::uint32_t>(std::numeric_limits<float>::infinity());
  for (std::uint32_t k = 0; k < kLanes; ++k) {
    const std::uint32_t real = k < count ? 1U : 0U;
    summary.any_within |= lanes.within[k] & real;
    const std::uint32_t bits = real != 0 ? std::bit_cast<std::uint32_t>(lanes.d2[k]) : ~0U;
    summary.min_d2_bits = bits < summary.min_d2_bits ? bits : summary.min_d2_bits;
  }
  return summary;
}

}  // namespace antcd::detail
