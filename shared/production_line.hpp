// shared/production_line.hpp — a procedural scene of a veneer production line (the generator
// behind `antcd demo`, `antcd scene generate`, the tests and the benchmarks; its parts are in
// production_line/: tessellation, equipment, robot arm, line builder, file mode, writer).
//
// The paper's experiment (section 5.1) runs collision detection on 90 models of the equipment of a
// veneer production line, about 750 vertices each, over 300 simulation runs. This generator builds
// such a scene in the antcd-scene/1 format (see antcd/scene.hpp):
//
// - Equipment along a line in +x, in metres: roller conveyors (bed + spinning rollers + veneer
//   sheets travelling over them), drying tunnels over conveyors, hot presses (frame, fixed lower
//   platen, upper platen closing on a sheet that slides in and out), robot cells (pedestal, upper
//   arm, forearm swinging down onto a pallet, beside a pallet conveyor), portal frames.
// - Every mesh is built from the generators of antcd/mesh.hpp, tessellated so that it has about
//   `vertices` vertices. Meshes are shared between objects (one file per kind of equipment).
// - "Touching" means a slight interpenetration (a few millimetres, larger than the chord error of
//   the tessellation), so exact triangle tests see it. Parts that should not touch keep gaps of a
//   centimetre or more. Most object pairs never touch; near pairs (neighbouring rollers, sheets
//   inside a tunnel) give the broad phase real work.
// - The result depends only on the options: the same options give byte-identical files.
#pragma once

#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared {

/// Limits of ProductionLineOptions (they keep memory use sane).
inline constexpr std::size_t kMinObjects = 2;
inline constexpr std::size_t kMaxObjects = 100'000;
/// 8 is the smallest closed solid the generators make: a box has 8 corners (and a 3-sided prism
/// with its two cap centres has 8 vertices).
inline constexpr std::size_t kMinVertices = 8;
inline constexpr std::size_t kMaxVertices = 1'000'000;
inline constexpr std::size_t kMaxFrames = 10'000'000;  ///< the scene format's limit
/// objects × frames: every moving object holds one pose per frame in memory and in the file.
inline constexpr std::size_t kMaxPoses = 20'000'000;

struct ProductionLineOptions {
  std::size_t objects = 90;    ///< number of scene objects
  std::size_t vertices = 750;  ///< requested vertices per mesh (the scene average is within ±15 %)
  std::size_t frames = 300;    ///< frames of motion
  std::uint64_t seed = 1;      ///< speeds, phases and spacings of the stations
  /// When non-empty: place these meshes (cycled over the objects) instead of generated
  /// equipment. Each file is loaded (load_mesh), centred on its bounding-box centre and written
  /// into the scene folder; `vertices` is then not used. Objects come in pairs: one static, one
  /// that spins and moves from well apart (bounding spheres disjoint) to the other's centre and
  /// back, so their surfaces meet on the way.
  std::vector<std::filesystem::path> mesh_files;
  /// The veneer sheets of the roller conveyors (dryers' included) become deforming objects
  /// (`antcd scene generate --flexible`; production_line/flexible.hpp): tessellated sheets of zero
  /// thickness (a grid of about vertices / 2 vertices) that sag between the rollers, droop past
  /// the conveyor's ends, and (the first of them) fold onto themselves period after period, their
  /// flap passing through the sheet for some frames. Each has its vertices per frame (a side file,
  /// SceneObject::vertex_frames) and self_collision. The press's sheets stay rigid boxes (a
  /// sheet of no thickness cannot be held between both platens). Not with mesh_files.
  bool flexible = false;
};

/// flexible: the largest (sheet vertices) x frames, positions of one sheet held in memory and
/// written to its side file (24 bytes each).
inline constexpr std::size_t kMaxSheetPositions = 20'000'000;

/// A flat sheet of columns x rows vertices (each >= 2) in its z = 0 plane over [-half_x, half_x] x
/// [-half_y, half_y], two triangles per grid cell; vertices numbered in order of first use by the
/// triangles, so that an OBJ of it loads back in the same vertex order (load_mesh).
Mesh flexible_sheet_mesh(std::size_t columns, std::size_t rows, Scalar half_x, Scalar half_y);

struct GeneratedScene {
  /// Mesh paths are relative to the scene folder (mesh_text == mesh, e.g. "meshes/roller.obj").
  SceneDescription scene;
  /// File name relative to the scene folder → mesh, in first-use order; every object's mesh is
  /// here exactly once.
  std::vector<std::pair<std::string, Mesh>> meshes;
};

/// Throws antcd::ArgumentError naming the option ("--objects must be ...") when out of range.
void validate_options(const ProductionLineOptions& options);

/// Builds the scene in memory. Deterministic: the same options give the same scene. Throws
/// antcd::ArgumentError for bad options and MeshError for an unreadable mesh file.
GeneratedScene generate_production_line(const ProductionLineOptions& options);

/// Writes DIR/meshes/*.obj (save_obj), the side files of the deforming objects
/// (save_vertex_frames, at their vertex_file_text, e.g. DIR/frames/sheet_03.avf) and then
/// DIR/scene.json (save_scene), creating folders as needed; every file is written atomically.
/// Returns the path of scene.json. Throws antcd::ArgumentError for a mesh name that is absolute or
/// leaves the folder, antcd::Error when writing fails.
std::filesystem::path write_scene(const GeneratedScene& generated,
                                  const std::filesystem::path& dir);

/// The generated scene as a Scene, with its meshes taken from memory (no file round trip, so no
/// rounding through a mesh file format). Throws SceneError like Scene's constructor.
Scene make_scene(const GeneratedScene& generated, const BuildOptions& options = {});

/// Summary numbers for reports.
struct SceneStats {
  std::size_t objects = 0;
  std::size_t moving_objects = 0;  ///< objects with one pose per frame (frames > 1)
  std::size_t meshes = 0;
  double average_vertices = 0;   ///< mean over objects of their mesh's vertex count
  std::size_t min_vertices = 0;  ///< over meshes
  std::size_t max_vertices = 0;  ///< over meshes
};
SceneStats scene_stats(const GeneratedScene& generated);

}  // namespace antcd::shared
