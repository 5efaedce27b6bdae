// Embind export of antcd::World for the npm package (wasm/world.mjs wraps it): objects added,
// moved, deformed (setVertices, selfCollision) and removed; collideAll, pairsWithin, raycast; the
// continuous motion of rigid and deforming objects (sweepMotion, setMotionContinuous over
// World::sweep_motion and set_motion_continuous). The calling convention, the output block and the
// error handling are bindings.cpp's (abi.hpp).
#include <antcd/error.hpp>
#include <antcd/world.hpp>

#include <emscripten/bind.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "abi.hpp"

namespace {

using namespace antcd;
using namespace antcd::wasm;

constexpr double kGenerationScale = 4294967296.0;   // 2^32
constexpr std::uint32_t kMaxGeneration = 1U << 20;  // handles stay below 2^52

double handle_of(ObjectId id) { return id.slot + id.generation * kGenerationScale; }

// `handle` as an ObjectId; throws ArgumentError "<what> <handle> is not an object handle".
ObjectId id_of(double handle, const std::string& what) {
  if (!(handle >= 0 && handle < kMaxGeneration * kGenerationScale) ||
      handle != std::floor(handle)) {
    throw ArgumentError(what + " " + number_text(handle) + " is not an object handle");
  }
  const double gen = std::floor(handle / kGenerationScale);
  return ObjectId{static_cast<std::uint32_t>(handle - gen * kGenerationScale),
                  static_cast<std::uint32_t>(gen)};
}

std::uint32_t filter_bits(double v, const char* what) {
  if (!(v >= 0 && v <= 4294967295.0) || v != std::floor(v)) {
    throw ArgumentError(std::string(what) + " " + number_text(v) +
                        " is not an integer in [0, 2^32)");
  }
  return static_cast<std::uint32_t>(v);
}

// A World error in the package's terms: without the C++ function's name (fail_with puts the JS
// one first) and, before the first quoted object name, the arguments as the JS call names them.
std::string js_terms(std::string_view what, std::string_view cpp_function) {
  static constexpr std::pair<std::string_view, std::string_view> kTerms[] = {
      {"ids[", "handles["},
      {"new_poses[", "poses["},
      {"deforming[", "vertexMotions["},
      {"].vertices", "].positions"},
      {"].id", "].handle"},
      {"request.min_separation", "minSeparation"},
      {"request.time_tolerance", "timeTolerance"},
      {"request.max_iterations", "maxIterations"},
      {"vertices of", "positions of"},
      {"id (slot", "handle (slot"},
      {"options.rebuild_above", "rebuildAbove"},
  };
  if (what.size() > cpp_function.size() + 2 &&
      what.substr(0, cpp_function.size()) == cpp_function &&
      what.substr(cpp_function.size(), 2) == ": ") {
    what.remove_prefix(cpp_function.size() + 2);
  }
  const std::size_t quote = std::min(what.find('\''), what.size());
  std::string head(what.substr(0, quote));
  for (const auto& [from, to] : kTerms) {
    for (std::size_t at = head.find(from); at != std::string::npos;
         at = head.find(from, at + to.size())) {
      head.replace(at, from.size(), to);
    }
  }
  return head.append(what.substr(quote));
}

// Runs `body`, an ArgumentError of `cpp_function` rethrown in the package's terms (js_terms).
template <class F>
void in_js_terms(std::string_view cpp_function, F&& body) {
  try {
    body();
  } catch (const ArgumentError& e) {
    throw ArgumentError(js_terms(e.what(), cpp_function));
  }
}

// Continuous-motion records, kMotionStride numbers: handle a, handle b, kind (0 RigidSweep,
// 1 StartContact, 2 Deform), toi, tolerance_decided (0/1), point (3), triangles (2), the
// primitive pair record (write_pair), the sweep record (write_sweep).
constexpr std::size_t kMotionHead = 10;
constexpr std::size_t kMotionStride = kMotionHead + kPairStride + kSweepStride;

int write_motion(const std::vector<MotionToi>& hits) {
  double* out = out_resize(kMotionStride * hits.size());
  for (const MotionToi& h : hits) {
    out[0] = handle_of(h.a);
    out[1] = handle_of(h.b);
    out[2] = static_cast<double>(h.kind);
    out[3] = h.toi;
    out[4] = h.tolerance_decided ? 1 : 0;
    write_vec(out + 5, h.point);
    out[8] = h.triangles[0];
    out[9] = h.triangles[1];
    write_pair(out + kMotionHead, h.primitive);
    write_sweep(out + kMotionHead + kPairStride, h.sweep);
    out += kMotionStride;
  }
  return static_cast<int>(hits.size());
}

}  // namespace

class WasmWorld {
 public:
  /// Pose 0; name: n_name UTF-8 bytes at `name_bytes`. Returns the handle, or -1.
  double add(int model, std::uintptr_t name_bytes, double n_name, double group, double mask,
             bool self_collision, double rebuild_above) {
    double handle = -1;
    guarded("World.add", [&] {
      ObjectOptions o;
      o.name.assign(reinterpret_cast<const char*>(name_bytes), static_cast<std::size_t>(n_name));
      o.group = filter_bits(group, "group");
      o.mask = filter_bits(mask, "mask");
      o.self_collision = self_collision;
      o.rebuild_above = rebuild_above;
      const std::shared_ptr<Model>& shared = model_ref(model, "model");
      const Transform pose = pose_at(0, "World.add", "pose");
      ObjectId id;
      in_js_terms("World::add", [&] { id = world_.add(shared, pose, o); });
      if (id.generation >= kMaxGeneration) {
        world_.remove(id);
        throw ArgumentError("too many objects have used this slot");
      }
      handle = handle_of(id);
      return 0;
    });
    return handle;
  }
  int remove(double handle) {
    return guarded("World.remove", [&] {
      world_.remove(id_of(handle, "handle"));
      return 0;
    });
  }
  /// Pose 0.
  int set_pose(double handle) {
    return guarded("World.setPose", [&] {
      world_.set_pose(id_of(handle, "handle"), pose_at(0, "World.setPose", "pose"));
      return 0;
    });
  }
  /// New model-frame positions of a deforming object: n_coords numbers (a multiple of 3; float32
  /// when f32, else float64) at `positions`. World::set_vertices checks them.
  int set_vertices(double handle, std::uintptr_t positions, double n_coords, bool f32) {
    return guarded("World.setVertices", [&] {
      const ObjectId id = id_of(handle, "handle");
      std::vector<Vec3> v(static_cast<std::size_t>(n_coords) / 3);
      read_vec3s(positions, f32, v);
      in_js_terms("World::set_vertices", [&] { world_.set_vertices(id, v); });
      return 0;
    });
  }
  [[nodiscard]] double size() const { return static_cast<double>(world_.size()); }
  /// Out: per colliding pair (handle a, handle b, contact count, self triangle-pair count); then
  /// every contact record in pair order; then every self pair's triangle pairs (i, j) in pair
  /// order. Returns the number of pairs.
  int collide_all(bool all_contacts, double delta, bool normals, double max_contacts) {
    return guarded("World.collideAll", [&] {
      const auto pairs =
          world_.collide_all(collision_request(all_contacts, delta, normals, max_contacts));
      std::size_t contacts = 0;
      std::size_t self = 0;
      for (const PairContacts& p : pairs) {
        contacts += p.contacts.size();
        self += p.self_pairs.size();
      }
      double* out = out_resize(4 * pairs.size() + kContactStride * contacts + 2 * self);
      double* rec = out + 4 * pairs.size();
      double* tri = rec + kContactStride * contacts;
      for (const PairContacts& p : pairs) {
        out[0] = handle_of(p.a);
        out[1] = handle_of(p.b);
        out[2] = static_cast<double>(p.contacts.size());
        out[3] = static_cast<double>(p.self_pairs.size());
        out += 4;
        for (const Contact& c : p.contacts) {
          write_contact(rec, c);
          rec += kContactStride;
        }
        for (const auto& [i, j] : p.self_pairs) {
          *tri++ = i;
          *tri++ = j;
        }
      }
      return static_cast<int>(pairs.size());
    });
  }
  /// Out: (handle a, handle b) per pair. Returns the number of pairs.
  int pairs_within(double d) {
    return guarded("World.pairsWithin", [&] {
      const auto pairs = world_.pairs_within(d);
      double* out = out_resize(2 * pairs.size());
      for (const ObjectPair& p : pairs) {
        *out++ = handle_of(p.a);
        *out++ = handle_of(p.b);
      }
      return static_cast<int>(pairs.size());
    });
  }
  /// Out: handle, triangle, distance, point (3), normal (3). Returns 1 for a hit, 0 for none.
  int raycast(double ox, double oy, double oz, double dx, double dy, double dz, double max_d) {
    return guarded("World.raycast", [&] {
      Ray ray;
      ray.origin = Vec3(ox, oy, oz);
      ray.direction = Vec3(dx, dy, dz);
      ray.max_distance = max_d;
      const auto hit = world_.raycast(ray);
      if (!hit) return 0;
      double* out = out_resize(9);
      out[0] = handle_of(hit->object);
      out[1] = hit->triangle;
      out[2] = hit->distance;
      write_vec(out + 3, hit->point);
      write_vec(out + 6, hit->normal);
      return 1;
    });
  }
  /// The motion's arguments in one float64 block at `block` (JS allocated it): n handles, n poses
  /// (16 numbers each, column-major), m handles of deforming objects, m coordinate counts (each a
  /// multiple of 3), then those coordinates in order. Out: kMotionStride numbers per pair
  /// (write_motion). Returns the number of pairs.
  int sweep_motion(std::uintptr_t block, double n, double m, double min_separation,
                   double time_tolerance, double max_iterations) {
    return motion("World.sweepMotion", block, n, m, min_separation, time_tolerance, max_iterations,
                  false);
  }
  int set_motion_continuous(std::uintptr_t block, double n, double m, double min_separation,
                            double time_tolerance, double max_iterations) {
    return motion("World.setMotionContinuous", block, n, m, min_separation, time_tolerance,
                  max_iterations, true);
  }

 private:
  int motion(const char* function, std::uintptr_t block, double n_ids, double n_motions,
             double min_separation, double time_tolerance, double max_iterations, bool apply) {
    return guarded(function, [&] {
      SweepRequest r;
      r.min_separation = min_separation;
      r.time_tolerance = time_tolerance;
      r.max_iterations = positive_count(max_iterations, "maxIterations");
      const auto n = static_cast<std::size_t>(n_ids);
      const auto m = static_cast<std::size_t>(n_motions);
      const double* p = reinterpret_cast<const double*>(block);
      std::vector<ObjectId> ids(n);
      std::vector<Transform> poses(n);
      for (std::size_t k = 0; k < n; ++k) {
        ids[k] = id_of(p[k], "handles[" + std::to_string(k) + "]");
        poses[k] = rigid_pose(p + n + 16 * k, function, "poses[" + std::to_string(k) + "]");
      }
      const double* handles = p + 17 * n;
      const double* counts = handles + m;
      std::uintptr_t coords = reinterpret_cast<std::uintptr_t>(counts + m);
      std::vector<std::vector<Vec3>> vertices(m);
      std::vector<VertexMotion> motions(m);
      for (std::size_t k = 0; k < m; ++k) {
        motions[k].id = id_of(handles[k], "vertexMotions[" + std::to_string(k) + "].handle");
        vertices[k].resize(static_cast<std::size_t>(counts[k]) / 3);
        read_vec3s(coords, false, vertices[k]);
        coords += static_cast<std::uintptr_t>(counts[k]) * sizeof(double);
        motions[k].vertices = vertices[k];
      }
      std::vector<MotionToi> hits;
      // set_motion_continuous checks its arguments in sweep_motion (the C++ name it reports).
      in_js_terms("World::sweep_motion", [&] {
        hits = apply ? world_.set_motion_continuous(ids, poses, motions, r)
                     : world_.sweep_motion(ids, poses, motions, r);
      });
      return write_motion(hits);
    });
  }

  World world_;
};

EMSCRIPTEN_BINDINGS(antcd_world) {
  using namespace emscripten;
  class_<WasmWorld>("World")
      .constructor<>()
      .function("add", &WasmWorld::add)
      .function("remove", &WasmWorld::remove)
      .function("setPose", &WasmWorld::set_pose)
      .function("setVertices", &WasmWorld::set_vertices)
      .function("size", &WasmWorld::size)
      .function("collideAll", &WasmWorld::collide_all)
      .function("pairsWithin", &WasmWorld::pairs_within)
      .function("raycast", &WasmWorld::raycast)
      .function("sweepMotion", &WasmWorld::sweep_motion)
      .function("setMotionContinuous", &WasmWorld::set_motion_continuous);
  constant("motionStride", static_cast<int>(kMotionStride));
}
