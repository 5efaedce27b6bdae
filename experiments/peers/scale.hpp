// experiments/peers/scale.hpp — the scale protocol: the production line with up to 10 000 objects,
// antcd only: objects against candidate pairs against time per frame.
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>

namespace antcd::experiments::peers_bench {

struct ScaleRow {
  std::size_t objects = 0;
  std::size_t vertices_option = 0;
  std::size_t triangles = 0;
  std::size_t models = 0;
  std::size_t frames = 0;
  double candidates = 0;  ///< per frame, mean
  double colliding = 0;   ///< per frame, mean
  double median_ms = 0;
  double p99_ms = 0;
  double build_ms = 0;
  double model_mib = 0;
  double rss_mib = 0;
};

/// The line with `objects` objects of about `vertices` vertices, `frames` frames, written into
/// and loaded back from `dir`.
ScaleRow run_scale_row(std::size_t objects, std::size_t vertices, std::size_t frames,
                       const std::filesystem::path& dir, std::ostream& log);

}  // namespace antcd::experiments::peers_bench
