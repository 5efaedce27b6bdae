// The native side of wasm/bench/bench.mjs: the same mesh pair and poses through the native
// library, for the reference verdicts and the native time per query.
//
// Usage: antcd_wasm_bench_native [--all-contacts] [--rounds R] A.obj B.obj POSES.txt MIN_MS
//                                [SAME_POSE_REPEATS]
// POSES.txt: one query per line, 32 numbers: pose A then pose B, each a column-major 4x4 matrix
// (the bench writes the shortest round-trip text of its doubles, so both sides hold the same
// poses). Prints JSON: {"verdicts": [0/1 ...], "ns_per_query": mean over passes through every
// pose, repeated for at least MIN_MS milliseconds (as the bench times antcd-wasm)}; with
// SAME_POSE_REPEATS also "per_query_ns": per query, the best of 5 rounds of SAME_POSE_REPEATS
// consecutive calls at that pose (warm caches, as the bench's per-query times of antcd-wasm).
// --all-contacts (wasm/bench/simd.mjs): every contact, and per query "contacts" (their number)
// and "digests" / "pair_digests" (contact_digest below, as simd.mjs computes them of the
// package's answers);
// --rounds R: each per-query time is the median of R rounds instead of the best of 5.
#include <antcd/collide.hpp>
#include <antcd/load.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// FNV-1a (64-bit) of each contact's triangle indices, point and distance, as doubles' bytes in
// order (little-endian, as in WebAssembly memory): equal digests mean bit-identical contacts.
// `fields` 2: the triangle pairs alone.
std::uint64_t contact_digest(const std::vector<antcd::Contact>& contacts, int fields) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const antcd::Contact& c : contacts) {
    const double v[6] = {static_cast<double>(c.triangle_a),
                         static_cast<double>(c.triangle_b),
                         c.point.x(),
                         c.point.y(),
                         c.point.z(),
                         c.distance};
    for (int k = 0; k < fields; ++k) {
      const double x = v[k];
      unsigned char bytes[sizeof x];
      std::memcpy(bytes, &x, sizeof x);
      for (const unsigned char byte : bytes) h = (h ^ byte) * 0x100000001b3ULL;
    }
  }
  return h;
}

double elapsed_ns(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  antcd::CollisionRequest request;
  int rounds = 0;  // 0: the best of 5 rounds
  const char* const program = argv[0];
  while (argc > 1 && std::strncmp(argv[1], "--", 2) == 0) {
    if (std::strcmp(argv[1], "--all-contacts") == 0) {
      request.all_contacts = true;
      ++argv;
      --argc;
    } else if (std::strcmp(argv[1], "--rounds") == 0 && argc > 2 && std::atoi(argv[2]) > 0) {
      rounds = std::atoi(argv[2]);
      argv += 2;
      argc -= 2;
    } else {
      std::fprintf(stderr, "error: unknown option %s\n", argv[1]);
      return 2;
    }
  }
  if (argc != 5 && argc != 6) {
    std::fprintf(stderr,
                 "usage: %s [--all-contacts] [--rounds R] A.obj B.obj POSES.txt MIN_MS "
                 "[SAME_POSE_REPEATS]\n",
                 program);
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
        verdicts[q] = antcd::collide(a, pa[q], b, pb[q], request, result) ? 1 : 0;
      }
      ++passes;
    } while (elapsed_ns(start) < min_ns);
    const double ns = elapsed_ns(start);
    std::printf("{\"verdicts\": [");
    for (std::size_t q = 0; q < verdicts.size(); ++q) std::printf(q ? ",%d" : "%d", verdicts[q]);
    if (request.all_contacts) {
      std::string counts;
      std::string digests;
      std::string pair_digests;
      for (std::size_t q = 0; q < pa.size(); ++q) {
        antcd::collide(a, pa[q], b, pb[q], request, result);
        char text[48];
        std::snprintf(text, sizeof text, "%s%zu", q ? "," : "", result.contacts.size());
        counts += text;
        std::snprintf(text, sizeof text, "%s\"%016llx\"", q ? "," : "",
                      static_cast<unsigned long long>(contact_digest(result.contacts, 6)));
        digests += text;
        std::snprintf(text, sizeof text, "%s\"%016llx\"", q ? "," : "",
                      static_cast<unsigned long long>(contact_digest(result.contacts, 2)));
        pair_digests += text;
      }
      std::printf("], \"contacts\": [%s], \"digests\": [%s], \"pair_digests\": [%s", counts.c_str(),
                  digests.c_str(), pair_digests.c_str());
    }
    std::printf(
        "], \"ns_per_query\": %.1f",
        pa.empty() ? 0.0 : ns / (static_cast<double>(passes) * static_cast<double>(pa.size())));
    if (argc == 6) {
      const int same = std::max(1, std::atoi(argv[5]));
      std::printf(", \"per_query_ns\": [");
      for (std::size_t q = 0; q < pa.size(); ++q) {
        std::vector<double> times(rounds > 0 ? rounds : 5);
        for (double& t : times) {
          const auto t0 = std::chrono::steady_clock::now();
          for (int r = 0; r < same; ++r) antcd::collide(a, pa[q], b, pb[q], request, result);
          t = elapsed_ns(t0) / same;
        }
        std::sort(times.begin(), times.end());
        std::printf(q ? ",%.1f" : "%.1f", rounds > 0 ? times[times.size() / 2] : times.front());
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
