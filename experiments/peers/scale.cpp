#include "peers/scale.hpp"

#include "peers/generated_scenes.hpp"
#include "peers/machine.hpp"
#include "peers/stopwatch.hpp"
#include "shared/production_line.hpp"
#include "shared/statistics.hpp"

#include <antcd/scene.hpp>

#include <map>
#include <vector>

namespace antcd::experiments::peers_bench {

ScaleRow run_scale_row(std::size_t objects, std::size_t vertices, std::size_t frames,
                       const std::filesystem::path& dir, std::ostream& log) {
  shared::ProductionLineOptions po;
  po.objects = objects;
  po.vertices = vertices;
  po.frames = frames;
  const shared::GeneratedScene g = shared::generate_production_line(po);
  const auto scene = load_generated(g, dir);
  ScaleRow row;
  row.objects = objects;
  row.vertices_option = vertices;
  row.models = scene->model_count();
  row.frames = frames;
  row.build_ms = scene->build_ms();
  std::map<const Model*, int> seen;
  for (std::size_t i = 0; i < scene->object_count(); ++i) {
    const Model& m = scene->model_of(i);
    row.triangles += m.leaf_triangles().size();
    if (seen.emplace(&m, 0).second) {
      row.model_mib += static_cast<double>(m.stats().memory_bytes) / (1024.0 * 1024.0);
    }
  }
  SceneQuery q;
  q.method = Method::Exact;
  std::vector<double> ms;
  for (std::size_t f = 0; f < frames; ++f) {
    const Stopwatch sw;
    const FrameResult r = scene->run_frame(f, q);
    ms.push_back(sw.wall_ms());
    row.candidates += static_cast<double>(r.candidates.size());
    row.colliding += static_cast<double>(r.pairs.size());
  }
  row.candidates /= static_cast<double>(frames);
  row.colliding /= static_cast<double>(frames);
  row.median_ms = shared::median(ms);
  row.p99_ms = shared::quantile(ms, 0.99);
  row.rss_mib = rss_mib();
  log << "  scale: " << objects << " objects done\n";
  return row;
}

}  // namespace antcd::experiments::peers_bench
