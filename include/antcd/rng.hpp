// antcd/rng.hpp — the seed mixer and the random stream of antcd's stochastic methods, for the
// library and its tools alike. Header only.
//
// Every stochastic method takes a 64-bit seed; related seeds (0, 1, 2, ... or a seed combined with
// a frame and object indices) are spread with mix_seed before they start a stream.
#pragma once

#include <cstdint>
#include <random>

namespace antcd {

/// SplitMix64 finaliser: turns related seeds (0, 1, 2, ...) into unrelated 64-bit states.
constexpr std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// The searches' random stream: std::mt19937_64 (its output sequence is fixed by the standard)
/// with our own mappings to ranges, so a seed gives the same result with any standard library
/// (the std:: distributions are implementation-defined).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(mix_seed(seed)) {}

  /// Uniform integer in [0, n), n >= 1 (rejection sampling, unbiased).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = engine_();
      if (r >= threshold) return r % n;
    }
  }
  /// Uniform double in [0, 1).
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace antcd
