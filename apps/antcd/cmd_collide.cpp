// antcd collide A B: exact collision between two posed meshes.
#include <antcd/collide.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct CollideOptions {
  std::string mesh_a, mesh_b;
  std::string pose_a = "0,0,0", pose_b = "0,0,0";
  double delta = 0;
  bool all = false;
  bool volume = false;
  bool normals = false;
  std::uint32_t manifold = 0;
  bool json = false;
  std::uint32_t leaf_size = 4;
  std::string covariance = "area";
};

int run_collide(const CollideOptions& o) {
  const Transform pa = parse_pose(o.pose_a, "--pose-a");
  const Transform pb = parse_pose(o.pose_b, "--pose-b");
  const BuildOptions build{o.leaf_size, parse_covariance(o.covariance)};
  const Model a = load_model(o.mesh_a, build);
  const Model b = load_model(o.mesh_b, build);
  warn_degenerate(a);
  warn_degenerate(b);

  CollisionRequest request;
  request.delta = o.delta;
  request.all_contacts = o.all || o.manifold > 0;  // a manifold reduces every contact
  request.volume = o.volume;
  request.contact_normals = o.normals;
  request.manifold_points = o.manifold;
  const bool normals = o.normals || o.manifold > 0;
  CollisionResult result;
  const Stopwatch clock;
  collide(a, pa, b, pb, request, result);
  const double query_ms = clock.ms();

  if (o.json) {
    nlohmann::json j;
    j["mesh_a"] = o.mesh_a;
    j["mesh_b"] = o.mesh_b;
    j["delta"] = o.delta;
    j["colliding"] = result.colliding;
    if (o.volume) {
      j["contained"] = result.contained;
      j["surface_only"] = result.surface_only;
    }
    j["query_ms"] = query_ms;
    if (o.manifold > 0) j["regions"] = result.regions;
    nlohmann::json contacts = nlohmann::json::array();
    for (const Contact& c : result.contacts) {
      nlohmann::json jc = {{"triangle_a", c.triangle_a},
                           {"triangle_b", c.triangle_b},
                           {"point", vec_json(c.point)},
                           {"distance", c.distance}};
      if (normals) {
        jc["normal"] = vec_json(c.normal);
        jc["depth"] = c.depth;
      }
      if (o.manifold > 0) jc["region"] = c.region;
      contacts.push_back(std::move(jc));
    }
    j["contacts"] = std::move(contacts);
    j["stats"] = {{"node_pairs", result.traversal.node_pairs},
                  {"sphere_rejects", result.traversal.sphere_rejects},
                  {"obb_rejects", result.traversal.obb_rejects},
                  {"leaf_pairs", result.traversal.leaf_pairs},
                  {"triangle_rejects", result.traversal.triangle_rejects},
                  {"triangle_tests", result.triangle_tests}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("A: %s (%zu triangles)\nB: %s (%zu triangles)\ndelta: %g\n", o.mesh_a.c_str(),
              a.stats().triangles, o.mesh_b.c_str(), b.stats().triangles, o.delta);
  std::printf("verdict: %s%s\n", result.colliding ? "COLLIDING" : "separate",
              result.contained      ? " (one model lies inside the other)"
              : result.surface_only ? " (surfaces only: a model is not closed)"
                                    : "");
  std::printf("query: %.3f ms, %llu node pairs, %llu leaf pairs, %llu triangle tests\n", query_ms,
              static_cast<unsigned long long>(result.traversal.node_pairs),
              static_cast<unsigned long long>(result.traversal.leaf_pairs),
              static_cast<unsigned long long>(result.triangle_tests));
  if (!result.contacts.empty()) {
    std::printf("contacts: %zu%s\n", result.contacts.size(),
                request.all_contacts ? "" : " (first found; --all for every one)");
    if (o.manifold > 0) std::printf("manifold: %u regions\n", result.regions);
    std::printf("  %10s %10s %14s %14s %14s %12s", "tri_a", "tri_b", "x", "y", "z", "distance");
    if (normals) std::printf(" %10s %10s %10s %12s", "nx", "ny", "nz", "depth");
    std::printf("\n");
    for (const Contact& c : result.contacts) {
      std::printf("  %10u %10u %14.6g %14.6g %14.6g %12.6g", c.triangle_a, c.triangle_b,
                  c.point.x(), c.point.y(), c.point.z(), c.distance);
      if (normals) {
        std::printf(" %10.6f %10.6f %10.6f %12.6g", c.normal.x(), c.normal.y(), c.normal.z(),
                    c.depth);
      }
      std::printf("\n");
    }
  }
  return 0;
}

}  // namespace

void add_collide_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<CollideOptions>();
  CLI::App* cmd = app.add_subcommand("collide", "Exact collision test between two posed meshes");
  cmd->add_option("A", opts->mesh_a, "First mesh file (OBJ, STL, PLY, OFF, glTF, ...)")->required();
  cmd->add_option("B", opts->mesh_b, "Second mesh file")->required();
  cmd->add_option("--pose-a", opts->pose_a, "Pose of A: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--pose-b", opts->pose_b, "Pose of B: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--delta", opts->delta,
                  "Collision threshold δ in mesh units: collide when triangles are within δ")
      ->check(non_negative_finite());
  cmd->add_flag("--all", opts->all,
                "Report every colliding triangle pair (default: stop at first)");
  cmd->add_flag("--volume", opts->volume,
                "Closed models also collide when one lies wholly inside the other");
  cmd->add_flag("--normals", opts->normals,
                "Give each contact its normal (unit, world frame, from B towards A) and "
                "penetration depth");
  cmd->add_option("--manifold", opts->manifold,
                  "Every contact, reduced to at most K per touching region (implies --all and "
                  "--normals)")
      ->check(CLI::Range(1, 1 << 20))
      ->type_name("K");
  cmd->add_flag("--json", opts->json, "Print the result as JSON");
  cmd->add_option("--leaf-size", opts->leaf_size, "Triangles per leaf of the hierarchy")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--covariance", opts->covariance,
                  "OBB fit: 'area' (area-weighted centroid, Eq. 3) or 'vertex' (Eqs. 1-2)");
  cmd->callback([opts, &code] { code = run_collide(*opts); });
}

}  // namespace antcd::cli
