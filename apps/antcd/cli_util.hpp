// Helpers shared by the antcd commands: argument parsing, output, errors.
#pragma once

#include <antcd/bvh.hpp>
#include <antcd/math.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <streambuf>
#include <string>

namespace antcd {
class Scene;
namespace shared {
struct RunResult;
}
}  // namespace antcd

namespace antcd::cli {

/// A bad command-line value or input: main() prints "error: <what>" and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Wall time since construction, for the query times the commands print.
class Stopwatch {
 public:
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  [[nodiscard]] double ms() const { return 1000 * seconds(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// A point or vector as the JSON array [x, y, z].
inline nlohmann::json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

/// Parses "tx,ty,tz" or "tx,ty,tz,qw,qx,qy,qz" (quaternion normalised if within 1e-3 of unit).
/// Throws UsageError naming `option` on malformed or non-finite input.
Transform parse_pose(const std::string& text, const std::string& option);

/// "area" (Eq. 3 into Eq. 2, default) or "vertex" (Eqs. 1–2).
CovarianceMethod parse_covariance(const std::string& text);

/// While alive, std::cerr prints nothing: a reader inside assimp (the OpenDDL parser of OpenGEX
/// files) writes there directly, past assimp's logger, before antcd reports the file as bad. The
/// CLI's own messages are printed outside such a scope. Main thread only, while no other thread
/// prints.
class QuietStderr {
 public:
  QuietStderr();
  ~QuietStderr();
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  std::streambuf* saved_;
};

/// Loads a mesh (std::cerr quiet meanwhile) and builds its hierarchy; errors name the file. A
/// model file (".antcd", Model::save) is loaded as saved: `options` do not apply to it.
Model load_model(const std::filesystem::path& path, const BuildOptions& options);
/// Prints "warning: SOURCE: N zero-area triangle(s) ignored" on stderr when the model left some
/// out.
void warn_degenerate(const Model& model);

/// Option check for --delta and friends: a finite decimal number >= 0 (no hex).
/// (CLI::NonNegativeNumber lets NaN through, and its message prints the largest double in full.)
CLI::Validator non_negative_finite();
/// The same, > 0.
CLI::Validator positive_finite();
/// A number >= 0 or "inf" (an upper bound that may be absent).
CLI::Validator non_negative_or_infinity();
/// Option check for seeds and counts: decimal digits only, at most 2^64 - 1. (CLI11 reads "-1" as
/// 2^64 - 1 and an overflowing value as the largest one.)
CLI::Validator unsigned_integer();

/// Option check for an output file, run when the command line is parsed (before any long work):
/// not empty; not a directory, device, FIFO or socket; its folder exists and is writable.
CLI::Validator writable_file();
/// Option check for an output folder (created if missing): not empty; an existing folder, or its
/// nearest existing parent is a folder; and that folder is writable.
CLI::Validator writable_folder();

/// Registers the subcommands; each returns its exit code through the callback's `code`.
void add_collide_command(CLI::App& app, int& code);
void add_distance_command(CLI::App& app, int& code);
void add_depth_command(CLI::App& app, int& code);
void add_points_command(CLI::App& app, int& code);
void add_info_command(CLI::App& app, int& code);
void add_demo_command(CLI::App& app, int& code);
void add_scene_commands(CLI::App& app, int& code);
void add_bench_commands(CLI::App& app, int& code);
void add_view_command(CLI::App& app, int& code);
void add_learn_commands(CLI::App& app, int& code);
/// `ccd-queries` and `sweep` (cmd_ccd.cpp): continuous collision detection.
void add_ccd_commands(CLI::App& app, int& code);
/// `self-intersect` and `self-proximity` (cmd_self.cpp): one mesh against itself.
void add_self_commands(CLI::App& app, int& code);
void add_deform_ccd_command(CLI::App& app, int& code);

/// "box-dnn" or "box-lstm": the learned baselines (cmd_learn.cpp), run through run_learned.
bool is_learned_method(const std::string& method);
/// Runs every frame of `scene` with the learned model in `model_path` (its kind must be `method`,
/// its training delta `delta`). Throws UsageError / antcd::Error (model file problems, or antcd
/// built without libtorch).
shared::RunResult run_learned(const Scene& scene, const std::string& scene_name,
                              const std::string& method, const std::string& model_path,
                              double delta,
                              const std::function<void(std::size_t, std::size_t)>& progress);

}  // namespace antcd::cli
