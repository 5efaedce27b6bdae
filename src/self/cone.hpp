// Private: the normal-cone cull of the self-intersection traversal (cone.cpp). The subtree
// boundaries it tests are ccd/normal_cone.hpp's, shared with the deforming sweep.
#pragma once

#include <antcd/bvh.hpp>

#include <cstdint>
#include <vector>

#include "ccd/normal_cone.hpp"

namespace antcd::self_detail {

using detail::cone_topology;
using detail::ConeTopology;
using detail::kConeMinTriangles;

/// Whether the subtree of `entry` is culled: `signs` is the AND of normal_signs (pair_test.hpp)
/// over its triangles; the boundary cycle, projected along the axis of one set bit, must be a
/// simple polygon (tested exactly). `boxes` is room reused between calls (no allocation once it
/// has grown to the longest boundary).
bool cone_culls(const Model& model, const ConeTopology& topology, const ConeTopology::Entry& entry,
                std::uint8_t signs, std::vector<detail::EdgeBox>& boxes);

}  // namespace antcd::self_detail
