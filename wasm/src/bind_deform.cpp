// Embind exports of the deforming sweeps (antcd/deform_ccd.hpp) for the npm package: deformSweep
// and collisionFreeStep (wasm/deform.mjs wraps them), and the pair record World.sweepMotion
// shares. The calling convention, the output block and
// the error handling are bindings.cpp's (abi.hpp).
#include <antcd/deform_ccd.hpp>
#include <antcd/error.hpp>

#include <emscripten/bind.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "abi.hpp"

namespace antcd::wasm {

void write_pair(double* out, const DeformPair& p) {
  out[0] = p.kind == DeformPairKind::VertexFace ? 0 : 1;
  out[1] = p.vertex_in_first ? 1 : 0;
  for (int k = 0; k < 4; ++k) out[2 + k] = p.indices[static_cast<std::size_t>(k)];
  out[6] = p.toi;
  out[7] = (p.tolerance_decided ? 1 : 0) + (p.budget_exhausted ? 2 : 0);
}

}  // namespace antcd::wasm

namespace {

using namespace antcd;
using namespace antcd::wasm;

// Positions of `model` for one end of the motion: n_coords float64 at `at` (JS allocated and
// filled them), three per vertex, as many vertices as the model has, each coordinate finite with
// magnitude <= kDeformMaxCoordinate; ArgumentError naming `name` otherwise.
std::vector<Vec3> positions_of(const Model& model, std::uintptr_t at, double n_coords,
                               const char* name) {
  const std::size_t nv = model.mesh().vertices.size();
  if (n_coords != 3.0 * static_cast<double>(nv)) {
    throw ArgumentError(std::string(name) + " has " + number_text(n_coords) + " numbers, model '" +
                        model.source() + "' has " + std::to_string(nv) + " vertices (" +
                        std::to_string(3 * nv) + ")");
  }
  const double* v = reinterpret_cast<const double*>(at);
  std::vector<Vec3> out(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = v[3 * i + static_cast<std::size_t>(c)];
      if (!std::isfinite(x) || std::abs(x) > kDeformMaxCoordinate) {
        throw ArgumentError(std::string(name) + "[" + std::to_string(3 * i + c) +
                            "] = " + number_text(x) + " is not finite with |x| <= 1e150");
      }
      out[i][c] = x;
    }
  }
  return out;
}

DeformSweepRequest request_of(double min_separation, double time_tolerance, bool all_pairs,
                              double pose_path_tolerance) {
  DeformSweepRequest r;
  r.min_separation = min_separation;
  r.time_tolerance = time_tolerance;
  r.all_pairs = all_pairs;
  r.pose_path_tolerance = pose_path_tolerance;
  return r;
}

constexpr std::size_t kHead = 7;

// Out: flags (1 hit, 2 tolerance_decided), toi, node_pairs, primitive_queries, tasks,
// scratch_bytes, k (the all_pairs count), then the earliest pair's record (zeros without a hit)
// and k pair records.
int write_result(const DeformSweepResult& r) {
  const std::size_t k = r.pairs.size();
  double* out = out_resize(kHead + kPairStride * (1 + k));
  out[0] = (r.hit ? 1 : 0) + (r.tolerance_decided ? 2 : 0);
  out[1] = r.toi;
  out[2] = static_cast<double>(r.node_pairs);
  out[3] = static_cast<double>(r.primitive_queries);
  out[4] = static_cast<double>(r.tasks);
  out[5] = static_cast<double>(r.scratch_bytes);
  out[6] = static_cast<double>(k);
  write_pair(out + kHead, r.hit ? r.pair : DeformPair{});
  for (std::size_t i = 0; i < k; ++i) write_pair(out + kHead + kPairStride * (1 + i), r.pairs[i]);
  return 1;
}

// mode 0: self (a only); 1: a against deforming b (b0, b1 its positions); 2: a against rigid b
// between poses 0 and 1 of the pose block. Each position block with its own count of numbers,
// checked by positions_of.
int wasm_deform_sweep(int mode, int a, std::uintptr_t a0, double n_a0, std::uintptr_t a1,
                      double n_a1, int b, std::uintptr_t b0, double n_b0, std::uintptr_t b1,
                      double n_b1, double min_separation, double time_tolerance, bool all_pairs,
                      double pose_path_tolerance) {
  return guarded("deformSweep", [&] {
    const DeformSweepRequest request =
        request_of(min_separation, time_tolerance, all_pairs, pose_path_tolerance);
    const Model& ma = *model_ref(a, "a");
    const std::vector<Vec3> p0 = positions_of(ma, a0, n_a0, "a0");
    const std::vector<Vec3> p1 = positions_of(ma, a1, n_a1, "a1");
    if (mode == 0) return write_result(deform_sweep(ma, p0, p1, request));
    const Model& mb = *model_ref(b, "b");
    if (mode == 1) {
      const std::vector<Vec3> q0 = positions_of(mb, b0, n_b0, "b0");
      const std::vector<Vec3> q1 = positions_of(mb, b1, n_b1, "b1");
      return write_result(deform_sweep(ma, p0, p1, mb, q0, q1, request));
    }
    const Transform pose0 = pose_at(0, "deformSweep", "poseB0");
    const Transform pose1 = pose_at(1, "deformSweep", "poseB1");
    return write_result(deform_sweep(ma, p0, p1, mb, pose0, pose1, request));
  });
}

// Out: the step.
int wasm_collision_free_step(int id, std::uintptr_t v0, double n_v0, std::uintptr_t v1, double n_v1,
                             double min_separation, double time_tolerance) {
  return guarded("collisionFreeStep", [&] {
    const Model& m = *model_ref(id, "model");
    const std::vector<Vec3> p0 = positions_of(m, v0, n_v0, "v0");
    const std::vector<Vec3> p1 = positions_of(m, v1, n_v1, "v1");
    const Scalar step = collision_free_step(m, p0, p1, min_separation, time_tolerance);
    out_resize(1)[0] = step;
    return 1;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(antcd_deform) {
  emscripten::function("deformSweep", &wasm_deform_sweep);
  emscripten::function("collisionFreeStep", &wasm_collision_free_step);
}
