// The scene engine: shared models in one World (its incremental broad phase), and the narrow
// phase of the chosen method on each surviving pair.
#include <antcd/collide.hpp>
#include <antcd/file.hpp>
#include <antcd/load.hpp>
#include <antcd/random.hpp>
#include <antcd/scene.hpp>
#include <antcd/self.hpp>
#include <antcd/world.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>

#include <antcd/pose.hpp>
#include "scene/pair_query.hpp"
#include "util/check.hpp"
#include "util/parallel.hpp"

namespace antcd {

struct Scene::Broad {
  std::mutex mutex;
  World world;
  std::vector<ObjectId> ids;  ///< per object index; ids[i].slot == i
  /// The objects with a pose per frame (the others keep the pose they were added with), their
  /// ids, and room for their poses of a frame.
  std::vector<std::uint32_t> moving;
  std::vector<ObjectId> moving_ids;
  std::vector<Transform> moving_poses;
  /// The World's candidate pairs of a frame (room reused from frame to frame).
  std::vector<ObjectPair> frame_pairs;
  /// The deforming objects (SceneObject::deforming), and room for a frame's scaled vertices.
  std::vector<std::uint32_t> deforming;
  std::vector<Vec3> scaled;
  /// Per object, the Model its queries use: the shared one of a rigid object; a deforming
  /// object's own refitted copy in the World (World::model, updated by each frame's vertices).
  std::vector<const Model*> current;
  /// The objects with SceneObject::self_collision.
  std::vector<std::uint32_t> self_objects;
  /// The frame whose vertices the deforming objects hold in the World (none yet: SIZE_MAX), and
  /// room for a continuous frame's end vertices (per deforming object) and its motion.
  std::size_t vertex_frame = SIZE_MAX;
  std::vector<std::vector<Vec3>> end_vertices;
  std::vector<VertexMotion> motions;

  /// Per object: it has one pose and no vertex frames, so it is the same in every frame.
  std::vector<char> fixed;

  /// What the exact method keeps of a candidate pair from frame to frame: its PairWitness, and
  /// for a pair of two fixed objects its verdict under (verdict_delta, verdict_volume) (-1: none
  /// yet). A fixed pair is the same in every frame, and so is the verdict of its boolean query:
  /// it is computed once per request and reused (the answer is bit-identical; a static x static
  /// pair costs a look-up). 40 bytes per candidate pair (a PairWitness alone: 32).
  struct PairHint {
    PairWitness witness;
    signed char verdict = -1;
  };
  /// The exact method's per-pair hints, one per candidate pair of the last frame that used them,
  /// sorted by pair. A frame that finds them in use by another run_frame call runs without (the
  /// hints change no verdict).
  std::mutex witnesses_mutex;
  std::vector<std::pair<std::uint64_t, PairHint>> witnesses;
  std::vector<std::pair<std::uint64_t, PairHint>> spare_witnesses;
  /// The request (delta, volume) of the verdicts in `witnesses`.
  Scalar verdict_delta = -1;
  bool verdict_volume = false;

  /// Drops the kept verdicts unless they are for (delta, volume). Hold witnesses_mutex.
  void verdicts_for(Scalar delta, bool volume) {
    if (delta == verdict_delta && volume == verdict_volume) return;
    for (auto& w : witnesses) w.second.verdict = -1;
    verdict_delta = delta;
    verdict_volume = volume;
  }

  /// Lines `witnesses` up with `cand` (sorted pairs): entry k is pair cand[k]'s, kept from the
  /// last frame when the pair was a candidate there, else new. Hold witnesses_mutex.
  void align_witnesses(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& cand) {
    spare_witnesses.clear();
    std::size_t old = 0;
    for (const auto& [i, j] : cand) {
      const std::uint64_t key = std::uint64_t{i} << 32 | j;
      while (old < witnesses.size() && witnesses[old].first < key) ++old;
      if (old < witnesses.size() && witnesses[old].first == key) {
        spare_witnesses.emplace_back(key, witnesses[old].second);
      } else {
        spare_witnesses.emplace_back(key, PairHint{});
      }
    }
    std::swap(witnesses, spare_witnesses);
  }

  /// The frame's poses into the World (the moving objects' only), the frame's vertices of the
  /// deforming objects, then its candidate pairs into `out` as object indices. Hold `mutex` (one
  /// caller at a time: the World's mutations must not overlap its queries).
  void candidates_locked(const std::vector<SceneObject>& objects, std::size_t frame, Scalar delta,
                         std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) {
    set_vertices_locked(objects, frame);
    moving_poses.clear();
    for (const std::uint32_t i : moving) moving_poses.push_back(objects[i].pose(frame));
    world.set_poses(moving_ids, moving_poses);
    world.candidate_pairs(delta, frame_pairs);
    out.clear();
    for (const ObjectPair& p : frame_pairs) out.emplace_back(p.a.slot, p.b.slot);
  }

  /// Object i's vertices of `frame`, scaled (model frame; `buffer` holds them when scaled).
  static std::span<const Vec3> frame_vertices(const SceneObject& o, std::size_t frame,
                                              std::vector<Vec3>& buffer) {
    const std::span<const Vec3> v = o.vertex_frames->frame(frame);
    if (o.scale == 1) return v;
    buffer.assign(v.begin(), v.end());
    for (Vec3& p : buffer) p *= o.scale;
    return buffer;
  }

  /// The deforming objects' vertices of `frame` into the World (a refit each, skipped when the
  /// World holds that frame's already: a refit depends on the new vertices alone). Hold `mutex`.
  void set_vertices_locked(const std::vector<SceneObject>& objects, std::size_t frame) {
    if (vertex_frame == frame) return;
    vertex_frame = SIZE_MAX;  // until every object has them (set_vertices does not throw here)
    for (const std::uint32_t i : deforming) {
      world.set_vertices(ids[i], frame_vertices(objects[i], frame, scaled));
      current[i] = &world.model(ids[i]);
    }
    vertex_frame = frame;
  }

  /// candidates_locked under the mutex.
  void candidates(const std::vector<SceneObject>& objects, std::size_t frame, Scalar delta,
                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) {
    const std::lock_guard<std::mutex> lock(mutex);
    candidates_locked(objects, frame, delta, out);
  }

  /// Continuous: the World to the poses of frame - 1 (frame 0: frame 0), then the swept broad
  /// phase and a sweep per candidate pair to the poses of `frame`, into `result`.
  void continuous(const std::vector<SceneObject>& objects, std::size_t frame, Scalar delta,
                  FrameResult& result) {
    const std::lock_guard<std::mutex> lock(mutex);
    moving_poses.clear();
    const std::size_t from = frame == 0 ? 0 : frame - 1;
    for (const std::uint32_t i : moving) moving_poses.push_back(objects[i].pose(from));
    world.set_poses(moving_ids, moving_poses);
    moving_poses.clear();
    for (const std::uint32_t i : moving) moving_poses.push_back(objects[i].pose(frame));
    SweepRequest request;
    request.min_separation = delta;
    if (deforming.empty() && self_objects.empty()) {
      for (const ObjectPair& p : world.swept_candidate_pairs(moving_ids, moving_poses, delta)) {
        result.candidates.emplace_back(p.a.slot, p.b.slot);
      }
      for (const PairToi& p : world.set_poses_continuous(moving_ids, moving_poses, request)) {
        result.pairs.emplace_back(p.a.slot, p.b.slot);
        result.toi.push_back(p.sweep.toi);
        result.contact_points.push_back(p.sweep.contact.point);
      }
      return;
    }
    // Deforming objects (or self pairs): from frame - 1's vertices to frame's, World::sweep_motion.
    set_vertices_locked(objects, from);
    end_vertices.resize(deforming.size());
    motions.clear();
    for (std::size_t k = 0; k < deforming.size(); ++k) {
      const std::uint32_t i = deforming[k];
      const std::span<const Vec3> v = frame_vertices(objects[i], frame, end_vertices[k]);
      motions.push_back({ids[i], v});
    }
    for (const ObjectPair& p :
         world.swept_candidate_pairs(moving_ids, moving_poses, motions, delta)) {
      result.candidates.emplace_back(p.a.slot, p.b.slot);
    }
    vertex_frame = SIZE_MAX;
    for (const MotionToi& p :
         world.set_motion_continuous(moving_ids, moving_poses, motions, request)) {
      result.pairs.emplace_back(p.a.slot, p.b.slot);
      result.toi.push_back(p.toi);
      result.contact_points.push_back(p.point);
    }
    vertex_frame = frame;
    for (const std::uint32_t i : deforming) current[i] = &world.model(ids[i]);
  }
};

namespace {

void check_frame(std::size_t frame, std::size_t frames, Scalar delta) {
  if (frame >= frames) {
    throw ArgumentError("frame " + std::to_string(frame) + " out of range (scene has " +
                        std::to_string(frames) + " frames)");
  }
  detail::require_non_negative("scene query", "delta", delta);
}

/// What would make a deforming object's frame fail, checked once at build: the side file's frame
/// and vertex counts, the hierarchy's left-out triangles (a refit cannot bring them back) and the
/// scaled positions' finiteness.
void check_deforming(const SceneObject& o, const Model& model, std::size_t frames) {
  const std::string where = "object '" + o.name + "': ";
  const std::string file = o.vertex_file_text.empty() ? "its vertex frames" : o.vertex_file_text;
  const VertexFrames& v = *o.vertex_frames;
  if (v.frames != frames || v.positions.size() != std::size_t{v.vertex_count} * v.frames) {
    throw SceneError(printable_line(where + file + ": holds " + std::to_string(v.frames) +
                                    " frames; the scene has " + std::to_string(frames)));
  }
  if (v.vertex_count != model.mesh().vertices.size()) {
    throw SceneError(printable_line(
        where + file + ": holds " + std::to_string(v.vertex_count) + " vertices per frame; mesh " +
        o.mesh_text + " has " + std::to_string(model.mesh().vertices.size()) +
        " as loaded (exactly coincident vertices are joined; docs/cli.md)"));
  }
  if (model.stats().degenerate_triangles > 0) {
    throw SceneError(printable_line(
        where + "mesh " + o.mesh_text + " has " +
        std::to_string(model.stats().degenerate_triangles) +
        " zero-area triangles, which a deforming object's hierarchy cannot take in later; remove "
        "them"));
  }
  if (o.scale != 1) {
    for (std::size_t k = 0; k < v.positions.size(); ++k) {
      if (!(v.positions[k] * o.scale).allFinite()) {
        throw SceneError(
            printable_line(where + file + ": frame " + std::to_string(k / v.vertex_count) +
                           ", vertex " + std::to_string(k % v.vertex_count) +
                           " is not finite once scaled by " + std::to_string(o.scale)));
      }
    }
  }
}

/// The self pairs (i, i) of the objects `self_objects` (ascending) whose Models intersect
/// themselves, merged into result.pairs (sorted: just before the pairs (i, b)), with their
/// triangle pairs in result.self_pairs.
void add_self_pairs(const std::vector<std::uint32_t>& self_objects,
                    const std::vector<const Model*>& current, FrameResult& result) {
  for (const std::uint32_t i : self_objects) {
    SelfIntersectionResult r = self_intersections(*current[i]);
    if (!r.intersecting) continue;
    result.self_pairs.push_back({i, std::move(r.pairs)});
    result.pairs.emplace_back(i, i);
  }
  if (!result.self_pairs.empty()) std::sort(result.pairs.begin(), result.pairs.end());
}

}  // namespace

Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene::Scene(SceneDescription description, const BuildOptions& options)
    : Scene(
          std::move(description), [](const SceneObject& o) { return load_mesh(o.mesh); }, options) {
}

Scene::Scene(SceneDescription description,
             const std::function<Mesh(const SceneObject&)>& mesh_source,
             const BuildOptions& options)
    : description_(std::move(description)), broad_(std::make_unique<Broad>()) {
  const auto start = std::chrono::steady_clock::now();
  load_vertex_frames(description_, "scene");  // the side files not read yet
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
    for (std::size_t k = 0; k < o.poses.size(); ++k) {
      if (const PoseCheck c = check_pose(o.poses[k]); !c.rigid()) {
        throw SceneError("object '" + o.name + "': pose " + std::to_string(k) + " " + c.problem());
      }
    }
    if (o.deforming()) check_deforming(o, model_of(i), description_.frames);
    ObjectOptions options;
    options.name = o.name;
    // The World's own self pairs serve continuous frames (sweep_motion); discrete frames test
    // them here (add_self_pairs), candidate_pairs never lists them.
    options.self_collision = o.self_collision;
    broad_->ids.push_back(broad_->world.add(models_[model_index_[i]], o.pose(0), options));
    broad_->current.push_back(&model_of(i));
    if (o.poses.size() > 1) {
      broad_->moving.push_back(static_cast<std::uint32_t>(i));
      broad_->moving_ids.push_back(broad_->ids.back());
    }
    if (o.deforming()) broad_->deforming.push_back(static_cast<std::uint32_t>(i));
    broad_->fixed.push_back(o.poses.size() <= 1 && !o.deforming() ? 1 : 0);
    if (o.self_collision) broad_->self_objects.push_back(static_cast<std::uint32_t>(i));
  }
  // oneTBB's one-time set-up (its allocator library, the thread's stack bounds read from
  // /proc/self/maps: milliseconds in a process with many libraries mapped) belongs to the build,
  // not to the first frame's time.
  parallel::prepare_thread_arena(1);
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> Scene::broad_phase(std::size_t frame,
                                                                        Scalar delta) const {
  check_frame(frame, description_.frames, delta);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  broad_->candidates(description_.objects, frame, delta, out);
  return out;
}

FrameResult Scene::run_frame(std::size_t frame, const SceneQuery& query,
                             SceneMemory* memory) const {
  check_frame(frame, description_.frames, query.delta);
  detail::require_at_least("scene query", "threads", query.threads, 1);
  if (query.volume && query.method != Method::Exact) {
    throw ArgumentError("volume queries are for the exact method, not " +
                        std::string(method_name(query.method)));
  }
  if (query.continuous && query.method != Method::Exact) {
    throw ArgumentError("continuous queries are for the exact method, not " +
                        std::string(method_name(query.method)));
  }
  if (query.continuous && query.volume) {
    throw ArgumentError("continuous queries test surfaces: volume must be off");
  }
  if (query.method != Method::Exact && query.method != Method::SphereObb) {
    DetectRequest request = query.random;
    request.delta = query.delta;
    request.search.method = query.method;
    check_detect_request(request, "scene query");
    detail::require_non_negative("scene query", "frame_seconds", query.frame_seconds);
  }
  const auto start = std::chrono::steady_clock::now();
  FrameResult result;
  result.frame = frame;
  const auto pose = [&](std::uint32_t i) -> const Transform& {
    return description_.objects[i].pose(frame);
  };
  // The Model each object's queries use this frame (a deforming object's is refitted to the
  // frame's vertices by the broad phase below).
  const std::vector<const Model*>& current = broad_->current;
  // With deforming objects the refitted Models are shared state: the frame holds the World's
  // mutex from their update to the end of its narrow phase. Rigid scenes release it after the
  // broad phase.
  std::unique_lock<std::mutex> frame_lock(broad_->mutex, std::defer_lock);
  // (A continuous frame holds it for its whole run itself.)
  if (!broad_->deforming.empty() && !query.continuous) frame_lock.lock();

  // Exact narrow phase: collide() on each candidate pair, a boolean query. Serially into a
  // result kept by the thread (collide() spawns no tasks, so no other call can interleave on this
  // thread and no frame allocates once its buffers have grown); in parallel, one per range.
  const auto exact_frame = [&] {
    CollisionRequest request{query.delta, false, 0};
    request.volume = query.volume;
    const auto& cand = result.candidates;
    const std::size_t m = cand.size();
    // Each pair's query starts where the last frame's query of the pair found its contact.
    std::unique_lock<std::mutex> hints(broad_->witnesses_mutex, std::try_to_lock);
    if (hints.owns_lock()) {
      broad_->verdicts_for(query.delta, query.volume);
      broad_->align_witnesses(cand);
    }
    const auto hit = [&](std::size_t k, CollisionResult& scratch) {
      const auto [i, j] = cand[k];
      if (hints.owns_lock()) {
        Broad::PairHint& h = broad_->witnesses[k].second;
        if (h.verdict >= 0) return h.verdict != 0;
        const bool v =
            collide(*current[i], pose(i), *current[j], pose(j), request, scratch, h.witness);
        if (broad_->fixed[i] != 0 && broad_->fixed[j] != 0) h.verdict = v ? 1 : 0;
        return v;
      }
      return collide(*current[i], pose(i), *current[j], pose(j), request, scratch);
    };
    result.pairs.reserve(m);  // one allocation, not a doubling series
    if (query.threads == 1 || m < 2) {
      thread_local CollisionResult scratch;
      for (std::size_t k = 0; k < m; ++k) {
        if (hit(k, scratch)) result.pairs.push_back(cand[k]);
      }
    } else {
      std::vector<char> colliding(m, 0);
      parallel::for_ranges(0, m, 1, [&](std::size_t first, std::size_t last) {
        CollisionResult scratch;
        for (std::size_t k = first; k != last; ++k) colliding[k] = hit(k, scratch) ? 1 : 0;
      });
      for (std::size_t k = 0; k < m; ++k) {
        if (colliding[k] != 0) result.pairs.push_back(cand[k]);
      }
    }
    if (!broad_->self_objects.empty()) add_self_pairs(broad_->self_objects, current, result);
  };

  // The other methods: one independent task per candidate pair.
  const auto other_frame = [&] {
    const std::size_t m = result.candidates.size();
    std::vector<detail::PairOutcome> outcomes(m);
    const detail::ForEach for_each = [&](std::size_t count,
                                         const std::function<void(std::size_t)>& body) {
      if (query.threads == 1 || count < 2) {
        for (std::size_t k = 0; k < count; ++k) body(k);
      } else {
        parallel::for_each_index(0, count, [&](std::size_t k) { body(k); });
      }
    };
    const auto side = [&](std::uint32_t i) {
      return detail::PairSide{current[i], pose(i), feature_radius_[model_index_[i]], i};
    };
    if (query.method == Method::SphereObb) {
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
  };

  // The whole frame runs in one task arena of query.threads slots, kept by the calling thread
  // from frame to frame, so that threads = 1 keeps it on the calling thread.
  parallel::in_thread_arena(query.threads, [&] {
    if (query.continuous) {
      broad_->continuous(description_.objects, frame, query.delta, result);
      return;
    }
    if (frame_lock.owns_lock()) {
      broad_->candidates_locked(description_.objects, frame, query.delta, result.candidates);
    } else {
      broad_->candidates(description_.objects, frame, query.delta, result.candidates);
    }
    if (query.method == Method::Exact) {
      exact_frame();
    } else {
      other_frame();
    }
  });
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace antcd
