// Embind bindings of the core for the npm package `antcd` (wasm/index.mjs wraps them in the
// documented JS API; index.d.ts states it). The package's C ABI: its pose block, output block,
// error buffer and checked allocation stay in this file; the functions other export files use (the
// deforming sweeps, bind_deform.cpp; the World, bind_world.cpp) are declared in abi.hpp, the
// globals themselves never leave it. Each export is a thin call of the library. The two hot
// queries, antcd_collide and antcd_distance, are raw exports (Module._antcd_collide: no Embind
// call wrapper; a rejected query from node fell from about 1.2 to 0.55 us); models are passed by
// id (the table g_models), World objects by handle.
//
// Calling convention (one thread, as in every Emscripten build without pthreads):
// - Poses: JS writes up to kPoseSlots column-major 4x4 matrices (16 doubles each, three.js
//   Matrix4.elements order) into the input block at poseBlock(); functions read pose k from slot k.
//   Calls taking any number of poses (World.sweepMotion) get them in a block JS allocated.
// - Results: a function fills the output block (at antcd_out_block(), a reused vector: no
//   allocation once it has grown) and returns a count, or -1 after an error whose one-line
//   message lastError() gives.
//   Contacts are records of kContactStride doubles (see write_contact).
// - Handles of World objects are doubles: slot + generation * 2^32 (exact below 2^53).
// - Memory: when WebAssembly memory runs out (malloc returns 0, operator new throws bad_alloc),
//   every function returns -1 with the message "<function>: out of WebAssembly memory ...",
//   composed in a fixed buffer without allocating (antcd_last_error() points at it), and nothing
//   is left half made: the module keeps answering. Strings cross by pointer and length into
//   buffers the JS side allocated and checked (Embind's own string marshalling would write through
//   an unchecked malloc).
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/penetration.hpp>
#include <antcd/pose.hpp>
#include <antcd/self.hpp>
#include <antcd/sweep.hpp>
#include <antcd/version.hpp>

#include <emscripten/bind.h>
#include <emscripten/emscripten.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "abi.hpp"

namespace {

using namespace antcd;
using namespace antcd::wasm;

constexpr int kPoseSlots = 4;

double g_poses[kPoseSlots * 16];
// Per slot, the last pose that passed pose_at's check, so that a pose repeated from call to call
// (a static object) is not checked again: equal numbers, the same verdict. The check of a changed
// pose was, with the JS call itself, most of a culled query's time (spider against Wuson).
double g_checked[kPoseSlots * 16];
bool g_checked_valid[kPoseSlots] = {};
std::vector<double> g_out;
// The last error message, NUL-terminated (bounded: one printable line).
constexpr std::size_t kErrorBytes = 512;
char g_error[kErrorBytes] = {};
CollisionResult g_collision;
constexpr const char* kOutOfMemory =
    "out of WebAssembly memory (delete() the models and Worlds no longer needed)";

// Sets the message to the parts' concatenation, truncated to the buffer; allocates nothing (it
// runs when memory has run out). Returns -1.
int fail(std::string_view first, std::string_view second = {}, std::string_view third = {}) {
  std::size_t n = 0;
  for (const std::string_view part : {first, second, third}) {
    const std::size_t k = std::min(part.size(), kErrorBytes - 1 - n);
    std::memcpy(g_error + n, part.data(), k);
    n += k;
  }
  g_error[n] = '\0';
  return -1;
}

}  // namespace

namespace antcd::wasm {

// The message of exception `e` thrown in `function`: "<function>: <what>" (once), or the
// out-of-memory message; allocates nothing. Returns -1.
int fail_with(const char* function, const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr) return fail(function, ": ", kOutOfMemory);
  const std::string_view what = e.what();
  if (what.rfind(function, 0) == 0) return fail(what);
  return fail(function, ": ", what);
}

namespace {

Transform transform_of(const double* m) {
  Transform t;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) t.rotation(r, c) = m[4 * c + r];
  }
  t.translation = Vec3(m[12], m[13], m[14]);
  return t;
}

}  // namespace

Transform rigid_pose(const double* m, const char* function, const std::string& what) {
  const Transform t = transform_of(m);
  const PoseCheck c = check_pose(t, m[3], m[7], m[11], m[15]);
  if (!c.rigid()) throw ArgumentError(std::string(function) + ": " + what + " " + c.problem());
  return t;
}

// Pose k of the input block as a rigid Transform; throws ArgumentError naming `what`.
Transform pose_at(int k, const char* function, const char* what) {
  const double* m = g_poses + 16 * k;
  double* checked = g_checked + 16 * k;
  if (g_checked_valid[k]) {
    bool same = true;
    for (int i = 0; i < 16; ++i) same &= m[i] == checked[i];  // a NaN is never equal
    if (same) return transform_of(m);
  }
  g_checked_valid[k] = false;
  const Transform t = rigid_pose(m, function, what);
  std::copy(m, m + 16, checked);
  g_checked_valid[k] = true;
  return t;
}

void read_vec3s(std::uintptr_t at, bool f32, std::vector<Vec3>& out) {
  const std::size_t n = out.size();
  if (f32) {
    const auto* p = reinterpret_cast<const float*>(at);
    for (std::size_t i = 0; i < n; ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  } else {
    const auto* p = reinterpret_cast<const double*>(at);
    for (std::size_t i = 0; i < n; ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  }
}

double* out_resize(std::size_t n) {
  if (g_out.size() < n) g_out.resize(n);
  return g_out.data();
}

void write_vec(double* out, const Vec3& v) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

void write_contact(double* out, const Contact& c) {
  out[0] = c.triangle_a;
  out[1] = c.triangle_b;
  write_vec(out + 2, c.point);
  out[5] = c.distance;
  write_vec(out + 6, c.normal);
  out[9] = c.depth;
}

std::uint32_t positive_count(double v, const char* name) {
  if (!(v >= 1 && v <= 4294967295.0) || v != std::floor(v)) {
    throw ArgumentError(std::string(name) + " " + number_text(v) +
                        " is not an integer in [1, 2^32)");
  }
  return static_cast<std::uint32_t>(v);
}

CollisionRequest collision_request(bool all_contacts, double delta, bool normals,
                                   double max_contacts) {
  CollisionRequest r;
  r.all_contacts = all_contacts;
  r.delta = delta;
  r.contact_normals = normals;
  if (!(max_contacts >= 0) || max_contacts != std::floor(max_contacts)) {
    throw ArgumentError("maxContacts " + number_text(max_contacts) +
                        " is not a non-negative integer");
  }
  r.max_contacts = static_cast<std::size_t>(max_contacts);
  return r;
}

void write_sweep(double* out, const SweepResult& s) {
  out[0] = s.toi;
  out[1] = s.distance;
  out[2] = s.motion_bound;
  out[3] = s.iterations;
  out[4] = (s.hit ? 1 : 0) + (s.tolerance_decided ? 2 : 0) + (s.budget_exhausted ? 4 : 0);
  write_contact(out + 5, s.contact);
}

}  // namespace antcd::wasm

namespace {

// Models by id (a JS Model holds its id), shared with the Worlds they were added to: JS may
// release a model while a World still uses it. Held as mutable Models for Model.setVertices
// (Model::refit), which refuses a model a World also holds (use_count() > 1).
std::vector<std::shared_ptr<Model>> g_models;
std::vector<int> g_free_ids;

int register_model(std::shared_ptr<Model> m) {
  if (!g_free_ids.empty()) {
    const int id = g_free_ids.back();
    g_free_ids.pop_back();
    g_models[static_cast<std::size_t>(id)] = std::move(m);
    return id;
  }
  g_models.push_back(std::move(m));
  return static_cast<int>(g_models.size()) - 1;
}

}  // namespace

namespace antcd::wasm {

const std::shared_ptr<Model>& model_ref(int id, const char* what) {
  if (id < 0 || static_cast<std::size_t>(id) >= g_models.size() ||
      !g_models[static_cast<std::size_t>(id)]) {
    throw ArgumentError(std::string(what) + " is not a live model");
  }
  return g_models[static_cast<std::size_t>(id)];
}

}  // namespace antcd::wasm

namespace {

// positions: n_coords numbers (float32 when f32, else float64) at `positions`; indices: n_indices
// uint32 at `indices` (the JS wrapper converted and range-checked the types).
// name: n_name UTF-8 bytes at `name_bytes`.
int model_create(std::uintptr_t positions, double n_coords, bool f32, std::uintptr_t indices,
                 double n_indices, std::uintptr_t name_bytes, double n_name) {
  try {
    const std::string name(reinterpret_cast<const char*>(name_bytes),
                           static_cast<std::size_t>(n_name));
    Mesh mesh;
    const auto nv = static_cast<std::size_t>(n_coords) / 3;
    const auto nt = static_cast<std::size_t>(n_indices) / 3;
    mesh.vertices.resize(nv);
    read_vec3s(positions, f32, mesh.vertices);
    const auto* ix = reinterpret_cast<const std::uint32_t*>(indices);
    mesh.triangles.resize(nt);
    for (std::size_t i = 0; i < nt; ++i)
      mesh.triangles[i] = {ix[3 * i], ix[3 * i + 1], ix[3 * i + 2]};
    return register_model(std::make_shared<Model>(std::move(mesh), BuildOptions{}, name));
  } catch (const std::exception& e) {
    return fail_with("Model", e);
  }
}

// Models built from the generated shapes of mesh.hpp (the same meshes as the native library's).
// kind: 0 box, 1 sphere, 2 cylinder, 3 torus.
int model_shape(int kind, double a, double b, double c, int n1, int n2) {
  static constexpr const char* kFunctions[] = {"Model.box", "Model.sphere", "Model.cylinder",
                                               "Model.torus"};
  if (kind < 0 || kind > 3) return fail("Model: shape code is not box, sphere, cylinder or torus");
  try {
    Mesh mesh;
    if (kind == 0) {
      mesh = make_box(Vec3(a, b, c), n1);
    } else if (kind == 1) {
      mesh = make_sphere(a, n1, n2);
    } else if (kind == 2) {
      mesh = make_cylinder(a, b, n1, n2);
    } else {
      mesh = make_torus(a, b, n1, n2);
    }
    static constexpr const char* kNames[] = {"box", "sphere", "cylinder", "torus"};
    return register_model(std::make_shared<Model>(std::move(mesh), BuildOptions{}, kNames[kind]));
  } catch (const std::exception& e) {
    return fail_with(kFunctions[kind], e);
  }
}

int write_mesh(const Mesh& mesh) {
  double* out = out_resize(2 + 3 * mesh.vertices.size() + 3 * mesh.triangles.size());
  out[0] = static_cast<double>(mesh.vertices.size());
  out[1] = static_cast<double>(mesh.triangles.size());
  double* p = out + 2;
  for (const Vec3& v : mesh.vertices) {
    write_vec(p, v);
    p += 3;
  }
  for (const TriangleIndices& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) *p++ = t[static_cast<std::size_t>(k)];
  }
  return 1;
}

void model_release(int id) {
  if (id >= 0 && static_cast<std::size_t>(id) < g_models.size() &&
      g_models[static_cast<std::size_t>(id)]) {
    g_models[static_cast<std::size_t>(id)].reset();
    g_free_ids.push_back(id);
  }
}

// Out: triangle count, vertex count, closed (0/1), degenerate triangles, refit growth.
int model_info(int id) {
  return guarded("Model", [&] {
    const Model& m = *model_ref(id, "this");
    double* out = out_resize(5);
    out[0] = static_cast<double>(m.mesh().triangles.size());
    out[1] = static_cast<double>(m.mesh().vertices.size());
    out[2] = m.is_closed() ? 1 : 0;
    out[3] = static_cast<double>(m.stats().degenerate_triangles);
    out[4] = m.refit_growth();
    return 1;
  });
}

// New vertex positions (Model::refit): n_coords numbers (float32 when f32, else float64) at
// `positions`, three per vertex, as many vertices as the model has. Everything is checked before
// the model changes; a model held by a World is refused (the World's broad phase keeps boxes of
// the current positions).
int model_set_vertices(int id, std::uintptr_t positions, double n_coords, bool f32) {
  return guarded("Model.setVertices", [&] {
    const std::shared_ptr<Model>& m = model_ref(id, "this");
    const std::size_t nv = m->mesh().vertices.size();
    if (n_coords != 3.0 * static_cast<double>(nv)) {
      throw ArgumentError("positions has " + number_text(n_coords) + " numbers, the model has " +
                          std::to_string(nv) + " vertices (" + std::to_string(3 * nv) + ")");
    }
    if (m.use_count() > 1) {
      throw ArgumentError("model '" + m->source() +
                          "' is held by a World, whose broad phase keeps the bounds of its current "
                          "positions; give the World's object new positions with "
                          "World.setVertices, or remove it from the World first");
    }
    std::vector<Vec3> v(nv);
    read_vec3s(positions, f32, v);
    for (std::size_t i = 0; i < nv; ++i) {
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(v[i][c])) {
          throw ArgumentError("positions[" + std::to_string(3 * i + c) +
                              "] = " + number_text(v[i][c]) + " is not finite");
        }
      }
    }
    m->refit(v);
    return 0;
  });
}

// Out: intersecting (0/1), pair count k, degenerate count d, the 7 counters of
// SelfIntersectionStats in declaration order, k pairs (i, j), d triangle indices.
int wasm_self_intersections(int id, bool first_only) {
  return guarded("selfIntersections", [&] {
    SelfIntersectionRequest request;
    request.first_only = first_only;
    const SelfIntersectionResult r = self_intersections(*model_ref(id, "model"), request);
    const std::size_t k = r.pairs.size();
    const std::size_t d = r.degenerate_triangles.size();
    double* out = out_resize(10 + 2 * k + d);
    out[0] = r.intersecting ? 1 : 0;
    out[1] = static_cast<double>(k);
    out[2] = static_cast<double>(d);
    const SelfIntersectionStats& s = r.stats;
    const std::uint64_t counters[] = {s.node_pairs,      s.volume_rejects, s.triangle_pairs,
                                      s.adjacent_pairs,  s.cone_culled,    s.cone_tests,
                                      s.cone_cache_bytes};
    for (int c = 0; c < 7; ++c) out[3 + c] = static_cast<double>(counters[c]);
    double* p = out + 10;
    for (const auto& pair : r.pairs) {
      *p++ = pair[0];
      *p++ = pair[1];
    }
    for (const std::uint32_t t : r.degenerate_triangles) *p++ = t;
    return 1;
  });
}

// Out: edge count e, vertex-triangle count, edge-edge count, e edges (lower, higher), then per
// pair (vertex-triangle ones first): a, b, distance, point_a (3), point_b (3).
int wasm_self_proximity(int id, double delta) {
  return guarded("selfProximity", [&] {
    const SelfProximityResult r = self_proximity(*model_ref(id, "model"), delta);
    const std::size_t e = r.edges.size();
    double* out = out_resize(3 + 2 * e + 9 * r.pairs.size());
    std::size_t vertex_triangle = 0;
    for (const SelfProximityPair& q : r.pairs) {
      if (q.kind == SelfProximityPair::Kind::vertex_triangle) ++vertex_triangle;
    }
    out[0] = static_cast<double>(e);
    out[1] = static_cast<double>(vertex_triangle);
    out[2] = static_cast<double>(r.pairs.size() - vertex_triangle);
    double* p = out + 3;
    for (const auto& edge : r.edges) {
      *p++ = edge[0];
      *p++ = edge[1];
    }
    for (const SelfProximityPair& q : r.pairs) {
      p[0] = q.a;
      p[1] = q.b;
      p[2] = q.distance;
      write_vec(p + 3, q.point_a);
      write_vec(p + 6, q.point_b);
      p += 9;
    }
    return 1;
  });
}

}  // namespace

// The model's name, NUL-terminated UTF-8 (the model's own string: nothing is allocated), or "".
extern "C" EMSCRIPTEN_KEEPALIVE std::uintptr_t antcd_model_name(int id) {
  static const char kNone[] = "";
  return reinterpret_cast<std::uintptr_t>(
      id >= 0 && static_cast<std::size_t>(id) < g_models.size() &&
              g_models[static_cast<std::size_t>(id)]
          ? g_models[static_cast<std::size_t>(id)]->source().c_str()
          : kNone);
}

// The last error message, NUL-terminated UTF-8 (a fixed buffer).
extern "C" EMSCRIPTEN_KEEPALIVE std::uintptr_t antcd_last_error() {
  return reinterpret_cast<std::uintptr_t>(g_error);
}

namespace {

// The mesh of a model into the output block: vertex count, triangle count, coordinates, indices.
int model_mesh(int id) {
  return guarded("Model.mesh", [&] { return write_mesh(model_ref(id, "this")->mesh()); });
}

}  // namespace

// Poses 0 (a) and 1 (b). Returns 0 when apart, 1 + the number of contact records written when
// colliding (a boolean query writes at most one; a volume containment none), or -1.
// flags: 1 all contacts, 2 contact normals, 4 volume. A raw export (no Embind wrapper): the hot
// path from JS.
extern "C" EMSCRIPTEN_KEEPALIVE int antcd_collide(int a, int b, int flags, double delta,
                                                  double max_contacts) {
  return guarded("collide", [&] {
    CollisionRequest r = collision_request((flags & 1) != 0, delta, (flags & 2) != 0, max_contacts);
    r.volume = (flags & 4) != 0;
    const Model& ma = *model_ref(a, "a");
    const Model& mb = *model_ref(b, "b");
    const Transform pa = pose_at(0, "collide", "poseA");
    const Transform pb = pose_at(1, "collide", "poseB");
    antcd::collide(ma, pa, mb, pb, r, g_collision);
    if (!g_collision.colliding) return 0;
    double* out = out_resize(kContactStride * g_collision.contacts.size());
    for (const Contact& c : g_collision.contacts) {
      write_contact(out, c);
      out += kContactStride;
    }
    return static_cast<int>(g_collision.contacts.size()) + 1;
  });
}

// Out: distance, lower_bound, point_a (3), point_b (3), triangle_a, triangle_b, flags
// (1 intersecting, 2 approximate, 4 beyond_upper_bound).
extern "C" EMSCRIPTEN_KEEPALIVE int antcd_distance(int a, int b, double upper_bound,
                                                   double abs_tolerance, double rel_tolerance,
                                                   int signed_distance) {
  return guarded("distance", [&] {
    DistanceRequest r;
    r.upper_bound = upper_bound;
    r.abs_tolerance = abs_tolerance;
    r.rel_tolerance = rel_tolerance;
    const Model& ma = *model_ref(a, "a");
    const Model& mb = *model_ref(b, "b");
    const Transform pa = pose_at(0, "distance", "poseA");
    const Transform pb = pose_at(1, "distance", "poseB");
    const DistanceResult d = signed_distance != 0 ? antcd::signed_distance(ma, pa, mb, pb, r)
                                                  : antcd::distance(ma, pa, mb, pb, r);
    double* out = out_resize(11);
    out[0] = d.distance;
    out[1] = d.lower_bound;
    write_vec(out + 2, d.point_a);
    write_vec(out + 5, d.point_b);
    out[8] = d.triangle_a;
    out[9] = d.triangle_b;
    out[10] = (d.intersecting ? 1 : 0) + (d.approximate ? 2 : 0) + (d.beyond_upper_bound ? 4 : 0);
    return 1;
  });
}

// The output block's address (it moves when the block grows): a raw export, read after every query.
extern "C" EMSCRIPTEN_KEEPALIVE std::uintptr_t antcd_out_block() {
  return reinterpret_cast<std::uintptr_t>(g_out.data());
}

namespace {

// Poses 0, 1 (A at t = 0, 1) and 2, 3 (B). Out: the sweep record (write_sweep).
int wasm_sweep(int a, int b, double min_separation, double time_tolerance, double max_iterations) {
  return guarded("sweep", [&] {
    SweepRequest r;
    r.min_separation = min_separation;
    r.time_tolerance = time_tolerance;
    r.max_iterations = positive_count(max_iterations, "maxIterations");
    const SweepResult s = antcd::sweep(
        *model_ref(a, "a"), pose_at(0, "sweep", "poseA0"), pose_at(1, "sweep", "poseA1"),
        *model_ref(b, "b"), pose_at(2, "sweep", "poseB0"), pose_at(3, "sweep", "poseB1"), r);
    write_sweep(out_resize(kSweepStride), s);
    return 1;
  });
}

// Poses 0, 1. shape: 0 auto, 1 convex, 2 general. Out: lower, upper, direction (3), witness (3),
// point_a (3), point_b (3), evaluations, flags (1 overlapping, 2 exact, 4 converged).
int wasm_penetration(int a, int b, int shape, double abs_tolerance, double rel_tolerance,
                     double max_evaluations) {
  return guarded("penetration", [&] {
    PenetrationRequest r;
    if (shape < 0 || shape > 2) throw ArgumentError("shape must be 'auto', 'convex' or 'general'");
    r.shape = static_cast<PenetrationRequest::Shape>(shape);
    r.abs_tolerance = abs_tolerance;
    r.rel_tolerance = rel_tolerance;
    r.max_evaluations = positive_count(max_evaluations, "maxEvaluations");
    const PenetrationResult p =
        antcd::penetration(*model_ref(a, "a"), pose_at(0, "penetration", "poseA"),
                           *model_ref(b, "b"), pose_at(1, "penetration", "poseB"), r);
    double* out = out_resize(16);
    out[0] = p.lower;
    out[1] = p.upper;
    write_vec(out + 2, p.direction);
    write_vec(out + 5, p.witness);
    write_vec(out + 8, p.point_a);
    write_vec(out + 11, p.point_b);
    out[14] = p.evaluations;
    out[15] = (p.overlapping ? 1 : 0) + (p.exact ? 2 : 0) + (p.converged ? 4 : 0);
    return 1;
  });
}

std::uintptr_t alloc_bytes(double n) {
  return reinterpret_cast<std::uintptr_t>(std::malloc(static_cast<std::size_t>(n)));
}
void free_bytes(std::uintptr_t p) { std::free(reinterpret_cast<void*>(p)); }
std::uintptr_t pose_block() { return reinterpret_cast<std::uintptr_t>(g_poses); }

std::string version() { return kVersion; }

}  // namespace

EMSCRIPTEN_BINDINGS(antcd_core) {
  using namespace emscripten;
  function("modelCreate", &model_create);
  function("modelShape", &model_shape);
  function("modelMesh", &model_mesh);
  function("modelRelease", &model_release);
  function("modelInfo", &model_info);
  function("modelSetVertices", &model_set_vertices);
  function("selfIntersections", &wasm_self_intersections);
  function("selfProximity", &wasm_self_proximity);
  function("sweep", &wasm_sweep);
  function("penetration", &wasm_penetration);
  function("allocBytes", &alloc_bytes);
  function("freeBytes", &free_bytes);
  function("poseBlock", &pose_block);
  function("version", &version);
  constant("poseSlots", kPoseSlots);
  constant("contactStride", kContactStride);
}
