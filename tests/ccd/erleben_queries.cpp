// Tests and benchmarks only: the rational CSV reader and the Erleben files (erleben_queries.hpp).
#include "erleben_queries.hpp"

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace antcd::test {

namespace {

/// The double nearest to q (ties to the even significand); mpq's get_d truncates instead.
double nearest_double(const mpq_class& q, const std::string& where) {
  const double down = q.get_d();  // |down| <= |q|, the nearest double toward zero
  if (!std::isfinite(down))
    throw std::runtime_error(where + ": coordinate out of the double range");
  if (mpq_class(down) == q) return down;
  const double up = std::nextafter(down, sgn(q) > 0 ? std::numeric_limits<double>::infinity()
                                                    : -std::numeric_limits<double>::infinity());
  if (!std::isfinite(up)) throw std::runtime_error(where + ": coordinate out of the double range");
  const mpq_class below = abs(q - mpq_class(down));
  const mpq_class above = abs(mpq_class(up) - q);
  if (below != above) return below < above ? down : up;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &down, sizeof bits);
  return (bits & 1u) == 0 ? down : up;
}

mpz_class parse_integer(const std::string& text, const std::string& where) {
  const std::size_t start = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
  if (start == text.size() || text.find_first_not_of("0123456789", start) != std::string::npos) {
    throw std::runtime_error(where + ": not an integer: '" + text + "'");
  }
  return mpz_class(text[0] == '+' ? text.substr(1) : text, 10);
}

}  // namespace

std::vector<RationalQuery> read_rational_csv(const std::string& path, CcdKind kind,
                                             const std::string& name_prefix) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<RationalQuery> out;
  RationalQuery current;
  std::string line;
  std::size_t row = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::string where = path + ": row " + std::to_string(row + 1);
    std::vector<std::string> fields;
    for (std::size_t begin = 0;;) {
      const std::size_t comma = line.find(',', begin);
      fields.push_back(line.substr(begin, comma == std::string::npos ? comma : comma - begin));
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
    if (fields.size() != 7) {
      throw std::runtime_error(where + ": expected 7 fields, got " + std::to_string(fields.size()));
    }
    if (fields[6] != "0" && fields[6] != "1") {
      throw std::runtime_error(where + ": truth must be 0 or 1, got '" + fields[6] + "'");
    }
    const std::size_t k = row % 8;
    Vec3 p;
    for (int c = 0; c < 3; ++c) {
      const auto i = static_cast<std::size_t>(2 * c);
      const mpz_class den = parse_integer(fields[i + 1], where);
      if (den == 0) throw std::runtime_error(where + ": zero denominator");
      mpq_class exact(parse_integer(fields[i], where), den);
      exact.canonicalize();
      p[c] = nearest_double(exact, where);
      if (mpq_class(p[c]) != exact) current.exact = false;
    }
    const bool truth = fields[6] == "1";
    if (k == 0) {
      current.truth = truth;
    } else if (truth != current.truth) {
      throw std::runtime_error(where + ": truth differs from the query's first row");
    }
    (k < 4 ? current.query.at_t0[k] : current.query.at_t1[k - 4]) = p;
    if (k == 7) {
      current.query.kind = kind;
      current.query.name = name_prefix + "#" + std::to_string(out.size());
      out.push_back(current);
      current = RationalQuery{};
    }
    ++row;
  }
  if (row % 8 != 0) {
    throw std::runtime_error(path + ": incomplete last query (" + std::to_string(row % 8) +
                             " of 8 rows)");
  }
  if (out.empty()) throw std::runtime_error(path + ": holds no query");
  return out;
}

std::vector<ErlebenFile> load_erleben(const std::string& dir) {
  static const char* const kScenes[] = {
      "cube-cliff-edges", "cube-internal-edges", "sliding-spike", "sliding-wedge", "spike-crack",
      "spike-hole",       "spike-wedge",         "spikes",        "wedge-crack",   "wedges"};
  std::vector<ErlebenFile> files;
  for (const char* scene : kScenes) {
    for (const CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
      const std::string sub = kind == CcdKind::VertexFace ? "vertex-face" : "edge-edge";
      ErlebenFile f;
      f.scene = scene;
      f.kind = kind;
      f.queries = read_rational_csv(dir + "/erleben-" + scene + "/" + sub + "/data_0_0.csv", kind,
                                    std::string(scene) + "/" + sub);
      files.push_back(std::move(f));
    }
  }
  return files;
}

}  // namespace antcd::test
