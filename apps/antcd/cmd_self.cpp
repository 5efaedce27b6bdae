// antcd self-intersect MESH / antcd self-proximity MESH --delta D: where one mesh meets or nears
// itself (antcd/self.hpp). Exit 0 whether or not it does (the answer is in the output).
#include <antcd/self.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct SelfOptions {
  std::string mesh;
  double delta = 0;
  bool json = false;
};

int run_self_intersect(const SelfOptions& o) {
  const Model model = load_model(o.mesh, {});
  const Stopwatch clock;
  const SelfIntersectionResult r = self_intersections(model);
  const double seconds = clock.seconds();
  if (o.json) {
    nlohmann::json j;
    j["triangles"] = model.mesh().triangles.size();
    j["pairs"] = nlohmann::json::array();
    for (const auto& p : r.pairs) j["pairs"].push_back({p[0], p[1]});
    j["count"] = r.pairs.size();
    j["degenerate_triangles"] = r.degenerate_triangles;
    j["seconds"] = seconds;
    std::cout << j.dump() << '\n';
    return 0;
  }
  std::printf("%s: %zu triangles\n", o.mesh.c_str(), model.mesh().triangles.size());
  std::printf("self-intersecting pairs: %zu\n", r.pairs.size());
  for (const auto& p : r.pairs) std::printf("  %u %u\n", p[0], p[1]);
  if (!r.degenerate_triangles.empty()) {
    std::printf("degenerate (zero-area) triangles, in no pair: %zu\n",
                r.degenerate_triangles.size());
  }
  std::printf("query: %.3f ms\n", 1000 * seconds);
  return 0;
}

int run_self_proximity(const SelfOptions& o) {
  const Model model = load_model(o.mesh, {});
  const Stopwatch clock;
  const SelfProximityResult r = self_proximity(model, o.delta);
  const double seconds = clock.seconds();
  std::size_t vt = 0;
  for (const auto& p : r.pairs) vt += p.kind == SelfProximityPair::Kind::vertex_triangle;
  if (o.json) {
    nlohmann::json j;
    j["triangles"] = model.mesh().triangles.size();
    j["delta"] = o.delta;
    j["vertex_triangle"] = nlohmann::json::array();
    j["edge_edge"] = nlohmann::json::array();
    for (const auto& p : r.pairs) {
      nlohmann::json row;
      if (p.kind == SelfProximityPair::Kind::vertex_triangle) {
        row["vertex"] = p.a;
        row["triangle"] = p.b;
      } else {
        row["edge_a"] = r.edges[p.a];
        row["edge_b"] = r.edges[p.b];
      }
      row["distance"] = p.distance;
      row["point_a"] = vec_json(p.point_a);
      row["point_b"] = vec_json(p.point_b);
      j[p.kind == SelfProximityPair::Kind::vertex_triangle ? "vertex_triangle" : "edge_edge"]
          .push_back(row);
    }
    j["count"] = r.pairs.size();
    j["seconds"] = seconds;
    std::cout << j.dump() << '\n';
    return 0;
  }
  std::printf("%s: %zu triangles, delta %.17g\n", o.mesh.c_str(), model.mesh().triangles.size(),
              o.delta);
  std::printf("vertex-triangle pairs: %zu\nedge-edge pairs: %zu\n", vt, r.pairs.size() - vt);
  for (const auto& p : r.pairs) {
    if (p.kind == SelfProximityPair::Kind::vertex_triangle) {
      std::printf("  vertex %u triangle %u: %.17g\n", p.a, p.b, p.distance);
    } else {
      std::printf("  edge %u-%u edge %u-%u: %.17g\n", r.edges[p.a][0], r.edges[p.a][1],
                  r.edges[p.b][0], r.edges[p.b][1], p.distance);
    }
  }
  std::printf("query: %.3f ms\n", 1000 * seconds);
  return 0;
}

}  // namespace

void add_self_commands(CLI::App& app, int& code) {
  auto opts = std::make_shared<SelfOptions>();
  CLI::App* si = app.add_subcommand(
      "self-intersect",
      "Triangle pairs of one mesh that intersect beyond their shared vertices or edge (exact)");
  si->add_option("MESH", opts->mesh, "Mesh file")->required();
  si->add_flag(
      "--json", opts->json,
      "Print {\"triangles\", \"pairs\", \"count\", \"degenerate_triangles\", \"seconds\"}");
  si->callback([opts, &code] { code = run_self_intersect(*opts); });

  auto popts = std::make_shared<SelfOptions>();
  CLI::App* sp = app.add_subcommand(
      "self-proximity",
      "Vertex-triangle and edge-edge pairs of one mesh within --delta (not sharing a vertex)");
  sp->add_option("MESH", popts->mesh, "Mesh file")->required();
  sp->add_option("--delta", popts->delta, "Distance threshold (mesh units, >= 0)")
      ->required()
      ->check(non_negative_finite());
  sp->add_flag("--json", popts->json, "Print the pairs as JSON");
  sp->callback([popts, &code] { code = run_self_proximity(*popts); });
}

}  // namespace antcd::cli
