#include "cli_util.hpp"

#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/tolerances.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

#include <unistd.h>

namespace antcd::cli {

Transform parse_pose(const std::string& text, const std::string& option) {
  std::vector<Scalar> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
    if (used == 0 || used != item.size()) {
      throw UsageError(option + ": '" + item +
                       "' is not a number (expected tx,ty,tz[,qw,qx,qy,qz])");
    }
    if (!std::isfinite(v)) throw UsageError(option + ": non-finite value '" + item + "'");
    values.push_back(v);
  }
  if (values.size() != 3 && values.size() != 7) {
    throw UsageError(option + ": expected 3 numbers (tx,ty,tz) or 7 (tx,ty,tz,qw,qx,qy,qz), got " +
                     std::to_string(values.size()));
  }
  const Vec3 t(values[0], values[1], values[2]);
  if (values.size() == 3) return Transform{Mat3::Identity(), t};
  const Scalar norm = std::sqrt(values[3] * values[3] + values[4] * values[4] +
                                values[5] * values[5] + values[6] * values[6]);
  if (!(std::abs(norm - 1.0) <= tolerance::kUnitQuaternion)) {
    throw UsageError(option + ": quaternion (w,x,y,z) has length " + std::to_string(norm) +
                     ", expected 1 (within " + number_text(tolerance::kUnitQuaternion) + ")");
  }
  return Transform::from_quaternion(t, values[3], values[4], values[5], values[6]);
}

CovarianceMethod parse_covariance(const std::string& text) {
  if (text == "area") return CovarianceMethod::AreaWeightedCentroid;
  if (text == "vertex") return CovarianceMethod::VertexMean;
  throw UsageError("--covariance: expected 'area' or 'vertex', got '" + text + "'");
}

QuietStderr::QuietStderr() : saved_(std::cerr.rdbuf(nullptr)) {}
QuietStderr::~QuietStderr() { std::cerr.rdbuf(saved_); }  // also clears the stream's bad state

Model load_model(const std::filesystem::path& path, const BuildOptions& options) {
  // A saved model keeps its own hierarchy (and the options it was built with).
  if (is_model_path(path)) return Model::load(path);
  Mesh mesh;
  {
    const QuietStderr quiet;
    mesh = load_mesh(path);
  }
  return Model(std::move(mesh), options, path.string());
}

void warn_degenerate(const Model& model) {
  if (model.stats().degenerate_triangles > 0) {
    std::cerr << "warning: " << model.source() << ": " << model.stats().degenerate_triangles
              << " zero-area triangle(s) ignored\n";
  }
}

namespace {

/// A decimal number >= 0 (> 0 unless zero_allowed), finite unless infinity_allowed ("inf").
CLI::Validator number_at_least_zero(bool zero_allowed, bool infinity_allowed) {
  return CLI::Validator(
      [zero_allowed, infinity_allowed](std::string& text) -> std::string {
        double value = 0;
        std::size_t used = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        // std::stod also reads hexadecimal ("0x10" is 16): decimal only.
        const bool hex = text.find_first_of("xX") != std::string::npos;
        const bool infinite = std::isinf(value) && !(infinity_allowed && value > 0);
        if (used == 0 || used != text.size() || hex || std::isnan(value) || infinite || value < 0 ||
            (!zero_allowed && value == 0)) {
          return std::string("expected a ") + (infinity_allowed ? "" : "finite ") + "number " +
                 (zero_allowed ? ">= 0" : "> 0") + (infinity_allowed ? " or inf" : "") + ", got '" +
                 text + "'";
        }
        return {};
      },
      std::string(zero_allowed ? "NUMBER >= 0" : "NUMBER > 0") +
          (infinity_allowed ? " or inf" : ""));
}

}  // namespace

CLI::Validator non_negative_finite() { return number_at_least_zero(true, false); }
CLI::Validator non_negative_or_infinity() { return number_at_least_zero(true, true); }

CLI::Validator unsigned_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        // 20 digits may still exceed 2^64 - 1 = 18446744073709551615 (string order = value order).
        if (!digits || (text.size() == 20 && text > "18446744073709551615")) {
          return "expected an integer 0 .. 18446744073709551615, got '" + text + "'";
        }
        return {};
      },
      "INTEGER >= 0");
}
CLI::Validator positive_finite() { return number_at_least_zero(false, false); }

namespace {

/// "" when `folder` (a path that exists) is a writable folder, else why not.
std::string writable_folder_problem(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    return "'" + folder.string() + "' is not a folder";
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    return "cannot write in '" + folder.string() + "': " + std::strerror(errno);
  }
  return {};
}

}  // namespace

CLI::Validator writable_file() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty()) return "expected a file name, got ''";
        const std::filesystem::path path(text);
        std::error_code ec;
        const auto status = std::filesystem::status(path, ec);
        if (std::filesystem::is_directory(status)) return "'" + text + "' is a folder";
        if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
          return "'" + text + "' is not a regular file (a device, FIFO or socket is not replaced)";
        }
        if (path.filename().empty()) return "'" + text + "' names no file";
        const std::filesystem::path folder =
            path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
        if (!std::filesystem::exists(folder, ec)) {
          return "cannot write '" + text + "': folder '" + folder.string() + "' does not exist";
        }
        const std::string problem = writable_folder_problem(folder);
        return problem.empty() ? problem : "cannot write '" + text + "': " + problem;
      },
      "FILE");
}

CLI::Validator writable_folder() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.empty()) return "expected a folder name, got ''";
        // The folder itself, or the nearest parent that exists (the rest is created).
        std::filesystem::path folder = std::filesystem::absolute(text);
        std::error_code ec;
        while (!std::filesystem::exists(folder, ec) && folder.has_relative_path()) {
          folder = folder.parent_path();
        }
        const std::string problem = writable_folder_problem(folder);
        return problem.empty() || folder == std::filesystem::absolute(text)
                   ? problem
                   : "cannot create '" + text + "': " + problem;
      },
      "DIR");
}

}  // namespace antcd::cli
