// Shared by the continuous tests: dense sub-stepping with the exact discrete query (the truth the
// sweeps are held to), and the generated fast-motion scene: thin sheets moving 10x their
// thickness per frame, so that per-frame discrete checks tunnel through most contacts.
#pragma once

#include <antcd/ccd.hpp>
#include <antcd/collide.hpp>
#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace antcd::test {

/// First of the times k / steps (k = 0 .. steps) at which the exact discrete query finds the
/// surfaces within `delta`, or nullopt.
inline std::optional<Scalar> first_substep_contact(const Model& a, const Transform& a0,
                                                   const Transform& a1, const Model& b,
                                                   const Transform& b0, const Transform& b1,
                                                   Scalar delta, int steps = 1000) {
  CollisionRequest req;
  req.delta = delta;
  CollisionResult res;
  for (int k = 0; k <= steps; ++k) {
    const Scalar t = static_cast<Scalar>(k) / steps;
    if (collide(a, ccd::interpolate_pose(a0, a1, t), b, ccd::interpolate_pose(b0, b1, t), req,
                res)) {
      return t;
    }
  }
  return std::nullopt;
}

/// Half extents of a sheet: 1 x 1 x 0.01.
inline Vec3 fast_sheet_half() { return {0.5, 0.5, 0.005}; }

/// `sheets` nearly horizontal sheets over each other in [-1, 1] height, each moving 0.1 (10x its
/// thickness) up or down per frame with a slight drift and a slight tilt: poses[sheet][frame] for
/// frames 0 .. frames - 1.
inline std::vector<std::vector<Transform>> fast_sheet_tracks(int sheets, int frames,
                                                             std::uint64_t seed = 10) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::vector<std::vector<Transform>> poses(static_cast<std::size_t>(sheets));
  for (auto& track : poses) {
    Vec3 at(0.3 * unit(rng), 0.3 * unit(rng), unit(rng));
    const Vec3 velocity(0.01 * unit(rng), 0.01 * unit(rng), unit(rng) < 0 ? -0.1 : 0.1);
    const Vec3 axis(unit(rng), unit(rng), unit(rng));
    for (int f = 0; f < frames; ++f) {
      track.push_back(Transform::from_axis_angle(axis, 0.05 * std::sin(0.3 * f), at));
      at += velocity;
    }
  }
  return poses;
}

}  // namespace antcd::test
