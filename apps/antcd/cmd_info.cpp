// antcd info MESH [--save MODEL.antcd]: mesh and hierarchy statistics; --save writes the model
// (mesh and hierarchy) as a model file (Model::save) that every command loads in place of a mesh.
#include <antcd/bvh.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli_util.hpp"

namespace antcd::cli {

namespace {

struct InfoOptions {
  std::string mesh;
  std::uint32_t leaf_size = 4;
  std::string covariance = "area";
  bool json = false;
  std::string save;
};

const char* covariance_name(CovarianceMethod method) {
  return method == CovarianceMethod::VertexMean ? "vertex" : "area";
}

int run_info(const InfoOptions& o) {
  if (!o.save.empty() && !is_model_path(o.save)) {
    throw UsageError("--save: '" + o.save +
                     "' does not end in .antcd (the loaders recognise model files by it)");
  }
  const Model model = load_model(o.mesh, {o.leaf_size, parse_covariance(o.covariance)});
  if (!o.save.empty()) {
    model.save(o.save);
    std::cerr << "saved " << o.save << '\n';
  }
  // A model file keeps the options it was built with.
  const std::uint32_t leaf_size = model.options().leaf_size;
  const std::string covariance = covariance_name(model.options().covariance);
  const BvhStats& s = model.stats();
  const Aabb box = model.mesh().bounds();
  if (o.json) {
    nlohmann::json j;
    j["mesh"] = o.mesh;
    j["vertices"] = model.mesh().vertices.size();
    j["triangles"] = s.triangles;
    j["degenerate_triangles"] = s.degenerate_triangles;
    j["bounds"] = {{"min", vec_json(box.min)}, {"max", vec_json(box.max)}};
    j["tree"] = {{"nodes", s.nodes},
                 {"leaves", s.leaves},
                 {"depth", s.depth},
                 {"leaf_size", leaf_size},
                 {"max_leaf", s.max_leaf_size},
                 {"build_ms", s.build_ms},
                 {"memory_bytes", s.memory_bytes},
                 {"obb_volume_sum", s.obb_volume_sum},
                 {"covariance", covariance}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  if (s.degenerate_triangles > 0) {
    std::cerr << "warning: " << o.mesh << ": " << s.degenerate_triangles
              << " zero-area triangle(s) ignored\n";
  }
  std::printf("mesh:        %s\n", o.mesh.c_str());
  std::printf("vertices:    %zu\n", model.mesh().vertices.size());
  std::printf("triangles:   %zu (%zu zero-area, ignored)\n", s.triangles, s.degenerate_triangles);
  std::printf("bounds:      [%g, %g, %g] .. [%g, %g, %g]\n", box.min.x(), box.min.y(), box.min.z(),
              box.max.x(), box.max.y(), box.max.z());
  std::printf("tree:        %zu nodes, %zu leaves, depth %zu\n", s.nodes, s.leaves, s.depth);
  std::printf("leaf size:   %u (largest leaf %zu)\n", leaf_size, s.max_leaf_size);
  std::printf("covariance:  %s\n", covariance.c_str());
  std::printf("OBB volume:  %g (sum over all nodes)\n", s.obb_volume_sum);
  std::printf("build time:  %.3f ms\n", s.build_ms);
  std::printf("memory:      %zu bytes (%.1f per triangle)\n", s.memory_bytes,
              static_cast<double>(s.memory_bytes) / static_cast<double>(s.triangles));
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd =
      app.add_subcommand("info", "Print a mesh's size, bounds and hierarchy statistics");
  cmd->add_option("MESH", opts->mesh, "Mesh file (or a model file, .antcd)")->required();
  cmd->add_option("--leaf-size", opts->leaf_size, "Triangles per leaf of the hierarchy")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--covariance", opts->covariance,
                  "OBB fit: 'area' (area-weighted centroid, Eq. 3) or 'vertex' (Eqs. 1-2)");
  cmd->add_flag("--json", opts->json, "Print as JSON");
  cmd->add_option("--save", opts->save,
                  "Also write the model (mesh and hierarchy) to this .antcd file, which any "
                  "command then loads in place of the mesh without building its hierarchy");
  cmd->callback([opts, &code] { code = run_info(*opts); });
}

}  // namespace antcd::cli
