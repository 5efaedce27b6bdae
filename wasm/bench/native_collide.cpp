// The native side of wasm/bench/bench.mjs: the same mesh pair and poses through the native
// library, for the reference verdicts and the native time per query.
//
// Usage: antcd_wasm_bench_native A.obj B.obj POSES.txt MIN_MS [SAME_POSE_REPEATS]
// POSES.txt: one query per line, 32 numbers: pose A then pose B, each a column-major 4x4 matrix
// (the bench writes the shortest round-trip text of its doubles, so both sides hold the same
// poses). Prints JSON: {"verdicts": [0/1 ...], "ns_per_query": mean over passes through every
// pose, repeated for at least MIN_MS milliseconds (as the bench times antcd-wasm)}; with
// SAME_POSE_REPEATS also "per_query_ns": per query, the best of 5 rounds of SAME_POSE_REPEATS
// consecutive calls at that pose (warm caches, as the bench's per-query times of antcd-wasm).
#include <antcd/collide.hpp>
#include <antcd/load.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace {

antcd::Transform from_column_major(const double* m) {
  antcd::Transform t;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) t.rotation(r, c) = m[4 * c + r];
  }
  t.translation = antcd::Vec3(m[12], m[13], m[14]);
  return t;
}

double elapsed_ns(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5 && argc != 6) {
    std::fprintf(stderr, "usage: %s A.obj B.obj POSES.txt MIN_MS [SAME_POSE_REPEATS]\n", argv[0]);
    return 2;
  }
  try {
    const antcd::Model a(antcd::load_mesh(argv[1]), {}, argv[1]);
    const antcd::Model b(antcd::load_mesh(argv[2]), {}, argv[2]);
    std::ifstream in(argv[3]);
    std::vector<antcd::Transform> pa;
    std::vector<antcd::Transform> pb;
    double m[32];
    while (true) {
      int k = 0;
      for (; k < 32 && (in >> m[k]); ++k) {
      }
      if (k < 32) break;
      pa.push_back(from_column_major(m));
      pb.push_back(from_column_major(m + 16));
    }
    const double min_ns = std::max(0.0, std::atof(argv[4])) * 1e6;
    antcd::CollisionResult result;
    std::vector<int> verdicts(pa.size());
    long passes = 0;
    const auto start = std::chrono::steady_clock::now();
    do {
      for (std::size_t q = 0; q < pa.size(); ++q) {
        verdicts[q] = antcd::collide(a, pa[q], b, pb[q], {}, result) ? 1 : 0;
      }
      ++passes;
    } while (elapsed_ns(start) < min_ns);
    const double ns = elapsed_ns(start);
    std::printf("{\"verdicts\": [");
    for (std::size_t q = 0; q < verdicts.size(); ++q) std::printf(q ? ",%d" : "%d", verdicts[q]);
    std::printf(
        "], \"ns_per_query\": %.1f",
        pa.empty() ? 0.0 : ns / (static_cast<double>(passes) * static_cast<double>(pa.size())));
    if (argc == 6) {
      const int same = std::max(1, std::atoi(argv[5]));
      std::printf(", \"per_query_ns\": [");
      for (std::size_t q = 0; q < pa.size(); ++q) {
        double best = 1e300;
        for (int round = 0; round < 5; ++round) {
          const auto t0 = std::chrono::steady_clock::now();
          for (int r = 0; r < same; ++r) antcd::collide(a, pa[q], b, pb[q], {}, result);
          best = std::min(best, elapsed_ns(t0) / same);
        }
        std::printf(q ? ",%.1f" : "%.1f", best);
      }
      std::printf("]");
    }
    std::printf("}\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
