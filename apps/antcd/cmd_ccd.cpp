// antcd ccd-queries FILE.csv: primitive CCD on a file of exact rational queries (the CSV format of
// Wang et al.'s CCD benchmark), scored against the file's truth column.
// antcd sweep A B: continuous collision between two meshes moving between two poses each.
#include <antcd/ccd.hpp>
#include <antcd/csv.hpp>
#include <antcd/sweep.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_util.hpp"

#ifdef ANTCD_HAVE_GMP
#include <gmpxx.h>
#endif

namespace antcd::cli {

namespace {

struct QueriesOptions {
  std::string file;
  std::string kind;
  double min_separation = 0;
  double time_tolerance = 1e-6;
  bool json = false;
};

struct FileQuery {
  FileQuery() {
    at_t0.fill(Vec3::Zero());
    at_t1.fill(Vec3::Zero());
  }
  std::array<Vec3, 4> at_t0, at_t1;
  bool truth = false;
  /// Largest |exact coordinate - its double| of the query (rounded up).
  double rounding = 0;
};

#ifdef ANTCD_HAVE_GMP
/// Longest row of a query file: 7 integers of the benchmark's size need a few hundred bytes.
constexpr std::size_t kMaxQueryLine = 4096;

/// One decimal integer (optional sign, digits only), or a UsageError naming the row and column.
mpz_class parse_integer(const std::string& text, const std::string& where) {
  std::size_t start = (!text.empty() && (text[0] == '-' || text[0] == '+')) ? 1 : 0;
  if (start == text.size() ||
      !std::all_of(text.begin() + static_cast<std::ptrdiff_t>(start), text.end(),
                   [](char c) { return c >= '0' && c <= '9'; })) {
    throw UsageError(where + ": not an integer: '" + text + "'");
  }
  return mpz_class(text[0] == '+' ? text.substr(1) : text, 10);
}

/// Reads the file: 8 rows per query, each x_num,x_den,y_num,y_den,z_num,z_den,truth.
std::vector<FileQuery> read_queries(const std::string& path) {
  // A regular file only, and bounded lines (antcd/csv.hpp): a FIFO, a device or a file without
  // line breaks is refused instead of blocking or filling the memory.
  std::ifstream in = open_regular_file(path, "query file");
  CsvLines lines(in, path, kMaxQueryLine);
  std::vector<FileQuery> queries;
  std::string line;
  std::size_t row = 0;
  FileQuery current;
  while (lines.next(line)) {
    if (line.empty()) continue;
    ++row;
    const std::string where = path + ": row " + std::to_string(row);
    std::vector<std::string> fields;
    std::size_t begin = 0;
    while (true) {
      const std::size_t comma = line.find(',', begin);
      std::string field = line.substr(begin, comma == std::string::npos ? comma : comma - begin);
      field.erase(0, field.find_first_not_of(" \t"));
      field.erase(field.find_last_not_of(" \t") + 1);
      fields.push_back(field);
      if (comma == std::string::npos) break;
      begin = comma + 1;
    }
    if (fields.size() != 7) {
      throw UsageError(where +
                       ": expected 7 fields (x_num,x_den,y_num,y_den,z_num,z_den,truth), got " +
                       std::to_string(fields.size()));
    }
    const std::size_t k = (row - 1) % 8;
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const auto i = static_cast<std::size_t>(2 * c);
      const mpz_class num = parse_integer(fields[i], where);
      const mpz_class den = parse_integer(fields[i + 1], where);
      if (den == 0) throw UsageError(where + ": zero denominator");
      mpq_class exact(num, den);
      exact.canonicalize();
      const double d = exact.get_d();
      if (!std::isfinite(d)) throw UsageError(where + ": coordinate out of the double range");
      p[c] = d;
      // get_d truncates: the error is exact here, then rounded up to a double.
      const mpq_class err = abs(exact - mpq_class(d));
      double e = err.get_d();
      if (mpq_class(e) < err) e = std::nextafter(e, 1e300);
      current.rounding = std::max(current.rounding, e);
    }
    if (fields[6] != "0" && fields[6] != "1") {
      throw UsageError(where + ": truth must be 0 or 1, got '" + fields[6] + "'");
    }
    const bool truth = fields[6] == "1";
    if (k == 0) {
      current.truth = truth;
    } else if (truth != current.truth) {
      throw UsageError(where + ": truth differs from the query's first row");
    }
    (k < 4 ? current.at_t0[k] : current.at_t1[k - 4]) = p;
    if (k == 7) {
      queries.push_back(current);
      current = FileQuery{};
    }
  }
  if (row % 8 != 0) {
    throw UsageError(path + ": row " + std::to_string(row) + ": incomplete query (" +
                     std::to_string(row % 8) + " of 8 rows)");
  }
  if (queries.empty()) throw UsageError(path + ": holds no query");
  return queries;
}
#else
std::vector<FileQuery> read_queries(const std::string&) {
  throw UsageError(
      "ccd-queries: this antcd was built without GMP (Debian libgmp-dev), which reading "
      "exact rationals needs");
}
#endif

int run_queries(const QueriesOptions& o) {
  if (o.kind != "vf" && o.kind != "ee") {
    throw UsageError("--kind must be vf or ee, got '" + o.kind + "'");
  }
  const std::vector<FileQuery> queries = read_queries(o.file);
  std::vector<ccd::PrimitiveResult> results(queries.size());
  std::vector<double> seconds(queries.size());
  double total = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const FileQuery& q = queries[i];
    // The doubles moved each point by at most `rounding`, so F by at most twice that per axis:
    // widening the separation by it keeps every exact contact a hit.
    const double separation = o.min_separation + 2 * q.rounding * (1 + 1e-15);
    const Stopwatch clock;
    results[i] = o.kind == "vf" ? ccd::vertex_face(q.at_t0, q.at_t1, separation, o.time_tolerance)
                                : ccd::edge_edge(q.at_t0, q.at_t1, separation, o.time_tolerance);
    seconds[i] = clock.seconds();
    total += seconds[i];
  }
  std::size_t hits = 0, false_negatives = 0, false_positives = 0, tolerance = 0, rounded = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    hits += results[i].hit ? 1 : 0;
    tolerance += results[i].hit && results[i].tolerance_decided ? 1 : 0;
    false_negatives += queries[i].truth && !results[i].hit ? 1 : 0;
    false_positives += !queries[i].truth && results[i].hit ? 1 : 0;
    rounded += queries[i].rounding > 0 ? 1 : 0;
  }
  std::vector<double> sorted = seconds;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.empty() ? 0 : sorted[sorted.size() / 2];
  if (o.json) {
    nlohmann::json j;
    j["queries"] = queries.size();
    j["seconds"] = total;
    j["median_seconds"] = median;
    j["hits"] = hits;
    j["false_negatives"] = false_negatives;
    j["false_positives"] = false_positives;
    nlohmann::json list = nlohmann::json::array();
    for (const auto& r : results) {
      list.push_back({{"hit", r.hit},
                      {"toi", r.toi},
                      {"tolerance_decided", r.tolerance_decided},
                      {"boxes", r.boxes}});
    }
    j["results"] = std::move(list);
    std::cout << j.dump() << '\n';
    return 0;
  }
  std::printf("queries: %zu (%s)\n", queries.size(), o.kind == "vf" ? "vertex-face" : "edge-edge");
  std::printf("hits: %zu (%zu decided by the tolerance)\n", hits, tolerance);
  std::printf("false negatives: %zu\nfalse positives: %zu\n", false_negatives, false_positives);
  if (rounded > 0) {
    std::printf("queries not exact in double: %zu (separation widened by their rounding)\n",
                rounded);
  }
  std::printf("time per query: mean %.3f us, median %.3f us (total %.3f ms)\n",
              queries.empty() ? 0.0 : 1e6 * total / static_cast<double>(queries.size()),
              1e6 * median, 1e3 * total);
  return 0;
}

struct SweepOptions {
  std::string mesh_a, mesh_b;
  std::string pose_a0 = "0,0,0", pose_a1 = "0,0,0", pose_b0 = "0,0,0", pose_b1 = "0,0,0";
  double min_separation = 0;
  double time_tolerance = 1e-6;
  std::uint32_t max_iterations = SweepRequest{}.max_iterations;
  bool json = false;
  std::uint32_t leaf_size = 4;
  std::string covariance = "area";
};

int run_sweep(const SweepOptions& o) {
  const Transform a0 = parse_pose(o.pose_a0, "--pose-a0");
  const Transform a1 = parse_pose(o.pose_a1, "--pose-a1");
  const Transform b0 = parse_pose(o.pose_b0, "--pose-b0");
  const Transform b1 = parse_pose(o.pose_b1, "--pose-b1");
  if (!(o.time_tolerance > 0)) throw UsageError("--time-tolerance must be > 0");
  const BuildOptions build{o.leaf_size, parse_covariance(o.covariance)};
  const Model a = load_model(o.mesh_a, build);
  const Model b = load_model(o.mesh_b, build);
  warn_degenerate(a);
  warn_degenerate(b);
  SweepRequest request;
  request.min_separation = o.min_separation;
  request.time_tolerance = o.time_tolerance;
  request.max_iterations = o.max_iterations;
  const Stopwatch clock;
  const SweepResult r = sweep(a, a0, a1, b, b0, b1, request);
  const double query_ms = clock.ms();
  const Contact& c = r.contact;
  if (o.json) {
    nlohmann::json j;
    j["mesh_a"] = o.mesh_a;
    j["mesh_b"] = o.mesh_b;
    j["hit"] = r.hit;
    j["toi"] = r.toi;
    j["tolerance_decided"] = r.tolerance_decided;
    j["budget_exhausted"] = r.budget_exhausted;
    j["distance"] = r.distance;
    j["motion_bound"] = r.motion_bound;
    if (r.hit) {
      j["contact"] = {{"triangle_a", c.triangle_a}, {"triangle_b", c.triangle_b},
                      {"point", vec_json(c.point)}, {"normal", vec_json(c.normal)},
                      {"distance", c.distance},     {"depth", c.depth}};
    }
    j["iterations"] = r.iterations;
    j["query_ms"] = query_ms;
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("A: %s (%zu triangles)\nB: %s (%zu triangles)\n", o.mesh_a.c_str(),
              a.stats().triangles, o.mesh_b.c_str(), b.stats().triangles);
  if (r.hit) {
    std::printf("hit: yes, toi %.17g (%s)\n", r.toi,
                r.budget_exhausted    ? "iteration budget ran out: conservative stop"
                : r.tolerance_decided ? "within the time tolerance"
                                      : "proven contact");
    std::printf(
        "contact: triangles %u / %u, point %.17g %.17g %.17g, normal %.6g %.6g %.6g, "
        "distance %.6g\n",
        c.triangle_a, c.triangle_b, c.point.x(), c.point.y(), c.point.z(), c.normal.x(),
        c.normal.y(), c.normal.z(), c.distance);
  } else {
    std::printf("hit: no (proven; a certified lower bound of the distance: %.6g)\n", r.distance);
  }
  std::printf(
      "query: %.3f ms, %u iterations (interval tests, distance queries and traversals), "
      "motion bound %.6g per unit time\n",
      query_ms, r.iterations, r.motion_bound);
  return 0;
}

}  // namespace

void add_ccd_commands(CLI::App& app, int& code) {
  auto q = std::make_shared<QueriesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "ccd-queries",
      "Primitive continuous collision queries from a rational CSV file (Wang et al.'s format)");
  cmd->add_option("FILE", q->file,
                  "CSV, 8 rows per query: x_num,x_den,y_num,y_den,z_num,z_den,truth")
      ->required();
  cmd->add_option("--kind", q->kind, "vf (vertex-face) or ee (edge-edge)")->required();
  cmd->add_option("--min-separation", q->min_separation,
                  "Report contact within this distance (>= 0)")
      ->check(non_negative_finite());
  cmd->add_option("--time-tolerance", q->time_tolerance, "Time tolerance (> 0)")
      ->check(positive_finite());
  cmd->add_flag("--json", q->json, "Print {queries, seconds, results: [{hit, toi}, ...]} as JSON");
  cmd->callback([q, &code] { code = run_queries(*q); });

  auto o = std::make_shared<SweepOptions>();
  CLI::App* sw = app.add_subcommand(
      "sweep", "Continuous collision: first time two meshes moving between two poses touch");
  sw->add_option("A", o->mesh_a, "First mesh file (OBJ, STL, PLY, OFF, glTF, ...)")->required();
  sw->add_option("B", o->mesh_b, "Second mesh file")->required();
  sw->add_option("--pose-a0", o->pose_a0, "Pose of A at t = 0: tx,ty,tz[,qw,qx,qy,qz]");
  sw->add_option("--pose-a1", o->pose_a1, "Pose of A at t = 1");
  sw->add_option("--pose-b0", o->pose_b0, "Pose of B at t = 0");
  sw->add_option("--pose-b1", o->pose_b1, "Pose of B at t = 1");
  sw->add_option("--min-separation", o->min_separation, "Contact distance (mesh units, >= 0)")
      ->check(non_negative_finite());
  sw->add_option("--time-tolerance", o->time_tolerance, "Time tolerance (> 0)")
      ->check(positive_finite());
  sw->add_option("--max-iterations", o->max_iterations,
                 "Most iterations (interval tests, distance queries and traversals)")
      ->check(CLI::Range(1u, 1u << 30));
  sw->add_flag("--json", o->json, "Print the result as JSON");
  sw->add_option("--leaf-size", o->leaf_size, "Triangles per leaf of the hierarchy")
      ->check(CLI::Range(1, 1 << 20));
  sw->add_option("--covariance", o->covariance,
                 "OBB fit: 'area' (area-weighted centroid, Eq. 3) or 'vertex' (Eqs. 1-2)");
  sw->callback([o, &code] { code = run_sweep(*o); });
}

}  // namespace antcd::cli
