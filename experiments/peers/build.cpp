#include "peers/build.hpp"

#include "peers/adapters/fcl.hpp"
#include "peers/adapters/peer_mesh.hpp"
#include "peers/stopwatch.hpp"
#include "shared/statistics.hpp"

#include <antcd/bvh.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace antcd::experiments::peers_bench {
namespace {

/// Builds FCL's hierarchy over `input` `reps` times (the previous one freed before each, outside
/// the clock); `median_ms` gets the median build time. Returns the last build.
template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> timed_fcl_builds(const peers::FclInput& input, int reps,
                                                    double& median_ms) {
  std::shared_ptr<fcl::BVHModel<BV>> model;
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    model.reset();
    const Stopwatch sw;
    model = peers::build_fcl<BV>(input);
    t.push_back(sw.wall_ms());
  }
  median_ms = shared::median(t);
  return model;
}

}  // namespace

BuildRow measure_build(std::size_t size, const Mesh& mesh, int reps) {
  BuildRow row;
  row.size = size;
  row.triangles = mesh.triangles.size();
  std::unique_ptr<Model> model;
  // Time only the construction: the copy handed to Model is made outside the timed region.
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    Mesh copy = mesh;
    model.reset();
    const Stopwatch sw;
    model = std::make_unique<Model>(std::move(copy));
    t.push_back(sw.wall_ms());
  }
  row.antcd_ms = shared::median(t);
  row.antcd_bytes_per_tri =
      static_cast<double>(model->stats().memory_bytes) / static_cast<double>(row.triangles);
  row.antcd_nodes = model->stats().nodes;
  model.reset();

  const peers::FclInput input = peers::fcl_input(peers::peer_mesh(mesh));
  {
    const auto obbrss = timed_fcl_builds<fcl::OBBRSSd>(input, reps, row.fcl_obbrss_ms);
    row.fcl_obbrss_bytes_per_tri = peers::fcl_bytes(*obbrss) / static_cast<double>(row.triangles);
    row.fcl_bvs = obbrss->getNumBVs();
  }
  const auto obb = timed_fcl_builds<fcl::OBBd>(input, reps, row.fcl_obb_ms);
  row.fcl_obb_bytes_per_tri = peers::fcl_bytes(*obb) / static_cast<double>(row.triangles);
  return row;
}

}  // namespace antcd::experiments::peers_bench
