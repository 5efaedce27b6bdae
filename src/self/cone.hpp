// Private: the normal-cone cull of the self-intersection traversal (cone.cpp).
#pragma once

#include <antcd/bvh.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace antcd::self_detail {

/// Subtrees of at least this many triangles may be culled whole (smaller ones are cheaper to
/// traverse than to test, and their boundaries would cost memory).
inline constexpr std::uint32_t kConeMinTriangles = 64;

/// Position-independent data of the cull, built once per Model (and kept by refit): for each
/// subtree of at least kConeMinTriangles triangles whose edges are each used by at most two of its
/// triangles, in opposite directions, and whose boundary edges form one directed cycle, that cycle.
/// A boundary edge is stored as 3 t + k: edge k of mesh triangle t, from corner k to corner k + 1.
struct ConeTopology {
  struct Entry {
    std::uint32_t node;
    std::uint32_t begin;  ///< into edges
    std::uint32_t end;
  };
  std::vector<Entry> entries;  ///< ascending by node
  std::vector<std::uint32_t> edges;
  /// The entry of `node`, or null.
  [[nodiscard]] const Entry* find(std::uint32_t node) const;
  [[nodiscard]] std::size_t bytes() const {
    return entries.capacity() * sizeof(Entry) + edges.capacity() * sizeof(std::uint32_t);
  }
};

/// The model's ConeTopology, built on first use (thread-safe).
std::shared_ptr<const ConeTopology> cone_topology(const Model& model);

/// Whether the subtree of `entry` is culled: `signs` is the AND of normal_signs (pair_test.hpp)
/// over its triangles; the boundary cycle, projected along the axis of one set bit, must be a
/// simple polygon (tested exactly).
bool cone_culls(const Model& model, const ConeTopology& topology, const ConeTopology::Entry& entry,
                std::uint8_t signs);

}  // namespace antcd::self_detail
