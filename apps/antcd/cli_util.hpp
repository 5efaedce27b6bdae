// Helpers shared by the antcd commands: argument parsing, output, errors.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace antcd::cli {

/// A bad command-line value or input: main() prints "error: <what>" and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses "tx,ty,tz" or "tx,ty,tz,qw,qx,qy,qz" (quaternion normalised if within 1e-3 of unit).
/// Throws UsageError naming `option` on malformed or non-finite input.
Transform parse_pose(const std::string& text, const std::string& option);

/// "area" (Eq. 3 into Eq. 2, default) or "vertex" (Eqs. 1–2).
CovarianceMethod parse_covariance(const std::string& text);

/// Loads a mesh and builds its hierarchy; errors name the file.
Model load_model(const std::filesystem::path& path, const BuildOptions& options);

/// Option check for --delta and friends: a finite number >= 0. (CLI::NonNegativeNumber lets NaN
/// through, and its message prints the largest double in full.)
CLI::Validator non_negative_finite();

/// Registers the subcommands; each returns its exit code through the callback's `code`.
void add_collide_command(CLI::App& app, int& code);
void add_distance_command(CLI::App& app, int& code);
void add_info_command(CLI::App& app, int& code);
void add_demo_command(CLI::App& app, int& code);
void add_scene_commands(CLI::App& app, int& code);
void add_bench_commands(CLI::App& app, int& code);

}  // namespace antcd::cli
