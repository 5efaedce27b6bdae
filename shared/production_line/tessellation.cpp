// The vertex-budget solver: a level (subdivisions, slices, stacks) per part so that a compound's
// vertex count is as near the target as the levels allow.
#include "shared/production_line/tessellation.hpp"

#include "shared/production_line/poses.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace antcd::shared::line {
namespace {

Scalar area(const Part& p) {
  const Vec3& d = p.dims;
  switch (p.shape) {
    case Shape::Box:
      return 8 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
    case Shape::Cylinder:
      return 2 * kPi * d.x() * (d.y() + d.x());
    case Shape::Sphere:
      return 4 * kPi * d.x() * d.x();
  }
  return 0;
}

/// The level with k around whose facets are roughly square.
Level square_level(const Part& p, std::uint64_t k) {
  switch (p.shape) {
    case Shape::Box:
      return {k, k};
    case Shape::Cylinder: {  // stacks: facet height ≈ facet width 2πr/k
      const Scalar stacks =
          std::round(static_cast<Scalar>(k) * p.dims.y() / (2 * kPi * p.dims.x()));
      return {k, std::max<std::uint64_t>(1, static_cast<std::uint64_t>(stacks))};
    }
    case Shape::Sphere:  // stacks from pole to pole: half the slices
      return {k, std::max<std::uint64_t>(2, (k + 1) / 2)};
  }
  return {k, 1};
}

std::uint64_t min_slices(const Part& p) { return p.shape == Shape::Box ? 1 : 3; }

/// Vertex count of the generator's output (see shapes.cpp).
std::uint64_t vertex_count(const Part& p, const Level& l) {
  switch (p.shape) {
    case Shape::Box:
      return 6 * l.k * l.k + 2;
    case Shape::Cylinder:
      return l.k * (l.s + 1) + 2;
    case Shape::Sphere:
      return l.k * (l.s - 1) + 2;
  }
  return 0;
}

Scalar miss(std::uint64_t count, Scalar budget) {
  return std::abs(static_cast<Scalar>(count) - budget);
}

/// The level whose vertex count is nearest to `budget` (ties: the coarser one). The count of the
/// result never decreases when the budget grows.
Level level_for(const Part& p, Scalar budget) {
  auto count = [&](std::uint64_t k) {
    return static_cast<Scalar>(vertex_count(p, square_level(p, k)));
  };
  std::uint64_t lo = min_slices(p);
  if (count(lo) >= budget) {
    const Level coarsest = square_level(p, lo);
    if (p.shape != Shape::Cylinder) return coarsest;
    // A long cylinder below its square tessellation: 3 slices and fewer stacks.
    const Scalar ideal = std::max<Scalar>(1, (budget - 2) / 3 - 1);
    Level best{3, 1};
    for (const Scalar stacks : {std::floor(ideal), std::ceil(ideal)}) {
      const Level l{3,
                    std::min(coarsest.s, static_cast<std::uint64_t>(std::max<Scalar>(1, stacks)))};
      if (miss(vertex_count(p, l), budget) < miss(vertex_count(p, best), budget)) best = l;
    }
    return best;
  }
  // The count is at least k, so the first k reaching the budget is at most max(lo, budget).
  std::uint64_t hi = std::max<std::uint64_t>(lo + 1, static_cast<std::uint64_t>(budget) + 1);
  while (hi - lo > 1) {  // invariant: count(lo) < budget <= count(hi)
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (count(mid) < budget) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return budget - count(lo) > count(hi) - budget ? square_level(p, hi) : square_level(p, lo);
}

struct Fit {
  std::vector<Level> levels;
  std::uint64_t vertices = 0;
};

/// Levels for the parts so that the total vertex count is as near `target` as the levels allow:
/// the target is shared in proportion to the parts' areas (even facet density), scaled by a
/// factor found by bisection (every part's count grows with its share).
Fit fit_parts(const std::vector<Part>& parts, std::size_t target) {
  std::vector<Scalar> share;
  Scalar total_area = 0;
  for (const Part& p : parts) total_area += area(p);
  for (const Part& p : parts) {
    share.push_back(static_cast<Scalar>(target) * area(p) / total_area);
  }
  auto fit_at = [&](Scalar scale) {
    Fit f;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      f.levels.push_back(level_for(parts[i], scale * share[i]));
      f.vertices += vertex_count(parts[i], f.levels.back());
    }
    return f;
  };
  const auto want = static_cast<std::uint64_t>(target);
  Fit low = fit_at(0);
  if (low.vertices >= want) return low;
  Scalar lo = 0;
  Scalar hi = 1;
  Fit high = fit_at(hi);
  while (high.vertices < want && hi < 1e9) {
    lo = hi;
    low = std::move(high);
    hi *= 2;
    high = fit_at(hi);
  }
  for (int i = 0; i < 60 && high.vertices != want; ++i) {
    const Scalar mid = (lo + hi) / 2;
    Fit f = fit_at(mid);
    if (f.vertices < want) {
      lo = mid;
      low = std::move(f);
    } else {
      hi = mid;
      high = std::move(f);
    }
  }
  if (high.vertices < want) return high;  // cannot reach the target (not for sane targets)
  const std::uint64_t below = want - low.vertices;
  const std::uint64_t above = high.vertices - want;
  return above < below ? high : low;
}

Mesh build_part(const Part& p, const Level& level) {
  const int k = static_cast<int>(level.k);
  const int s = static_cast<int>(level.s);
  Mesh m;
  switch (p.shape) {
    case Shape::Box:
      m = make_box(p.dims, k);
      break;
    case Shape::Cylinder:
      m = make_cylinder(p.dims.x(), p.dims.y(), k, s);
      break;
    case Shape::Sphere:
      m = make_sphere(p.dims.x(), k, s);
      break;
  }
  return transformed(std::move(m), p.place);
}

}  // namespace

Part box_part(const Vec3& half, const Vec3& centre) {
  return {Shape::Box, half, Transform{Mat3::Identity(), centre}};
}
Part cylinder_part(Scalar radius, Scalar height, const Mat3& axis, const Vec3& centre) {
  return {Shape::Cylinder, Vec3(radius, height, 0), Transform{axis, centre}};
}
Part sphere_part(Scalar radius, const Vec3& centre) {
  return {Shape::Sphere, Vec3(radius, 0, 0), Transform{Mat3::Identity(), centre}};
}

/// Builds the compound of `parts` with about `target` vertices. When `simple` is given (a version
/// with fewer primitives, for tiny budgets) and lands nearer the target, it is used instead.
Equipment build_equipment(const std::vector<Part>& parts, std::size_t target,
                          const std::vector<Part>& simple) {
  Fit fit = fit_parts(parts, target);
  const std::vector<Part>* chosen = &parts;
  if (!simple.empty()) {
    Fit alt = fit_parts(simple, target);
    auto miss = [&](const Fit& f) {
      return f.vertices > target ? f.vertices - target : target - f.vertices;
    };
    if (miss(alt) < miss(fit)) {
      fit = std::move(alt);
      chosen = &simple;
    }
  }
  std::vector<Mesh> meshes;
  for (std::size_t i = 0; i < chosen->size(); ++i) {
    meshes.push_back(build_part((*chosen)[i], fit.levels[i]));
  }
  return {{}, merge(meshes), *chosen, fit.levels};
}

/// Distance from a tessellated sphere's or cylinder's centre line to its facets is at least
/// radius·(1 - sag); contacts are placed deeper than the sag.
Scalar cylinder_sag(const Equipment& e) {
  return e.parts.front().dims.x() * (1 - std::cos(kPi / static_cast<Scalar>(e.levels.front().k)));
}

}  // namespace antcd::shared::line
