// `antcd bench paper --quick`: every promised file is written, well formed and in range.
#include "paper/paper_bench.hpp"
#include "paper/learned.hpp"

#include <gtest/gtest.h>
#include <antcd/file.hpp>
#include <antcd/mesh.hpp>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace antcd::experiments {
namespace {

namespace fs = std::filesystem;

struct Csv {
  std::string header;
  std::vector<std::map<std::string, std::string>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

Csv read_csv(const fs::path& path) {
  Csv csv;
  std::istringstream in(read_file(path));
  std::getline(in, csv.header);
  const std::vector<std::string> names = split(csv.header);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = split(line);
    EXPECT_EQ(fields.size(), names.size()) << path << ": " << line;
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < names.size() && k < fields.size(); ++k) row[names[k]] = fields[k];
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

double value(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end()) {
    ADD_FAILURE() << "missing column " << key;
    return 0;
  }
  return std::stod(it->second);
}

bool empty_field(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  return it == row.end() || it->second.empty();
}

void expect_fraction(const std::map<std::string, std::string>& row, const std::string& key) {
  const double v = value(row, key);
  EXPECT_GE(v, 0.0) << key;
  EXPECT_LE(v, 1.0) << key;
}

void check_files(const fs::path& out, const std::string& log) {
  for (const char* name :
       {"table1.md", "table1.csv", "table1.png", "table2.md", "table2.csv", "table2.png",
        "fig3.csv", "fig3.png", "fig4.csv", "fig4.png", "fig5.csv", "fig5.png", "report.md",
        "delta_sensitivity.csv", "ablation.csv", "scene/scene.json"}) {
    const fs::path path = out / name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    EXPECT_GT(fs::file_size(path), 0u) << path;
  }
  // Temporary files (written then renamed) are gone.
  for (const auto& entry : fs::directory_iterator(out)) {
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
  }
  EXPECT_NE(log.find("done"), std::string::npos) << log;
}

void check_pngs(const fs::path& out) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  for (const char* name : {"table1.png", "table2.png", "fig3.png", "fig4.png", "fig5.png"}) {
    const std::string bytes = read_file(out / name);
    ASSERT_GE(bytes.size(), signature.size()) << name;
    EXPECT_EQ(bytes.substr(0, signature.size()), signature) << name;
  }
}

void check_table1(const fs::path& out) {
  const Csv csv = read_csv(out / "table1.csv");
  EXPECT_EQ(csv.header,
            "method,features,candidates_a,candidates_b,space_a,space_b,target_rate,runs,reached,"
            "median_ms,median_evaluations,median_build_ms,paper_ms");
  // 5 searches x 2 feature counts (quick) x 4 rates.
  ASSERT_EQ(csv.rows.size(), 40u);
  for (const auto& row : csv.rows) {
    const double rate = value(row, "target_rate");
    EXPECT_TRUE(rate == 0.2 || rate == 0.4 || rate == 0.6 || rate == 0.8) << rate;
    const double features = value(row, "features");
    EXPECT_TRUE(features == 1000 || features == 2000) << features;
    // The measured pair is re-tessellated until both sides have n candidate triangles: every
    // row's space is truly n x n.
    EXPECT_EQ(value(row, "space_a"), features);
    EXPECT_EQ(value(row, "space_b"), features);
    EXPECT_GE(value(row, "candidates_a"), features);
    EXPECT_GE(value(row, "candidates_b"), features);
    EXPECT_GT(value(row, "runs"), 0);
    EXPECT_LE(value(row, "reached"), value(row, "runs"));
    EXPECT_GT(value(row, "median_build_ms"), 0);
    if (!empty_field(row, "median_ms")) {
      EXPECT_GT(value(row, "median_ms"), 0);
      EXPECT_GT(value(row, "median_evaluations"), 0);
    } else {
      EXPECT_LT(2 * value(row, "reached"), value(row, "runs") + 1);
    }
    if (row.at("method") == "maco") {
      EXPECT_GT(value(row, "paper_ms"), 0);
    }
  }
  // The exhaustive scan always reaches 80 %.
  for (const auto& row : csv.rows) {
    if (row.at("method") == "exhaustive") {
      EXPECT_EQ(value(row, "reached"), value(row, "runs"));
    }
  }
}

void check_table2(const fs::path& out) {
  const Csv csv = read_csv(out / "table2.csv");
  EXPECT_EQ(csv.header,
            "method,features,target_rate,runs,reached,median_a,median_b,median_ab,"
            "median_coverage,paper_ab");
  ASSERT_EQ(csv.rows.size(), 40u);
  for (const auto& row : csv.rows) {
    EXPECT_GT(value(row, "median_b"), 0);
    expect_fraction(row, "median_coverage");
    if (!empty_field(row, "median_ab")) {
      expect_fraction(row, "median_ab");
      EXPECT_LE(value(row, "median_a"), value(row, "median_b"));
      // A search cannot find contacts that were not sampled (medians over the same runs).
      if (value(row, "reached") == value(row, "runs")) {
        EXPECT_LE(value(row, "median_ab"), value(row, "median_coverage") + 1e-9);
      }
    }
    if (row.at("method") == "maco") {
      expect_fraction(row, "paper_ab");
    }
  }
}

void check_ablation(const fs::path& out) {
  const Csv csv = read_csv(out / "ablation.csv");
  EXPECT_EQ(csv.header,
            "variant,features,target_rate,runs,reached,median_ms,median_evaluations,"
            "evaluations_vs_maco");
  ASSERT_EQ(csv.rows.size(), 44u);  // MACO + 10 variants, 4 rates each
  std::map<std::string, int> seen;
  for (const auto& row : csv.rows) {
    ++seen[row.at("variant")];
    EXPECT_EQ(value(row, "features"), 1000);  // the quick plan's ablation size
    EXPECT_GT(value(row, "runs"), 0);
    EXPECT_LE(value(row, "reached"), value(row, "runs"));
    if (row.at("variant") == "MACO" && !empty_field(row, "evaluations_vs_maco")) {
      EXPECT_EQ(value(row, "evaluations_vs_maco"), 1.0);
    }
  }
  for (const char* v : {"MACO", "MACO-without-1-exponents", "MACO-only-4-reward",
                        "MACO-corridor-eq12", "MACO-greedy-route"}) {
    EXPECT_EQ(seen[v], 4) << v;
  }
}

void check_fig3(const fs::path& out) {
  const Csv csv = read_csv(out / "fig3.csv");
  EXPECT_EQ(csv.header, "features,ants,runs,mean_rate,median_rate,mean_ms,mean_evaluations");
  ASSERT_EQ(csv.rows.size(), 10u);  // 2 feature counts x 5 colony sizes
  for (const auto& row : csv.rows) {
    EXPECT_GT(value(row, "runs"), 0);
    expect_fraction(row, "mean_rate");
    expect_fraction(row, "median_rate");
    EXPECT_GT(value(row, "mean_ms"), 0);
    EXPECT_GT(value(row, "mean_evaluations"), 0);
  }
}

void check_scene_csv(const fs::path& path, std::size_t rows,
                     const std::vector<std::string>& methods) {
  const Csv csv = read_csv(path);
  EXPECT_EQ(csv.header,
            "method,budget_evaluations,frames,candidate_pairs,colliding_pairs,mean_pair_ms,"
            "mean_frame_ms,time_vs_exact,mean_pair_evaluations,recall,precision,accuracy");
  ASSERT_EQ(csv.rows.size(), rows) << path;
  std::map<std::string, int> seen;
  for (const auto& row : csv.rows) {
    ++seen[row.at("method")];
    EXPECT_GT(value(row, "candidate_pairs"), 0);
    EXPECT_GT(value(row, "colliding_pairs"), 0);
    EXPECT_GT(value(row, "mean_pair_ms"), 0);
    expect_fraction(row, "recall");
    expect_fraction(row, "precision");
    expect_fraction(row, "accuracy");
    // Exact is the ground truth; the hierarchy alone never misses a contact.
    if (row.at("method") == "exact") {
      EXPECT_EQ(value(row, "accuracy"), 1.0);
      EXPECT_EQ(value(row, "recall"), 1.0);
    }
    if (row.at("method") == "sphere-obb") {
      EXPECT_EQ(value(row, "recall"), 1.0);
    }
    // The witness verdict: every reported pair is a confirmed contact.
    const std::string& m = row.at("method");
    if (m == "maco" || m == "aco" || m == "pso" || m == "ga") {
      EXPECT_EQ(value(row, "precision"), 1.0) << m;
      EXPECT_GT(value(row, "mean_pair_evaluations"), 0) << m;
    }
    EXPECT_GT(value(row, "time_vs_exact"), 0);
  }
  for (const std::string& m : methods) EXPECT_GT(seen[m], 0) << m;
}

void check_fig4_fig5(const fs::path& out) {
  // sphere-obb + exact + (aco, maco) x (witness, paper centroid) x 3 budgets
  check_scene_csv(
      out / "fig4.csv", 14,
      {"sphere-obb", "aco", "maco", "aco (paper centroid)", "maco (paper centroid)", "exact"});
  if (paper::learned_available()) {  // + box-dnn and box-lstm, one row each
    check_scene_csv(out / "fig5.csv", 15,
                    {"maco", "maco (paper centroid)", "pso", "ga", "box-dnn", "box-lstm", "exact"});
  } else {  // 4 series x 3 budgets + exact
    check_scene_csv(out / "fig5.csv", 13, {"maco", "maco (paper centroid)", "pso", "ga", "exact"});
  }
}

void check_report(const fs::path& out) {
  const std::string report = read_file(out / "report.md");
  for (const char* text :
       {"Table 1", "Table 2", "Figure 3", "Figure 4", "Figure 5", "table1.png", "table2.png",
        "fig3.png", "fig4.png", "fig5.png", "paper", "LSTM", "quick",
        // the definitions, quoted; the threads; the new measurements
        "\"Detection Rate 20%\"", "sphere-OBB) could only reach 0.65", "Threads: 2", "--threads 1",
        "ns / evaluation", "aco / maco", "Ablation of MACO's switches",
        "without (1) adaptive exponents", "maco (paper centroid)", "× exact's time", "1000 × 1000",
        "2000 × 2000"}) {
    EXPECT_NE(report.find(text), std::string::npos) << text;
  }
  // The learned baselines' training is reported apart from their detection.
  EXPECT_EQ(report.find("| box-dnn | 2 × 60 |") != std::string::npos, paper::learned_available());
  const std::string table1 = read_file(out / "table1.md");
  EXPECT_NE(table1.find("| 1000 × 1000 |"), std::string::npos);
  EXPECT_NE(table1.find("| 2000 × 2000 |"), std::string::npos);
  EXPECT_EQ(table1.find("asked"), std::string::npos) << "a quick row is not n x n";
  // No stale claims from the method as it was.
  for (const char* stale : {"preliminary detection at the centroid threshold",
                            "report many pairs that do not touch", "507/197"}) {
    EXPECT_EQ(report.find(stale), std::string::npos) << stale;
  }
  const std::string table2 = read_file(out / "table2.md");
  EXPECT_NE(table2.find("A/B"), std::string::npos);
}

// One test runs the quick mode (the expensive part, about half a minute in Release) and checks
// every output; CTest runs each TEST in its own process, so splitting it would repeat the run.
TEST(PaperBench, QuickModeWritesEveryFileWellFormed) {
  const fs::path out = test::fresh_temp_dir("paper_bench_quick");
  PaperBenchOptions options;
  options.quick = true;
  options.out = out;
  options.seed = 1;
  options.threads = 2;
  std::ostringstream log;
  run_paper_bench(options, log);
  {
    SCOPED_TRACE("files");
    check_files(out, log.str());
  }
  {
    SCOPED_TRACE("pngs");
    check_pngs(out);
  }
  {
    SCOPED_TRACE("table1.csv");
    check_table1(out);
  }
  {
    SCOPED_TRACE("table2.csv");
    check_table2(out);
  }
  {
    SCOPED_TRACE("ablation.csv");
    check_ablation(out);
  }
  {
    SCOPED_TRACE("fig3.csv");
    check_fig3(out);
  }
  {
    SCOPED_TRACE("fig4.csv, fig5.csv");
    check_fig4_fig5(out);
  }
  {
    SCOPED_TRACE("report.md");
    check_report(out);
  }
}

TEST(PaperBench, MissingGnuplotIsAClearErrorBeforeAnyWork) {
  const fs::path out = test::fresh_temp_dir("paper_bench_no_gnuplot");
  PaperBenchOptions options;
  options.quick = true;
  options.out = out;
  options.gnuplot = (out / "no-such-gnuplot").string();
  std::ostringstream log;
  try {
    run_paper_bench(options, log);
    FAIL() << "expected antcd::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnuplot"), std::string::npos) << what;
    EXPECT_NE(what.find("gnuplot-nox"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(out / "scene")) << "work started before gnuplot was checked";
  EXPECT_FALSE(fs::exists(out / "report.md"));
}

TEST(PaperBench, RejectsBadOptions) {
  std::ostringstream log;
  PaperBenchOptions no_out;
  EXPECT_THROW(run_paper_bench(no_out, log), antcd::ArgumentError);
  PaperBenchOptions no_threads;
  no_threads.out = test::fresh_temp_dir("paper_bench_bad_options");
  no_threads.threads = 0;
  EXPECT_THROW(run_paper_bench(no_threads, log), antcd::ArgumentError);
}

}  // namespace
}  // namespace antcd::experiments
