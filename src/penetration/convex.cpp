// Convexity detection and the exact penetration depth of convex polytopes (see convex.hpp).
//
// For convex A and B the interiors overlap exactly when the origin is inside the Minkowski
// difference M = A - B, and the depth is the distance from the origin to M's boundary: the
// minimum over M's facets (outward unit normal n) of the support value h(n) = max_A n·a -
// min_B n·b. M's facet normals are A's face normals, B's face normals negated, and the cross
// products of an edge of A and an edge of B whose arcs on the Gauss map cross (those pairs span a
// facet of M); the arc test is the hemisphere test of the two great-circle arcs.
#include "penetration/convex.hpp"

#include "bvh/model_cache.hpp"

#include <antcd/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
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

}  // namespace

Scalar signed_volume6(const Mesh& mesh) {
  Scalar vol = 0;
  for (const TriangleIndices& t : mesh.triangles) {
    vol += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return vol;
}

std::size_t ConvexPolytope::support_index(const Vec3& n, std::size_t start) const {
  std::size_t cur = start;
  Scalar value = n.dot(vertices[cur]);
  for (bool improved = true; improved;) {
    improved = false;
    std::size_t next = cur;
    for (std::uint32_t k = adjacent_begin[cur]; k < adjacent_begin[cur + 1]; ++k) {
      const Scalar v = n.dot(vertices[adjacent[k]]);
      if (v > value) {
        value = v;
        next = adjacent[k];
        improved = true;
      }
    }
    cur = next;
  }
  return cur;
}

Scalar ConvexPolytope::plane_margin(const Vec3& p) const {
  Scalar m = -std::numeric_limits<Scalar>::infinity();
  for (std::size_t i = 0; i < normals.size(); ++i)
    m = std::max(m, normals[i].dot(p - face_point[i]));
  return m;
}

namespace {

// Builds the model-frame polytope (pose identity) when the model is convex.
bool build_polytope(const Model& model, ConvexPolytope* out) {
  const Transform pose = Transform::identity();
  const Mesh& mesh = model.mesh();
  if (!model.is_closed()) return false;
  const Scalar vol = signed_volume6(mesh);
  const int orient = (vol > 0) - (vol < 0);
  if (orient == 0) return false;
  // Heights within 1e-10 of the model's size count as flat: the rounding of generated or
  // exported coordinates bends flat quads by that much (a floating-point test is enough then).
  const Aabb box = mesh.bounds();
  const Scalar flat = 1e-10 * (box.max - box.min).norm();
  const std::size_t nt = mesh.triangles.size();
  // Outward unit normal of each triangle, model frame.
  std::vector<Vec3> normal(nt, Vec3::Zero());
  std::vector<Scalar> area(nt, 0);
  for (std::size_t i = 0; i < nt; ++i) {
    const TriangleIndices& t = mesh.triangles[i];
    if (!has_area(t)) continue;
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a) * orient;
    area[i] = n.norm();
    if (area[i] > 0) normal[i] = n / area[i];
  }
  bool convex = true;
  UnionFind parts(nt);    // connected pieces
  UnionFind patches(nt);  // coplanar neighbours: one face normal per patch
  std::vector<std::array<std::uint32_t, 4>> edges;  // u, v, t1, t2 of the non-flat edges
  std::vector<std::array<std::uint32_t, 2>> graph;  // every edge
  for_each_edge(mesh, [&](std::uint32_t t1, std::uint32_t t2, std::uint32_t u, std::uint32_t v) {
    if (!convex) return;
    parts.join(t1, t2);
    graph.push_back({u, v});
    // Height of the far vertex of t2 in front of t1's plane: > 0 is a reflex (concave) edge.
    const Vec3& w = mesh.vertices[third(mesh.triangles[t2], u, v)];
    const Scalar h = normal[t1].dot(w - mesh.vertices[u]);
    if (h > flat) {
      convex = false;
    } else if (h >= -flat) {
      patches.join(t1, t2);
    } else {
      edges.push_back({u, v, t1, t2});
    }
  });
  if (!convex) return false;
  std::uint32_t root = UINT32_MAX;
  for (std::uint32_t i = 0; i < nt; ++i) {
    if (!has_area(mesh.triangles[i])) continue;
    const std::uint32_t r = parts.find(i);
    if (root == UINT32_MAX) root = r;
    if (r != root) return false;  // several pieces
  }
  ConvexPolytope& p = *out;
  p = {};
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const TriangleIndices& t : mesh.triangles) {
    if (has_area(t)) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  std::vector<Vec3> world(mesh.vertices.size());
  std::vector<std::uint32_t> index(mesh.vertices.size(), 0);  // mesh vertex -> p.vertices
  for (std::size_t i = 0; i < world.size(); ++i) {
    world[i] = pose.apply(mesh.vertices[i]);
    if (used[i] == 0) continue;
    index[i] = static_cast<std::uint32_t>(p.vertices.size());
    p.vertices.push_back(world[i]);
  }
  p.adjacent_begin.assign(p.vertices.size() + 1, 0);
  for (const auto& [u, v] : graph) {
    ++p.adjacent_begin[index[u] + 1];
    ++p.adjacent_begin[index[v] + 1];
  }
  for (std::size_t i = 0; i < p.vertices.size(); ++i)
    p.adjacent_begin[i + 1] += p.adjacent_begin[i];
  p.adjacent.resize(p.adjacent_begin.back());
  std::vector<std::uint32_t> fill(p.adjacent_begin.begin(), p.adjacent_begin.end() - 1);
  for (const auto& [u, v] : graph) {
    p.adjacent[fill[index[u]]++] = index[v];
    p.adjacent[fill[index[v]]++] = index[u];
  }
  for (Vec3& n : normal) n = pose.apply_vector(n);
  for (const auto& [u, v, t1, t2] : edges) {
    const Vec3 arc = normal[t2].cross(normal[t1]);
    if (arc.squaredNorm() == 0) continue;
    Vec3 cap = normal[t1] + normal[t2];
    const Scalar len = cap.norm();
    // Opposite normals (a flat wedge) have no cap: the whole sphere (chord 2).
    cap = len > 0 ? Vec3(cap / len) : Vec3::UnitX();
    const Scalar chord = len > 0 ? (normal[t1] - cap).norm() : 2;
    p.edges.push_back({world[u], world[v], normal[t1], normal[t2], arc, cap, chord});
  }
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
  return true;
}

// The model-frame analysis, derived once per Model (the model's cache; a refit starts a new one).
struct ConvexEntry {
  bool convex = false;
  ConvexPolytope shape;  // model frame
};

const ConvexEntry& convex_entry(const Model& model) {
  static const std::size_t slot = new_cache_slot();
  return derived<ConvexEntry>(model, slot, [&] {
    ConvexEntry entry;
    entry.convex = build_polytope(model, &entry.shape);
    if (!entry.convex) entry.shape = {};
    return entry;
  });
}

}  // namespace

bool convex_polytope(const Model& model, const Transform& pose, ConvexPolytope* out) {
  const ConvexEntry& entry = convex_entry(model);
  if (!entry.convex) return false;
  if (out == nullptr) return true;
  const ConvexPolytope& m = entry.shape;
  ConvexPolytope& p = *out;
  p.vertices.resize(m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) p.vertices[i] = pose.apply(m.vertices[i]);
  p.normals.resize(m.normals.size());
  p.face_point.resize(m.face_point.size());
  for (std::size_t i = 0; i < m.normals.size(); ++i) {
    p.normals[i] = pose.apply_vector(m.normals[i]);
    p.face_point[i] = pose.apply(m.face_point[i]);
  }
  p.edges.resize(m.edges.size());
  for (std::size_t i = 0; i < m.edges.size(); ++i) {
    const ConvexPolytope::Edge& e = m.edges[i];
    p.edges[i] = {pose.apply(e.p0),
                  pose.apply(e.p1),
                  pose.apply_vector(e.n0),
                  pose.apply_vector(e.n1),
                  pose.apply_vector(e.arc),
                  pose.apply_vector(e.cap),
                  e.chord};
  }
  p.adjacent_begin = m.adjacent_begin;
  p.adjacent = m.adjacent;
  return true;
}

namespace {

using EdgeList = std::vector<const ConvexPolytope::Edge*>;

// Calls f(ea, eb) for every pair of the listed edges of A and B whose arcs (A's, and B's negated)
// might cross: all pairs for short lists; else only pairs whose caps meet, found through a
// uniform grid of B's cap centres (cell = the largest chord at which two caps can still meet), so
// that fine tessellations cost about E log E instead of E².
template <typename F>
void for_each_candidate_pair(const EdgeList& a, const EdgeList& b, const F& f) {
  const auto all_pairs = [&] {
    for (const auto* ea : a) {
      for (const auto* eb : b) f(*ea, *eb);
    }
  };
  if (static_cast<double>(a.size()) * static_cast<double>(b.size()) <= (1 << 14)) {
    all_pairs();
    return;
  }
  // Two caps meet only if their centres are within the sum of their chords (chords of angles
  // add up to at least the chord of the sum). B's caps are negated.
  Scalar max_a = 0, max_b = 0;
  for (const auto* ea : a) max_a = std::max(max_a, ea->chord);
  for (const auto* eb : b) max_b = std::max(max_b, eb->chord);
  const Scalar reach = max_a + max_b;
  if (reach >= 1.0) {  // long arcs: the grid would not prune
    all_pairs();
    return;
  }
  const Scalar cell = reach * (1 + 1e-6) + 1e-9;  // with a margin for rounding
  const auto coord = [&](Scalar x) {
    return static_cast<std::int64_t>(std::floor((x + 1) / cell));
  };
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>((i << 42) | (j << 21) | k);
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> grid;
  grid.reserve(b.size());
  for (std::uint32_t i = 0; i < b.size(); ++i) {
    const Vec3 c = -b[i]->cap;
    grid.emplace_back(key(coord(c.x()), coord(c.y()), coord(c.z())), i);
  }
  std::sort(grid.begin(), grid.end());
  for (std::size_t ia = 0; ia < a.size(); ++ia) {
    const Vec3& c = a[ia]->cap;
    const std::int64_t x = coord(c.x()), y = coord(c.y()), z = coord(c.z());
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          if (x + dx < 0 || y + dy < 0 || z + dz < 0) continue;
          const std::uint64_t k = key(x + dx, y + dy, z + dz);
          auto it = std::lower_bound(grid.begin(), grid.end(), std::pair{k, std::uint32_t{0}});
          for (; it != grid.end() && it->first == k; ++it) f(*a[ia], *b[it->second]);
        }
      }
    }
  }
}

// The centroid of the vertices and the radius of a ball about it inside the polytope.
struct InnerBall {
  Vec3 center;
  Scalar radius;
};

InnerBall inner_ball(const ConvexPolytope& p) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : p.vertices) c += v;
  c /= static_cast<Scalar>(std::max<std::size_t>(1, p.vertices.size()));
  return {c, std::max<Scalar>(0, -p.plane_margin(c))};
}

// The edges of one polytope that can span a facet of the Minkowski difference with a support
// value below `limit`. An edge e of A spanning a facet of normal n gives h = n·e.p0 + h_B(-n) >=
// n·(e.p0 - c) + r for a ball (c, r) inside B, and n lies in e's cap (centre u, half angle t),
// so n·w >= u·w - |w| |n - u| >= u·w - |w| chord. For an edge of B the facet normal is -v, v in its
// cap, and h = h_A(-v) + v·e.p0 >= v·(e.p0 - c) + r with A's ball: the same bound.
EdgeList useful_edges(const ConvexPolytope& p, const InnerBall& other, Scalar limit) {
  EdgeList out;
  for (const auto& e : p.edges) {
    const Vec3 w = e.p0 - other.center;
    const Scalar lb = e.cap.dot(w) - w.norm() * e.chord + other.radius;
    if (!(lb > limit)) out.push_back(&e);
  }
  return out;
}

// A smaller support value wins; an exact tie (symmetric configurations such as two coincident
// boxes) goes to the lexicographically smaller direction, so the answer does not depend on the
// order of the faces.
bool better(Scalar h, const Vec3& direction, const ConvexDepth& best) {
  if (h != best.depth) return h < best.depth;
  return std::lexicographical_compare(direction.data(), direction.data() + 3, best.direction.data(),
                                      best.direction.data() + 3);
}

}  // namespace

ConvexDepth convex_depth(const ConvexPolytope& a, const ConvexPolytope& b) {
  ConvexDepth best;
  best.depth = std::numeric_limits<Scalar>::infinity();
  Scalar scale = 0;
  for (const Vec3& v : a.vertices) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  for (const Vec3& v : b.vertices) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  const Scalar slack = 1e-9 * scale;  // the bounds below are compared with this rounding margin
  const InnerBall ball_a = inner_ball(a);
  const InnerBall ball_b = inner_ball(b);
  // Faces of A (outward n): move A along -n until its face is level with B's lowest vertex along
  // n. h = n·f + h_B(-n) >= n·(f - c_B) + r_B: faces whose bound exceeds the best are skipped.
  std::size_t hint_b = 0;
  const auto face_a = [&](std::size_t i) {
    const Vec3& n = a.normals[i];
    hint_b = b.support_index(-n, hint_b);
    const Vec3& pb = b.vertices[hint_b];
    const Scalar h = n.dot(a.face_point[i]) - n.dot(pb);
    if (better(h, -n, best)) best = {h, -n, Vec3(pb + h * n), pb};
  };
  // Faces of B (outward m): M's facet normal is -m; A moves along m.
  std::size_t hint_a = 0;
  const auto face_b = [&](std::size_t i) {
    const Vec3& m = b.normals[i];
    hint_a = a.support_index(-m, hint_a);
    const Vec3& pa = a.vertices[hint_a];
    const Scalar h = m.dot(b.face_point[i]) - m.dot(pa);
    if (better(h, m, best)) best = {h, m, pa, Vec3(pa + h * m)};
  };
  std::vector<Scalar> bound_a(a.normals.size()), bound_b(b.normals.size());
  for (std::size_t i = 0; i < a.normals.size(); ++i) {
    bound_a[i] = a.normals[i].dot(a.face_point[i] - ball_b.center) + ball_b.radius;
  }
  for (std::size_t i = 0; i < b.normals.size(); ++i) {
    bound_b[i] = b.normals[i].dot(b.face_point[i] - ball_a.center) + ball_a.radius;
  }
  // The most promising face of each first, so that the others are mostly skipped.
  if (!bound_a.empty()) {
    face_a(static_cast<std::size_t>(std::min_element(bound_a.begin(), bound_a.end()) -
                                    bound_a.begin()));
  }
  if (!bound_b.empty()) {
    face_b(static_cast<std::size_t>(std::min_element(bound_b.begin(), bound_b.end()) -
                                    bound_b.begin()));
  }
  for (std::size_t i = 0; i < bound_a.size(); ++i) {
    if (!(bound_a[i] > best.depth + slack)) face_a(i);
  }
  for (std::size_t i = 0; i < bound_b.size(); ++i) {
    if (!(bound_b[i] > best.depth + slack)) face_b(i);
  }
  // Edge pairs spanning a facet of M: the arcs (n0, n1) of A and (-m0, -m1) of B cross. An edge
  // pair wins only by more than rounding: an edge pair whose cross product is a face normal (its
  // arcs meet at a Gauss-map vertex) ties with that face, and the face's points are the exact ones.
  const Scalar margin = 1e-12 * scale;
  // Only edges that can beat the best face (with a rounding margin) are paired.
  const Scalar limit = best.depth + slack;
  const EdgeList edges_a = useful_edges(a, ball_b, limit);
  const EdgeList edges_b = useful_edges(b, ball_a, limit);
  for_each_candidate_pair(
      edges_a, edges_b, [&](const ConvexPolytope::Edge& ea, const ConvexPolytope::Edge& eb) {
        const Scalar cba = -eb.n0.dot(ea.arc);
        const Scalar dba = -eb.n1.dot(ea.arc);
        if (cba * dba >= 0) return;
        const Scalar adc = ea.n0.dot(eb.arc);
        const Scalar bdc = ea.n1.dot(eb.arc);
        if (adc * bdc >= 0 || cba * bdc <= 0) return;
        const Vec3 da = ea.p1 - ea.p0;
        const Vec3 db = eb.p1 - eb.p0;
        Vec3 n = da.cross(db);
        const Scalar n2 = n.squaredNorm();
        if (!(n2 > 1e-24 * da.squaredNorm() * db.squaredNorm())) return;  // parallel edges
        n /= std::sqrt(n2);
        if (n.dot(ea.n0 + ea.n1) < 0) n = -n;
        const Scalar h = n.dot(ea.p0 - eb.p0);
        if (h < best.depth - margin) {
          Vec3 ca, cb;
          geometry::segment_segment_distance_squared(ea.p0, ea.p1, eb.p0, eb.p1, &ca, &cb);
          best = {h, -n, ca, cb};
        }
      });
  return best;
}

}  // namespace antcd::detail

namespace antcd::detail {

Vec3 convex_witness(const ConvexPolytope& a, const ConvexPolytope& b, const ConvexDepth& d,
                    Scalar& margin) {
  // Points of the segment from point_a (on A's surface) to point_b (on B's): A moved along it by
  // the depth touches B at point_b, so the overlap lies about it.
  margin = std::numeric_limits<Scalar>::infinity();
  Vec3 best = d.point_a;
  for (const Scalar t : {0.5, 0.25, 0.75}) {
    const Vec3 c = d.point_a + t * (d.point_b - d.point_a);
    const Scalar m = std::max(a.plane_margin(c), b.plane_margin(c));
    if (m < margin) {
      margin = m;
      best = c;
    }
  }
  return best;
}

Vec3 push_inside(const ConvexPolytope& a, const ConvexPolytope& b, Vec3 p, Scalar depth,
                 Scalar& margin) {
  for (int it = 0; it < 256; ++it) {
    margin = -std::numeric_limits<Scalar>::infinity();
    const Vec3* worst = nullptr;
    for (const ConvexPolytope* poly : {&a, &b}) {
      for (std::size_t i = 0; i < poly->normals.size(); ++i) {
        const Scalar m = poly->normals[i].dot(p - poly->face_point[i]);
        if (m > margin) {
          margin = m;
          worst = &poly->normals[i];
        }
      }
    }
    if (worst == nullptr || margin <= -depth) break;
    p -= (margin + depth) * *worst;
  }
  return p;
}

}  // namespace antcd::detail
