// antcd distance A B: minimum distance between two posed meshes, with closest points.
#include <antcd/distance.hpp>
#include <antcd/penetration.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct DistanceOptions {
  std::string mesh_a, mesh_b;
  std::string pose_a = "0,0,0", pose_b = "0,0,0";
  double upper_bound = std::numeric_limits<double>::infinity();
  double abs_tolerance = 0;
  double rel_tolerance = 0;
  bool json = false;
  bool signed_distance = false;
  std::uint32_t leaf_size = 4;
  std::string covariance = "area";
};

int run_distance(const DistanceOptions& o) {
  const Transform pa = parse_pose(o.pose_a, "--pose-a");
  const Transform pb = parse_pose(o.pose_b, "--pose-b");
  if (!(o.rel_tolerance < 1)) {
    throw UsageError("--rel-tolerance must be below 1, got " + std::to_string(o.rel_tolerance));
  }
  const BuildOptions build{o.leaf_size, parse_covariance(o.covariance)};
  const Model a = load_model(o.mesh_a, build);
  const Model b = load_model(o.mesh_b, build);
  warn_degenerate(a);
  warn_degenerate(b);
  DistanceRequest request;
  request.upper_bound = o.upper_bound;
  request.abs_tolerance = o.abs_tolerance;
  request.rel_tolerance = o.rel_tolerance;
  const Stopwatch clock;
  const DistanceResult r =
      o.signed_distance ? signed_distance(a, pa, b, pb, request) : distance(a, pa, b, pb, request);
  const double query_ms = clock.ms();
  const bool found = std::isfinite(r.distance);

  if (o.json) {
    nlohmann::json j;
    j["mesh_a"] = o.mesh_a;
    j["mesh_b"] = o.mesh_b;
    // JSON has no infinity: an absent bound or an unknown distance is null.
    j["distance"] = found ? nlohmann::json(r.distance) : nlohmann::json(nullptr);
    j["lower_bound"] = r.lower_bound;
    j["intersecting"] = r.intersecting;
    j["signed"] = o.signed_distance;
    j["approximate"] = r.approximate;
    j["beyond_upper_bound"] = r.beyond_upper_bound;
    j["upper_bound"] =
        std::isfinite(o.upper_bound) ? nlohmann::json(o.upper_bound) : nlohmann::json(nullptr);
    if (found) {
      j["point_a"] = vec_json(r.point_a);
      j["point_b"] = vec_json(r.point_b);
      j["triangle_a"] = r.triangle_a;
      j["triangle_b"] = r.triangle_b;
    }
    j["query_ms"] = query_ms;
    j["stats"] = {{"node_pairs", r.node_pairs}, {"triangle_tests", r.triangle_tests}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("A: %s (%zu triangles)\nB: %s (%zu triangles)\n", o.mesh_a.c_str(),
              a.stats().triangles, o.mesh_b.c_str(), b.stats().triangles);
  if (r.beyond_upper_bound) {
    std::printf("distance: > %.17g (upper bound %.17g; proven lower bound %.17g)\n", o.upper_bound,
                o.upper_bound, r.lower_bound);
  } else {
    std::printf("distance: %.17g%s\n", r.distance,
                r.distance < 0   ? " (solids overlap: minus the penetration depth)"
                : r.intersecting ? " (surfaces intersect)"
                : r.approximate  ? " (approximate)"
                                 : "");
    if (r.approximate) std::printf("lower bound: %.17g\n", r.lower_bound);
    std::printf("closest point on A: %.17g %.17g %.17g (triangle %u)\n", r.point_a.x(),
                r.point_a.y(), r.point_a.z(), r.triangle_a);
    std::printf("closest point on B: %.17g %.17g %.17g (triangle %u)\n", r.point_b.x(),
                r.point_b.y(), r.point_b.z(), r.triangle_b);
  }
  std::printf("query: %.3f ms, %llu node pairs, %llu triangle tests\n", query_ms,
              static_cast<unsigned long long>(r.node_pairs),
              static_cast<unsigned long long>(r.triangle_tests));
  return 0;
}

}  // namespace

void add_distance_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<DistanceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "distance", "Minimum distance and closest points between two posed meshes");
  cmd->add_option("A", opts->mesh_a, "First mesh file (OBJ, STL, PLY, OFF, glTF, ...)")->required();
  cmd->add_option("B", opts->mesh_b, "Second mesh file")->required();
  cmd->add_option("--pose-a", opts->pose_a, "Pose of A: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--pose-b", opts->pose_b, "Pose of B: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--upper-bound", opts->upper_bound,
                  "Stop once the distance is known to exceed this (mesh units)")
      ->check(non_negative_or_infinity());
  cmd->add_option("--abs-tolerance", opts->abs_tolerance,
                  "Accept an answer this much above the minimum (mesh units)")
      ->check(non_negative_finite());
  cmd->add_option("--rel-tolerance", opts->rel_tolerance,
                  "Accept an answer this fraction above the minimum (0 <= value < 1)")
      ->check(non_negative_finite());
  cmd->add_flag(
      "--signed", opts->signed_distance,
      "Signed distance of two closed meshes: -(penetration depth) when the solids overlap "
      "(antcd depth)");
  cmd->add_flag("--json", opts->json, "Print the result as JSON");
  cmd->add_option("--leaf-size", opts->leaf_size, "Triangles per leaf of the hierarchy")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--covariance", opts->covariance,
                  "OBB fit: 'area' (area-weighted centroid, Eq. 3) or 'vertex' (Eqs. 1-2)");
  cmd->callback([opts, &code] { code = run_distance(*opts); });
}

}  // namespace antcd::cli
