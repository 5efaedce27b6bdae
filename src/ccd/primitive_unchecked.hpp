// Private: ccd::vertex_face and ccd::edge_edge (antcd/ccd.hpp) without their argument checks, for
// callers that checked every argument once for many queries (deform_sweep.cpp: finite points,
// min_separation finite and >= 0, time_tolerance finite and > 0). Same answers otherwise.
#pragma once

#include <antcd/ccd.hpp>

#include <array>

namespace antcd::ccd::unchecked {

PrimitiveResult vertex_face(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                            Scalar min_separation, Scalar time_tolerance);
PrimitiveResult edge_edge(const std::array<Vec3, 4>& at_t0, const std::array<Vec3, 4>& at_t1,
                          Scalar min_separation, Scalar time_tolerance);

}  // namespace antcd::ccd::unchecked
