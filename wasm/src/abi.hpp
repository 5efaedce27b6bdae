// wasm/src/abi.hpp — the parts of the package's C ABI (bindings.cpp) that the exports in other
// files of wasm/src share: the checked call wrapper, the output block, the model table, the pose
// block and the record writers. The calling convention is stated at the top of bindings.cpp.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/math.hpp>
#include <antcd/sweep.hpp>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace antcd::wasm {

/// Sets the last error to the message of `e` thrown in `function` (or the out-of-memory message),
/// allocating nothing; returns -1.
int fail_with(const char* function, const std::exception& e);

/// Runs `body` (returning an int), turning a thrown antcd or standard exception into -1 and its
/// message. Hot paths do not throw; only argument errors and exhausted memory do.
template <class F>
int guarded(const char* function, F&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    return fail_with(function, e);
  }
}

/// The output block, grown to at least n doubles (may throw std::bad_alloc).
double* out_resize(std::size_t n);

/// The live model with id `id`; throws ArgumentError naming `what` otherwise.
const std::shared_ptr<Model>& model_ref(int id, const char* what);

/// Pose k of the input block as a rigid Transform; throws ArgumentError naming `what`.
Transform pose_at(int k, const char* function, const char* what);

/// The column-major 4x4 matrix at `m` as a rigid Transform (its last row 0 0 0 1); throws
/// ArgumentError "<function>: <what> <problem>" otherwise.
Transform rigid_pose(const double* m, const char* function, const std::string& what);

/// out.size() vertices from 3 * out.size() numbers at `at` (float32 when f32, else float64), as
/// they are (no check).
void read_vec3s(std::uintptr_t at, bool f32, std::vector<Vec3>& out);

/// An integer in [1, 2^32) given as a JS number; throws ArgumentError naming it.
std::uint32_t positive_count(double v, const char* name);

/// collide()'s request from the JS options; throws ArgumentError for a bad maxContacts.
CollisionRequest collision_request(bool all_contacts, double delta, bool normals,
                                   double max_contacts);

/// Contact records: triangle_a, triangle_b, point (3), distance, normal (3), depth.
constexpr int kContactStride = 10;
void write_vec(double* out, const Vec3& v);
void write_contact(double* out, const Contact& c);

/// A sweep record: toi, distance, motion_bound, iterations, flags (1 hit, 2 tolerance_decided,
/// 4 budget_exhausted), then the contact record.
constexpr std::size_t kSweepStride = 5 + kContactStride;
void write_sweep(double* out, const SweepResult& s);

/// A deforming pair record: kind (0 vertex-face, 1 edge-edge), vertex_in_first (0/1), indices
/// (4), toi, flags (1 tolerance_decided, 2 budget_exhausted).
constexpr std::size_t kPairStride = 8;
void write_pair(double* out, const DeformPair& p);

}  // namespace antcd::wasm
