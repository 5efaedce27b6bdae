// Convexity detection and the exact penetration depth of convex polytopes (see convex.hpp).
//
// For convex A and B the interiors overlap exactly when the origin is inside the Minkowski
// difference M = A - B, and the depth is the distance from the origin to M's boundary: the
// minimum over M's facets (outward unit normal n) of the support value h(n) = max_A n·a -
// min_B n·b. M's facet normals are A's face normals, B's face normals negated, and the cross
// products of an edge of A and an edge of B whose arcs on the Gauss map cross (those pairs span a
// facet of M); the arc test is the hemisphere test of the two great-circle arcs.
#include "penetration/convex.hpp"

#include <antcd/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace antcd::detail {

namespace {

// A directed edge (u -> v) of triangle `tri`, as one sortable key.
struct DirectedEdge {
  std::uint64_t key;
  std::uint32_t tri;
  bool operator<(const DirectedEdge& o) const { return key < o.key; }
};

std::uint64_t edge_key(std::uint32_t u, std::uint32_t v) { return (std::uint64_t{u} << 32) | v; }

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t x, std::uint32_t y) { parent[find(x)] = find(y); }
};

bool has_area(const TriangleIndices& t) { return t[0] != t[1] && t[1] != t[2] && t[2] != t[0]; }

// Each undirected edge of a closed, consistently oriented mesh: the triangle traversing it u -> v
// and the one traversing v -> u. Calls f(t1, t2, u, v) once per edge.
template <typename F>
void for_each_edge(const Mesh& mesh, const F& f) {
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const TriangleIndices& t = mesh.triangles[i];
    if (!has_area(t)) continue;
    for (int k = 0; k < 3; ++k) edges.push_back({edge_key(t[k], t[(k + 1) % 3]), i});
  }
  std::sort(edges.begin(), edges.end());
  for (const DirectedEdge& e : edges) {
    const auto u = static_cast<std::uint32_t>(e.key >> 32);
    const auto v = static_cast<std::uint32_t>(e.key);
    if (u > v) continue;
    const auto it = std::lower_bound(edges.begin(), edges.end(), DirectedEdge{edge_key(v, u), 0});
    if (it == edges.end() || it->key != edge_key(v, u)) continue;  // not closed: caller checked
    f(e.tri, it->tri, u, v);
  }
}

std::uint32_t third(const TriangleIndices& t, std::uint32_t u, std::uint32_t v) {
  for (std::uint32_t x : t) {
    if (x != u && x != v) return x;
  }
  return t[0];
}

Scalar signed_volume6(const Mesh& mesh) {
  Scalar vol = 0;
  for (const TriangleIndices& t : mesh.triangles) {
    vol += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return vol;
}

}  // namespace

bool convex_mesh(const Mesh& mesh, int* orientation) {
  if (!is_closed(mesh)) return false;
  const Scalar vol = signed_volume6(mesh);
  const int orient = (vol > 0) - (vol < 0);
  if (orientation != nullptr) *orientation = orient;
  if (orient == 0) return false;
  // Edges concave by less than 1e-10 of the model's size count as convex: the rounding of
  // generated or exported coordinates bends flat quads by that much.
  const Aabb box = mesh.bounds();
  const Scalar flat = 1e-10 * (box.max - box.min).norm();
  bool convex = true;
  UnionFind parts(mesh.triangles.size());
  for_each_edge(mesh, [&](std::uint32_t t1, std::uint32_t t2, std::uint32_t u, std::uint32_t v) {
    if (!convex) return;
    parts.join(t1, t2);
    const TriangleIndices& a = mesh.triangles[t1];
    const Vec3& w = mesh.vertices[third(mesh.triangles[t2], u, v)];
    // orient3d > 0: w below a's plane, i.e. behind it for an outward (counter-clockwise from
    // outside) triangle.
    const Vec3& a0 = mesh.vertices[a[0]];
    const Scalar o = geometry::orient3d(a0, mesh.vertices[a[1]], mesh.vertices[a[2]], w) * orient;
    if (o >= 0) return;
    // Height of w in front of a's plane: |o| / |normal|.
    const Scalar n = (mesh.vertices[a[1]] - a0).cross(mesh.vertices[a[2]] - a0).norm();
    if (-o > flat * n) convex = false;
  });
  if (!convex) return false;
  std::uint32_t root = UINT32_MAX;
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    if (!has_area(mesh.triangles[i])) continue;
    const std::uint32_t r = parts.find(i);
    if (root == UINT32_MAX) root = r;
    if (r != root) return false;  // several pieces
  }
  return true;
}

std::size_t ConvexPolytope::support_index(const Vec3& n) const {
  std::size_t best = 0;
  Scalar best_value = -std::numeric_limits<Scalar>::infinity();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Scalar v = n.dot(vertices[i]);
    if (v > best_value) {
      best_value = v;
      best = i;
    }
  }
  return best;
}

ConvexPolytope make_polytope(const Model& model, const Transform& pose) {
  const Mesh& mesh = model.mesh();
  const int orient = signed_volume6(mesh) < 0 ? -1 : 1;
  ConvexPolytope p;
  std::vector<Vec3> world(mesh.vertices.size());
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const TriangleIndices& t : mesh.triangles) {
    if (has_area(t)) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  for (std::size_t i = 0; i < world.size(); ++i) {
    world[i] = pose.apply(mesh.vertices[i]);
    if (used[i] != 0) p.vertices.push_back(world[i]);
  }
  p.centroid = Vec3::Zero();
  for (const Vec3& v : p.vertices) p.centroid += v;
  p.centroid /= static_cast<Scalar>(std::max<std::size_t>(1, p.vertices.size()));

  // Outward unit normal of each triangle; coplanar neighbours (exact test) form one patch, whose
  // normal is tested once.
  const std::size_t nt = mesh.triangles.size();
  std::vector<Vec3> normal(nt, Vec3::Zero());
  std::vector<Scalar> area(nt, 0);
  for (std::size_t i = 0; i < nt; ++i) {
    const TriangleIndices& t = mesh.triangles[i];
    if (!has_area(t)) continue;
    const Vec3 n = (world[t[1]] - world[t[0]]).cross(world[t[2]] - world[t[0]]) * orient;
    area[i] = n.norm();
    if (area[i] > 0) normal[i] = n / area[i];
  }
  UnionFind patches(nt);
  for_each_edge(mesh, [&](std::uint32_t t1, std::uint32_t t2, std::uint32_t u, std::uint32_t v) {
    const TriangleIndices& a = mesh.triangles[t1];
    const Scalar o =
        geometry::orient3d(mesh.vertices[a[0]], mesh.vertices[a[1]], mesh.vertices[a[2]],
                           mesh.vertices[third(mesh.triangles[t2], u, v)]);
    if (o == 0) {
      patches.join(t1, t2);
      return;
    }
    const Vec3 arc = normal[t2].cross(normal[t1]);
    if (arc.squaredNorm() == 0) return;
    p.edges.push_back({world[u], world[v], normal[t1], normal[t2], arc});
  });
  std::vector<std::uint32_t> best(nt, UINT32_MAX);  // per patch root: its largest triangle
  for (std::uint32_t i = 0; i < nt; ++i) {
    if (area[i] == 0) continue;
    std::uint32_t& b = best[patches.find(i)];
    if (b == UINT32_MAX || area[i] > area[b]) b = i;
  }
  for (std::uint32_t b : best) {
    if (b == UINT32_MAX) continue;
    p.normals.push_back(normal[b]);
    p.face_point.push_back(world[mesh.triangles[b][0]]);
  }
  return p;
}

namespace {

// A smaller support value wins; an exact tie (symmetric configurations such as two coincident
// boxes) goes to the lexicographically smaller direction, so the answer does not depend on the
// order of the faces.
bool better(Scalar h, const Vec3& direction, const ConvexDepth& best) {
  if (h != best.depth) return h < best.depth;
  return std::lexicographical_compare(direction.data(), direction.data() + 3,
                                      best.direction.data(), best.direction.data() + 3);
}

}  // namespace

ConvexDepth convex_depth(const ConvexPolytope& a, const ConvexPolytope& b) {
  ConvexDepth best;
  best.depth = std::numeric_limits<Scalar>::infinity();
  // Faces of A: move A along -n until its face is level with B's lowest vertex along n.
  for (std::size_t i = 0; i < a.normals.size(); ++i) {
    const Vec3& n = a.normals[i];
    const Vec3& pb = b.vertices[b.support_index(-n)];
    const Scalar h = n.dot(a.face_point[i]) - n.dot(pb);
    if (better(h, -n, best)) best = {h, -n, Vec3(pb + h * n), pb};
  }
  // Faces of B (outward m): M's facet normal is -m; A moves along m.
  for (std::size_t i = 0; i < b.normals.size(); ++i) {
    const Vec3& m = b.normals[i];
    const Vec3& pa = a.vertices[a.support_index(-m)];
    const Scalar h = m.dot(b.face_point[i]) - m.dot(pa);
    if (better(h, m, best)) best = {h, m, pa, Vec3(pa + h * m)};
  }
  // Edge pairs spanning a facet of M: the arcs (n0, n1) of A and (-m0, -m1) of B cross.
  for (const ConvexPolytope::Edge& ea : a.edges) {
    const Vec3 da = ea.p1 - ea.p0;
    for (const ConvexPolytope::Edge& eb : b.edges) {
      const Scalar cba = -eb.n0.dot(ea.arc);
      const Scalar dba = -eb.n1.dot(ea.arc);
      if (cba * dba >= 0) continue;
      const Scalar adc = ea.n0.dot(eb.arc);
      const Scalar bdc = ea.n1.dot(eb.arc);
      if (adc * bdc >= 0 || cba * bdc <= 0) continue;
      const Vec3 db = eb.p1 - eb.p0;
      Vec3 n = da.cross(db);
      const Scalar n2 = n.squaredNorm();
      if (!(n2 > 1e-24 * da.squaredNorm() * db.squaredNorm())) continue;  // parallel edges
      n /= std::sqrt(n2);
      if (n.dot(ea.n0 + ea.n1) < 0) n = -n;
      const Scalar h = n.dot(ea.p0 - eb.p0);
      if (better(h, -n, best)) {
        Vec3 ca, cb;
        geometry::segment_segment_distance_squared(ea.p0, ea.p1, eb.p0, eb.p1, &ca, &cb);
        best = {h, -n, ca, cb};
      }
    }
  }
  return best;
}

}  // namespace antcd::detail
