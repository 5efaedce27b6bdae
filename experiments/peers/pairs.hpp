// experiments/peers/pairs.hpp — the pair protocol: two tori, one tumbling past the other, at four
// clearances; antcd against FCL-OBBRSS, boolean and all contacts, verdicts and triangle-pair sets
// compared pose by pose.
#pragma once

#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace antcd::experiments::peers_bench {

enum class Clearance { Deep, Shallow, Touching, Separated };
inline constexpr std::array<Clearance, 4> kClearances = {Clearance::Deep, Clearance::Shallow,
                                                         Clearance::Touching, Clearance::Separated};

const char* clearance_name(Clearance c);
/// How B is placed from the contact distance s*, e.g. "s = 0.7 s*".
const char* clearance_rule(Clearance c);

/// One size and clearance: counts over the poses and the times of every query (µs).
struct PairCell {
  std::size_t size = 0;
  std::size_t triangles = 0;
  Clearance clearance = Clearance::Deep;
  std::size_t poses = 0;
  std::size_t colliding_antcd = 0;
  std::size_t colliding_fcl = 0;
  std::size_t triangle_pairs_antcd = 0;
  std::size_t triangle_pairs_fcl = 0;
  std::size_t disagreements = 0;
  std::string first_disagreement;
  std::vector<double> antcd_bool_us, fcl_bool_us, antcd_all_us, fcl_all_us;
};

/// The torus of `size` nominal triangles at every clearance over `poses` poses.
std::vector<PairCell> run_pairs_at(std::size_t size, std::size_t poses, std::ostream& log);

}  // namespace antcd::experiments::peers_bench
