// libFuzzer target: the deforming sweeps (antcd/deform_ccd.hpp: deform_sweep's three forms and
// collision_free_step) and World::set_vertices on small meshes and motions made from arbitrary
// bytes (issue 41: the flexible-objects surfaces get fuzz targets).
//
// Input: byte 0 picks the vertex count of mesh A (3 .. 18), the form (self, against a second
// deforming mesh B, against a rigid B between two poses) and the coordinate mode (grid: small
// integers, so that coplanar, collinear, coincident and grazing geometry is common; raw: any
// double, NaN, infinity and 1e300 included); byte 1 the request (min_separation, time_tolerance,
// pose_path_tolerance, some of them invalid) and whether one position array is one vertex short;
// then A's triangles (a count byte, three index bytes each), A's positions at t = 0 and t = 1,
// and for the two-mesh forms B's vertex count, triangles and positions (B0, B1; or B's vertices
// and two poses from a table of exact rotations with grid translations). Per input at most 18 + 10
// vertices and 16 + 8 triangles: a few milliseconds.
//
// Findings: a crash, a sanitizer report, an exception other than antcd::Error, or a broken
// contract:
// - an ArgumentError exactly for bad input: a position array whose size is not the mesh's vertex
//   count, a coordinate that is not finite or beyond kDeformMaxCoordinate, min_separation < 0,
//   time_tolerance <= 0, pose_path_tolerance < 0, any of them not finite; in the rigid form also
//   "the scene is too large" (documented);
// - the result's shape: toi in [0, 1], 1 without a hit; the pair's indices in range, a self
//   vertex-face pair's vertex not a corner of its triangle, an edge-edge pair's edges sharing no
//   vertex (self) with ascending ends; all_pairs sorted, its first entry the first-hit answer
//   (unless a primitive exhausted its budget, the documented exception); collision_free_step ==
//   deform_sweep's toi;
// - time reversal (the motion V1 -> V0 meets exactly when V0 -> V1 does, at 1 - t): a miss in
//   one direction (a proof) and a proven hit (not tolerance_decided) in the other contradict; a
//   pair proven to touch one way is among all_pairs the other way;
// - the exact discrete tests, for grid input (within the exact predicates' range) whose meshes
//   have no zero-area triangle at t = 0: when the mesh does not intersect itself
//   (self_intersections) or the other mesh (collide) at t = 0 but does at t = 1, some vertex-face
//   or edge-edge pair meets in between: deform_sweep must report a hit.
// - World::set_vertices (A as a deforming object beside B): an ArgumentError exactly for a wrong
//   count, a non-finite coordinate, or a zero-area-at-build triangle gaining an area (the message
//   says "area"); a refused call changes nothing; after an accepted one collide_all answers as a
//   World built from the moved mesh.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/self.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "finding.hpp"
#include "reader.hpp"

namespace {

using antcd::DeformPair;
using antcd::DeformPairKind;
using antcd::DeformSweepRequest;
using antcd::DeformSweepResult;
using antcd::Mesh;
using antcd::Model;
using antcd::Scalar;
using antcd::Transform;
using antcd::Vec3;
using Positions = std::vector<Vec3>;

[[noreturn]] void finding(const char* what, const std::string& detail = "") {
  antcd::fuzz::finding("fuzz_deform_ccd", what, detail.c_str());
}

using antcd::fuzz::Reader;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

Positions read_positions(Reader& in, std::size_t n, bool raw) {
  Positions p;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = in.coordinate(raw), y = in.coordinate(raw), z = in.coordinate(raw);
    p.emplace_back(x, y, z);
  }
  return p;
}

/// A count byte (1 .. most triangles), then three index bytes (mod n) per triangle.
Triangles read_triangles(Reader& in, std::size_t n, std::size_t most) {
  Triangles t(1 + in.byte() % most);
  for (auto& tri : t) {
    for (auto& i : tri) i = static_cast<std::uint32_t>(in.byte() % n);
  }
  return t;
}

/// Positions deform_sweep accepts: finite, |x| <= kDeformMaxCoordinate.
bool acceptable(const Positions& p) {
  return std::all_of(p.begin(), p.end(), [](const Vec3& v) {
    return v.allFinite() && v.cwiseAbs().maxCoeff() <= antcd::kDeformMaxCoordinate;
  });
}

/// A Model of `triangles` at `positions`, or nothing when the mesh is refused (no triangle of
/// non-zero area, a non-finite coordinate).
std::shared_ptr<Model> model_at(const Triangles& triangles, const Positions& positions,
                                const char* name) {
  Mesh mesh;
  mesh.vertices = positions;
  mesh.triangles = triangles;
  try {
    return std::make_shared<Model>(mesh, antcd::BuildOptions{}, name);
  } catch (const antcd::Error&) {
    return nullptr;
  }
}

/// A Model that deform_sweep can take for these triangles: built at `positions` when possible,
/// else at fixed points in general position (deform_sweep reads only the triangles and the
/// hierarchy's topology, never the stored positions).
std::shared_ptr<Model> sweep_model(const Triangles& triangles, const Positions& positions,
                                   const char* name) {
  if (acceptable(positions)) {
    if (auto m = model_at(triangles, positions, name)) return m;
  }
  Positions general(positions.size());
  for (std::size_t i = 0; i < general.size(); ++i) {
    const double k = static_cast<double>(i);
    general[i] = Vec3(k, k * k, k * k * k);  // on the moment curve: no three collinear
  }
  return model_at(triangles, general, name);
}

/// Exact rotations (entries 0, +-1) and one with irrational entries.
Transform pose_from(std::uint8_t which, const Vec3& translation) {
  Transform t;
  switch (which % 5) {
    case 1:
      t.rotation << 1, 0, 0, 0, -1, 0, 0, 0, -1;
      break;  // half turn about x
    case 2:
      t.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
      break;  // quarter turn about z
    case 3:
      t.rotation << 0, 0, 1, 1, 0, 0, 0, 1, 0;
      break;  // cyclic permutation
    case 4:
      t = Transform::from_quaternion(translation, 0.8, 0.36, 0.48, 0);
      break;
    default:
      break;
  }
  t.translation = translation;
  return t;
}

struct Input {
  int form = 0;  // 0 self, 1 deforming B, 2 rigid B
  bool grid = true;
  DeformSweepRequest request;
  bool request_ok = true;
  int short_array = -1;  // which position array lost its last vertex (-1: none)
  Triangles ta, tb;
  Positions a0, a1, b0, b1;
  Transform pose0, pose1;
};

bool in_exact_range(const Positions& p) {
  for (const Vec3& v : p) {
    for (int k = 0; k < 3; ++k) {
      const double x = std::abs(v[k]);
      if (x != 0 && !(x >= 1e-75 && x <= 1e75)) return false;
    }
  }
  return true;
}

Input read_input(Reader& in) {
  Input s;
  const std::uint8_t head = in.byte();
  const std::size_t na = 3 + head % 16;
  s.form = (head >> 4) % 3;
  s.grid = (head & 0x80) == 0;
  const std::uint8_t req = in.byte();
  static constexpr double kSeparations[] = {0, 0, 0, 0.25, 1, -1, NAN, INFINITY};
  // Time tolerances from 1e-3 up: on coplanar grid meshes the primitives' cost rises steeply as
  // the tolerance shrinks (two inputs libFuzzer found, 9 vertices and 8 triangles or fewer: 1-2
  // ms per input at 1e-3, 30-60 ms at 1e-4 or 1e-6 in a release build, some 300 times that under
  // the sanitizers, past libFuzzer's timeout). The contracts checked do not depend on it.
  static constexpr double kTolerances[] = {1e-3, 1e-2, 0.1, 0.25, 1e-3, 1e-2, 0, -1};
  s.request.min_separation = kSeparations[req & 7];
  s.request.time_tolerance = kTolerances[(req >> 3) & 7];
  // Coarse chords for a turning rigid B (the default, 1e-3 of B's radius, cuts [0, 1] into tens
  // of pieces, each a sweep: seconds per input under the sanitizers).
  s.request.pose_path_tolerance = (req & 0x40) ? 0.5 : 0.1;
  s.request.all_pairs = false;
  s.request_ok = (req & 7) < 5 && ((req >> 3) & 7) < 6;
  if ((req & 0x80) && (req & 0x40)) s.short_array = (req >> 3) & 3;
  s.ta = read_triangles(in, na, 16);
  s.a0 = read_positions(in, na, !s.grid);
  s.a1 = read_positions(in, na, !s.grid);
  if (s.form != 0) {
    const std::size_t nb = 3 + in.byte() % 8;
    s.tb = read_triangles(in, nb, 8);
    s.b0 = read_positions(in, nb, !s.grid);
    if (s.form == 1) {
      s.b1 = read_positions(in, nb, !s.grid);
    } else {
      const std::uint8_t r = in.byte();
      s.pose0 = pose_from(r, read_positions(in, 1, !s.grid)[0]);
      s.pose1 = pose_from(r >> 4, read_positions(in, 1, !s.grid)[0]);
    }
  }
  return s;
}

/// Every vertex index the pair names is in range, and the pair is well formed.
void check_pair(const DeformPair& p, const Input& s, const char* where) {
  if (!(p.toi >= 0 && p.toi <= 1)) finding("a pair's toi outside [0, 1]", where);
  if (p.budget_exhausted && !p.tolerance_decided)
    finding("budget_exhausted without tolerance_decided");
  const std::size_t na = s.a0.size();
  const std::size_t nb = s.form == 0 ? na : s.b0.size();
  const bool self = s.form == 0;
  if (p.kind == DeformPairKind::VertexFace) {
    const bool vertex_in_a = self || p.vertex_in_first;
    const std::size_t nv = vertex_in_a ? na : nb;
    const auto& tris = (self || !p.vertex_in_first) ? s.ta : s.tb;
    if (p.indices[0] >= nv || p.indices[1] >= tris.size())
      finding("vertex-face index out of range");
    const auto& t = tris[p.indices[1]];
    if (self && (t[0] == p.indices[0] || t[1] == p.indices[0] || t[2] == p.indices[0])) {
      finding("a vertex paired with its own triangle");
    }
  } else {
    if (!(p.indices[0] < p.indices[1]) || !(p.indices[2] < p.indices[3])) {
      finding("an edge's ends not ascending");
    }
    if (p.indices[1] >= na || p.indices[3] >= nb) finding("edge-edge index out of range");
    if (self) {
      for (int i = 0; i < 2; ++i) {
        for (int j = 2; j < 4; ++j) {
          if (p.indices[static_cast<std::size_t>(i)] == p.indices[static_cast<std::size_t>(j)]) {
            finding("edges sharing a vertex paired");
          }
        }
      }
      if (!(std::tie(p.indices[0], p.indices[1]) < std::tie(p.indices[2], p.indices[3]))) {
        finding("self edge pair not in order");
      }
    }
  }
}

std::string describe(const DeformPair& p) {
  char text[160];
  std::snprintf(text, sizeof text, "%s%s (%u %u %u %u) toi %.17g%s",
                p.kind == DeformPairKind::VertexFace ? "vertex-face" : "edge-edge",
                p.vertex_in_first ? "" : " (vertex in b)", p.indices[0], p.indices[1], p.indices[2],
                p.indices[3], p.toi, p.tolerance_decided ? " tolerance" : "");
  return text;
}

auto pair_key(const DeformPair& p) { return std::make_tuple(p.kind, p.vertex_in_first, p.indices); }

void check_result(const DeformSweepResult& r, const Input& s, const char* where) {
  if (!r.hit && r.toi != 1) finding("a miss with toi != 1", where);
  if (!(r.toi >= 0 && r.toi <= 1)) finding("toi outside [0, 1]", where);
  if (r.hit) {
    check_pair(r.pair, s, where);
    if (r.pair.toi != r.toi || r.pair.tolerance_decided != r.tolerance_decided) {
      finding("the result disagrees with its pair", where);
    }
  }
  for (const DeformPair& p : r.pairs) check_pair(p, s, where);
  // (toi, kind, vertex_in_first, indices) with the pairs whose vertex is the first mesh's first,
  // as the library orders them.
  const auto earlier = [](const DeformPair& x, const DeformPair& y) {
    return std::make_tuple(x.toi, x.kind, !x.vertex_in_first, x.indices) <
           std::make_tuple(y.toi, y.kind, !y.vertex_in_first, y.indices);
  };
  const auto unsorted = std::is_sorted_until(r.pairs.begin(), r.pairs.end(), earlier);
  if (unsorted != r.pairs.end()) {
    finding("all_pairs not sorted", describe(*(unsorted - 1)) + " before " + describe(*unsorted));
  }
}

/// Runs the form of `s` from `first` to `second` (a's positions; b's likewise, or the poses).
DeformSweepResult run(const Input& s, const Model& a, const Model* b, bool reversed,
                      bool all_pairs) {
  DeformSweepRequest request = s.request;
  request.all_pairs = all_pairs;
  const Positions& a0 = reversed ? s.a1 : s.a0;
  const Positions& a1 = reversed ? s.a0 : s.a1;
  if (s.form == 0) return antcd::deform_sweep(a, a0, a1, request);
  if (s.form == 1) {
    return antcd::deform_sweep(a, a0, a1, *b, reversed ? s.b1 : s.b0, reversed ? s.b0 : s.b1,
                               request);
  }
  return antcd::deform_sweep(a, a0, a1, *b, s.pose0, s.pose1, request);
}

bool any_budget_exhausted(const DeformSweepResult& r) {
  return std::any_of(r.pairs.begin(), r.pairs.end(),
                     [](const DeformPair& p) { return p.budget_exhausted; });
}

/// Time reversal: forward and backward must agree on whether a contact is proven to exist.
void check_reversal(const DeformSweepResult& fwd, const DeformSweepResult& bwd) {
  for (const auto* pair : {&fwd, &bwd}) {
    const DeformSweepResult& one = *pair;
    const DeformSweepResult& other = pair == &fwd ? bwd : fwd;
    for (const DeformPair& p : one.pairs) {
      if (p.tolerance_decided) continue;
      if (!other.hit) finding("a miss (a proof) against a proven hit of the reversed motion");
      const bool found =
          std::any_of(other.pairs.begin(), other.pairs.end(),
                      [&](const DeformPair& q) { return pair_key(q) == pair_key(p); });
      if (!found) finding("a proven pair missing from the reversed motion's all_pairs");
    }
  }
}

bool has_degenerate(const Model& m) {
  return !antcd::self_intersections(m).degenerate_triangles.empty();
}

/// The discrete oracle: free at t = 0 and intersecting at t = 1 needs a hit in between.
void check_discrete(const Input& s, const DeformSweepResult& r) {
  if (!s.grid || !in_exact_range(s.a0) || !in_exact_range(s.a1)) return;
  const auto a_start = model_at(s.ta, s.a0, "a at t=0");
  const auto a_end = model_at(s.ta, s.a1, "a at t=1");
  if (!a_start || !a_end || has_degenerate(*a_start)) return;
  if (s.form == 0) {
    antcd::SelfIntersectionRequest first;
    first.first_only = true;
    if (!antcd::self_intersections(*a_start, first).intersecting &&
        antcd::self_intersections(*a_end, first).intersecting && !r.hit) {
      finding("free at t = 0, self-intersecting at t = 1, and deform_sweep reports a miss");
    }
    return;
  }
  const Transform id;
  const auto b_start = model_at(s.tb, s.b0, "b at t=0");
  if (!b_start || has_degenerate(*b_start) || !in_exact_range(s.b0)) return;
  std::shared_ptr<Model> b_end = b_start;
  Transform pose0 = id, pose1 = id;
  if (s.form == 1) {
    b_end = model_at(s.tb, s.b1, "b at t=1");
    if (!b_end || !in_exact_range(s.b1)) return;
  } else {
    pose0 = s.pose0;
    pose1 = s.pose1;
  }
  if (!antcd::collide(*a_start, id, *b_start, pose0).colliding &&
      antcd::collide(*a_end, id, *b_end, pose1).colliding && !r.hit) {
    finding("apart at t = 0, colliding at t = 1, and deform_sweep reports a miss");
  }
}

void check_sweeps(const Input& s) {
  const auto a = sweep_model(s.ta, s.a0, "a");
  if (!a) return;  // no triangle of non-zero area in any position: no Model to sweep
  std::shared_ptr<Model> b;
  if (s.form != 0) {
    b = s.form == 1 ? sweep_model(s.tb, s.b0, "b") : model_at(s.tb, s.b0, "b");
    if (!b) return;
  }
  Input t = s;
  bool bad = !s.request_ok || !acceptable(s.a0) || !acceptable(s.a1);
  if (s.form == 1) bad = bad || !acceptable(s.b0) || !acceptable(s.b1);
  if (s.form == 2) {
    bad = bad || !s.pose0.rotation.allFinite() || !s.pose0.translation.allFinite() ||
          !s.pose1.rotation.allFinite() || !s.pose1.translation.allFinite();
  }
  if (s.short_array >= 0) {
    Positions* arrays[] = {&t.a0, &t.a1, &t.b0, &t.b1};
    Positions* p = arrays[s.short_array];
    if (!p->empty() && !(s.form != 1 && s.short_array >= 2)) {
      p->pop_back();
      bad = true;
    }
  }
  DeformSweepResult fwd;
  try {
    fwd = run(t, *a, b.get(), false, false);
  } catch (const antcd::ArgumentError& e) {
    const bool too_large = s.form == 2 && std::strstr(e.what(), "too large") != nullptr;
    if (!bad && !too_large) finding("an ArgumentError for valid input", e.what());
    return;
  }
  if (bad) finding("bad input accepted");
  check_result(fwd, s, "first hit");
  const DeformSweepResult all = run(s, *a, b.get(), false, true);
  check_result(all, s, "all pairs");
  if (all.hit != fwd.hit) finding("all_pairs and first-hit disagree on hit");
  if (all.hit && all.pairs.empty()) finding("all_pairs: a hit without pairs");
  if (fwd.hit && !any_budget_exhausted(all) &&
      (all.pairs.front().toi != fwd.toi || pair_key(all.pairs.front()) != pair_key(fwd.pair))) {
    finding("the first hit is not all_pairs' first entry");
  }
  if (s.form == 0) {
    const Scalar step = antcd::collision_free_step(*a, s.a0, s.a1, s.request.min_separation,
                                                   s.request.time_tolerance);
    if (step != fwd.toi) finding("collision_free_step differs from deform_sweep's toi");
  }
  if (s.form != 2) check_reversal(all, run(s, *a, b.get(), true, true));
  check_discrete(s, fwd);
}

/// World::set_vertices on A (a deforming object) beside B.
void check_world(const Input& s) {
  const auto a = model_at(s.ta, s.a0, "a");
  const auto b = model_at(s.form == 0 ? s.ta : s.tb, s.form == 0 ? s.a1 : s.b0, "b");
  if (!a || !b) return;
  antcd::World world;
  const antcd::ObjectId ia = world.add(a, Transform{});
  const antcd::ObjectId ib = world.add(b, Transform{});
  const auto pairs_of = [](const antcd::World& w) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const antcd::PairContacts& p : w.collide_all()) out.emplace_back(p.a.slot, p.b.slot);
    return out;
  };
  const auto before = pairs_of(world);
  Positions moved = s.a1;
  const bool short_count = s.short_array >= 0 && !moved.empty();
  if (short_count) moved.pop_back();
  const bool finite =
      std::all_of(moved.begin(), moved.end(), [](const Vec3& v) { return v.allFinite(); });
  try {
    world.set_vertices(ia, moved);
  } catch (const antcd::ArgumentError& e) {
    if (!short_count && finite && std::strstr(e.what(), "area") == nullptr) {
      finding("World::set_vertices refused valid positions", e.what());
    }
    if (world.model(ia).mesh().vertices != s.a0) finding("a refused set_vertices changed the mesh");
    if (pairs_of(world) != before) finding("a refused set_vertices changed collide_all");
    return;
  }
  if (short_count || !finite) finding("World::set_vertices accepted a wrong count or a NaN");
  if (world.model(ia).mesh().vertices != moved) finding("set_vertices did not store the positions");
  if (!s.grid || !in_exact_range(moved) || !in_exact_range(s.a0)) return;
  // (A triangle that lost its area stays in the refitted hierarchy but not in a fresh one: such
  // meshes are left out of the comparison, as are raw coordinates, for the exact range.)
  const auto fresh = model_at(s.ta, moved, "a moved");
  if (!fresh || has_degenerate(*fresh) || has_degenerate(*a)) return;
  antcd::World rebuilt;
  (void)rebuilt.add(fresh, Transform{});
  (void)rebuilt.add(b, Transform{});
  if (pairs_of(world) != pairs_of(rebuilt)) finding("set_vertices and a fresh World disagree");
  (void)ib;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in{data, size};
  const Input s = read_input(in);
  try {
    check_sweeps(s);
    check_world(s);
  } catch (const antcd::Error& e) {
    finding("an antcd error where none was documented", e.what());
  } catch (const std::exception& e) {
    finding("unexpected exception", e.what());
  } catch (...) {
    finding("unexpected exception", "not a std::exception");
  }
  return 0;
}
