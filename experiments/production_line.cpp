// Procedural veneer production line: equipment meshes, station layout and motions.
//
// Lengths are in metres, the line runs along +x, z is up and the floor is z = 0 (there is no floor
// object). Stations follow each other with gaps of 1.2–1.5 m, in a fixed cycle:
//   conveyor, dryer, press, conveyor, robot cell, press, conveyor, (repeat)
// until the next station would exceed the requested object count; the rest is filled with a short
// conveyor (or a column when only one object is left).
#include "production_line.hpp"

#include <antcd/io.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd::experiments {
namespace {

constexpr Scalar kPi = std::numbers::pi;

// ---- Random numbers: SplitMix64, fully specified (the standard distributions are not, so they
// could differ between standard libraries) ----

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  /// A stream for one purpose (one station), independent of how much other streams were used.
  Rng(std::uint64_t seed, std::uint64_t stream) : state_(seed) {
    state_ ^= Rng(stream * 0xD1B54A32D192ED03ULL + 0x8CB92BA72F3D8DD7ULL).next();
    next();
  }

  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  Scalar uniform() { return static_cast<Scalar>(next() >> 11) * 0x1.0p-53; }
  Scalar uniform(Scalar lo, Scalar hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

// ---- Small helpers ----

Scalar smoothstep(Scalar t) {
  t = std::clamp(t, Scalar{0}, Scalar{1});
  return t * t * (3 - 2 * t);
}

Scalar lerp(Scalar a, Scalar b, Scalar t) { return a + (b - a) * t; }

/// Fractional part in [0, 1).
Scalar fraction(Scalar x) {
  const Scalar f = x - std::floor(x);
  return f < 1 ? f : 0;
}

/// Translations are rounded to the micrometre: the file stays compact, and contact depths are
/// millimetres.
Vec3 round_um(const Vec3& v) {
  return {std::round(v.x() * 1e6) / 1e6, std::round(v.y() * 1e6) / 1e6,
          std::round(v.z() * 1e6) / 1e6};
}

Transform pose(const Mat3& rotation, const Vec3& translation) {
  Transform t;
  t.rotation = rotation;
  t.translation = round_um(translation);
  return t;
}

Transform at(const Vec3& translation) { return pose(Mat3::Identity(), translation); }

Mat3 rot(const Vec3& axis, Scalar angle) {
  return Eigen::AngleAxis<Scalar>(angle, axis.normalized()).toRotationMatrix();
}

/// Exact quarter turns (no rounding in cos(π/2)): the generators' z axis onto x or y.
Mat3 z_to_x() {
  Mat3 r;
  r << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // rotation of +90° about y
  return r;
}
Mat3 z_to_y() {
  Mat3 r;
  r << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // rotation of +90° about x (z → -y; the axis is what matters)
  return r;
}

// ---- Meshes: primitives tessellated to a vertex budget ----

enum class Shape { Box, Cylinder, Sphere };

/// One primitive of a compound mesh. dims: box half extents; cylinder (radius, height, -) along
/// its z; sphere (radius, -, -). `place` maps the primitive into the mesh's frame.
struct Part {
  Shape shape = Shape::Box;
  Vec3 dims = Vec3::Zero();
  Transform place;
};

Part box_part(const Vec3& half, const Vec3& centre) {
  return {Shape::Box, half, Transform{Mat3::Identity(), centre}};
}
Part cylinder_part(Scalar radius, Scalar height, const Mat3& axis, const Vec3& centre) {
  return {Shape::Cylinder, Vec3(radius, height, 0), Transform{axis, centre}};
}
Part sphere_part(Scalar radius, const Vec3& centre) {
  return {Shape::Sphere, Vec3(radius, 0, 0), Transform{Mat3::Identity(), centre}};
}

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

/// Tessellation of a part: k is the box subdivisions or the slices around a cylinder or sphere;
/// s is the stacks of a cylinder or sphere (unused for a box).
struct Level {
  std::uint64_t k = 1;
  std::uint64_t s = 1;
};

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

/// A mesh of equipment: its parts at the levels chosen for the vertex budget.
struct Equipment {
  std::string file;  ///< relative to the scene folder, set when the builder registers it
  Mesh mesh;
  std::vector<Part> parts;
  std::vector<Level> levels;
};

/// Builds the compound of `parts` with about `target` vertices. When `simple` is given (a version
/// with fewer primitives, for tiny budgets) and lands nearer the target, it is used instead.
Equipment build_equipment(const std::vector<Part>& parts, std::size_t target,
                          const std::vector<Part>& simple = {}) {
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

// ---- Dimensions of the equipment (metres) ----

constexpr Scalar kContact = 0.002;  ///< interpenetration of resting contacts beyond the sag
constexpr Scalar kRollerRadius = 0.05;
constexpr Scalar kRollerLength = 1.30;
constexpr Scalar kRollerPitch = 0.25;
constexpr Scalar kRollerAxisZ = 0.80;
constexpr Scalar kRollerTop = kRollerAxisZ + kRollerRadius;
constexpr Scalar kRailHalfY = 0.04;
constexpr Scalar kRailY = kRollerLength / 2 + 0.02 + kRailHalfY;  // 2 cm gap to the roller ends
constexpr Scalar kSheetHalfX = 0.45;
constexpr Scalar kSheetHalfY = 0.45;
constexpr Scalar kSheetHalfZ = 0.005;
constexpr Scalar kPalletHalfX = 0.60;
constexpr Scalar kPalletHeight = 0.122;
constexpr Scalar kStationGap = 1.2;  ///< plus 0–0.3 m from the seed

// Hot press: platens 1.2 × 1.1 × 0.1, lower platen top at the conveyor's sheet level.
constexpr Scalar kPlatenHalfX = 0.60;
constexpr Scalar kPlatenHalfZ = 0.05;
constexpr Scalar kPressLength = 3.2;
constexpr Scalar kPressSheetTravel = 1.10;  ///< sheet centre: from -travel (off the platen) to 0
constexpr Scalar kPressOpening = 0.40;

// Robot: shoulder 0.9 m above the floor, both links 1 m.
constexpr Scalar kShoulderZ = 0.90;
constexpr Scalar kUpperArm = 1.0;
constexpr Scalar kForearm = 1.0;
constexpr Scalar kTipRadius = 0.08;
constexpr Scalar kRobotY = -1.5;        ///< base, beside the pallet conveyor
constexpr Scalar kRobotTargetY = -2.7;  ///< the pallet the robot touches
constexpr Scalar kRobotCellLength = 2.6;

std::vector<Part> roller_parts() {
  return {cylinder_part(kRollerRadius, kRollerLength, z_to_y(), Vec3::Zero())};
}

std::vector<Part> sheet_parts() {
  return {box_part(Vec3(kSheetHalfX, kSheetHalfY, kSheetHalfZ), Vec3::Zero())};
}

/// Conveyor bed under `rollers` rollers, centred on x = 0, floor at z = 0: two side rails with a
/// 2 cm gap to the roller ends, cross members below the rollers, four legs.
std::vector<Part> bed_parts(std::size_t rollers, bool simple) {
  const Scalar half = static_cast<Scalar>(rollers) * kRollerPitch / 2;
  std::vector<Part> parts;
  for (const Scalar y : {-kRailY, kRailY}) {
    parts.push_back(box_part(Vec3(half, kRailHalfY, 0.06), Vec3(0, y, kRollerAxisZ)));
  }
  if (simple) return parts;
  // Cross members between two rollers, 2 cm below them.
  const Scalar cross_z = kRollerAxisZ - kRollerRadius - 0.02 - 0.03;
  std::vector<std::size_t> gaps{1};
  if (rollers >= 4) gaps.push_back(rollers / 2);
  if (rollers >= 3) gaps.push_back(rollers - 1);
  gaps.erase(std::unique(gaps.begin(), gaps.end()), gaps.end());
  for (const std::size_t g : gaps) {
    const Scalar x = -half + kRollerPitch * static_cast<Scalar>(g);
    parts.push_back(box_part(Vec3(0.03, kRailY + kRailHalfY, 0.03), Vec3(x, 0, cross_z)));
  }
  const Scalar leg_half_z = (kRollerAxisZ - 0.06) / 2;
  for (const Scalar x : {-half + 0.06, half - 0.06}) {
    for (const Scalar y : {-kRailY, kRailY}) {
      parts.push_back(box_part(Vec3(0.04, 0.04, leg_half_z), Vec3(x, y, leg_half_z)));
    }
  }
  return parts;
}

/// Portal frame across a conveyor: two columns 0.1 m outside the rails and a beam at 1.66 m.
std::vector<Part> portal_parts(bool simple) {
  std::vector<Part> parts;
  if (!simple) {
    for (const Scalar y : {-0.9, 0.9}) {
      parts.push_back(box_part(Vec3(0.06, 0.06, 0.8), Vec3(0, y, 0.8)));
    }
  }
  parts.push_back(box_part(Vec3(0.06, 0.96, 0.06), Vec3(0, 0, 1.66)));
  return parts;
}

/// Drying tunnel over a conveyor of `rollers` rollers: roof and two side walls.
std::vector<Part> dryer_parts(std::size_t rollers, bool simple) {
  const Scalar half = static_cast<Scalar>(rollers) * kRollerPitch / 2 + 0.1;
  std::vector<Part> parts{box_part(Vec3(half, 1.0, 0.05), Vec3(0, 0, 1.65))};
  if (simple) return parts;
  for (const Scalar y : {-0.95, 0.95}) {
    parts.push_back(box_part(Vec3(half, 0.05, 0.8), Vec3(0, y, 0.8)));
  }
  return parts;
}

/// Press frame: base, four columns 6 cm clear of the platens, crown.
std::vector<Part> press_frame_parts(bool simple) {
  std::vector<Part> parts{box_part(Vec3(0.8, 0.8, 0.08), Vec3(0, 0, 1.98))};
  if (simple) return parts;
  parts.push_back(box_part(Vec3(0.8, 0.8, 0.15), Vec3(0, 0, 0.15)));
  for (const Scalar x : {-0.72, 0.72}) {
    for (const Scalar y : {-0.68, 0.68}) {
      parts.push_back(box_part(Vec3(0.06, 0.06, 0.95), Vec3(x, y, 0.95)));
    }
  }
  return parts;
}

std::vector<Part> press_plate_parts() {
  return {box_part(Vec3(kPlatenHalfX, 0.55, kPlatenHalfZ), Vec3::Zero())};
}

/// Pallet 1.2 × 1.0 × 0.122, origin at the bottom centre: three runners along x, five top slats.
std::vector<Part> pallet_parts(bool simple) {
  if (simple) {
    return {box_part(Vec3(kPalletHalfX, 0.5, kPalletHeight / 2), Vec3(0, 0, kPalletHeight / 2))};
  }
  std::vector<Part> parts;
  for (const Scalar y : {-0.44, 0.0, 0.44}) {
    parts.push_back(box_part(Vec3(kPalletHalfX, 0.05, 0.05), Vec3(0, y, 0.05)));
  }
  for (const Scalar x : {-0.52, -0.26, 0.0, 0.26, 0.52}) {
    parts.push_back(box_part(Vec3(0.07, 0.5, 0.011), Vec3(x, 0, 0.111)));
  }
  return parts;
}

/// Robot pedestal (0.7 m) with a floor flange; the shoulder sphere (on the upper arm) clears its
/// top by 5 cm.
std::vector<Part> robot_base_parts(bool simple) {
  std::vector<Part> parts{cylinder_part(0.2, 0.7, Mat3::Identity(), Vec3(0, 0, 0.35))};
  if (!simple) parts.push_back(cylinder_part(0.32, 0.04, Mat3::Identity(), Vec3(0, 0, 0.02)));
  return parts;
}

/// Upper arm along +x from the shoulder: shoulder sphere and a tube that stops 2 cm short of the
/// elbow sphere (which belongs to the forearm).
std::vector<Part> upper_arm_parts(bool simple) {
  const Scalar tube = kUpperArm - 0.11 - 0.02;
  std::vector<Part> parts{cylinder_part(0.06, tube, z_to_x(), Vec3(tube / 2, 0, 0))};
  if (!simple) parts.push_back(sphere_part(0.15, Vec3::Zero()));
  return parts;
}

/// Forearm along +x from the elbow: elbow sphere, tube, and the tip sphere (the gripper) at 1 m.
std::vector<Part> forearm_parts(bool simple) {
  std::vector<Part> parts{sphere_part(kTipRadius, Vec3(kForearm, 0, 0))};
  if (simple) return parts;
  parts.push_back(cylinder_part(0.045, kForearm, z_to_x(), Vec3(kForearm / 2, 0, 0)));
  parts.push_back(sphere_part(0.11, Vec3::Zero()));
  return parts;
}

std::vector<Part> column_parts() { return {box_part(Vec3(0.1, 0.1, 1.0), Vec3(0, 0, 1.0))}; }

// ---- Robot kinematics ----

/// Joint angles: yaw about z, then the elevations of the upper arm and forearm above horizontal.
struct ArmPose {
  Scalar yaw = 0;
  Scalar upper = 0;
  Scalar fore = 0;
};

/// Elbow-up inverse kinematics of the two links for a tip at horizontal reach r and height z
/// (relative to the shoulder) in the vertical plane of `yaw`.
ArmPose solve_arm(Scalar yaw, Scalar r, Scalar z) {
  const Scalar d = std::clamp(std::hypot(r, z), std::abs(kUpperArm - kForearm) + 1e-6,
                              kUpperArm + kForearm - 1e-6);
  const Scalar phi = std::atan2(z, r);
  const Scalar beta = std::acos(std::clamp(
      (kUpperArm * kUpperArm + d * d - kForearm * kForearm) / (2 * kUpperArm * d), -1.0, 1.0));
  ArmPose a;
  a.yaw = yaw;
  a.upper = phi + beta;
  a.fore = std::atan2(z - kUpperArm * std::sin(a.upper), r - kUpperArm * std::cos(a.upper));
  return a;
}

ArmPose blend(const ArmPose& a, const ArmPose& b, Scalar t) {
  const Scalar s = smoothstep(t);
  return {lerp(a.yaw, b.yaw, s), lerp(a.upper, b.upper, s), lerp(a.fore, b.fore, s)};
}

// ---- The scene builder ----

class LineBuilder {
 public:
  explicit LineBuilder(const ProductionLineOptions& options)
      : options_(options), frames_(options.frames) {
    const std::size_t last = options.objects - 1;
    std::size_t digits = 1;
    for (std::size_t n = last; n >= 10; n /= 10) ++digits;
    name_width_ = std::max<std::size_t>(2, digits);
  }

  GeneratedScene take() {
    out_.scene.frames = frames_;
    return std::move(out_);
  }

  [[nodiscard]] std::size_t remaining() const {
    return options_.objects - out_.scene.objects.size();
  }

  // -- meshes --

  /// The mesh file `name` (under meshes/), built on first use by `make`.
  const Equipment& equipment(const std::string& name, const std::function<Equipment()>& make) {
    auto it = equipment_.find(name);
    if (it == equipment_.end()) {
      Equipment e = make();
      e.file = "meshes/" + name + ".obj";
      out_.meshes.emplace_back(e.file, e.mesh);
      it = equipment_.emplace(name, std::move(e)).first;
    }
    return it->second;
  }

  const Equipment& kind(const std::string& name, const std::vector<Part>& parts,
                        const std::vector<Part>& simple = {}) {
    return equipment(name, [&] { return build_equipment(parts, options_.vertices, simple); });
  }

  const Equipment& roller() { return kind("roller", roller_parts()); }
  const Equipment& sheet() { return kind("veneer_sheet", sheet_parts()); }
  const Equipment& pallet() { return kind("pallet", pallet_parts(false), pallet_parts(true)); }

  // -- objects --

  void add_static(const std::string& prefix, const std::string& mesh, const Transform& t) {
    add(prefix, mesh, {t});
  }

  void add_moving(const std::string& prefix, const std::string& mesh,
                  const std::function<Transform(std::size_t)>& pose_at) {
    std::vector<Transform> poses;
    poses.reserve(frames_);
    for (std::size_t f = 0; f < frames_; ++f) poses.push_back(pose_at(f));
    add(prefix, mesh, std::move(poses));
  }

  // -- stations; each starts at x0 and returns its length along x --

  /// Roller conveyor from x0: `rollers` rollers spinning with the `loads` sheets (or pallets)
  /// that travel over them at one speed, wrapping from the exit back to the entry.
  Scalar conveyor(Rng& rng, Scalar x0, std::size_t rollers, std::size_t loads, bool pallets,
                  bool with_bed, bool with_portal) {
    const Scalar length = static_cast<Scalar>(rollers) * kRollerPitch;
    const Scalar speed = rng.uniform(0.012, 0.024);  // m per frame
    const Equipment& r = roller();
    const Scalar depth = kContact + cylinder_sag(r);  // loads rest this far into the rollers
    for (std::size_t i = 0; i < rollers; ++i) {
      const Vec3 axis_at(x0 + kRollerPitch * (static_cast<Scalar>(i) + 0.5), 0, kRollerAxisZ);
      const Scalar angle0 = rng.uniform(0, 2 * kPi);
      add_moving("roller", r.file, [=](std::size_t f) {
        // Rolling without slip under the loads: the top of the roller moves with them (+x).
        const Scalar angle = angle0 + speed * static_cast<Scalar>(f) / kRollerRadius;
        return pose(rot(Vec3::UnitY(), std::fmod(angle, 2 * kPi)), axis_at);
      });
    }
    const Scalar load_half_x = pallets ? kPalletHalfX : kSheetHalfX;
    // Loads travel with their centre from x0 to x0 + travel; consecutive loads 5 cm apart at least.
    const Scalar travel = std::max(length, static_cast<Scalar>(loads) * (2 * load_half_x + 0.05));
    const Scalar phase = rng.uniform(0, travel);
    const std::string load_file = pallets ? pallet().file : sheet().file;
    const Scalar load_z = pallets ? kRollerTop - depth : kRollerTop + kSheetHalfZ - depth;
    for (std::size_t k = 0; k < loads; ++k) {
      const Scalar offset = phase + travel * static_cast<Scalar>(k) / static_cast<Scalar>(loads);
      add_moving(pallets ? "pallet" : "sheet", load_file, [=](std::size_t f) {
        const Scalar s = travel * fraction((offset + speed * static_cast<Scalar>(f)) / travel);
        return at(Vec3(x0 + s, 0, load_z));
      });
    }
    const Scalar middle = x0 + length / 2;
    if (with_bed) {
      const std::string name = "conveyor_bed_" + std::to_string(rollers);
      add_static("bed", kind(name, bed_parts(rollers, false), bed_parts(rollers, true)).file,
                 at(Vec3(middle, 0, 0)));
    }
    if (with_portal) {
      add_static("portal", kind("portal_frame", portal_parts(false), portal_parts(true)).file,
                 at(Vec3(middle, 0, 0)));
    }
    return std::max(length, travel);
  }

  /// Drying tunnel over a 12-roller conveyor carrying three sheets.
  Scalar dryer(Rng& rng, Scalar x0) {
    constexpr std::size_t rollers = 12;
    const Scalar length = static_cast<Scalar>(rollers) * kRollerPitch;
    const std::string name = "dryer_" + std::to_string(rollers);
    add_static("dryer", kind(name, dryer_parts(rollers, false), dryer_parts(rollers, true)).file,
               at(Vec3(x0 + length / 2, 0, 0)));
    return conveyor(rng, x0, rollers, 3, false, true, false);
  }

  /// Hot press: a sheet slides onto the lower platen, the upper platen closes on it, holds, opens,
  /// and the sheet slides out.
  Scalar press(Rng& rng, Scalar x0) {
    const Scalar xc = x0 + kPressLength / 2;
    const Scalar period = std::round(rng.uniform(90, 130));
    const Scalar phase = rng.uniform(0, 1);
    const std::string plate = kind("press_plate", press_plate_parts()).file;
    add_static("press_frame",
               kind("press_frame", press_frame_parts(false), press_frame_parts(true)).file,
               at(Vec3(xc, 0, 0)));
    const Scalar lower_z = kRollerTop - kPlatenHalfZ;  // top at the sheet level of the conveyors
    add_static("press_lower", plate, at(Vec3(xc, 0, lower_z)));
    const Scalar sheet_z = kRollerTop + kSheetHalfZ - kContact;
    const Scalar closed_z = sheet_z + kSheetHalfZ - kContact + kPlatenHalfZ;
    const Scalar open_z = closed_z + kPressOpening;
    auto cycle = [=](std::size_t f) { return fraction(phase + static_cast<Scalar>(f) / period); };
    add_moving("press_upper", plate, [=](std::size_t f) {
      const Scalar u = cycle(f);
      Scalar z = open_z;
      if (u >= 0.20 && u < 0.35) z = lerp(open_z, closed_z, smoothstep((u - 0.20) / 0.15));
      if (u >= 0.35 && u < 0.55) z = closed_z;
      if (u >= 0.55 && u < 0.70) z = lerp(closed_z, open_z, smoothstep((u - 0.55) / 0.15));
      return at(Vec3(xc, 0, z));
    });
    const std::string sheet_file = sheet().file;
    add_moving("sheet", sheet_file, [=](std::size_t f) {
      const Scalar u = cycle(f);
      Scalar x = kPressSheetTravel;
      if (u < 0.20) x = lerp(-kPressSheetTravel, 0, smoothstep(u / 0.20));
      if (u >= 0.20 && u < 0.70) x = 0;
      if (u >= 0.70 && u < 0.90) x = lerp(0, kPressSheetTravel, smoothstep((u - 0.70) / 0.20));
      return at(Vec3(xc + x, 0, sheet_z));
    });
    return kPressLength;
  }

  /// Robot cell: a pallet conveyor along the line; beside it a robot swings from above the
  /// conveyor to a pallet on the floor, presses its gripper onto the middle slat, and back.
  Scalar robot_cell(Rng& rng, Scalar x0) {
    const Scalar xr = x0 + 1.0;
    const Scalar period = std::round(rng.uniform(100, 140));
    const Scalar phase = rng.uniform(0, 1);
    const Equipment& fore = kind("robot_forearm", forearm_parts(false), forearm_parts(true));
    const std::string fore_file = fore.file;
    const std::string upper_file =
        kind("robot_upper_arm", upper_arm_parts(false), upper_arm_parts(true)).file;
    add_static("pallet", pallet().file, at(Vec3(xr, kRobotTargetY, 0)));
    add_static("robot_base",
               kind("robot_base", robot_base_parts(false), robot_base_parts(true)).file,
               at(Vec3(xr, kRobotY, 0)));

    // The tip sphere's facets lie at least radius·cos(π/slices)·cos(π/(2·stacks)) from its
    // centre; it is pressed that far plus 3 mm into the slat.
    const Level tip = fore.levels.front();
    const Scalar inner = std::cos(kPi / static_cast<Scalar>(tip.k)) *
                         std::cos(kPi / (2 * static_cast<Scalar>(tip.s)));
    const Scalar tip_z = kPalletHeight + kTipRadius * inner - 0.003;
    const Scalar reach = std::abs(kRobotTargetY - kRobotY);
    const ArmPose touch = solve_arm(-kPi / 2, reach, tip_z - kShoulderZ);
    const ArmPose above = solve_arm(-kPi / 2, reach, tip_z + 0.35 - kShoulderZ);
    const ArmPose home = solve_arm(kPi / 2, 1.2, 0.6);  // tip at 1.5 m over the conveyor
    auto arm_at = [=](std::size_t f) {
      const Scalar u = fraction(phase + static_cast<Scalar>(f) / period);
      if (u < 0.30) return blend(home, above, u / 0.30);
      if (u < 0.40) return blend(above, touch, (u - 0.30) / 0.10);
      if (u < 0.50) return touch;
      if (u < 0.60) return blend(touch, above, (u - 0.50) / 0.10);
      if (u < 0.90) return blend(above, home, (u - 0.60) / 0.30);
      return home;
    };
    const Vec3 shoulder(xr, kRobotY, kShoulderZ);
    add_moving("robot_upper_arm", upper_file, [=](std::size_t f) {
      const ArmPose a = arm_at(f);
      return pose(rot(Vec3::UnitZ(), a.yaw) * rot(Vec3::UnitY(), -a.upper), shoulder);
    });
    add_moving("robot_forearm", fore_file, [=](std::size_t f) {
      const ArmPose a = arm_at(f);
      const Mat3 yaw = rot(Vec3::UnitZ(), a.yaw);
      const Vec3 elbow =
          shoulder + yaw * Vec3(kUpperArm * std::cos(a.upper), 0, kUpperArm * std::sin(a.upper));
      return pose(yaw * rot(Vec3::UnitY(), -a.fore), elbow);
    });
    const Scalar length = conveyor(rng, x0, 8, 1, true, true, false);
    return std::max(length, kRobotCellLength);
  }

  /// The last objects when no full station fits: a short conveyor, or a column.
  Scalar filler(Rng& rng, Scalar x0, std::size_t count) {
    if (count == 1) {
      add_static("column", kind("column", column_parts()).file, at(Vec3(x0, 0, 0)));
      return 0.2;
    }
    if (count == 2) return conveyor(rng, x0, 1, 1, false, false, false);
    return conveyor(rng, x0, count - 2, 1, false, true, false);
  }

 private:
  void add(const std::string& prefix, const std::string& mesh, std::vector<Transform> poses) {
    if (remaining() == 0) {
      throw std::logic_error("production line: more objects than requested (internal error)");
    }
    std::string number = std::to_string(counters_[prefix]++);
    if (number.size() < name_width_) number.insert(0, name_width_ - number.size(), '0');
    SceneObject o;
    o.name = prefix + "_" + number;
    o.mesh_text = mesh;
    o.mesh = mesh;
    o.poses = std::move(poses);
    out_.scene.objects.push_back(std::move(o));
  }

  const ProductionLineOptions& options_;
  std::size_t frames_;
  std::size_t name_width_ = 2;
  GeneratedScene out_;
  std::map<std::string, Equipment> equipment_;
  std::map<std::string, std::size_t> counters_;
};

enum class Station { Conveyor, Dryer, Press, RobotCell };

/// Objects of each station (see the station functions).
std::size_t station_objects(Station s) {
  switch (s) {
    case Station::Conveyor:
      return 10 + 2 + 2;  // rollers, sheets, bed, portal
    case Station::Dryer:
      return 1 + 12 + 3 + 1;  // tunnel, rollers, sheets, bed
    case Station::Press:
      return 4;  // frame, lower and upper platen, sheet
    case Station::RobotCell:
      return 4 + 8 + 1 + 1;  // pallet, base, two links; rollers, pallet, bed
  }
  return 0;
}

GeneratedScene generate_equipment(const ProductionLineOptions& options) {
  constexpr Station cycle[] = {Station::Conveyor, Station::Dryer,     Station::Press,
                               Station::Conveyor, Station::RobotCell, Station::Press,
                               Station::Conveyor};
  LineBuilder line(options);
  Scalar x = 0;
  for (std::uint64_t index = 0; line.remaining() > 0; ++index) {
    Rng rng(options.seed, index);
    const Station s = cycle[index % std::size(cycle)];
    Scalar length = 0;
    if (station_objects(s) > line.remaining()) {
      length = line.filler(rng, x, line.remaining());
    } else {
      switch (s) {
        case Station::Conveyor:
          length = line.conveyor(rng, x, 10, 2, false, true, true);
          break;
        case Station::Dryer:
          length = line.dryer(rng, x);
          break;
        case Station::Press:
          length = line.press(rng, x);
          break;
        case Station::RobotCell:
          length = line.robot_cell(rng, x);
          break;
      }
    }
    x += length + kStationGap + rng.uniform(0, 0.3);
  }
  return line.take();
}

// ---- Given mesh files ----

std::string sanitized_stem(const std::filesystem::path& path) {
  std::string stem = path.stem().string();
  for (char& c : stem) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) c = '_';
  }
  return stem.empty() ? std::string("mesh") : stem;
}

std::string padded(std::size_t value, std::size_t width) {
  std::string s = std::to_string(value);
  if (s.size() < width) s.insert(0, width - s.size(), '0');
  return s;
}

/// Objects in pairs along x: one static, one that spins and moves from well apart (bounding
/// spheres disjoint) to the other's centre and back.
GeneratedScene generate_from_files(const ProductionLineOptions& options) {
  GeneratedScene out;
  out.scene.frames = options.frames;
  // Files beyond the object count would not be used: they are not loaded.
  const std::size_t files = std::min(options.mesh_files.size(), options.objects);
  const std::size_t width = std::max<std::size_t>(2, std::to_string(options.objects - 1).size());
  std::vector<std::string> names;
  std::vector<std::string> stems;
  std::vector<Scalar> radius;
  for (std::size_t k = 0; k < files; ++k) {
    Mesh mesh = load_mesh(options.mesh_files[k]);
    const Aabb box = mesh.bounds();
    const Vec3 centre = (box.min + box.max) / 2;
    for (Vec3& v : mesh.vertices) v -= centre;
    const Scalar r = box.extent().norm() / 2;
    radius.push_back(r > 0 ? r : 1);
    stems.push_back(sanitized_stem(options.mesh_files[k]));
    names.push_back("meshes/" + padded(k, 2) + "_" + stems.back() + ".obj");
    out.meshes.emplace_back(names.back(), std::move(mesh));
  }
  const Scalar largest = *std::max_element(radius.begin(), radius.end());
  const Scalar pitch = 6 * largest;
  for (std::size_t i = 0; i < options.objects; ++i) {
    Rng rng(options.seed, i);
    const std::size_t k = i % files;
    SceneObject o;
    o.name = stems[k] + "_" + padded(i, width);
    o.mesh_text = names[k];
    o.mesh = names[k];
    const Vec3 home(pitch * static_cast<Scalar>(i / 2), 0, 0);
    const Vec3 tilt(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Mat3 start = rot(tilt.norm() > 1e-3 ? tilt : Vec3::UnitZ(), rng.uniform(0, 2 * kPi));
    const bool mover = i % 2 == 1;
    if (!mover) {
      o.poses.push_back(pose(start, home));
    } else {
      const Scalar far = 1.05 * (radius[k] + radius[(i - 1) % files]);
      const Scalar period = std::round(rng.uniform(60, 120));
      const Scalar phase = rng.uniform(0, 1);
      const Scalar spin = rng.uniform(0.01, 0.05);
      const Vec3 axis(rng.uniform(-1, 1), rng.uniform(-1, 1), 1);
      o.poses.reserve(options.frames);
      for (std::size_t f = 0; f < options.frames; ++f) {
        const Scalar u = phase + static_cast<Scalar>(f) / period;
        const Scalar d = far * (0.5 + 0.5 * std::cos(2 * kPi * u));
        const Scalar angle = std::fmod(spin * static_cast<Scalar>(f), 2 * kPi);
        o.poses.push_back(pose(rot(axis, angle) * start, home + Vec3(d, 0, 0)));
      }
    }
    out.scene.objects.push_back(std::move(o));
  }
  return out;
}

}  // namespace

void validate_options(const ProductionLineOptions& options) {
  if (options.objects < kMinObjects || options.objects > kMaxObjects) {
    throw antcd::ArgumentError("--objects must be between " + std::to_string(kMinObjects) +
                               " and " + std::to_string(kMaxObjects) + ", got " +
                               std::to_string(options.objects));
  }
  if (options.vertices < kMinVertices || options.vertices > kMaxVertices) {
    throw antcd::ArgumentError(
        "--vertices must be between " + std::to_string(kMinVertices) +
        " (a box's 8 corners: the coarsest closed solid the equipment is built from) and " +
        std::to_string(kMaxVertices) + ", got " + std::to_string(options.vertices));
  }
  if (options.frames < 1 || options.frames > kMaxFrames) {
    throw antcd::ArgumentError("--frames must be between 1 and " + std::to_string(kMaxFrames) +
                               ", got " + std::to_string(options.frames));
  }
  if (options.objects * options.frames > kMaxPoses) {
    throw antcd::ArgumentError("--objects × --frames must be at most " + std::to_string(kMaxPoses) +
                               " (one pose per moving object and " +
                               "frame is kept in memory), got " +
                               std::to_string(options.objects * options.frames));
  }
  for (const std::filesystem::path& p : options.mesh_files) {
    if (p.empty()) throw antcd::ArgumentError("--mesh: an empty file name was given");
  }
}

GeneratedScene generate_production_line(const ProductionLineOptions& options) {
  validate_options(options);
  return options.mesh_files.empty() ? generate_equipment(options) : generate_from_files(options);
}

std::filesystem::path write_scene(const GeneratedScene& generated,
                                  const std::filesystem::path& dir) {
  // Check every name before writing anything.
  for (const auto& [name, mesh] : generated.meshes) {
    const std::filesystem::path rel = std::filesystem::path(name).lexically_normal();
    if (name.empty() || rel.is_absolute() || rel.has_root_path() || rel.empty() ||
        *rel.begin() == "..") {
      throw antcd::ArgumentError("write_scene: mesh file name '" + name +
                                 "' must be relative and stay inside the scene folder");
    }
  }
  create_folders(dir);
  for (const auto& [name, mesh] : generated.meshes) {
    const std::filesystem::path path = dir / std::filesystem::path(name);
    create_folders(path.parent_path());
    save_obj(mesh, path);
  }
  const std::filesystem::path scene_path = dir / "scene.json";
  save_scene(generated.scene, scene_path);
  return scene_path;
}

SceneStats scene_stats(const GeneratedScene& generated) {
  SceneStats s;
  s.objects = generated.scene.objects.size();
  s.meshes = generated.meshes.size();
  std::map<std::string, std::size_t> vertices_of;
  s.min_vertices = std::numeric_limits<std::size_t>::max();
  for (const auto& [name, mesh] : generated.meshes) {
    vertices_of[name] = mesh.vertices.size();
    s.min_vertices = std::min(s.min_vertices, mesh.vertices.size());
    s.max_vertices = std::max(s.max_vertices, mesh.vertices.size());
  }
  if (generated.meshes.empty()) s.min_vertices = 0;
  double sum = 0;
  for (const SceneObject& o : generated.scene.objects) {
    if (generated.scene.frames > 1 && o.poses.size() == generated.scene.frames) ++s.moving_objects;
    const auto it = vertices_of.find(o.mesh_text);
    if (it != vertices_of.end()) sum += static_cast<double>(it->second);
  }
  if (s.objects > 0) s.average_vertices = sum / static_cast<double>(s.objects);
  return s;
}

}  // namespace antcd::experiments
