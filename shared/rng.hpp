// shared/rng.hpp — the tools' random numbers: the SplitMix64 generator over the library's seed
// mixer (antcd/rng.hpp), fully specified, so that generated scenes, pose sets and derived seeds
// are the same with every standard library (the standard distributions are not specified bit for
// bit). The library's own stream (antcd::Rng) is a different generator: the tools keep SplitMix64
// so that the generated scenes stay what they were.
#pragma once

#include <antcd/rng.hpp>

#include <cstdint>

namespace antcd::shared {

/// The library's seed mixer (SplitMix64's output for the state x), antcd/rng.hpp.
using antcd::mix_seed;

/// A seed for one purpose, from a run's seed, a tag naming the purpose and up to three indices.
constexpr std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t tag, std::uint64_t a = 0,
                                    std::uint64_t b = 0, std::uint64_t c = 0) {
  return mix_seed(mix_seed(mix_seed(mix_seed(mix_seed(seed) ^ tag) ^ a) ^ b) ^ c);
}

/// The SplitMix64 generator.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  /// A stream for one purpose (one station, one object), independent of how much other streams
  /// were used.
  SplitMix64(std::uint64_t seed, std::uint64_t stream) : state_(seed) {
    state_ ^= SplitMix64(stream * 0xD1B54A32D192ED03ULL + 0x8CB92BA72F3D8DD7ULL).next();
    next();
  }

  std::uint64_t next() {
    const std::uint64_t out = mix_seed(state_);
    state_ += 0x9E3779B97F4A7C15ULL;
    return out;
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

}  // namespace antcd::shared
