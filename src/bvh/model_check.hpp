// Private: the model file reader's proofs about a tree it has read (model_check.cpp), apart from
// the reading itself (model_file.cpp). Each throws a MeshError naming the file `name` at the first
// problem. The format and the list of checks are docs/model_file.md.
#pragma once

#include <antcd/bvh.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace antcd::detail {

/// Models at least this large are read and checked in parallel.
inline constexpr std::size_t kParallelCheck = 16384;

/// Checks the nodes' values and the tree's shape (depth-first order: node 0 the root, an internal
/// node's left child next to it, its right child after the left subtree; the leaves' triangle
/// ranges consecutive and covering [0, leaf_count); at most kMaxTreeLevels levels, the build's
/// bound, which every traversal's stack is sized for). Iterative: a crafted chain of a million
/// nodes is refused at the first node too deep. `finite_volumes`: the build's radii and half
/// extents would all be finite, so +inf ones are refused too. Returns the tree's depth in levels.
std::size_t check_tree(const std::vector<BvhNode>& nodes, std::size_t leaf_count,
                       std::uint32_t leaf_size, bool finite_volumes, const std::string& name);

/// Checks, on a model whose tree passed check_tree, that the triangles left out of the tree are
/// exactly the degenerate ones, that every node's axes are orthonormal, and that every node's box
/// and sphere hold every vertex of its subtree's triangles (up to tolerance::kArithmetic of the
/// node's size): what every query's pruning relies on. `in_tree[t]`: whether mesh triangle t is
/// one of the model's leaf triangles.
void check_volumes(const Model& m, const std::vector<bool>& in_tree, const std::string& name);

}  // namespace antcd::detail
