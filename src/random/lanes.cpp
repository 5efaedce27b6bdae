// The lane arithmetic of a colony step (Recorder::evaluate_batch): 16 candidates' centroid
// distances and reaches in fixed-length, branch-free loops the compiler vectorises (baseline and
// AVX2 clones, same arithmetic: fast_math.hpp).
#include "random/fast_math.hpp"
#include "random/recorder.hpp"

#include <cmath>

namespace antcd::detail {

ANTCD_VECTOR_CLONES void Recorder::compute_lanes(Lanes& lanes, bool witness, float delta,
                                                 float centroid) {
  if (witness) {
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
}

}  // namespace antcd::detail
