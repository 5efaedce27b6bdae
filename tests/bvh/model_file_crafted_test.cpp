// Crafted model files (issue 41): trees deeper than the build makes (a chain of loose volumes that
// passes every other check crashed every query with SIGSEGV from depth 601 on), infinite volumes,
// zero-area triangles in a leaf and a vertex just outside one node's volume are refused with
// one-line errors; what is accepted answers as the model rebuilt from the same mesh.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/sweep.hpp>
#include <antcd/tolerances.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "bvh/model_file.hpp"

namespace antcd {
namespace {

/// kMaxTreeLevels (antcd/bvh.hpp), as documented in docs/model_file.md.
constexpr std::size_t kLevels = 73;

using Bytes = std::vector<std::uint8_t>;

/// A model file written field by field from its parts (docs/model_file.md, format version 1),
/// its checksum sealed: what a hostile writer can make.
class Crafter {
 public:
  void u32(std::uint32_t v) { put(v, 4); }
  void u64(std::uint64_t v) { put(v, 8); }
  void f32(float v) {
    std::uint32_t b = 0;
    std::memcpy(&b, &v, 4);
    put(b, 4);
  }
  void f64(double v) {
    std::uint64_t b = 0;
    std::memcpy(&b, &v, 8);
    put(b, 8);
  }
  void vec3(const Vec3& v) {
    for (int k = 0; k < 3; ++k) f64(v[k]);
  }

  static Bytes file(const Mesh& mesh, const std::vector<BvhNode>& nodes,
                    const std::vector<std::uint32_t>& leaves, std::uint32_t leaf_size) {
    Crafter c;
    c.bytes_.reserve(64 + 24 * mesh.vertices.size() + 12 * mesh.triangles.size() +
                     96 * nodes.size() + 4 * leaves.size());
    c.bytes_.resize(detail::kModelHeaderSize);
    c.u32(leaf_size);
    c.u32(1);  // area-weighted covariance
    c.u32(is_closed(mesh) ? 1 : 0);
    c.u32(0);
    c.f64(0);
    c.u64(7);
    for (const char ch : std::string("crafted")) c.bytes_.push_back(static_cast<std::uint8_t>(ch));
    c.u64(mesh.vertices.size());
    for (const Vec3& v : mesh.vertices) c.vec3(v);
    c.u64(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
      for (const std::uint32_t v : t) c.u32(v);
    }
    c.u64(nodes.size());
    for (const BvhNode& n : nodes) {
      c.vec3(n.center);
      c.f32(n.radius);
      c.u32(n.count);
      c.u32(n.first_or_right);
      for (const float h : n.half) c.f32(h);
      c.vec3(n.axis0);
      c.vec3(n.axis1);
    }
    c.u64(leaves.size());
    for (const std::uint32_t t : leaves) c.u32(t);
    Bytes& b = c.bytes_;
    std::copy(std::begin(detail::kModelMagic), std::end(detail::kModelMagic), b.begin());
    detail::write_le(b.data() + 8, detail::kModelFormatVersion, 4);
    detail::write_le(b.data() + 12, 0, 4);
    const std::span<const std::uint8_t> payload = std::span(b).subspan(detail::kModelHeaderSize);
    detail::write_le(b.data() + detail::kModelPayloadSizeOffset, payload.size(), 8);
    detail::write_le(b.data() + detail::kModelChecksumOffset, detail::model_checksum(payload), 8);
    return std::move(c.bytes_);
  }

 private:
  void put(std::uint64_t v, int n) {
    const std::size_t at = bytes_.size();
    bytes_.resize(at + static_cast<std::size_t>(n));
    detail::write_le(bytes_.data() + at, v, n);
  }
  Bytes bytes_;
};

/// A node with a loose volume: a box and a ball of `size` about the origin (holds everything).
BvhNode loose_node(float size) {
  BvhNode n;
  n.center = Vec3::Zero();
  n.radius = size;
  n.half = {size, size, size};
  n.axis0 = Vec3::UnitX();
  n.axis1 = Vec3::UnitY();
  return n;
}

/// A chain `levels` deep: internal nodes down the right spine, each with a leaf of one triangle
/// as its left child, the last level a leaf too; a strip of `levels` small triangles along x.
Bytes chain_file(std::size_t levels) {
  Mesh strip;
  for (std::size_t k = 0; k < levels + 2; ++k) {
    const Scalar x = 1e-3 * static_cast<Scalar>(k);
    strip.vertices.emplace_back(x, k % 2 == 0 ? 0.0 : 1e-3, 0.0);
  }
  for (std::size_t k = 0; k < levels; ++k) {
    const auto v = static_cast<std::uint32_t>(k);
    strip.triangles.push_back({v, v + 1, v + 2});
  }
  std::vector<BvhNode> nodes;
  std::vector<std::uint32_t> leaves;
  const float size = static_cast<float>(1e-3 * static_cast<Scalar>(levels) + 1);
  for (std::size_t k = 0; k + 1 < levels; ++k) {
    BvhNode inner = loose_node(size);
    inner.count = 0;
    inner.first_or_right = static_cast<std::uint32_t>(nodes.size() + 2);
    nodes.push_back(inner);
    BvhNode leaf = loose_node(size);
    leaf.count = 1;
    leaf.first_or_right = static_cast<std::uint32_t>(leaves.size());
    leaves.push_back(static_cast<std::uint32_t>(k));
    nodes.push_back(leaf);
  }
  BvhNode last = loose_node(size);
  last.count = 1;
  last.first_or_right = static_cast<std::uint32_t>(leaves.size());
  leaves.push_back(static_cast<std::uint32_t>(levels - 1));
  nodes.push_back(last);
  return Crafter::file(strip, nodes, leaves, 1);
}

/// The MeshError message of loading `bytes` ("" when it loads).
std::string load_error(const Bytes& bytes) {
  try {
    (void)Model::from_bytes(bytes, "crafted.antcd");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Depths 601 .. 5001 crashed collide, distance, sweep and the CLI: the traversals' fixed stacks
// (512 pairs) overflowed. The reader now refuses any tree deeper than the build makes.
TEST(ModelFileCrafted, TreesDeeperThanTheBuildMakesAreRefused) {
  for (const std::size_t levels : {std::size_t{10000}, std::size_t{1000000}}) {
    const std::string error = load_error(chain_file(levels));
    EXPECT_TRUE(contains(error, "crafted.antcd: the tree is deeper than 73 levels (node "))
        << levels << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos);
    EXPECT_LT(error.size(), 200U);
  }
  // One level past the bound is refused; at the bound the chain loads and answers like the
  // model built from the same strip, in every traversal.
  EXPECT_TRUE(contains(load_error(chain_file(kLevels + 1)), "deeper than 73 levels"));
  const Model chain = Model::from_bytes(chain_file(kLevels), "chain");
  EXPECT_EQ(chain.stats().depth, kLevels);
  const Model built(chain.mesh(), {1, CovarianceMethod::AreaWeightedCentroid}, "built");
  const Model probe(make_box({0.01, 0.01, 0.01}), {}, "probe");
  const Transform id = Transform::identity();
  for (const Scalar x : {0.0, 0.03, 0.2}) {
    const Transform p = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0.02, 0));
    EXPECT_EQ(collide(chain, id, probe, p).colliding, collide(built, id, probe, p).colliding) << x;
    EXPECT_EQ(distance(chain, id, probe, p).distance, distance(built, id, probe, p).distance) << x;
    const Transform q = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(x, 0.02, 1));
    const SweepResult a = sweep(probe, q, p, chain, id, id);
    const SweepResult b = sweep(probe, q, p, built, id, id);
    EXPECT_EQ(a.hit, b.hit) << x;
  }
}

// Every radius and half extent +inf: accepted before, then sweep failed naming distance's
// abs_tolerance. The build makes finite volumes for coordinates within 4.25e37: refused there.
TEST(ModelFileCrafted, InfiniteVolumesAreRefusedWhereTheBuildMakesFiniteOnes) {
  const Model m(make_box({1, 0.5, 0.25}, 2), {2, CovarianceMethod::AreaWeightedCentroid}, "box");
  std::vector<BvhNode> nodes(m.nodes().begin(), m.nodes().end());
  const std::vector<std::uint32_t> leaves(m.leaf_triangles().begin(), m.leaf_triangles().end());
  ASSERT_EQ(load_error(Crafter::file(m.mesh(), nodes, leaves, 2)), "");
  for (BvhNode& n : nodes) {
    n.radius = std::numeric_limits<float>::infinity();
    n.half = {n.radius, n.radius, n.radius};
  }
  const std::string error = load_error(Crafter::file(m.mesh(), nodes, leaves, 2));
  EXPECT_TRUE(contains(error, "crafted.antcd: node 0 has an infinite radius or half extent"))
      << error;
  // One infinite half extent deep in the tree.
  nodes.assign(m.nodes().begin(), m.nodes().end());
  nodes.back().half[1] = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(contains(load_error(Crafter::file(m.mesh(), nodes, leaves, 2)),
                       "node " + std::to_string(nodes.size() - 1) + " has an infinite"));
}

// A flat tree (one leaf) holding a zero-area triangle away from the box: distance and collide
// answered against its segment, which the rebuilt model leaves out (0.3 against 0.748).
TEST(ModelFileCrafted, ZeroAreaTrianglesInALeafAreRefused) {
  Mesh mesh = make_box({0.5, 0.5, 0.5});
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), {Vec3(2, 0, 0), Vec3(2, 0.5, 0), Vec3(2, 1, 0)});
  mesh.triangles.push_back({first, first + 1, first + 2});
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  const Model built(mesh, {n, CovarianceMethod::AreaWeightedCentroid}, "built");
  ASSERT_EQ(built.nodes().size(), 1U);
  ASSERT_EQ(built.leaf_triangles().size(), n - 1);
  std::vector<BvhNode> nodes(built.nodes().begin(), built.nodes().end());
  std::vector<std::uint32_t> leaves(built.leaf_triangles().begin(), built.leaf_triangles().end());
  ASSERT_EQ(load_error(Crafter::file(mesh, nodes, leaves, n)), "");
  // The degenerate triangle added to the one leaf, the volumes grown to hold it.
  leaves.push_back(n - 1);
  nodes[0] = loose_node(4);
  nodes[0].count = n;
  nodes[0].first_or_right = 0;
  const std::string error = load_error(Crafter::file(mesh, nodes, leaves, n));
  EXPECT_TRUE(contains(error, "crafted.antcd: triangle " + std::to_string(n - 1) +
                                  " is in the tree but degenerate (zero area)"))
      << error;
}

/// One past node i's subtree (depth-first order: the subtree is [i, end)).
std::size_t subtree_end(std::span<const BvhNode> nodes, std::size_t i) {
  return nodes[i].is_leaf() ? i + 1 : subtree_end(nodes, nodes[i].first_or_right);
}

// The volume check descends a node's subtree only where no descendant's volume already holds that
// node's face or sphere (bvh/model_check.cpp). A vertex of a large subtree moved just outside
// one face (or the sphere) of its node, by ten times the check's allowance (kArithmetic of the
// node's size; the traversal's own kVolume is a thousand times that), must still be refused,
// naming that node, while every other node (grown a little) still holds the moved vertex.
TEST(ModelFileCrafted, AVertexJustOutsideOneNodesVolumeIsRefused) {
  const Model m(make_torus(1, 0.3, 64, 32), {}, "torus");  // 4096 triangles
  const std::span<const BvhNode> tree = m.nodes();
  const std::vector<std::uint32_t> leaves(m.leaf_triangles().begin(), m.leaf_triangles().end());
  std::vector<BvhNode> grown(tree.begin(), tree.end());
  for (BvhNode& n : grown) {
    n.radius = n.radius * 1.01F + 1e-3F;
    for (float& h : n.half) h = h * 1.01F + 1e-3F;
  }
  std::size_t checked = 0;
  for (std::size_t a = 0; a < tree.size(); ++a) {
    const std::size_t end = subtree_end(tree, a);
    std::size_t lo = leaves.size(), hi = 0;  // the subtree's leaf triangles
    for (std::size_t i = a; i < end; ++i) {
      if (!tree[i].is_leaf()) continue;
      lo = std::min<std::size_t>(lo, tree[i].first_or_right);
      hi = std::max<std::size_t>(hi, tree[i].first_or_right + tree[i].count);
    }
    if (hi - lo < 512) continue;  // small subtrees are point-tested whole
    const BvhNode& node = tree[a];
    std::vector<BvhNode> nodes = grown;
    nodes[a] = node;
    ASSERT_EQ(load_error(Crafter::file(m.mesh(), nodes, leaves, 4)), "") << a;
    const Mat3 axes = node.axes();
    const Scalar allowance = tolerance::kArithmetic * (node.center.cwiseAbs().maxCoeff() +
                                                       std::min(static_cast<Scalar>(node.radius),
                                                                node.half_extents().norm()));
    // Directions: +-axis k (to the face at half[k]), then the sphere (radially, to the radius).
    for (int side = 0; side < 7; ++side) {
      const Vec3 dir = side < 6 ? Vec3(axes.col(side % 3) * (side < 3 ? 1.0 : -1.0)) : Vec3::Zero();
      std::uint32_t far = 0;
      Scalar reach = -1;
      for (std::size_t k = lo; k < hi; ++k) {
        for (const std::uint32_t v : m.mesh().triangles[leaves[k]]) {
          const Vec3 d = m.mesh().vertices[v] - node.center;
          const Scalar r = side < 6 ? dir.dot(d) : d.norm();
          if (r > reach) reach = r, far = v;
        }
      }
      Mesh moved = m.mesh();
      const Vec3 d = moved.vertices[far] - node.center;
      const Scalar bound =
          side < 6 ? static_cast<Scalar>(node.half[side % 3]) : static_cast<Scalar>(node.radius);
      const Vec3 out = side < 6 ? dir : Vec3(d.normalized());
      moved.vertices[far] += out * (bound - reach + 10 * allowance);
      const std::string error = load_error(Crafter::file(moved, nodes, leaves, 4));
      EXPECT_TRUE(contains(error, "crafted.antcd: node " + std::to_string(a) +
                                      "'s box or sphere does not hold its triangles"))
          << "node " << a << ", side " << side << ": " << error;
      ++checked;
    }
  }
  EXPECT_GE(checked, 7U * 7U);  // the root and the nodes of its first levels
}

}  // namespace
}  // namespace antcd
