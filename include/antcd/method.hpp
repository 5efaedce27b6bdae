// antcd/method.hpp — the detection methods of the paper's comparison and their names, one table
// for the libraries and their tools. Part of antcd::random: the random searches select their
// engine by it (SearchRequest::method), and the scene runner (antcd::scene) runs each of them.
#pragma once

#include <antcd/random_export.hpp>

#include <string_view>

namespace antcd {

/// A detection method. Exact and SphereObb are deterministic; the others are the random searches
/// of random.hpp (Exhaustive scans every feature pair: the searches' reference).
enum class Method {
  Exact,       ///< triangle–triangle tests (ground truth, default)
  SphereObb,   ///< hierarchy only: collide when some pair of leaf volumes overlaps
  Aco,         ///< classic ant colony (Sphere-OBB-ACO): Eqs. 7–8, fixed alpha, beta, rho
  Maco,        ///< improved ant colony (Sphere-OBB-MACO): Eqs. 9–15, each switch in MacoSwitches
  Pso,         ///< particle swarm (BOX-PSO / PSO random collision detection baseline)
  Ga,          ///< genetic algorithm baseline
  Exhaustive,  ///< every feature pair in row order: the searches' reference
  Grid,        ///< fixed-radius neighbour search on a uniform grid: the second reference
};

/// True for the random searches (Aco, Maco, Pso, Ga, Exhaustive, Grid).
constexpr bool is_search_method(Method m) { return m != Method::Exact && m != Method::SphereObb; }

/// The method's name on command lines and in files: "exact", "sphere-obb", "aco", "maco", "pso",
/// "ga", "exhaustive", "grid".
ANTCD_RANDOM_API std::string_view method_name(Method m);

/// The method's name in tables and reports: "Exact", "Sphere-OBB", "ACO", "MACO", "PSO", "GA",
/// "Exhaustive", "Grid".
ANTCD_RANDOM_API std::string_view method_label(Method m);

/// The method named `name` (see method_name). Throws ArgumentError listing the accepted names.
ANTCD_RANDOM_API Method parse_method(std::string_view name);

}  // namespace antcd
