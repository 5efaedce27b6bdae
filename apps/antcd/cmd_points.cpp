// antcd points MESH: inside/outside and signed distance of many points against one posed mesh.
#include <antcd/csv.hpp>
#include <antcd/points.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct PointsOptions {
  std::string mesh;
  std::string points_file;
  std::size_t random = 0;
  std::uint64_t seed = 1;
  std::string pose = "0,0,0";
  bool json = false;
};

/// `n` points uniform in the world box of the posed mesh grown by 10 % on each side.
std::vector<Vec3> random_points(const Model& model, const Transform& pose, std::size_t n,
                                std::uint64_t seed) {
  Aabb box;
  for (const Vec3& v : model.mesh().vertices) box.extend(pose.apply(v));
  const Vec3 grow = 0.1 * box.extent();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Scalar> u(0, 1);
  std::vector<Vec3> points(n);
  for (Vec3& p : points) {
    const Vec3 t(u(rng), u(rng), u(rng));
    p = box.min - grow + t.cwiseProduct(box.extent() + 2 * grow);
  }
  return points;
}

int run_points(const PointsOptions& o) {
  if (o.points_file.empty() == (o.random == 0)) {
    throw UsageError("give one of a POINTS file or --random N");
  }
  const Transform pose = parse_pose(o.pose, "--pose");
  const Model model = load_model(o.mesh, BuildOptions{});
  warn_degenerate(model);
  const std::vector<Vec3> points =
      o.random > 0 ? random_points(model, pose, o.random, o.seed) : read_points_csv(o.points_file);
  if (!model.is_closed()) {
    std::fprintf(stderr,
                 "warning: %s is not closed and consistently oriented: distances are unsigned, "
                 "no inside/outside\n",
                 o.mesh.c_str());
  }
  const Stopwatch clock;
  const SignedDistanceResult sd = signed_distance(model, pose, points);
  std::vector<std::uint8_t> inside;
  if (model.is_closed()) inside = contains(model, pose, points);
  const double query_ms = clock.ms();

  std::ostringstream out;
  out.precision(17);
  if (o.json) {
    nlohmann::json j;
    j["mesh"] = o.mesh;
    j["signed"] = sd.is_signed;
    j["query_ms"] = query_ms;
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointDistance& d = sd.points[i];
      rows.push_back(
          {{"point", vec_json(points[i])},
           {"inside", inside.empty() ? nlohmann::json(nullptr) : nlohmann::json(inside[i] != 0)},
           {"distance", d.distance},
           {"closest", vec_json(d.closest)},
           {"triangle", d.triangle}});
    }
    j["points"] = std::move(rows);
    out << j.dump(2) << '\n';
  } else {
    out << (sd.is_signed ? "x,y,z,inside,signed_distance" : "x,y,z,inside,distance")
        << ",closest_x,closest_y,closest_z,triangle\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointDistance& d = sd.points[i];
      out << points[i].x() << ',' << points[i].y() << ',' << points[i].z() << ','
          << (inside.empty()   ? ""
              : inside[i] != 0 ? "1"
                               : "0")
          << ',' << d.distance << ',' << d.closest.x() << ',' << d.closest.y() << ','
          << d.closest.z() << ',' << d.triangle << '\n';
    }
    std::fprintf(stderr, "%zu points against %s (%zu triangles): %.3f ms\n", points.size(),
                 o.mesh.c_str(), model.stats().triangles, query_ms);
  }
  std::cout << out.str();
  return 0;
}

}  // namespace

void add_points_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<PointsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "points", "Inside/outside and signed distance (closest point, triangle) of many points");
  cmd->add_option("MESH", opts->mesh, "Mesh file (OBJ, STL, PLY, OFF, glTF, ...)")->required();
  cmd->add_option("POINTS", opts->points_file,
                  "CSV of world-frame points, one 'x,y,z' per line (optional header)");
  cmd->add_option("--random", opts->random,
                  "Instead of a file: N random points in the mesh's box grown by 10%")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100'000'000}));
  cmd->add_option("--seed", opts->seed, "Seed of --random")->check(unsigned_integer());
  cmd->add_option("--pose", opts->pose, "Pose of the mesh: tx,ty,tz[,qw,qx,qy,qz] (world frame)");
  cmd->add_flag("--json", opts->json, "Print the result as JSON (else CSV)");
  cmd->callback([opts, &code] { code = run_points(*opts); });
}

}  // namespace antcd::cli
