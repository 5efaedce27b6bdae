// Labelled samples of generated scenes for the learned baselines (see dataset.hpp).
#include <antcd/rng.hpp>
#include <antcd_learned/dataset.hpp>
#include <antcd_learned/meshes.hpp>

#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "shared/production_line.hpp"

namespace antcd::learned {
namespace {

namespace fs = std::filesystem;
namespace gen = antcd::shared;

/// Seed of training scene k. The top bit is set, so a training scene never has the small seeds
/// scenes are evaluated with (antcd scene generate and bench paper default to 1).
std::uint64_t scene_seed(std::uint64_t seed, std::size_t k) {
  return mix_seed(mix_seed(seed) ^ (0x6C6561726E6564ULL + k)) | (std::uint64_t{1} << 63);
}

/// A temporary folder, removed with everything in it when the object goes.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "antcd-learn-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw Error(pattern + ": cannot create a temporary folder: " + std::strerror(errno));
    }
    path_ = pattern;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

enum class Layout { ProductionLine, ShapePairs, MeshPairs };

struct SceneSpec {
  Layout layout = Layout::ProductionLine;
  std::size_t objects = 0;
  std::size_t vertices = 0;
  std::uint64_t seed = 0;
};

/// A mesh-pair training scene: this many of the training meshes, and two generated shapes, each
/// pair kMeshRounds times (with other motions).
constexpr std::size_t kMeshesPerScene = 5;
constexpr std::size_t kMeshRounds = 8;

SceneSpec scene_spec(const TrainingSetOptions& o, std::size_t k) {
  SceneSpec s;
  s.seed = scene_seed(o.seed, k);
  s.layout = k % 3 == 2                            ? Layout::ShapePairs
             : k % 3 == 1 && !o.mesh_files.empty() ? Layout::MeshPairs
                                                   : Layout::ProductionLine;
  const std::uint64_t r = mix_seed(s.seed);
  const std::size_t span = o.max_objects - o.min_objects + 1;
  s.objects = s.layout == Layout::ShapePairs ? 16 + 2 * (r % 8)
                                             : o.min_objects + static_cast<std::size_t>(r % span);
  if (s.layout == Layout::MeshPairs) {
    s.objects = 2 * kMeshRounds * (std::min(kMeshesPerScene, o.mesh_files.size()) + 2);
  }
  s.vertices = 250 + static_cast<std::size_t>((r >> 20) % 1000);
  return s;
}

/// Generated shapes for the shape-pair layout, written as OBJ files into `dir`: tori, spheres,
/// boxes, cylinders and two compound parts, sized and tessellated from the seed.
std::vector<fs::path> write_shapes(const fs::path& dir, std::uint64_t seed) {
  std::uint64_t state = seed;
  const auto uniform = [&](double lo, double hi) {
    state = mix_seed(state);
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  const auto segments = [&](int lo, int hi) { return static_cast<int>(uniform(lo, hi + 1)); };
  std::vector<Mesh> meshes;
  meshes.push_back(
      make_torus(uniform(0.5, 1.0), uniform(0.08, 0.3), segments(16, 48), segments(8, 20)));
  meshes.push_back(make_sphere(uniform(0.3, 1.0), segments(10, 32), segments(6, 16)));
  meshes.push_back(
      make_box(Vec3(uniform(0.1, 1.0), uniform(0.1, 1.0), uniform(0.05, 0.6)), segments(1, 4)));
  meshes.push_back(
      make_cylinder(uniform(0.1, 0.5), uniform(0.5, 2.0), segments(8, 32), segments(1, 4)));
  meshes.push_back(
      merge({make_box(Vec3(0.8, 0.1, 0.1), 2),
             transformed(make_cylinder(0.15, 0.9, 16),
                         Transform::from_axis_angle(Vec3::UnitX(), 1.5707963, Vec3::Zero()))}));
  meshes.push_back(
      merge({make_torus(0.6, 0.1, 32, 10),
             transformed(make_sphere(0.25, 16, 8),
                         Transform::from_axis_angle(Vec3::UnitZ(), 0.0, Vec3(0.6, 0.0, 0.0)))}));
  // A different order per scene, so that different shapes meet.
  for (std::size_t i = meshes.size(); i > 1; --i) {
    std::swap(meshes[i - 1], meshes[static_cast<std::size_t>(uniform(0, static_cast<double>(i)))]);
  }
  std::vector<fs::path> files;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    files.push_back(dir / ("shape_" + std::to_string(i) + ".obj"));
    save_obj(meshes[i], files.back());
  }
  return files;
}

/// The training meshes of a mesh-pair scene: kMeshesPerScene of them (all when fewer), drawn
/// from `seed`.
std::vector<fs::path> scene_meshes(const std::vector<fs::path>& meshes, std::uint64_t seed) {
  std::vector<fs::path> order = meshes;
  std::uint64_t state = mix_seed(seed ^ 0x4D45534845ULL);
  for (std::size_t i = order.size(); i > 1; --i) {
    state = mix_seed(state);
    std::swap(order[i - 1], order[state % i]);
  }
  order.resize(std::min(order.size(), kMeshesPerScene));
  return order;
}

}  // namespace

std::size_t Dataset::positives() const {
  return static_cast<std::size_t>(std::count(labels.begin(), labels.end(), std::uint8_t{1}));
}

void Dataset::append(const Dataset& other) {
  if (other.size() == 0) return;
  if (size() == 0 && features.empty()) {
    window = other.window;
    delta = other.delta;
  }
  if (other.window != window || other.delta != delta) {
    throw Error("cannot join samples of different windows or thresholds");
  }
  features.insert(features.end(), other.features.begin(), other.features.end());
  labels.insert(labels.end(), other.labels.begin(), other.labels.end());
}

Dataset Dataset::last_frame() const {
  Dataset out;
  out.window = 1;
  out.delta = delta;
  out.labels = labels;
  out.features.reserve(size() * kFeatureCount);
  const std::size_t stride = sample_floats();
  for (std::size_t i = 0; i < size(); ++i) {
    const auto first =
        features.begin() + static_cast<std::ptrdiff_t>((i + 1) * stride - kFeatureCount);
    out.features.insert(out.features.end(), first,
                        first + static_cast<std::ptrdiff_t>(kFeatureCount));
  }
  return out;
}

void Dataset::zero_features(std::size_t first, std::size_t count) {
  if (first > kFeatureCount || count > kFeatureCount - first) {
    throw std::out_of_range("features " + std::to_string(first) + " + " + std::to_string(count) +
                            " are past the vector's " + std::to_string(kFeatureCount));
  }
  for (std::size_t at = 0; at < features.size(); at += kFeatureCount) {
    std::fill_n(features.begin() + static_cast<std::ptrdiff_t>(at + first), count, 0.0F);
  }
}

std::size_t PairHistory::KeyHash::operator()(const Key& k) const {
  return static_cast<std::size_t>(mix_seed((static_cast<std::uint64_t>(k.i) << 32 | k.j) ^
                                           mix_seed(static_cast<std::uint64_t>(k.frame))));
}

PairHistory::PairHistory(const Scene& scene, std::size_t window, Scalar delta)
    : scene_(&scene), window_(window), delta_(delta) {
  if (window < 1) throw std::invalid_argument("the feature window must be at least 1 frame");
}

void PairHistory::window_features(std::uint32_t i, std::uint32_t j, std::size_t frame, float* out) {
  const auto& objects = scene_->description().objects;
  for (std::size_t w = 0; w < window_; ++w) {
    const std::size_t back = window_ - 1 - w;
    const std::size_t f = frame >= back ? frame - back : 0;
    const Key key{i, j, f};
    auto it = cache_.find(key);
    if (it == cache_.end()) {
      it = cache_
               .emplace(key, pair_features(scene_->model_of(i), objects[i].pose(f),
                                           scene_->model_of(j), objects[j].pose(f), delta_))
               .first;
    }
    std::copy(it->second.begin(), it->second.end(), out + w * kFeatureCount);
  }
}

void PairHistory::forget_before(std::size_t frame) {
  const std::size_t keep = frame >= window_ - 1 ? frame - (window_ - 1) : 0;
  std::erase_if(cache_, [&](const auto& entry) { return entry.first.frame < keep; });
}

Dataset scene_samples(const Scene& scene, std::size_t first, std::size_t last, std::size_t window,
                      Scalar delta) {
  if (last > scene.description().frames) {
    throw std::out_of_range("frames up to " + std::to_string(last) + " asked, the scene has " +
                            std::to_string(scene.description().frames));
  }
  Dataset out;
  out.window = window;
  out.delta = delta;
  PairHistory history(scene, window, delta);
  SceneQuery exact;
  exact.method = Method::Exact;
  exact.delta = delta;
  std::vector<float> buf(window * kFeatureCount);
  for (std::size_t f = first; f < last; ++f) {
    const FrameResult r = scene.run_frame(f, exact);
    for (const auto& [i, j] : r.candidates) {
      history.window_features(i, j, f, buf.data());
      out.features.insert(out.features.end(), buf.begin(), buf.end());
      out.labels.push_back(
          std::binary_search(r.pairs.begin(), r.pairs.end(), std::make_pair(i, j)) ? 1 : 0);
    }
    history.forget_before(f + 1);
  }
  return out;
}

std::string training_scene_label(const TrainingSetOptions& options, std::size_t k) {
  const SceneSpec s = scene_spec(options, k);
  if (s.layout == Layout::MeshPairs) {
    return "mesh pairs (" + mesh_names(scene_meshes(options.mesh_files, s.seed)) +
           " and 2 generated shapes), " + std::to_string(s.objects) + " objects, seed " +
           std::to_string(s.seed);
  }
  return (s.layout == Layout::ProductionLine ? "production line, " : "shape pairs, ") +
         std::to_string(s.objects) + " objects" +
         (s.layout == Layout::ProductionLine ? ", ~" + std::to_string(s.vertices) + " vertices"
                                             : std::string()) +
         ", seed " + std::to_string(s.seed);
}

Dataset training_set(const TrainingSetOptions& options,
                     const std::function<void(const std::string&)>& log) {
  if (options.scenes < 1) throw std::invalid_argument("--scenes must be at least 1");
  if (options.frames < 1) throw std::invalid_argument("--frames must be at least 1");
  if (options.min_objects < gen::kMinObjects || options.max_objects < options.min_objects) {
    throw std::invalid_argument("training scenes need a valid object range");
  }
  const TempDir tmp;
  Dataset all;
  all.window = options.window;
  all.delta = options.delta;
  for (std::size_t k = 0; k < options.scenes; ++k) {
    const SceneSpec spec = scene_spec(options, k);
    gen::ProductionLineOptions line;
    line.objects = spec.objects;
    line.vertices = spec.vertices;
    line.frames = options.frames;
    line.seed = spec.seed;
    const fs::path dir = tmp.path() / ("scene_" + std::to_string(k));
    if (spec.layout == Layout::ShapePairs) line.mesh_files = write_shapes(tmp.path(), spec.seed);
    if (spec.layout == Layout::MeshPairs) {
      std::vector<fs::path> files = scene_meshes(options.mesh_files, spec.seed);
      const std::vector<fs::path> shapes = write_shapes(tmp.path(), spec.seed);
      files.insert(files.end(), shapes.begin(), shapes.begin() + 2);
      line.mesh_files = pairing_order(files);
    }
    const fs::path file = gen::write_scene(gen::generate_production_line(line), dir);
    const Scene scene(load_scene(file));
    Dataset d = scene_samples(scene, 0, options.frames, options.window, options.delta);
    if (log) {
      log("  scene " + std::to_string(k + 1) + "/" + std::to_string(options.scenes) + " (" +
          training_scene_label(options, k) + "): " + std::to_string(d.size()) + " samples, " +
          std::to_string(d.positives()) + " colliding");
    }
    all.append(d);
  }
  return all;
}

}  // namespace antcd::learned
