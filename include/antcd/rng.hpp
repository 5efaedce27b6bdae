// antcd/rng.hpp — the seed mixer and the random stream of antcd's stochastic methods, for the
// library and its tools alike. Header only.
//
// Every stochastic method takes a 64-bit seed; related seeds (0, 1, 2, ... or a seed combined with
// a frame and object indices) are spread with mix_seed before they start a stream.
#pragma once

#include <cstdint>

namespace antcd {

/// SplitMix64 finaliser: turns related seeds (0, 1, 2, ...) into unrelated 64-bit states.
constexpr std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// The searches' random stream: xoshiro256** (Blackman and Vigna), 32 bytes of state and a few
/// cycles per draw, seeded through SplitMix64; our own mappings to ranges, so a seed gives the
/// same result with any standard library.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    std::uint64_t x = seed;
    for (std::uint64_t& word : s_) {
      x += 0x9E3779B97F4A7C15ULL;
      word = mix_seed(x);
    }
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform integer in [0, n), n >= 1 (rejection sampling, unbiased).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }
  /// Uniform integer in [0, n) for n < 2^32 by one multiply (Lemire's method without the
  /// rejection step; bias below n / 2^32, far under anything a search can notice).
  std::uint32_t below32(std::uint32_t n) {
    return static_cast<std::uint32_t>(((next() >> 32) * std::uint64_t{n}) >> 32);
  }
  /// Uniform double in [0, 1).
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform float in [0, 1).
  float unit_float() { return static_cast<float>(next() >> 40) * 0x1.0p-24f; }
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4]{};
};

}  // namespace antcd
