// The scene engine: shared models in one World (its incremental broad phase), and the narrow
// phase of the chosen method on each surviving pair.
#include <antcd/collide.hpp>
#include <antcd/random.hpp>
#include <antcd/scene.hpp>
#include <antcd/world.hpp>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>

#include "random/detect.hpp"
#include "scene/pair_query.hpp"

namespace antcd {

struct Scene::Broad {
  std::mutex mutex;
  World world;
  std::vector<ObjectId> ids;  ///< per object index; ids[i].slot == i
};

Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene::Scene(SceneDescription description, const BuildOptions& options)
    : Scene(std::move(description), [](const SceneObject& o) { return load_mesh(o.mesh); },
            options) {}

Scene::Scene(SceneDescription description,
             const std::function<Mesh(const SceneObject&)>& mesh_source,
             const BuildOptions& options)
    : description_(std::move(description)), broad_(std::make_unique<Broad>()) {
  const auto start = std::chrono::steady_clock::now();
  std::map<std::pair<std::string, Scalar>, std::size_t> built;
  model_index_.reserve(description_.objects.size());
  for (const SceneObject& o : description_.objects) {
    const auto key = std::make_pair(o.mesh.lexically_normal().string(), o.scale);
    auto it = built.find(key);
    if (it == built.end()) {
      Mesh mesh;
      try {
        mesh = mesh_source(o);
      } catch (const MeshError& e) {
        throw SceneError("object '" + o.name + "': " + e.what());
      }
      if (o.scale != 1) {
        for (Vec3& v : mesh.vertices) v *= o.scale;
      }
      models_.push_back(std::make_shared<const Model>(std::move(mesh), options, o.mesh.string()));
      feature_radius_.push_back(feature_radius(*models_.back()));
      it = built.emplace(key, models_.size() - 1).first;
    }
    model_index_.push_back(it->second);
  }
  for (std::size_t i = 0; i < description_.objects.size(); ++i) {
    const SceneObject& o = description_.objects[i];
    broad_->ids.push_back(broad_->world.add(models_[model_index_[i]], o.pose(0), {o.name}));
  }
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> Scene::broad_phase(std::size_t frame,
                                                                      Scalar delta) const {
  if (frame >= description_.frames) {
    throw ArgumentError("frame " + std::to_string(frame) + " out of range (scene has " +
                        std::to_string(description_.frames) + " frames)");
  }
  if (!(delta >= 0) || !std::isfinite(delta)) throw ArgumentError("delta must be finite and >= 0");
  // The frame's poses into the World, then its candidate pairs: one caller at a time (the World's
  // mutations must not overlap its queries).
  const std::size_t n = description_.objects.size();
  std::vector<Transform> poses(n);
  for (std::size_t i = 0; i < n; ++i) poses[i] = description_.objects[i].pose(frame);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  const std::lock_guard<std::mutex> lock(broad_->mutex);
  broad_->world.set_poses(broad_->ids, poses);
  const std::vector<ObjectPair> pairs = broad_->world.candidate_pairs(delta);
  candidates.reserve(pairs.size());
  for (const ObjectPair& p : pairs) candidates.emplace_back(p.a.slot, p.b.slot);
  return candidates;
}

FrameResult Scene::run_frame(std::size_t frame, const SceneQuery& query,
                             SceneMemory* memory) const {
  if (frame >= description_.frames) {
    throw ArgumentError("frame " + std::to_string(frame) + " out of range (scene has " +
                        std::to_string(description_.frames) + " frames)");
  }
  if (!(query.delta >= 0) || !std::isfinite(query.delta)) {
    throw ArgumentError("delta must be finite and >= 0");
  }
  if (query.threads < 1) throw ArgumentError("threads must be at least 1");
  if (query.volume && query.method != Method::Exact) {
    throw ArgumentError("volume queries are for the exact method, not " +
                        std::string(method_name(query.method)));
  }
  if (query.method != Method::Exact && query.method != Method::SphereObb) {
    DetectRequest request = query.random;
    request.delta = query.delta;
    request.search.method = query.method;
    detail::validate_detect(request, "scene query");
    if (!(query.frame_seconds >= 0) || !std::isfinite(query.frame_seconds)) {
      throw ArgumentError("frame seconds must be finite and >= 0");
    }
  }
  const auto start = std::chrono::steady_clock::now();
  FrameResult result;
  result.frame = frame;
  const std::size_t n = description_.objects.size();

  // Poses of the frame, then the World's broad phase inside this query's arena, so that
  // threads = 1 keeps the whole frame on the calling thread.
  std::vector<Transform> poses(n);
  for (std::size_t i = 0; i < n; ++i) poses[i] = description_.objects[i].pose(frame);
  tbb::task_arena arena(query.threads);
  result.candidates = arena.execute([&] { return broad_phase(frame, query.delta); });

  // Narrow phase, one independent task per candidate pair.
  const std::size_t m = result.candidates.size();
  std::vector<detail::PairOutcome> outcomes(m);
  const detail::ForEach for_each = [&](std::size_t count,
                                       const std::function<void(std::size_t)>& body) {
    if (query.threads == 1 || count < 2) {
      for (std::size_t k = 0; k < count; ++k) body(k);
    } else {
      tbb::task_arena arena(query.threads);
      arena.execute(
          [&] { tbb::parallel_for(std::size_t{0}, count, [&](std::size_t k) { body(k); }); });
    }
  };
  const auto side = [&](std::uint32_t i) {
    return detail::PairSide{&model_of(i), poses[i], feature_radius_[model_index_[i]], i};
  };
  if (query.method == Method::Exact || query.method == Method::SphereObb) {
    for_each(m, [&](std::size_t k) {
      const auto [i, j] = result.candidates[k];
      outcomes[k] = detail::query_pair(side(i), side(j), query);
    });
  } else {
    std::vector<std::pair<detail::PairSide, detail::PairSide>> pairs;
    pairs.reserve(m);
    std::vector<ColonyMemory*> memories;
    for (const auto& [i, j] : result.candidates) {
      pairs.emplace_back(side(i), side(j));
      // Entries are created here, serially; each task then touches only its own.
      if (memory != nullptr) memories.push_back(&memory->pairs_[{i, j}]);
    }
    detail::random_frame(pairs, query, frame, memories, outcomes, for_each);
  }
  for (std::size_t k = 0; k < m; ++k) {
    if (outcomes[k].colliding) result.pairs.push_back(result.candidates[k]);
    result.feature_hits += outcomes[k].feature_hits;
    result.feature_truth += outcomes[k].feature_truth;
    result.evaluations += outcomes[k].evaluations;
    if (outcomes[k].undecided) result.undecided.push_back(result.candidates[k]);
  }
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace antcd
