// Private: ccd::vertex_face and ccd::edge_edge (antcd/ccd.hpp) without their argument checks, for
// callers that checked every argument once for many queries (deform_sweep.cpp: finite points,
// min_separation finite and >= 0, time_tolerance finite and > 0, max_boxes >= 1). Same answers
// otherwise; max_boxes is the box budget (ccd::kMaxBoxes in the public calls).
#pragma once

#include <antcd/ccd.hpp>

#include <array>
#include <cstdint>

namespace antcd::ccd::unchecked {

PrimitiveResult vertex_face(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                            Scalar min_separation, Scalar time_tolerance,
                            std::uint32_t max_boxes = kMaxBoxes);
PrimitiveResult edge_edge(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                          Scalar min_separation, Scalar time_tolerance,
                          std::uint32_t max_boxes = kMaxBoxes);

}  // namespace antcd::ccd::unchecked
