// libFuzzer target: self-collision (antcd/self.hpp) and the vertex update (Model::refit) on meshes
// made from arbitrary bytes.
//
// Input: byte 0 picks the vertex count (4 .. 35) and the coordinate mode, byte 1 the self-proximity
// delta; then three coordinates per vertex (mode 0: small integers on a grid, so that coplanar,
// collinear, coincident and duplicated geometry is common; mode 1: raw doubles, any bits, NaN and
// infinity included), then three index bytes per triangle, and the same count of coordinates once
// more for the moved vertices of a refit. Refusals (MeshError, ArgumentError) are accepted
// outcomes. Findings: any other exception, a crash, a sanitizer report, or, for meshes within the
// documented coordinate range (docs/guarantees.md: every non-zero |coordinate| in 1e-75 .. 1e75,
// where the exact predicates' arithmetic neither underflows nor overflows), an answer that breaks
// one of these properties:
// - self_intersections with and without the normal-cone cull give the same pairs (the cull may
//   only save work), sorted with i < j, no degenerate triangle in a pair;
// - first_only reports one of those pairs, and a pair exactly when there is one;
// - self_proximity's pairs are sorted, within delta, between primitives that share no vertex;
// - after refit(moved), self_intersections equals that of a Model built from the moved mesh, and
//   a refused refit leaves the vertices as they were.
#include <antcd/bvh.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/self.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "finding.hpp"
#include "reader.hpp"

namespace {

using antcd::Mesh;
using antcd::Model;
using antcd::Scalar;
using antcd::Vec3;
using Pairs = std::vector<std::array<std::uint32_t, 2>>;

[[noreturn]] void finding(const char* what, const char* detail = "") {
  antcd::fuzz::finding("fuzz_self", what, detail);
}

using antcd::fuzz::Reader;

/// Every coordinate 0 or of magnitude within the documented range (docs/guarantees.md).
bool in_range(const std::vector<Vec3>& vertices) {
  for (const Vec3& v : vertices) {
    for (int k = 0; k < 3; ++k) {
      const double a = std::abs(v[k]);
      if (a != 0 && !(a >= 1e-75 && a <= 1e75)) return false;
    }
  }
  return true;
}

Pairs intersections(const Model& model, bool cones) {
  antcd::SelfIntersectionRequest request;
  request.normal_cones = cones;
  return antcd::self_intersections(model, request).pairs;
}

void check_pairs(const Model& model, bool oracle) {
  const antcd::SelfIntersectionResult full = antcd::self_intersections(model);
  if (intersections(model, false) != full.pairs && oracle)
    finding("the cone cull changed the pairs");
  if (full.intersecting != !full.pairs.empty()) finding("intersecting disagrees with the pairs");
  if (!std::is_sorted(full.pairs.begin(), full.pairs.end())) finding("pairs not sorted");
  for (const auto& p : full.pairs) {
    if (!(p[0] < p[1])) finding("a pair with i >= j");
    for (const std::uint32_t t : p) {
      if (std::binary_search(full.degenerate_triangles.begin(), full.degenerate_triangles.end(),
                             t)) {
        finding("a degenerate triangle in a pair");
      }
    }
  }
  antcd::SelfIntersectionRequest first;
  first.first_only = true;
  const antcd::SelfIntersectionResult one = antcd::self_intersections(model, first);
  if (one.intersecting != full.intersecting) finding("first_only disagrees on intersecting");
  if (one.pairs.size() != (full.intersecting ? 1u : 0u)) finding("first_only pair count");
  if (!one.pairs.empty() &&
      !std::binary_search(full.pairs.begin(), full.pairs.end(), one.pairs.front())) {
    finding("first_only reports a pair the full query does not");
  }
}

void check_proximity(const Model& model, Scalar delta) {
  const antcd::SelfProximityResult r = antcd::self_proximity(model, delta);
  const auto& tris = model.mesh().triangles;
  for (const antcd::SelfProximityPair& p : r.pairs) {
    if (!(p.distance <= delta) || !(p.distance >= 0)) finding("a proximity pair beyond delta");
    if (p.kind == antcd::SelfProximityPair::Kind::vertex_triangle) {
      if (p.b >= tris.size() || p.a >= model.mesh().vertices.size()) finding("index out of range");
      const auto& t = tris[p.b];
      if (t[0] == p.a || t[1] == p.a || t[2] == p.a) finding("a vertex paired with its triangle");
    } else {
      if (p.a >= r.edges.size() || p.b >= r.edges.size() || !(p.a < p.b)) {
        finding("edge pair indices");
      }
      const auto& ea = r.edges[p.a];
      const auto& eb = r.edges[p.b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) {
        finding("edges sharing a vertex paired");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in{data, size};
  const std::uint8_t head = in.byte();
  const bool raw = (head & 0x80) != 0;
  const std::size_t n = 4 + (head & 0x1F);
  const Scalar delta = in.byte() / 64.0;
  Mesh mesh;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = in.coordinate(raw), y = in.coordinate(raw), z = in.coordinate(raw);
    mesh.vertices.emplace_back(x, y, z);
  }
  const std::size_t triangles = std::min<std::size_t>(48, 1 + in.byte() % 48);
  for (std::size_t t = 0; t < triangles; ++t) {
    mesh.triangles.push_back({static_cast<std::uint32_t>(in.byte() % n),
                              static_cast<std::uint32_t>(in.byte() % n),
                              static_cast<std::uint32_t>(in.byte() % n)});
  }
  std::vector<Vec3> moved;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = in.coordinate(raw), y = in.coordinate(raw), z = in.coordinate(raw);
    moved.emplace_back(x, y, z);
  }
  try {
    Model model(mesh, {}, "fuzz");
    check_pairs(model, in_range(mesh.vertices));
    check_proximity(model, delta);
    const std::vector<Vec3> before = model.mesh().vertices;
    try {
      (void)model.refit(moved);
    } catch (const antcd::Error&) {
      if (model.mesh().vertices != before) finding("a refused refit changed the vertices");
      return 0;
    }
    const bool oracle = in_range(mesh.vertices) && in_range(moved);
    check_pairs(model, oracle);
    if (!oracle) return 0;
    Mesh moved_mesh = mesh;
    moved_mesh.vertices = moved;
    try {
      const Model fresh(moved_mesh, {}, "fuzz moved");
      if (intersections(model, true) != intersections(fresh, true)) {
        finding("refit and a fresh build disagree");
      }
    } catch (const antcd::Error&) {
      // A moved mesh with no triangle of non-zero area has no fresh Model to compare with.
    }
  } catch (const antcd::Error&) {
    // Refused input: accepted.
  } catch (const std::exception& e) {
    finding("unexpected exception", e.what());
  } catch (...) {
    finding("unexpected exception", "not a std::exception");
  }
  return 0;
}
