// antcd deform-ccd MESH_T0 MESH_T1: continuous collision of a deforming mesh (antcd/deform_ccd.hpp)
// whose vertices move linearly from their positions in MESH_T0 to those in MESH_T1.
//
// Indices are those of the loaded meshes. load_mesh joins identical vertex positions; a file with
// no two coincident vertices (or a .antcd model file, read bit for bit) keeps its own indices. Two
// vertices that coincide in one file but not in the other are joined in one only: the topologies
// then differ and the command exits 2 naming the difference.
#include <antcd/deform_ccd.hpp>
#include <antcd/load.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli_util.hpp"

namespace antcd::cli {
namespace {

struct DeformOptions {
  std::string mesh_t0, mesh_t1;
  bool all_pairs = false;
  double min_separation = 0;
  double time_tolerance = 1e-6;
  bool json = false;
};

/// UsageError naming the first difference between the two meshes' topologies.
void require_same_topology(const Mesh& m0, const Mesh& m1, const DeformOptions& o) {
  const std::string names = o.mesh_t0 + " and " + o.mesh_t1;
  if (m0.vertices.size() != m1.vertices.size()) {
    throw UsageError(names + " differ in vertex count (" + std::to_string(m0.vertices.size()) +
                     " vs " + std::to_string(m1.vertices.size()) +
                     ", after joining identical positions)");
  }
  if (m0.triangles.size() != m1.triangles.size()) {
    throw UsageError(names + " differ in triangle count (" + std::to_string(m0.triangles.size()) +
                     " vs " + std::to_string(m1.triangles.size()) + ")");
  }
  for (std::size_t f = 0; f < m0.triangles.size(); ++f) {
    if (m0.triangles[f] != m1.triangles[f]) {
      const auto& a = m0.triangles[f];
      const auto& b = m1.triangles[f];
      throw UsageError(names + " differ at triangle " + std::to_string(f) + " (" +
                       std::to_string(a[0]) + " " + std::to_string(a[1]) + " " +
                       std::to_string(a[2]) + " vs " + std::to_string(b[0]) + " " +
                       std::to_string(b[1]) + " " + std::to_string(b[2]) + ")");
    }
  }
}

int run_deform(const DeformOptions& o) {
  const Mesh m0 = load_mesh(o.mesh_t0);
  const Mesh m1 = load_mesh(o.mesh_t1);
  require_same_topology(m0, m1, o);
  const Model model(m0, {}, o.mesh_t0);
  DeformSweepRequest request;
  request.all_pairs = o.all_pairs;
  request.min_separation = o.min_separation;
  request.time_tolerance = o.time_tolerance;
  const Stopwatch clock;
  const DeformSweepResult r = deform_sweep(model, m0.vertices, m1.vertices, request);
  const double seconds = clock.ms() / 1000;
  std::vector<DeformPair> pairs = r.pairs;
  if (!o.all_pairs && r.hit) pairs = {r.pair};
  if (o.json) {
    nlohmann::json vf = nlohmann::json::array();
    nlohmann::json ee = nlohmann::json::array();
    for (const DeformPair& p : pairs) {
      if (p.kind == DeformPairKind::VertexFace) {
        vf.push_back({p.indices[0], p.indices[1], p.toi});
      } else {
        ee.push_back({p.indices[0], p.indices[1], p.indices[2], p.indices[3], p.toi});
      }
    }
    nlohmann::json j;
    j["hit"] = r.hit;
    j["toi"] = r.toi;
    j["tolerance_decided"] = r.tolerance_decided;
    j["vertex_face"] = vf;
    j["edge_edge"] = ee;
    j["seconds"] = seconds;
    std::cout << j.dump() << '\n';
    return 0;
  }
  std::printf("%s -> %s: %zu vertices, %zu triangles\n", o.mesh_t0.c_str(), o.mesh_t1.c_str(),
              m0.vertices.size(), m0.triangles.size());
  if (!r.hit) {
    std::printf("hit: no (proven: no pair within %.17g over [0, 1])\n", o.min_separation);
  } else {
    std::printf("hit: yes, toi %.17g (%s)\n", r.toi,
                r.tolerance_decided ? "within the time tolerance" : "proven contact");
  }
  for (const DeformPair& p : pairs) {
    if (p.kind == DeformPairKind::VertexFace) {
      std::printf("vertex %u / triangle %u at %.17g\n", p.indices[0], p.indices[1], p.toi);
    } else {
      std::printf("edge %u-%u / edge %u-%u at %.17g\n", p.indices[0], p.indices[1], p.indices[2],
                  p.indices[3], p.toi);
    }
  }
  std::printf("query: %.6f s, %llu primitive queries\n", seconds,
              static_cast<unsigned long long>(r.primitive_queries));
  return 0;
}

}  // namespace

void add_deform_ccd_command(CLI::App& app, int& code) {
  auto o = std::make_shared<DeformOptions>();
  CLI::App* cmd = app.add_subcommand(
      "deform-ccd",
      "Continuous collision of a deforming mesh: vertices move linearly from MESH_T0 to MESH_T1");
  cmd->add_option("MESH_T0", o->mesh_t0, "Mesh at t = 0")->required();
  cmd->add_option("MESH_T1", o->mesh_t1, "The same mesh (same topology) at t = 1")->required();
  cmd->add_flag("--all-pairs", o->all_pairs, "Every colliding primitive pair with its toi");
  cmd->add_option("--min-separation", o->min_separation, "Contact distance (mesh units, >= 0)")
      ->check(non_negative_finite());
  cmd->add_option("--time-tolerance", o->time_tolerance, "Time tolerance (> 0)")
      ->check(positive_finite());
  cmd->add_flag("--json", o->json,
                "Print {hit, toi, tolerance_decided, vertex_face: [[v, f, toi], ...], edge_edge: "
                "[[a0, a1, b0, b1, toi], ...], seconds}");
  cmd->callback([o, &code] { code = run_deform(*o); });
}

}  // namespace antcd::cli
