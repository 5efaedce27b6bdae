#include "cli_util.hpp"

#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

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
  if (std::abs(norm - 1.0) > 1e-3) {
    throw UsageError(option + ": quaternion (w,x,y,z) has length " + std::to_string(norm) +
                     ", expected 1 (within 1e-3)");
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

CLI::Validator finite_at_least_zero(bool zero_allowed) {
  return CLI::Validator(
      [zero_allowed](std::string& text) -> std::string {
        double value = 0;
        std::size_t used = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size() || !std::isfinite(value) || value < 0 ||
            (!zero_allowed && value == 0)) {
          return std::string("expected a finite number ") + (zero_allowed ? ">= 0" : "> 0") +
                 ", got '" + text + "'";
        }
        return {};
      },
      zero_allowed ? "NUMBER >= 0" : "NUMBER > 0");
}

}  // namespace

CLI::Validator non_negative_finite() { return finite_at_least_zero(true); }

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
CLI::Validator positive_finite() { return finite_at_least_zero(false); }

}  // namespace antcd::cli
