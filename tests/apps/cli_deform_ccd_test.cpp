// antcd deform-ccd MESH_T0 MESH_T1: the JSON answer equals the library's deform_sweep on the same
// meshes; a topology difference exits 2 naming it.
#include <antcd/bvh.hpp>
#include <antcd/deform_ccd.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "support/test_support.hpp"

namespace antcd {
namespace {

namespace fs = std::filesystem;

/// A 6 x 6 sheet and a triangle above it whose vertex 0 moves down through the sheet.
Mesh poke(bool at_t1) {
  Mesh m;
  m.vertices = {{0.53, 0.47, at_t1 ? -0.5 : 0.5}, {0.6, 0.5, 0.5}, {0.5, 0.6, 0.5}};
  m.triangles = {{0, 1, 2}};
  Mesh sheet = make_box({0.5, 0.5, 0.01}, 3);
  for (Vec3& p : sheet.vertices) p += Vec3(0.5, 0.5, 0);
  return merge({m, sheet});
}

TEST(CliDeformCcd, JsonEqualsTheLibrary) {
  const fs::path dir = test::fresh_temp_dir("cli_deform_ccd");
  const Mesh m0 = poke(false), m1 = poke(true);
  save_obj(m0, dir / "t0.obj");
  save_obj(m1, dir / "t1.obj");
  const Mesh l0 = load_mesh(dir / "t0.obj");
  const Mesh l1 = load_mesh(dir / "t1.obj");
  ASSERT_EQ(l0.vertices.size(), m0.vertices.size());  // no coincident vertices: nothing joined
  const Model model(l0, {}, "t0");
  DeformSweepRequest req;
  req.all_pairs = true;
  const DeformSweepResult lib = deform_sweep(model, l0.vertices, l1.vertices, req);
  ASSERT_TRUE(lib.hit);
  const test::CliRun r = test::run_program(
      ANTCD_CLI, {"deform-ccd", "t0.obj", "t1.obj", "--all-pairs", "--json"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["hit"].get<bool>());
  EXPECT_EQ(j["toi"].get<double>(), lib.toi);
  EXPECT_EQ(j["vertex_face"].size() + j["edge_edge"].size(), lib.pairs.size());
  std::size_t vf = 0, ee = 0;
  for (const DeformPair& p : lib.pairs) {
    if (p.kind == DeformPairKind::VertexFace) {
      const auto& row = j["vertex_face"][vf++];
      EXPECT_EQ(row[0].get<std::uint32_t>(), p.indices[0]);
      EXPECT_EQ(row[1].get<std::uint32_t>(), p.indices[1]);
      EXPECT_EQ(row[2].get<double>(), p.toi);
    } else {
      const auto& row = j["edge_edge"][ee++];
      for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(row[k].get<std::uint32_t>(), p.indices[static_cast<std::size_t>(k)]);
      }
      EXPECT_EQ(row[4].get<double>(), p.toi);
    }
  }
  EXPECT_GE(j["seconds"].get<double>(), 0);
  // The vertex that moves (file vertex 0) is in the earliest pair.
  EXPECT_EQ(j["vertex_face"][0][0].get<std::uint32_t>(), 0u);
  // Without --all-pairs: the earliest pair only; a still mesh: no hit.
  const test::CliRun first =
      test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "t1.obj", "--json"}, dir);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const nlohmann::json jf = nlohmann::json::parse(first.out);
  EXPECT_EQ(jf["toi"].get<double>(), lib.toi);
  EXPECT_EQ(jf["vertex_face"].size() + jf["edge_edge"].size(), 1u);
  const test::CliRun still =
      test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "t0.obj", "--json"}, dir);
  ASSERT_EQ(still.exit_code, 0) << still.err;
  EXPECT_FALSE(nlohmann::json::parse(still.out)["hit"].get<bool>());
}

TEST(CliDeformCcd, TopologyDifferenceIsRefused) {
  const fs::path dir = test::fresh_temp_dir("cli_deform_ccd_bad");
  save_obj(poke(false), dir / "t0.obj");
  save_obj(make_box({1, 1, 1}), dir / "box.obj");
  Mesh flipped = poke(true);
  std::swap(flipped.triangles[3][0], flipped.triangles[3][1]);
  save_obj(flipped, dir / "flipped.obj");
  test::expect_clean_refusal(test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "box.obj"}, dir),
                             "vertex count");
  test::expect_clean_refusal(
      test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "flipped.obj"}, dir), "triangle 3");
  test::expect_clean_refusal(
      test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "t0.obj", "--min-separation", "-1"},
                        dir),
      "min-separation");
  test::expect_clean_refusal(
      test::run_program(ANTCD_CLI, {"deform-ccd", "t0.obj", "none.obj"}, dir), "none.obj");
}

}  // namespace
}  // namespace antcd
