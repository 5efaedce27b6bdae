// The antcd-scene/1 parser: a valid file, and one clear error per violation.
#include <antcd/file.hpp>
#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace antcd {
namespace {

const char* kValid = R"({
  "format": "antcd-scene/1", "frames": 3,
  "objects": [
    { "name": "roller_07", "mesh": "meshes/roller.obj", "scale": 2.0,
      "poses": [ { "translation": [0.0, 1.5, 0.0], "rotation_wxyz": [1.0, 0.0, 0.0, 0.0] } ] },
    { "name": "press_02", "mesh": "/abs/press.stl",
      "poses": [ { "translation": [1, 2, 3] },
                 { "rotation_wxyz": [0.7071068, 0.7071068, 0, 0] },
                 { "translation": [0, 0, 0], "rotation_wxyz": [1.0005, 0, 0, 0] } ] }
  ] })";

TEST(SceneFile, ParsesAValidScene) {
  const SceneDescription s = parse_scene(kValid, "/base", "scene.json");
  EXPECT_EQ(s.frames, 3u);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].name, "roller_07");
  EXPECT_EQ(s.objects[0].mesh, std::filesystem::path("/base/meshes/roller.obj"));
  EXPECT_EQ(s.objects[0].scale, 2.0);
  EXPECT_EQ(s.objects[0].poses.size(), 1u);
  EXPECT_EQ(s.objects[0].pose(2).translation, Vec3(0, 1.5, 0));  // static: same pose every frame
  EXPECT_EQ(s.objects[1].mesh, std::filesystem::path("/abs/press.stl"));
  EXPECT_EQ(s.objects[1].scale, 1.0);
  EXPECT_EQ(s.objects[1].pose(0).translation, Vec3(1, 2, 3));
  EXPECT_TRUE(s.objects[1].pose(1).rotation.isApprox(
      Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix(), 1e-6));
  // Within 1e-3 of unit length: normalised.
  EXPECT_TRUE(s.objects[1].pose(2).rotation.isApprox(Mat3::Identity(), 1e-12));
}

TEST(SceneFile, RoundTripsThroughJson) {
  const SceneDescription s = parse_scene(kValid, "/base", "scene.json");
  const SceneDescription t = parse_scene(scene_to_json(s), "/base", "again.json");
  ASSERT_EQ(t.objects.size(), s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    EXPECT_EQ(t.objects[i].name, s.objects[i].name);
    EXPECT_EQ(t.objects[i].mesh, s.objects[i].mesh);
    EXPECT_EQ(t.objects[i].scale, s.objects[i].scale);
    ASSERT_EQ(t.objects[i].poses.size(), s.objects[i].poses.size());
    for (std::size_t k = 0; k < s.objects[i].poses.size(); ++k) {
      EXPECT_TRUE(t.objects[i].poses[k].rotation.isApprox(s.objects[i].poses[k].rotation, 1e-12));
      EXPECT_TRUE(t.objects[i].poses[k].translation.isApprox(s.objects[i].poses[k].translation));
    }
  }
}

struct BadCase {
  const char* name;
  const char* json;
  const char* expect;  // a substring the message must hold
};

class SceneFileErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneFileErrors, NamesTheProblem) {
  const BadCase& c = GetParam();
  try {
    parse_scene(c.json, "/base", "bad.json");
    FAIL() << "expected SceneError for " << c.name;
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("bad.json: ", 0), 0u) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

#define OBJ(name, poses) R"({ "name": ")" name R"(", "mesh": "m.obj", "poses": )" poses " }"
#define SCENE(frames, objects) \
  R"({ "format": "antcd-scene/1", "frames": )" frames R"(, "objects": [)" objects "] }"
#define P0 R"([ { "translation": [0, 0, 0] } ])"

INSTANTIATE_TEST_SUITE_P(
    AllViolations, SceneFileErrors,
    ::testing::Values(
        BadCase{"not_json", "{ nope", "not valid JSON"},
        BadCase{"not_object", "[1, 2]", "JSON object"},
        BadCase{"no_format", R"({ "frames": 1, "objects": [] })", "missing 'format'"},
        BadCase{"unknown_format", R"({ "format": "antcd-scene/2", "frames": 1, "objects": [] })",
                "unknown format"},
        BadCase{"no_frames", R"({ "format": "antcd-scene/1", "objects": [] })", "'frames'"},
        BadCase{"zero_frames", SCENE("0", OBJ("a", P0)), "'frames'"},
        BadCase{"fractional_frames", SCENE("1.5", OBJ("a", P0)), "'frames'"},
        BadCase{"no_objects", R"({ "format": "antcd-scene/1", "frames": 1 })", "'objects'"},
        BadCase{"empty_objects", SCENE("1", ""), "'objects' is empty"},
        BadCase{"unknown_top_field",
                R"({ "format": "antcd-scene/1", "frames": 1, "objects": [], "x": 1 })",
                "unknown field 'x'"},
        BadCase{"no_name", SCENE("1", R"({ "mesh": "m.obj", "poses": [ {} ] })"), "object 0"},
        BadCase{"duplicate_name", SCENE("1", OBJ("a", P0) "," OBJ("a", P0)),
                "object 'a': duplicate name"},
        BadCase{"missing_mesh", SCENE("1", R"({ "name": "a", "poses": [ {} ] })"),
                "object 'a': missing or empty 'mesh'"},
        BadCase{"wrong_pose_count", SCENE("3", OBJ("a", R"([ {}, {} ])")),
                "object 'a': has 2 poses; expected 1 or 3"},
        BadCase{"no_poses", SCENE("1", OBJ("a", "[]")), "object 'a': missing 'poses'"},
        BadCase{"nan_translation", SCENE("1", OBJ("a", R"([ { "translation": [0, NaN, 0] } ])")),
                "not valid JSON"},
        BadCase{"huge_translation", SCENE("1", OBJ("a", R"([ { "translation": [0, 1e999, 0] } ])")),
                "number overflow"},
        BadCase{"short_translation", SCENE("1", OBJ("a", R"([ { "translation": [0, 1] } ])")),
                "object 'a': pose 0: 'translation' must be an array of 3 numbers"},
        BadCase{"string_coordinate", SCENE("1", OBJ("a", R"([ { "translation": [0, "1", 2] } ])")),
                "must be a number"},
        BadCase{"far_from_unit", SCENE("1", OBJ("a", R"([ { "rotation_wxyz": [1, 0.1, 0, 0] } ])")),
                "object 'a': pose 0: quaternion has length"},
        BadCase{"zero_quaternion", SCENE("1", OBJ("a", R"([ { "rotation_wxyz": [0, 0, 0, 0] } ])")),
                "quaternion has length 0"},
        BadCase{"bad_scale",
                SCENE("1", R"({ "name": "a", "mesh": "m.obj", "scale": -1, "poses": [ {} ] })"),
                "object 'a': 'scale' must be > 0"},
        BadCase{"unknown_object_field",
                SCENE("1", R"({ "name": "a", "mesh": "m.obj", "colour": 1, "poses": [ {} ] })"),
                "object 'a': unknown field 'colour'"},
        BadCase{"unknown_pose_field", SCENE("1", OBJ("a", R"([ { "position": [0, 0, 0] } ])")),
                "unknown pose field 'position'"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

TEST(SceneFile, MissingFileAndDirectory) {
  const auto dir = test::fresh_temp_dir("scene_missing");
  EXPECT_THROW(load_scene(dir / "nope.json"), SceneError);
  try {
    load_scene(dir);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos);
  }
  // A device would read forever: refused before reading.
  if (std::filesystem::exists("/dev/zero")) {
    try {
      load_scene("/dev/zero");
      FAIL();
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
    }
  }
}

TEST(SceneFile, MissingMeshNamesTheObject) {
  const auto dir = test::fresh_temp_dir("scene_mesh_missing");
  write_file_atomic(dir / "scene.json", SCENE("1", OBJ("crane", P0)));
  try {
    Scene scene(load_scene(dir / "scene.json"));
    FAIL();
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("object 'crane'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("m.obj"), std::string::npos) << msg;
  }
}

TEST(SceneFile, SaveIsAtomicAndLoadable) {
  const auto dir = test::fresh_temp_dir("scene_save");
  const SceneDescription s = parse_scene(kValid, dir, "scene.json");
  save_scene(s, dir / "out.json");
  const SceneDescription t = load_scene(dir / "out.json");
  EXPECT_EQ(t.objects.size(), 2u);
  // No temporary file left beside it.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  EXPECT_THROW(save_scene(s, dir / "no_such_dir" / "x.json"), Error);
}

}  // namespace
}  // namespace antcd
