// Shared helpers for the antcd test suite: test-data paths, random poses, brute-force references.
#pragma once

#include <antcd/collide.hpp>
#include <antcd/mesh.hpp>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace antcd::test {

/// Path of a file of Debian's assimp-testmodels package, e.g. "OBJ/spider.obj". Fails the current
/// test (fatal) if the file is absent: the README's test command installs the package.
std::filesystem::path assimp_model(const std::string& relative);

/// A fresh, empty folder under the build tree for the calling test.
std::filesystem::path fresh_temp_dir(const std::string& name);

/// The whole content of the file at `path` (binary-safe; empty when it cannot be read).
std::string read_all(const std::filesystem::path& path);

/// Writes `text` to `path` (binary-safe).
void write_file(const std::filesystem::path& path, const std::string& text);

/// `m` centred on its bounding box's centre and scaled so that the box's longest side is 1.
Mesh unit_size(Mesh m);

/// Uniformly random rotation and a translation uniform in the cube [-extent, extent]^3.
Transform random_pose(std::mt19937_64& rng, Scalar extent);

/// Brute force over all pairs of non-degenerate triangles: the set of (triangle_a, triangle_b)
/// pairs within delta, sorted.
std::vector<std::pair<std::uint32_t, std::uint32_t>> brute_force_pairs(
    const Mesh& a, const Transform& pa, const Mesh& b, const Transform& pb, Scalar delta);

}  // namespace antcd::test
