// Contact manifold reduction: cluster contacts by normal, keep the deepest and the extreme points
// of each cluster (see manifold.hpp).
#include "exact/manifold.hpp"

#include <algorithm>
#include <limits>

namespace antcd::detail {

std::uint32_t reduce_to_manifold(std::vector<Contact>& contacts, std::uint32_t per_region,
                                 Scalar min_cos) {
  if (contacts.empty()) return 0;
  // Deepest first; the triangle pair breaks ties so the result does not depend on traversal order.
  std::sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) {
    if (x.depth != y.depth) return x.depth > y.depth;
    if (x.triangle_a != y.triangle_a) return x.triangle_a < y.triangle_a;
    return x.triangle_b < y.triangle_b;
  });
  std::vector<std::uint32_t> seeds;  // index of each region's deepest contact
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    std::uint32_t r = 0;
    while (r < seeds.size() && c.normal.dot(contacts[seeds[r]].normal) < min_cos) ++r;
    if (r == seeds.size()) seeds.push_back(static_cast<std::uint32_t>(i));
    c.region = r;
  }

  std::vector<Contact> kept;
  kept.reserve(std::min<std::size_t>(contacts.size(), seeds.size() * std::size_t{per_region}));
  std::vector<Scalar> gap;  // per member: squared distance to the nearest kept point
  std::vector<std::uint32_t> members;
  for (std::uint32_t r = 0; r < seeds.size(); ++r) {
    members.clear();
    for (std::uint32_t i = seeds[r]; i < contacts.size(); ++i) {
      if (contacts[i].region == r) members.push_back(i);
    }
    gap.assign(members.size(), std::numeric_limits<Scalar>::infinity());
    std::size_t pick = 0;  // the seed: the region's deepest contact
    for (std::uint32_t n = 0; n < per_region; ++n) {
      const Contact& chosen = contacts[members[pick]];
      kept.push_back(chosen);
      gap[pick] = -1;  // taken
      std::size_t next = members.size();
      Scalar far = 0;
      for (std::size_t m = 0; m < members.size(); ++m) {
        if (gap[m] < 0) continue;
        gap[m] = std::min(gap[m], (contacts[members[m]].point - chosen.point).squaredNorm());
        if (gap[m] > far) {
          far = gap[m];
          next = m;
        }
      }
      if (next == members.size()) break;  // every other member coincides with a kept point
      pick = next;
    }
  }
  contacts.swap(kept);
  return static_cast<std::uint32_t>(seeds.size());
}

}  // namespace antcd::detail
