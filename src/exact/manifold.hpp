// Private: contact manifold reduction (manifold.cpp): a few representative contacts per touching
// region, for physics users (see CollisionRequest::manifold_points).
#pragma once

#include <antcd/collide.hpp>

#include <cstdint>
#include <vector>

namespace antcd::detail {

/// Replaces `contacts` (each with its normal and depth) by at most `per_region` (>= 1) of them per
/// region and numbers the regions (Contact::region); returns the number of regions.
/// Regions: contacts are taken deepest first (ties by triangle pair); each joins the first region
/// whose seed (its deepest contact) has a normal within the angle whose cosine is `min_cos`, else
/// seeds a new region. Per region the deepest contact is kept, then repeatedly the one farthest
/// from those kept (farthest-point sampling: the extremes of the patch), until `per_region` are
/// kept or the rest coincide with kept points. Output: region by region, in selection order.
std::uint32_t reduce_to_manifold(std::vector<Contact>& contacts, std::uint32_t per_region,
                                 Scalar min_cos);

}  // namespace antcd::detail
