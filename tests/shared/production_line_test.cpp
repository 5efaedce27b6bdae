// Tests of the production-line scene generator: options, structure, vertex budget, determinism,
// files, and that the motions bring objects in and out of contact under the exact narrow phase.
#include "shared/production_line.hpp"
#include "support/test_support.hpp"

#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace antcd::shared {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

std::string invalid_message(const ProductionLineOptions& options) {
  try {
    (void)generate_production_line(options);
  } catch (const antcd::ArgumentError& e) {
    return e.what();
  }
  return "(no exception)";
}

/// The kind of an object: its name without the trailing "_NN".
std::string kind_of(const std::string& name) { return name.substr(0, name.rfind('_')); }

/// Mean over objects of the vertex count of their mesh.
double object_vertex_average(const GeneratedScene& g) {
  std::map<std::string, std::size_t> vertices;
  for (const auto& [name, mesh] : g.meshes) vertices[name] = mesh.vertices.size();
  double sum = 0;
  for (const SceneObject& o : g.scene.objects) sum += static_cast<double>(vertices.at(o.mesh_text));
  return sum / static_cast<double>(g.scene.objects.size());
}

void expect_same_meshes(const GeneratedScene& a, const GeneratedScene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].first, b.meshes[i].first);
    EXPECT_EQ(a.meshes[i].second.vertices, b.meshes[i].second.vertices) << a.meshes[i].first;
    EXPECT_EQ(a.meshes[i].second.triangles, b.meshes[i].second.triangles) << a.meshes[i].first;
  }
}

/// Structural checks that hold for every generated scene.
void expect_well_formed(const GeneratedScene& g, const ProductionLineOptions& options) {
  ASSERT_EQ(g.scene.objects.size(), options.objects);
  EXPECT_EQ(g.scene.frames, options.frames);
  std::set<std::string> mesh_names;
  for (const auto& [name, mesh] : g.meshes) {
    EXPECT_TRUE(mesh_names.insert(name).second) << "duplicate mesh " << name;
    EXPECT_NO_THROW(validate_mesh(mesh, name));
    EXPECT_EQ(mesh.degenerate_triangle_count(), 0u) << name;
  }
  std::set<std::string> names;
  std::set<std::string> used;
  for (const SceneObject& o : g.scene.objects) {
    EXPECT_FALSE(o.name.empty());
    EXPECT_TRUE(names.insert(o.name).second) << "duplicate name " << o.name;
    EXPECT_TRUE(mesh_names.contains(o.mesh_text)) << o.name << " uses unknown mesh " << o.mesh_text;
    EXPECT_EQ(o.mesh.generic_string(), o.mesh_text);
    used.insert(o.mesh_text);
    EXPECT_TRUE(o.poses.size() == 1 || o.poses.size() == options.frames)
        << o.name << " has " << o.poses.size() << " poses";
    EXPECT_EQ(o.scale, 1.0);
    for (const Transform& t : o.poses) {
      ASSERT_TRUE(t.translation.allFinite()) << o.name;
      ASSERT_LT((t.rotation.transpose() * t.rotation - Mat3::Identity()).norm(), 1e-12) << o.name;
      ASSERT_NEAR(t.rotation.determinant(), 1.0, 1e-12) << o.name;
    }
  }
  EXPECT_EQ(used, mesh_names) << "every mesh is used by some object";
}

// ---- options ----

TEST(ProductionLine, RejectsBadOptionsNamingTheOption) {
  ProductionLineOptions o;
  o.objects = 1;
  EXPECT_NE(invalid_message(o).find("--objects"), std::string::npos) << invalid_message(o);
  o.objects = 100'001;
  EXPECT_NE(invalid_message(o).find("--objects"), std::string::npos);

  o = {};
  o.vertices = 7;
  EXPECT_NE(invalid_message(o).find("--vertices"), std::string::npos) << invalid_message(o);
  o.vertices = 1'000'001;
  EXPECT_NE(invalid_message(o).find("--vertices"), std::string::npos);

  o = {};
  o.frames = 0;
  EXPECT_NE(invalid_message(o).find("--frames"), std::string::npos) << invalid_message(o);
  o.frames = 10'000'001;
  EXPECT_NE(invalid_message(o).find("--frames"), std::string::npos);

  o = {};
  o.objects = 100'000;
  o.frames = 1'000;  // 10^8 poses
  EXPECT_NE(invalid_message(o).find("--frames"), std::string::npos) << invalid_message(o);

  o = {};
  o.mesh_files = {std::filesystem::path()};
  EXPECT_THROW((void)generate_production_line(o), antcd::ArgumentError);

  // The limits themselves are accepted.
  o = {};
  o.objects = 2;
  o.vertices = 8;
  o.frames = 1;
  EXPECT_NO_THROW(validate_options(o));
  EXPECT_NO_THROW((void)generate_production_line(o));
}

// ---- structure ----

TEST(ProductionLine, DefaultSceneIsAVeneerLine) {
  const ProductionLineOptions options;
  const GeneratedScene g = generate_production_line(options);
  expect_well_formed(g, options);
  EXPECT_GE(g.meshes.size(), 8u) << "several distinct meshes";
  EXPECT_LT(g.meshes.size(), options.objects) << "meshes are shared between objects";

  std::map<std::string, std::size_t> kinds;
  std::size_t moving = 0;
  for (const SceneObject& o : g.scene.objects) {
    ++kinds[kind_of(o.name)];
    if (o.poses.size() == options.frames) ++moving;
  }
  for (const char* k :
       {"roller", "sheet", "bed", "portal", "dryer", "press_frame", "press_lower", "press_upper",
        "pallet", "robot_base", "robot_upper_arm", "robot_forearm"}) {
    EXPECT_GT(kinds[k], 0u) << "no " << k;
  }
  EXPECT_GT(moving, 0u);
  EXPECT_LT(moving, options.objects) << "some equipment is static";

  const SceneStats stats = scene_stats(g);
  EXPECT_EQ(stats.objects, options.objects);
  EXPECT_EQ(stats.moving_objects, moving);
  EXPECT_EQ(stats.meshes, g.meshes.size());
  EXPECT_DOUBLE_EQ(stats.average_vertices, object_vertex_average(g));
  EXPECT_LE(stats.min_vertices, stats.max_vertices);
}

TEST(ProductionLine, AnyObjectCountAndSingleFrame) {
  for (const std::size_t objects : {2u, 3u, 4u, 5u, 13u, 17u, 91u, 150u}) {
    ProductionLineOptions options;
    options.objects = objects;
    options.vertices = 60;
    options.frames = 1;
    const GeneratedScene g = generate_production_line(options);
    SCOPED_TRACE(objects);
    expect_well_formed(g, options);
    for (const SceneObject& o : g.scene.objects) EXPECT_EQ(o.poses.size(), 1u) << o.name;
  }
  ProductionLineOptions wide;
  wide.objects = 150;
  wide.frames = 2;
  const GeneratedScene g = generate_production_line(wide);
  EXPECT_EQ(g.scene.objects.back().name.size(), g.scene.objects.back().name.rfind('_') + 4)
      << "names padded to the digits of the object count: " << g.scene.objects.back().name;
}

class VertexBudget : public ::testing::TestWithParam<std::size_t> {};

TEST_P(VertexBudget, AverageWithinFifteenPercent) {
  ProductionLineOptions options;
  options.vertices = GetParam();
  options.frames = 2;
  const GeneratedScene g = generate_production_line(options);
  const double average = object_vertex_average(g);
  const double request = static_cast<double>(options.vertices);
  EXPECT_NEAR(average, request, 0.15 * request);
  // Every mesh is near the request too, not only the average.
  for (const auto& [name, mesh] : g.meshes) {
    EXPECT_NEAR(static_cast<double>(mesh.vertices.size()), request, 0.25 * request) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(ProductionLine, VertexBudget, ::testing::Values(300, 750, 2000));

TEST(ProductionLine, TinyVertexBudgetStaysSmall) {
  ProductionLineOptions options;
  options.vertices = 8;
  options.frames = 1;
  const GeneratedScene g = generate_production_line(options);
  EXPECT_LT(object_vertex_average(g), 16.0);
}

// ---- determinism ----

TEST(ProductionLine, DeterministicBySeed) {
  ProductionLineOptions options;
  options.seed = 42;
  const GeneratedScene a = generate_production_line(options);
  const GeneratedScene b = generate_production_line(options);
  EXPECT_EQ(scene_to_json(a.scene), scene_to_json(b.scene));
  expect_same_meshes(a, b);

  options.seed = 43;
  const GeneratedScene c = generate_production_line(options);
  EXPECT_NE(scene_to_json(a.scene), scene_to_json(c.scene));
  ASSERT_EQ(c.scene.objects.size(), a.scene.objects.size());
}

// ---- files ----

TEST(ProductionLine, WriteSceneRoundTrips) {
  ProductionLineOptions options;
  options.frames = 50;
  const GeneratedScene g = generate_production_line(options);
  const std::filesystem::path dir = test::fresh_temp_dir("production_line_write") / "line";
  const std::filesystem::path path = write_scene(g, dir);
  EXPECT_EQ(path, dir / "scene.json");
  ASSERT_TRUE(std::filesystem::is_regular_file(path));

  const SceneDescription loaded = load_scene(path);
  ASSERT_EQ(loaded.frames, g.scene.frames);
  ASSERT_EQ(loaded.objects.size(), g.scene.objects.size());
  for (std::size_t i = 0; i < loaded.objects.size(); ++i) {
    const SceneObject& a = g.scene.objects[i];
    const SceneObject& b = loaded.objects[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.mesh_text, b.mesh_text);
    EXPECT_EQ(b.mesh, dir / a.mesh_text);
    EXPECT_EQ(a.scale, b.scale);
    ASSERT_EQ(a.poses.size(), b.poses.size()) << a.name;
    for (std::size_t k = 0; k < a.poses.size(); ++k) {
      ASSERT_LT((a.poses[k].translation - b.poses[k].translation).norm(), 1e-12) << a.name;
      ASSERT_LT((a.poses[k].rotation - b.poses[k].rotation).norm(), 1e-12) << a.name;
    }
  }
  for (const auto& [name, mesh] : g.meshes) {
    const std::filesystem::path file = dir / name;
    ASSERT_TRUE(std::filesystem::is_regular_file(file)) << file;
    const Mesh back = load_mesh(file);
    EXPECT_EQ(back.triangles.size(), mesh.triangles.size()) << name;
  }

  // Writing the same scene again gives byte-identical files.
  const std::filesystem::path dir2 = test::fresh_temp_dir("production_line_write2");
  (void)write_scene(generate_production_line(options), dir2);
  EXPECT_EQ(read_file(path), read_file(dir2 / "scene.json"));
  for (const auto& [name, mesh] : g.meshes) {
    EXPECT_EQ(read_file(dir / name), read_file(dir2 / name)) << name;
  }
}

TEST(ProductionLine, WriteSceneRejectsNamesLeavingTheFolder) {
  const std::filesystem::path dir = test::fresh_temp_dir("production_line_escape");
  for (const char* bad : {"../outside.obj", "/tmp/absolute.obj", "meshes/../../up.obj", ""}) {
    GeneratedScene g;
    g.meshes.emplace_back(bad, make_box(Vec3(1, 1, 1)));
    EXPECT_THROW((void)write_scene(g, dir / "scene"), antcd::ArgumentError) << bad;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "outside.obj"));
}

// ---- contacts ----

struct ContactLog {
  std::size_t frames_sampled = 0;
  std::vector<std::size_t> pairs_per_frame;
  std::map<Pair, std::size_t> frames_in_contact;  ///< per colliding pair
  std::size_t candidates = 0;
};

ContactLog run_every(const Scene& scene, std::size_t step) {
  ContactLog log;
  for (std::size_t f = 0; f < scene.description().frames; f += step) {
    const FrameResult r = scene.run_frame(f, SceneQuery{});
    ++log.frames_sampled;
    log.pairs_per_frame.push_back(r.pairs.size());
    log.candidates += r.candidates.size();
    for (const Pair& p : r.pairs) ++log.frames_in_contact[p];
  }
  return log;
}

std::set<std::pair<std::string, std::string>> kind_pairs(const Scene& scene,
                                                         const ContactLog& log) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& [p, n] : log.frames_in_contact) {
    std::string a = kind_of(scene.description().objects[p.first].name);
    std::string b = kind_of(scene.description().objects[p.second].name);
    if (b < a) std::swap(a, b);
    out.emplace(a, b);
  }
  return out;
}

TEST(ProductionLine, NeighboursComeInAndOutOfContact) {
  const GeneratedScene g = generate_production_line({});
  const std::filesystem::path path =
      write_scene(g, test::fresh_temp_dir("production_line_contacts"));
  const Scene scene(load_scene(path));
  const ContactLog log = run_every(scene, 10);

  const std::size_t most =
      *std::max_element(log.pairs_per_frame.begin(), log.pairs_per_frame.end());
  EXPECT_GT(most, 0u) << "some frame has colliding pairs";
  const std::size_t all_pairs = 90 * 89 / 2;
  EXPECT_LT(most, all_pairs / 20) << "most object pairs never touch";
  std::size_t colliding = 0;
  for (const std::size_t n : log.pairs_per_frame) colliding += n;
  EXPECT_GT(log.candidates, colliding) << "the broad phase passes near, non-colliding pairs too";

  // Some pair is in contact in some sampled frame and apart in another.
  std::size_t changing = 0;
  for (const auto& [p, n] : log.frames_in_contact) {
    if (n < log.frames_sampled) ++changing;
  }
  EXPECT_GT(changing, 0u);

  // The designed contacts happen; the designed gaps hold.
  const auto kinds = kind_pairs(scene, log);
  EXPECT_TRUE(kinds.contains({"roller", "sheet"}));
  EXPECT_TRUE(kinds.contains({"press_lower", "sheet"}));
  EXPECT_TRUE(kinds.contains({"press_upper", "sheet"}));
  EXPECT_TRUE(kinds.contains({"pallet", "roller"}));
  EXPECT_TRUE(kinds.contains({"pallet", "robot_forearm"}));
  for (const auto& [a, b] : kinds) {
    for (const char* never :
         {"bed", "portal", "dryer", "press_frame", "robot_base", "robot_upper_arm"}) {
      EXPECT_TRUE(a != never && b != never) << a << " touches " << b;
    }
    EXPECT_FALSE(a == "sheet" && b == "sheet") << "sheets keep their distance";
  }
}

TEST(ProductionLine, PlacesGivenMeshFiles) {
  const std::filesystem::path dir = test::fresh_temp_dir("production_line_files");
  save_obj(transformed(make_box(Vec3(0.5, 0.3, 0.2), 2),
                       Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(7, 8, 9))),
           dir / "crate.obj");
  save_obj(make_torus(1.0, 0.25, 24, 12), dir / "ring.obj");

  ProductionLineOptions options;
  options.objects = 7;
  options.frames = 120;
  options.mesh_files = {dir / "crate.obj", dir / "ring.obj"};
  const GeneratedScene g = generate_production_line(options);
  expect_well_formed(g, options);
  ASSERT_EQ(g.meshes.size(), 2u);
  EXPECT_EQ(g.scene.objects[0].mesh_text, g.meshes[0].first);
  EXPECT_EQ(g.scene.objects[1].mesh_text, g.meshes[1].first);
  EXPECT_EQ(g.scene.objects[2].mesh_text, g.meshes[0].first);
  EXPECT_EQ(kind_of(g.scene.objects[0].name), "crate");
  EXPECT_EQ(kind_of(g.scene.objects[1].name), "ring");
  // Meshes are centred on their bounding-box centre.
  const Aabb box = g.meshes[0].second.bounds();
  EXPECT_LT(((box.min + box.max) / 2).norm(), 1e-12);
  EXPECT_EQ(g.meshes[1].second.triangles.size(), make_torus(1.0, 0.25, 24, 12).triangles.size());

  const ProductionLineOptions again = options;
  EXPECT_EQ(scene_to_json(generate_production_line(again).scene), scene_to_json(g.scene));

  const Scene scene(load_scene(write_scene(g, dir / "scene")));
  const ContactLog log = run_every(scene, 3);
  std::size_t changing = 0;
  for (const auto& [p, n] : log.frames_in_contact) {
    if (n < log.frames_sampled) ++changing;
  }
  EXPECT_GT(changing, 0u) << "the moving copies meet the static ones and leave again";
}

TEST(ProductionLine, MissingMeshFileIsAMeshError) {
  ProductionLineOptions options;
  options.mesh_files = {test::fresh_temp_dir("production_line_missing") / "nothing.obj"};
  EXPECT_THROW((void)generate_production_line(options), MeshError);
}

}  // namespace
}  // namespace antcd::shared
