// Deforming scene objects, the file side: the vertex-frames side file (round trip, one clear error
// per bad input, memory bounded by the file's size), the scene fields that name it, and the
// Scene's checks of a side file against its mesh. The runs are in flex_scene_test.cpp.
#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/scene.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "scene/flex_support.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no SceneError)";
}

void expect_one_line(const std::string& msg, const std::string& part1, const std::string& part2) {
  EXPECT_NE(msg.find(part1), std::string::npos) << msg;
  EXPECT_NE(msg.find(part2), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_LE(msg.size(), kPrintableLineLength) << msg;
}

TEST(VertexFrames, RoundTripsBitForBit) {
  const VertexFrames v = test::wave_frames(test::grid_mesh(4, 3), 5);
  const std::string bytes = vertex_frames_bytes(v);
  EXPECT_EQ(bytes.size(), 24 + 24 * 12 * 5u);
  EXPECT_EQ(std::memcmp(bytes.data(), "ANTCDVFR", 8), 0);
  const VertexFrames w = parse_vertex_frames(
      {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, "x.avf");
  EXPECT_EQ(w.vertex_count, 12u);
  EXPECT_EQ(w.frames, 5u);
  ASSERT_EQ(w.positions.size(), v.positions.size());
  for (std::size_t k = 0; k < v.positions.size(); ++k) EXPECT_EQ(w.positions[k], v.positions[k]);
  EXPECT_EQ(w.frame(3)[2], v.positions[3 * 12 + 2]);
  // Little-endian whatever the host: the version is byte 8, the vertex count's low byte byte 12.
  EXPECT_EQ(static_cast<unsigned char>(bytes[8]), 1u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[12]), 12u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[16]), 5u);
}

TEST(VertexFrames, RefusesEveryBadFileWithOneLine) {
  const auto dir = test::fresh_temp_dir("vertex_frames_bad");
  const std::string good = vertex_frames_bytes(test::wave_frames(test::grid_mesh(3, 3), 2));
  const auto refuse = [&](const std::string& name, const std::string& bytes,
                          const std::string& expect) {
    test::write_file(dir / name, bytes);
    const std::string msg = error_of([&] { (void)read_vertex_frames(dir / name); });
    expect_one_line(msg, name, expect);
  };
  std::string wrong_magic = good;
  wrong_magic[0] = 'X';
  refuse("magic.avf", wrong_magic, "wrong magic");
  std::string version = good;
  version[8] = 2;
  refuse("version.avf", version, "version 2");
  refuse("short_header.avf", good.substr(0, 10), "truncated");
  refuse("empty.avf", "", "truncated");
  refuse("truncated.avf", good.substr(0, good.size() - 1), "truncated");
  refuse("trailing.avf", good + "x", "trailing bytes");
  std::string zero_vertices = good;
  std::memset(zero_vertices.data() + 12, 0, 4);
  refuse("zero_vertices.avf", zero_vertices, "vertex count is 0");
  std::string zero_frames = good;
  std::memset(zero_frames.data() + 16, 0, 8);
  refuse("zero_frames.avf", zero_frames, "frame count is 0");
  // A header that claims 2^40 frames over a 24-byte file: refused on the size, nothing allocated
  // (an allocation of 24 * 9 * 2^40 bytes would throw bad_alloc, not SceneError).
  std::string huge = good.substr(0, 24);
  huge[21] = 1;  // frames = 2^40
  refuse("huge.avf", huge, "expected");
  std::string overflow = good.substr(0, 24);
  std::memset(overflow.data() + 16, 0xFF, 8);
  refuse("overflow.avf", overflow, "does not fit");
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::string nan = good;
    std::memcpy(nan.data() + 24 + 24 * 10 + 8, &bad, 8);  // frame 1, vertex 1, y
    refuse("nan.avf", nan, "frame 1, vertex 1: coordinate y is not finite");
  }
  expect_one_line(error_of([&] { (void)read_vertex_frames(dir / "missing.avf"); }), "missing.avf",
                  "no such file");
  expect_one_line(error_of([&] { (void)read_vertex_frames(dir); }), "vertex_frames_bad",
                  "is a directory");
}

TEST(VertexFrames, WriterRefusesInconsistentFrames) {
  VertexFrames v = test::wave_frames(test::grid_mesh(3, 3), 2);
  v.positions.pop_back();
  EXPECT_THROW((void)vertex_frames_bytes(v), ArgumentError);
  v = test::wave_frames(test::grid_mesh(3, 3), 2);
  v.positions[4].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)vertex_frames_bytes(v), ArgumentError);
}

const char* kDeformingScene = R"({ "format": "antcd-scene/1", "frames": 4, "objects": [
  { "name": "sheet", "mesh": "sheet.obj", "vertex_frames": "frames/sheet.avf",
    "self_collision": true, "poses": [ {} ] },
  { "name": "block", "mesh": "sheet.obj", "poses": [ { "translation": [0, 0, 5] } ] } ] })";

TEST(VertexFrames, SceneFieldsParseAndRoundTrip) {
  const SceneDescription s = parse_scene(kDeformingScene, "/base", "scene.json");
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_TRUE(s.objects[0].deforming());
  EXPECT_TRUE(s.objects[0].self_collision);
  EXPECT_EQ(s.objects[0].vertex_file, std::filesystem::path("/base/frames/sheet.avf"));
  EXPECT_EQ(s.objects[0].vertex_frames, nullptr);  // parse_scene opens no file
  EXPECT_FALSE(s.objects[1].deforming());
  EXPECT_FALSE(s.objects[1].self_collision);
  const SceneDescription t = parse_scene(scene_to_json(s), "/base", "again.json");
  EXPECT_EQ(t.objects[0].vertex_file_text, "frames/sheet.avf");
  EXPECT_TRUE(t.objects[0].self_collision);
  EXPECT_FALSE(t.objects[1].deforming());
  // A scene without the new fields writes none of them (old readers keep reading it).
  const std::string old = scene_to_json(parse_scene(
      R"({ "format": "antcd-scene/1", "frames": 1, "objects": [
           { "name": "a", "mesh": "m.obj", "poses": [ {} ] } ] })",
      "/base", "old.json"));
  EXPECT_EQ(old.find("vertex_frames"), std::string::npos);
  EXPECT_EQ(old.find("self_collision"), std::string::npos);
}

TEST(VertexFrames, SceneFieldErrorsNameTheObject) {
  const auto bad = [](const std::string& fields) {
    return R"({ "format": "antcd-scene/1", "frames": 1, "objects": [
      { "name": "s", "mesh": "m.obj", )" +
           fields + R"(, "poses": [ {} ] } ] })";
  };
  const auto msg = [](const std::string& text) {
    return error_of([&] { (void)parse_scene(text, "/b", "bad.json"); });
  };
  expect_one_line(msg(bad(R"("vertex_frames": 3)")), "object 's'", "'vertex_frames' must be");
  expect_one_line(msg(bad(R"("vertex_frames": "")")), "object 's'", "'vertex_frames' must be");
  expect_one_line(msg(bad(R"("vertex_frames": "a\u0000b")")), "object 's'", "NUL byte");
  expect_one_line(msg(bad(R"("self_collision": 1)")), "object 's'", "'self_collision' must be");
}

/// A folder with sheet.obj (a 4 x 3 grid) and scene.json naming frames/sheet.avf.
std::filesystem::path deforming_folder(const std::string& name) {
  const auto dir = test::fresh_temp_dir(name);
  save_obj(test::grid_mesh(4, 3), dir / "sheet.obj");
  write_file_atomic(dir / "scene.json", kDeformingScene);
  create_folders(dir / "frames");
  return dir;
}

TEST(VertexFrames, LoadSceneReadsAndChecksTheSideFile) {
  const auto dir = deforming_folder("vertex_frames_load");
  const Mesh grid = test::grid_mesh(4, 3);
  save_vertex_frames(test::wave_frames(grid, 4), dir / "frames" / "sheet.avf");
  const SceneDescription s = load_scene(dir / "scene.json");
  ASSERT_NE(s.objects[0].vertex_frames, nullptr);
  EXPECT_EQ(s.objects[0].vertex_frames->frames, 4u);
  const Scene scene(s);  // the counts fit the loaded mesh
  EXPECT_EQ(scene.object_count(), 2u);

  // Frames other than the scene's: named with the object and the file.
  save_vertex_frames(test::wave_frames(grid, 3), dir / "frames" / "sheet.avf");
  expect_one_line(error_of([&] { (void)load_scene(dir / "scene.json"); }), "object 'sheet'",
                  "holds 3 frames; the scene has 4");
  // A vertex count other than the loaded mesh's: refused when the Scene is built.
  save_vertex_frames(test::wave_frames(test::grid_mesh(3, 3), 4), dir / "frames" / "sheet.avf");
  expect_one_line(error_of([&] { Scene bad(load_scene(dir / "scene.json")); }), "object 'sheet'",
                  "holds 9 vertices per frame; mesh sheet.obj has 12");
  // Missing: the scene file, the object and the side file.
  std::filesystem::remove(dir / "frames" / "sheet.avf");
  const std::string missing = error_of([&] { (void)load_scene(dir / "scene.json"); });
  expect_one_line(missing, "object 'sheet'", "sheet.avf: no such file");
  EXPECT_NE(missing.find("scene.json"), std::string::npos) << missing;
}

TEST(VertexFrames, SceneRefusesAZeroAreaTriangleInADeformingMesh) {
  const auto dir = deforming_folder("vertex_frames_degenerate");
  Mesh grid = test::grid_mesh(4, 3);
  grid.triangles.push_back({0, 1, 4});  // (0, 0), (1, 0), (2, 0) of the grid: collinear
  save_obj(grid, dir / "sheet.obj");
  save_vertex_frames(test::wave_frames(grid, 4), dir / "frames" / "sheet.avf");
  expect_one_line(error_of([&] { Scene bad(load_scene(dir / "scene.json")); }), "object 'sheet'",
                  "zero-area triangles");
}

TEST(VertexFrames, LoadedGridKeepsItsVertexOrder) {
  // The generator and the tests write grids whose vertices are in first-use order; the OBJ loader
  // then gives them back in that order, which is what a side file indexes.
  const auto dir = test::fresh_temp_dir("vertex_frames_order");
  const Mesh grid = test::grid_mesh(5, 4);
  save_obj(grid, dir / "g.obj");
  const Mesh loaded = load_mesh(dir / "g.obj");
  ASSERT_EQ(loaded.vertices.size(), grid.vertices.size());
  for (std::size_t i = 0; i < grid.vertices.size(); ++i) {
    EXPECT_EQ(loaded.vertices[i], grid.vertices[i]) << i;
  }
}

}  // namespace
}  // namespace antcd
