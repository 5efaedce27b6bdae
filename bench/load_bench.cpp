// bench/load_bench.cpp — loading a 5-million-triangle OBJ, OFF, ASCII PLY and binary STL:
// antcd::load_mesh (double precision: tinyobjloader for OBJ, assimp plus re-read coordinates for
// OFF and PLY, its own reader for binary STL) against assimp's import of the same file (single
// precision, the reader antcd used before), in one binary and one run: the ratio per format is the
// figure. load_and_build/stl is issue 12's target: the binary STL loaded and its Model built
// (<= 10 s, <= 1.5 GB peak), with the peak resident memory of that step as a counter (peak_mib,
// Linux: the process's high-water mark is reset before the step and read after it).
//
// The files are generated at start-up into a fresh temporary folder and removed at exit: a height
// field of 2000 x 1250 cells, two triangles each (5,000,000 triangles on 2,503,251 vertices),
// coordinates printed as the shortest text that reads back to their double (none is a float
// value). assimp_import runs assimp's reader with the post-processing antcd's assimp path used
// (triangulate, join identical vertices): antcd's conversion to a Mesh is not in it, so it is
// the lower bound of that path. Each benchmark reports `triangles`.
//
// Model files (issues 27, 41): model_build/<mesh> builds the Model of a mesh (in memory),
// model_load/<mesh> loads the same model from its .antcd file (Model::load: read, checksum,
// validation, no build; the file is in the page cache after its first read),
// model_from_bytes/<mesh> from bytes in memory (what unpickling does). Meshes: torus_5m,
// make_torus(1, 0.3, 2500, 1000), 5,000,000 triangles, one iteration; torus_100k,
// make_torus(1, 0.3, 250, 200), 100,000; suzanne, assimp's SuzanneSubdiv_252.blend, 251,904
// (skipped when assimp-testmodels is not installed). The load-vs-build ratio is model_build /
// model_load. Run them alone with --benchmark_filter='model_'. Instruction counts (a shared
// machine's wall clock is no figure): each measured step is one out-of-line function, so that
// with one thread (oneTBB follows the affinity mask) and one iteration
//   taskset -c 0 valgrind --tool=callgrind --toggle-collect='*measured_build*'
//       build/bench/antcd_bench_load --benchmark_filter='model_build/torus_100k/'
//       --benchmark_min_time=0.000001
// counts the build alone (measured_load, measured_from_bytes likewise).
// Medians: --benchmark_repetitions=3 --benchmark_report_aggregates_only=true.
#include <antcd/bvh.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <benchmark/benchmark.h>
#include <assimp/Importer.hpp>

#include <unistd.h>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kCellsX = 2000;
constexpr std::uint32_t kCellsY = 1250;

void append_number(std::string& out, double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  if (ec != std::errc{}) throw std::runtime_error("to_chars failed");
  out.append(buffer, end);
}

enum class Format { Obj, Off, Ply, Stl };

/// The generated files (the same grid as OBJ, OFF and ASCII PLY), written once, removed at exit.
class GridFiles {
 public:
  GridFiles() {
    dir_ = fs::temp_directory_path() / ("antcd_load_bench_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::uint32_t vertices = (kCellsX + 1) * (kCellsY + 1);
    const std::uint32_t faces = 2 * kCellsX * kCellsY;
    write(Format::Obj, "grid.obj", "", "v ", "f ", 1);
    write(Format::Off, "grid.off",
          "OFF\n" + std::to_string(vertices) + ' ' + std::to_string(faces) + " 0\n", "", "3 ", 0);
    write(Format::Ply, "grid.ply",
          "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
              "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
              std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n",
          "", "3 ", 0);
    write_binary_stl("grid.stl");
  }
  ~GridFiles() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  GridFiles(const GridFiles&) = delete;
  GridFiles& operator=(const GridFiles&) = delete;
  [[nodiscard]] const fs::path& path(Format f) const { return paths_[static_cast<int>(f)]; }

 private:
  void write(Format format, const char* name, const std::string& header, const char* vertex,
             const char* face, std::uint32_t base) {
    fs::path& path = paths_[static_cast<int>(format)];
    path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    std::string chunk = header;
    for (std::uint32_t i = 0; i <= kCellsX; ++i) {
      for (std::uint32_t j = 0; j <= kCellsY; ++j) {
        chunk += vertex;
        append_number(chunk, i * 0.1 + 1e-7);
        chunk += ' ';
        append_number(chunk, j * 0.1 - 123456.789012345);
        chunk += ' ';
        append_number(chunk, 0.3 * ((i * 7 + j * 13) % 11) / 7.0);
        chunk += '\n';
      }
      out.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      chunk.clear();
    }
    auto index = [&](std::uint32_t i, std::uint32_t j) { return i * (kCellsY + 1) + j + base; };
    for (std::uint32_t i = 0; i < kCellsX; ++i) {
      for (std::uint32_t j = 0; j < kCellsY; ++j) {
        const std::uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                            d = index(i, j + 1);
        chunk += face + std::to_string(a) + ' ' + std::to_string(b) + ' ' + std::to_string(c) +
                 '\n' + face + std::to_string(a) + ' ' + std::to_string(c) + ' ' +
                 std::to_string(d) + '\n';
      }
      out.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      chunk.clear();
    }
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }

  // The same grid as binary STL: each triangle's corners as floats, the normal left zero.
  void write_binary_stl(const char* name) {
    fs::path& path = paths_[static_cast<int>(Format::Stl)];
    path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    std::string chunk(80, '\0');
    const std::uint32_t faces = 2 * kCellsX * kCellsY;
    append_bytes(chunk, &faces, 4);
    auto corner = [&](std::uint32_t i, std::uint32_t j) {
      const float xyz[3] = {static_cast<float>(i * 0.1 + 1e-7),
                            static_cast<float>(j * 0.1 - 123456.789012345),
                            static_cast<float>(0.3 * ((i * 7 + j * 13) % 11) / 7.0)};
      append_bytes(chunk, xyz, sizeof xyz);
    };
    const char zero[14] = {};
    for (std::uint32_t i = 0; i < kCellsX; ++i) {
      for (std::uint32_t j = 0; j < kCellsY; ++j) {
        append_bytes(chunk, zero, 12);
        corner(i, j), corner(i + 1, j), corner(i + 1, j + 1);
        append_bytes(chunk, zero, 2);
        append_bytes(chunk, zero, 12);
        corner(i, j), corner(i + 1, j + 1), corner(i, j + 1);
        append_bytes(chunk, zero, 2);
      }
      out.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
      chunk.clear();
    }
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }

  static void append_bytes(std::string& out, const void* data, std::size_t n) {
    out.append(static_cast<const char*>(data), n);
  }

  fs::path dir_;
  fs::path paths_[4];
};

const GridFiles& grid() {
  static const GridFiles files;
  return files;
}

void load_mesh_double(benchmark::State& state, Format format) {
  const fs::path& path = grid().path(format);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const antcd::Mesh mesh = antcd::load_mesh(path);
    triangles = mesh.triangles.size();
    benchmark::DoNotOptimize(mesh.vertices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  if (triangles != 2ULL * kCellsX * kCellsY) state.SkipWithError("wrong triangle count");
}

// Linux: VmHWM (peak resident memory) of this process in MiB, and its reset; -1 when unavailable.
double peak_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return -1;
}

void reset_peak() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

void load_and_build(benchmark::State& state, Format format) {
  const fs::path& path = grid().path(format);
  std::size_t triangles = 0;
  double peak = 0;
  double bytes_per_triangle = 0;
  for (auto _ : state) {
    reset_peak();
    const antcd::Model model(antcd::load_mesh(path));
    peak = std::max(peak, peak_mib());
    triangles = model.mesh().triangles.size();
    bytes_per_triangle = static_cast<double>(model.stats().memory_bytes) / triangles;
    benchmark::DoNotOptimize(model.nodes().data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["peak_mib"] = peak;
  state.counters["model_B_per_triangle"] = bytes_per_triangle;
}

void assimp_import(benchmark::State& state, Format format) {
  const fs::path& path = grid().path(format);
  std::size_t triangles = 0;
  for (auto _ : state) {
    Assimp::Importer importer;
    const aiScene* scene =
        importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_SortByPType |
                                             aiProcess_JoinIdenticalVertices);
    if (scene == nullptr) {
      state.SkipWithError(importer.GetErrorString());
      return;
    }
    triangles = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) triangles += scene->mMeshes[m]->mNumFaces;
    benchmark::DoNotOptimize(scene);
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

/// A mesh of the model benchmarks, its Model and that model saved, made once, removed at exit.
class SavedModel {
 public:
  SavedModel(antcd::Mesh mesh, const std::string& name) : mesh_(std::move(mesh)), model_(mesh_) {
    dir_ = fs::temp_directory_path() /
           ("antcd_model_bench_" + name + "_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    path_ = dir_ / (name + ".antcd");
    model_.save(path_);
    bytes_ = model_.to_bytes();
  }
  ~SavedModel() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  SavedModel(const SavedModel&) = delete;
  SavedModel& operator=(const SavedModel&) = delete;
  [[nodiscard]] const antcd::Mesh& mesh() const { return mesh_; }
  [[nodiscard]] const fs::path& path() const { return path_; }
  [[nodiscard]] const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  antcd::Mesh mesh_;
  antcd::Model model_;
  fs::path dir_;
  fs::path path_;
  std::vector<std::uint8_t> bytes_;
};

enum class Saved { Torus5M, Torus100k, Suzanne };

constexpr const char* kSuzanne = "/usr/share/assimp/models/BLEND/SuzanneSubdiv_252.blend";

/// The saved model of `which`, made on first use (nullptr: Suzanne's file is not installed).
const SavedModel* saved(Saved which) {
  switch (which) {
    case Saved::Torus5M: {
      static const SavedModel torus(antcd::make_torus(1.0, 0.3, 2500, 1000), "torus_5m");
      return &torus;
    }
    case Saved::Torus100k: {
      static const SavedModel torus(antcd::make_torus(1.0, 0.3, 250, 200), "torus_100k");
      return &torus;
    }
    case Saved::Suzanne:
      break;
  }
  if (!fs::exists(kSuzanne)) return nullptr;
  static const SavedModel suzanne(antcd::load_mesh(kSuzanne), "suzanne");
  return &suzanne;
}

// The measured steps alone, out of line, for callgrind's --toggle-collect (see the top).
[[gnu::noinline]] std::size_t measured_build(antcd::Mesh mesh) {
  const antcd::Model model(std::move(mesh));
  benchmark::DoNotOptimize(model.nodes().data());
  return model.mesh().triangles.size();
}

[[gnu::noinline]] std::size_t measured_load(const fs::path& path) {
  const antcd::Model model = antcd::Model::load(path);
  benchmark::DoNotOptimize(model.nodes().data());
  return model.mesh().triangles.size();
}

[[gnu::noinline]] std::size_t measured_from_bytes(const std::vector<std::uint8_t>& bytes) {
  const antcd::Model model = antcd::Model::from_bytes(bytes);
  benchmark::DoNotOptimize(model.nodes().data());
  return model.mesh().triangles.size();
}

void model_build(benchmark::State& state, Saved which) {
  const SavedModel* m = saved(which);
  if (m == nullptr) {
    state.SkipWithError("the assimp test models are not installed");
    return;
  }
  std::size_t triangles = 0;
  for (auto _ : state) {
    state.PauseTiming();
    antcd::Mesh mesh = m->mesh();
    state.ResumeTiming();
    triangles = measured_build(std::move(mesh));
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

void model_load(benchmark::State& state, Saved which) {
  const SavedModel* m = saved(which);
  if (m == nullptr) {
    state.SkipWithError("the assimp test models are not installed");
    return;
  }
  std::size_t triangles = 0;
  for (auto _ : state) triangles = measured_load(m->path());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["file_MiB"] = static_cast<double>(m->bytes().size()) / (1 << 20);
}

void model_from_bytes(benchmark::State& state, Saved which) {
  const SavedModel* m = saved(which);
  if (m == nullptr) {
    state.SkipWithError("the assimp test models are not installed");
    return;
  }
  std::size_t triangles = 0;
  for (auto _ : state) triangles = measured_from_bytes(m->bytes());
  state.counters["triangles"] = static_cast<double>(triangles);
}

BENCHMARK_CAPTURE(model_build, torus_5m, Saved::Torus5M)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_load, torus_5m, Saved::Torus5M)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_from_bytes, torus_5m, Saved::Torus5M)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_build, torus_100k, Saved::Torus100k)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_load, torus_100k, Saved::Torus100k)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_from_bytes, torus_100k, Saved::Torus100k)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_build, suzanne, Saved::Suzanne)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_load, suzanne, Saved::Suzanne)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(model_from_bytes, suzanne, Saved::Suzanne)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(load_mesh_double, obj, Format::Obj)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(assimp_import, obj, Format::Obj)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(load_mesh_double, off, Format::Off)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(assimp_import, off, Format::Off)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(load_mesh_double, ply, Format::Ply)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(assimp_import, ply, Format::Ply)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(load_mesh_double, stl, Format::Stl)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(assimp_import, stl, Format::Stl)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(load_and_build, stl, Format::Stl)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
