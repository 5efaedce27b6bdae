// The per-call swept bounds of a deforming mesh's hierarchy and the primitive ownership masks
// (ccd/deform_bounds.hpp).
#include "ccd/deform_bounds.hpp"

#include <algorithm>

namespace antcd::detail {
namespace {

void add_vertex(SweptNode& n, const Vec3& p0, const Vec3& p1) {
  const Vec3 d = p1 - p0;
  n.lo0 = n.lo0.cwiseMin(p0);
  n.hi0 = n.hi0.cwiseMax(p0);
  n.lo1 = n.lo1.cwiseMin(p1);
  n.hi1 = n.hi1.cwiseMax(p1);
  n.dneg = n.dneg.cwiseMax(-d);
  n.dpos = n.dpos.cwiseMax(d);
}

SweptNode empty_node() {
  constexpr Scalar kInf = std::numeric_limits<Scalar>::infinity();
  SweptNode n;
  n.lo0 = n.lo1 = Vec3::Constant(kInf);
  n.hi0 = n.hi1 = Vec3::Constant(-kInf);
  n.dneg = n.dpos = Vec3::Zero();
  return n;
}

void merge_into(SweptNode& n, const SweptNode& c) {
  n.lo0 = n.lo0.cwiseMin(c.lo0);
  n.hi0 = n.hi0.cwiseMax(c.hi0);
  n.lo1 = n.lo1.cwiseMin(c.lo1);
  n.hi1 = n.hi1.cwiseMax(c.hi1);
  n.dneg = n.dneg.cwiseMax(c.dneg);
  n.dpos = n.dpos.cwiseMax(c.dpos);
}

void fill_leaf(SweptNode& n, const std::vector<TriangleIndices>& tris,
               std::span<const std::uint32_t> order, std::span<const Vec3> V0,
               std::span<const Vec3> V1) {
  for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
    for (std::uint32_t v : tris[order[k]]) add_vertex(n, V0[v], V1[v]);
  }
}

/// Ownership: a triangle owns a corner (an edge) when it is the lowest-indexed triangle holding
/// that vertex (those two vertices) and the corner (edge) is its first slot holding it.
std::vector<OwnerMask> owner_masks(const Mesh& mesh, std::size_t& scratch) {
  const auto& tris = mesh.triangles;
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const auto& t : tris) {
    for (int c = 0; c < 3; ++c) {
      if (c > 0 && t[c] == t[0]) continue;
      if (c == 2 && t[2] == t[1]) continue;
      ++start[t[c] + 1];
    }
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> incident(start[nv]);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t f = 0; f < tris.size(); ++f) {
    const auto& t = tris[f];
    for (int c = 0; c < 3; ++c) {
      if (c > 0 && t[c] == t[0]) continue;
      if (c == 2 && t[2] == t[1]) continue;
      incident[fill[t[c]]++] = f;  // ascending f per vertex
    }
  }
  scratch = (start.capacity() + incident.capacity() + fill.capacity()) * sizeof(std::uint32_t);
  std::vector<OwnerMask> owner(tris.size(), 0);
  for (std::uint32_t f = 0; f < tris.size(); ++f) {
    const auto& t = tris[f];
    OwnerMask m = 0;
    for (int c = 0; c < 3; ++c) {
      bool first_slot = true;
      for (int p = 0; p < c; ++p) first_slot = first_slot && t[p] != t[c];
      if (first_slot && incident[start[t[c]]] == f) m = static_cast<OwnerMask>(m | (1u << c));
      const std::uint32_t a = t[c];
      const std::uint32_t b = t[(c + 1) % 3];
      if (a == b) continue;
      bool first_edge = true;
      for (int p = 0; p < c; ++p) {
        const std::uint32_t pa = t[p], pb = t[(p + 1) % 3];
        if ((pa == a && pb == b) || (pa == b && pb == a)) first_edge = false;
      }
      if (!first_edge) continue;
      std::uint32_t lowest = f;
      for (std::uint32_t k = start[a]; k < start[a + 1]; ++k) {
        const auto& g = tris[incident[k]];
        if (g[0] == b || g[1] == b || g[2] == b) {
          lowest = incident[k];  // ascending: the first is the lowest
          break;
        }
      }
      if (lowest == f) m = static_cast<OwnerMask>(m | (1u << (3 + c)));
    }
    owner[f] = m;
  }
  return owner;
}

}  // namespace

DeformBounds make_deform_bounds(const Model& model, std::span<const Vec3> V0,
                                std::span<const Vec3> V1) {
  DeformBounds b;
  const Mesh& mesh = model.mesh();
  const std::span<const BvhNode> tree = model.nodes();
  const std::span<const std::uint32_t> leaves = model.leaf_triangles();

  // The leaf order, then the triangles the hierarchy leaves out (zero area).
  b.triangles.assign(leaves.begin(), leaves.end());
  if (leaves.size() < mesh.triangles.size()) {
    std::vector<bool> in_tree(mesh.triangles.size(), false);
    for (std::uint32_t f : leaves) in_tree[f] = true;
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
      if (!in_tree[f]) b.triangles.push_back(f);
    }
  }

  b.nodes.resize(tree.size() + (b.triangles.size() > leaves.size() ? 2 : 0), empty_node());
  for (std::size_t i = tree.size(); i-- > 0;) {  // children come after their parent
    SweptNode& n = b.nodes[i];
    const BvhNode& t = tree[i];
    if (t.is_leaf()) {
      n.first = t.first_or_right;
      n.count = t.count;
      fill_leaf(n, mesh.triangles, b.triangles, V0, V1);
    } else {
      n.left = static_cast<std::uint32_t>(i + 1);
      n.right = t.first_or_right;
      merge_into(n, b.nodes[n.left]);
      merge_into(n, b.nodes[n.right]);
    }
  }
  b.root = 0;
  if (b.nodes.size() > tree.size()) {  // the zero-area triangles' leaf and a root above both
    const auto extra = static_cast<std::uint32_t>(tree.size());
    SweptNode& e = b.nodes[extra];
    e.first = static_cast<std::uint32_t>(leaves.size());
    e.count = static_cast<std::uint32_t>(b.triangles.size() - leaves.size());
    fill_leaf(e, mesh.triangles, b.triangles, V0, V1);
    SweptNode& r = b.nodes[extra + 1];
    r.left = 0;
    r.right = extra;
    merge_into(r, b.nodes[0]);
    merge_into(r, e);
    b.root = extra + 1;
  }

  for (std::size_t v = 0; v < V0.size(); ++v) {
    b.max_coordinate =
        std::max({b.max_coordinate, V0[v].cwiseAbs().maxCoeff(), V1[v].cwiseAbs().maxCoeff()});
    b.max_displacement = std::max(b.max_displacement, (V1[v] - V0[v]).cwiseAbs().maxCoeff());
  }
  std::size_t owner_scratch = 0;
  b.owner = owner_masks(mesh, owner_scratch);
  const std::size_t held = b.nodes.capacity() * sizeof(SweptNode) +
                           b.triangles.capacity() * sizeof(std::uint32_t) +
                           b.owner.capacity() * sizeof(OwnerMask);
  b.scratch_bytes = held + owner_scratch;
  return b;
}

}  // namespace antcd::detail
