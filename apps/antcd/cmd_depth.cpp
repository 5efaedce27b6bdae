// antcd depth A B: penetration depth of two closed meshes (solids), with certified bounds.
#include <antcd/penetration.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct DepthOptions {
  std::string mesh_a, mesh_b;
  std::string pose_a = "0,0,0", pose_b = "0,0,0";
  double rel_tolerance = 0.01;
  double abs_tolerance = 0;
  std::uint32_t max_evaluations = 64;
  std::string shape = "auto";
  bool json = false;
};

int run_depth(const DepthOptions& o) {
  const Transform pa = parse_pose(o.pose_a, "--pose-a");
  const Transform pb = parse_pose(o.pose_b, "--pose-b");
  if (!(o.rel_tolerance < 1)) {
    throw UsageError("--rel-tolerance must be below 1, got " + std::to_string(o.rel_tolerance));
  }
  PenetrationRequest request;
  request.rel_tolerance = o.rel_tolerance;
  request.abs_tolerance = o.abs_tolerance;
  request.max_evaluations = o.max_evaluations;
  if (o.shape == "convex") {
    request.shape = PenetrationRequest::Shape::Convex;
  } else if (o.shape == "general") {
    request.shape = PenetrationRequest::Shape::General;
  } else if (o.shape != "auto") {
    throw UsageError("--shape must be auto, convex or general, got '" + o.shape + "'");
  }
  const Model a = load_model(o.mesh_a, {});
  const Model b = load_model(o.mesh_b, {});
  warn_degenerate(a);
  warn_degenerate(b);
  const Stopwatch clock;
  const PenetrationResult r = penetration(a, pa, b, pb, request);
  const double query_ms = clock.ms();
  if (o.json) {
    nlohmann::json j;
    j["mesh_a"] = o.mesh_a;
    j["mesh_b"] = o.mesh_b;
    j["overlapping"] = r.overlapping;
    j["exact"] = r.exact;
    j["converged"] = r.converged;
    j["lower"] = r.lower;
    // JSON has no infinity: no separating translation found within the budget is null.
    j["upper"] = std::isfinite(r.upper) ? nlohmann::json(r.upper) : nlohmann::json(nullptr);
    j["direction"] = vec_json(r.direction);
    j["witness"] = vec_json(r.witness);
    j["point_a"] = vec_json(r.point_a);
    j["point_b"] = vec_json(r.point_b);
    j["evaluations"] = r.evaluations;
    j["query_ms"] = query_ms;
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("A: %s (%zu triangles)\nB: %s (%zu triangles)\n", o.mesh_a.c_str(),
              a.stats().triangles, o.mesh_b.c_str(), b.stats().triangles);
  if (!r.overlapping && r.upper == 0) {
    std::printf("penetration depth: 0 (the solids do not overlap)\n");
  } else {
    std::printf("penetration depth: %s in [%.17g, %.17g]%s\n", r.exact ? "exact" : "certified",
                r.lower, r.upper, r.converged ? "" : " (not converged within the budget)");
    std::printf("move A by upper along: %.17g %.17g %.17g\n", r.direction.x(), r.direction.y(),
                r.direction.z());
    if (r.overlapping) {
      std::printf("witness inside both: %.17g %.17g %.17g\n", r.witness.x(), r.witness.y(),
                  r.witness.z());
    }
  }
  std::printf("query: %.3f ms, %u collide calls\n", query_ms, r.evaluations);
  return 0;
}

}  // namespace

void add_depth_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<DepthOptions>();
  CLI::App* cmd = app.add_subcommand(
      "depth",
      "Penetration depth of two closed meshes (solids): exact when convex, else certified "
      "bounds [lower, upper]");
  cmd->add_option("A", opts->mesh_a, "First mesh file (closed; the one that moves)")->required();
  cmd->add_option("B", opts->mesh_b, "Second mesh file (closed)")->required();
  cmd->add_option("--pose-a", opts->pose_a, "Pose of A: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--pose-b", opts->pose_b, "Pose of B: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_option("--rel-tolerance", opts->rel_tolerance,
                  "Stop when upper - lower <= this fraction of upper (0 <= value < 1)")
      ->check(non_negative_finite());
  cmd->add_option("--abs-tolerance", opts->abs_tolerance,
                  "Stop when upper - lower <= this (mesh units)")
      ->check(non_negative_finite());
  cmd->add_option("--max-evaluations", opts->max_evaluations, "Budget of exact collide calls")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--shape", opts->shape,
                  "'auto' (detect convexity), 'convex' (declared) or 'general' (bounds)");
  cmd->add_flag("--json", opts->json, "Print the result as JSON");
  cmd->callback([opts, &code] { code = run_depth(*opts); });
}

}  // namespace antcd::cli
