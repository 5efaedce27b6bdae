// The veneer line's stations and their motions.
//
// Lengths are in metres, the line runs along +x, z is up and the floor is z = 0 (there is no floor
// object). Stations follow each other with gaps of 1.2–1.5 m, in a fixed cycle:
//   conveyor, dryer, press, conveyor, robot cell, press, conveyor, (repeat)
// until the next station would exceed the requested object count; the rest is filled with a short
// conveyor (or a column when only one object is left).
#include "shared/production_line/modes.hpp"

#include "shared/production_line/equipment.hpp"
#include "shared/production_line/flexible.hpp"
#include "shared/production_line/poses.hpp"
#include "shared/production_line/robot_arm.hpp"
#include "shared/production_line/tessellation.hpp"
#include "shared/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared::line {
namespace {

using Rng = SplitMix64;

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
  /// The flexible sheet (options.flexible): a grid of about vertices / 2 vertices, about twice
  /// as many columns (along the travel, where it bends) per metre as rows.
  const Equipment& flexible_sheet() {
    return equipment("veneer_sheet_flexible", [&] {
      const auto target = static_cast<Scalar>(std::max<std::size_t>(options_.vertices / 2, 16));
      const auto columns =
          static_cast<std::size_t>(std::max(4.0, std::round(std::sqrt(2 * target))));
      const auto rows = static_cast<std::size_t>(
          std::max(3.0, std::round(target / static_cast<Scalar>(columns))));
      Equipment e;
      e.mesh = flexible_sheet_mesh(columns, rows, kSheetHalfX, kSheetHalfY);
      return e;
    });
  }

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

  /// A deforming object: its pose and its vertices (model frame) at each frame, with self
  /// collision on; the side file is frames/<name>.avf.
  void add_flexible(const std::string& prefix, const Equipment& e,
                    const std::function<Transform(std::size_t)>& pose_at,
                    const std::function<std::vector<Vec3>(std::size_t, const Transform&,
                                                          const Mesh&)>& at_frame) {
    std::vector<Transform> poses;
    poses.reserve(frames_);
    auto frames = std::make_shared<VertexFrames>();
    frames->vertex_count = static_cast<std::uint32_t>(e.mesh.vertices.size());
    frames->frames = frames_;
    frames->positions.reserve(e.mesh.vertices.size() * frames_);
    for (std::size_t f = 0; f < frames_; ++f) {
      poses.push_back(pose_at(f));
      const std::vector<Vec3> v = at_frame(f, poses.back(), e.mesh);
      frames->positions.insert(frames->positions.end(), v.begin(), v.end());
    }
    SceneObject& o = add(prefix, e.file, std::move(poses));
    o.vertex_file_text = "frames/" + o.name + ".avf";
    o.vertex_file = o.vertex_file_text;
    o.vertex_frames = std::move(frames);
    o.self_collision = true;
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
    const bool flexible = options_.flexible && !pallets;
    const std::string load_file =
        pallets ? pallet().file : (flexible ? flexible_sheet().file : sheet().file);
    // A flexible sheet has no thickness: its surface lies where a rigid sheet's bottom does.
    const Scalar load_z =
        pallets || flexible ? kRollerTop - depth : kRollerTop + kSheetHalfZ - depth;
    for (std::size_t k = 0; k < loads; ++k) {
      const Scalar offset = phase + travel * static_cast<Scalar>(k) / static_cast<Scalar>(loads);
      const auto pose_at = [=](std::size_t f) {
        const Scalar s = travel * fraction((offset + speed * static_cast<Scalar>(f)) / travel);
        return at(Vec3(x0 + s, 0, load_z));
      };
      if (!flexible) {
        add_moving(pallets ? "pallet" : "sheet", load_file, pose_at);
        continue;
      }
      const RollerSupport support{x0 + kRollerPitch / 2, rollers, kRollerPitch, kRollerRadius};
      const bool folds = !folded_;
      folded_ = true;
      // The fold's period: 80 frames, or the whole run when shorter (at least 8 frames), so that
      // every run of 8 frames or more sees the flap pass through the sheet.
      const Scalar period = static_cast<Scalar>(std::clamp<std::size_t>(frames_, 8, 80));
      add_flexible("sheet", flexible_sheet(), pose_at,
                   [=](std::size_t f, const Transform& t, const Mesh& rest) {
                     const Fold fold =
                         folds ? fold_at(fraction(static_cast<Scalar>(f) / period)) : Fold{};
                     return sheet_frame(rest, support, t.translation.x(), fold);
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
  SceneObject& add(const std::string& prefix, const std::string& mesh,
                   std::vector<Transform> poses) {
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
    return out_.scene.objects.back();
  }

  const ProductionLineOptions& options_;
  std::size_t frames_;
  std::size_t name_width_ = 2;
  GeneratedScene out_;
  std::map<std::string, Equipment> equipment_;
  std::map<std::string, std::size_t> counters_;
  bool folded_ = false;  ///< the folding sheet has been placed
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

}  // namespace

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

}  // namespace antcd::shared::line
