// antcd::World against FCL's DynamicAABBTreeCollisionManager, in one binary (Google Benchmark).
//
// world_frame_<engine>/<objects>[/<threads>]: a world of N small moving meshes (boxes and spheres
// of 12 and 64 triangles, radius about 0.5, density 1 object per 8 volume units so that a few
// percent of them touch). One iteration = one frame: every object gets its next pose (a drift and a
// spin, the same sequence for both engines), then every pair is queried exactly (boolean).
//   antcd: World::set_poses + World::collide_all, in oneTBB's default arena (threads 0: every
//          core) or in an arena of 1 thread (FCL's manager is single-threaded).
//   FCL:   setTransform + computeAABB per object, manager.update(), manager.collide() with a
//          callback that runs fcl::collide (BVHModel<OBBRSS>, boolean) on each broad-phase pair.
// Counters: colliding pairs and broad-phase pairs per frame, heap bytes of the engine's world
// structures (mallinfo2 before/after building the world; the shared meshes excluded). The engines
// must find the same colliding pairs on every frame (antcd's run records them, FCL's compares,
// outside the timed part); otherwise FCL's run stops with an error and the first pair on which they
// differ is printed to stderr with antcd's exact distance of that pair.
//
// dense_threads/<threads>: a dense world of tumbling real meshes (assimp test models when
// installed, else generated tori), World::collide_all inside a oneTBB arena of 1 or 2 threads.
// world_interleaved/<objects>: both engines frame by frame in turn (see there).
// nearest/<objects>/<signed>: World::nearest_pair against a scan of every pair (see there).
// parallel_control/<threads>: the machine's own two-thread ratio in the same run (see there).
//
// The numbers only mean something in one run on an otherwise idle machine; quote ratios of the two
// engines measured in the same run.
#include <antcd/distance.hpp>
#include <antcd/load.hpp>
#include <antcd/penetration.hpp>
#include <antcd/world.hpp>

#include <benchmark/benchmark.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <malloc.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace antcd;

std::size_t heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

// Deterministic motion of object i: a start pose, a drift velocity and a spin, wrapped into the
// cube [-L/2, L/2]^3.
struct Motion {
  std::vector<Vec3> start;
  std::vector<Vec3> velocity;
  std::vector<Vec3> axis;
  std::vector<Scalar> spin;
  std::vector<Quat> orientation;
  Scalar side = 1;

  Motion(std::size_t n, Scalar side_length, std::uint64_t seed) : side(side_length) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<Scalar> u(-0.5, 0.5);
    std::normal_distribution<Scalar> g(0, 1);
    for (std::size_t i = 0; i < n; ++i) {
      start.emplace_back(side * u(rng), side * u(rng), side * u(rng));
      velocity.emplace_back(0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng));
      axis.push_back(Vec3(g(rng), g(rng), g(rng)).normalized());
      spin.push_back(0.05 * u(rng));
      orientation.push_back(Quat(g(rng), g(rng), g(rng), g(rng)).normalized());
    }
  }

  [[nodiscard]] Transform pose(std::size_t i, std::size_t frame) const {
    const auto f = static_cast<Scalar>(frame);
    Vec3 p = start[i] + f * velocity[i];
    for (int k = 0; k < 3; ++k) p[k] = p[k] - side * std::floor(p[k] / side + 0.5);
    Transform t;
    t.rotation =
        (Eigen::AngleAxis<Scalar>(spin[i] * f, axis[i]) * orientation[i]).toRotationMatrix();
    t.translation = p;
    return t;
  }
};

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fcl_model(const Mesh& m) {
  std::vector<fcl::Vector3d> vertices(m.vertices.begin(), m.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const auto& t : m.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d to_fcl(const Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

const std::vector<Mesh>& small_meshes() {
  static const std::vector<Mesh> meshes{make_box(Vec3(0.4, 0.25, 0.2), 1), make_sphere(0.35, 8, 4)};
  return meshes;
}

Scalar side_for(std::size_t n) { return std::cbrt(8.0 * static_cast<Scalar>(n)); }

// Object-index pairs (i < j), sorted.
using IndexPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The colliding pairs of each frame, per world size, as antcd found them: FCL must agree.
std::vector<IndexPairs>& expected_pairs(std::size_t n) {
  static std::vector<std::vector<IndexPairs>> by_size(2);
  return by_size[n >= 100000 ? 1 : 0];
}

void world_frame_antcd(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  // 0: oneTBB's default arena (every core); otherwise an arena of that many threads.
  const int threads = static_cast<int>(state.range(1));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  std::vector<std::shared_ptr<const Model>> models;
  for (const Mesh& m : small_meshes()) models.push_back(std::make_shared<const Model>(m));
  const Motion motion(n, side_for(n), 42);
  const std::size_t before = heap_in_use();
  World world;
  std::vector<ObjectId> ids;
  ids.reserve(n);
  for (std::size_t i = 0; i < n; ++i) ids.push_back(world.add(models[i % 2], motion.pose(i, 0)));
  const std::size_t bytes = heap_in_use() - before;
  std::vector<Transform> poses(n);
  std::size_t frame = 0;
  std::size_t colliding = 0;
  std::size_t candidates = 0;
  std::vector<std::uint32_t> index_of_slot;
  for (std::size_t i = 0; i < n; ++i) {
    if (index_of_slot.size() <= ids[i].slot) index_of_slot.resize(ids[i].slot + 1);
    index_of_slot[ids[i].slot] = static_cast<std::uint32_t>(i);
  }
  auto& expected = expected_pairs(n);
  for (auto _ : state) {
    ++frame;
    for (std::size_t i = 0; i < n; ++i) poses[i] = motion.pose(i, frame);
    const std::vector<PairContacts> pairs = arena.execute([&] {
      world.set_poses(ids, poses);
      return world.collide_all();
    });
    benchmark::DoNotOptimize(pairs.data());
    colliding += pairs.size();
    state.PauseTiming();
    IndexPairs found;
    for (const PairContacts& p : pairs) {
      const std::uint32_t a = index_of_slot[p.a.slot];
      const std::uint32_t b = index_of_slot[p.b.slot];
      found.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(found.begin(), found.end());
    if (expected.size() < frame) {
      expected.push_back(std::move(found));
    } else if (found != expected[frame - 1]) {  // another thread count must find the same pairs
      state.SkipWithError("antcd's pairs differ from its first run's at this frame");
      break;
    }
    state.ResumeTiming();
  }
  candidates = world.candidate_pairs(0).size();  // after the timed loop
  state.counters["colliding_per_frame"] =
      static_cast<double>(colliding) / static_cast<double>(frame);
  state.counters["candidates_last_frame"] = static_cast<double>(candidates);
  state.counters["world_heap_MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["world_bytes_per_object"] =
      static_cast<double>(world.memory_bytes()) / static_cast<double>(n);
}

struct FclData {
  fcl::CollisionRequestd request{1, false};
  fcl::CollisionResultd result;
  std::size_t colliding = 0;
  std::size_t tested = 0;
  IndexPairs pairs;  // object indices (user data) of the colliding pairs
};

std::uint32_t index_of(const fcl::CollisionObjectd* o) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o->getUserData()));
}

bool fcl_callback(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto& d = *static_cast<FclData*>(data);
  ++d.tested;
  d.result.clear();
  fcl::collide(a, b, d.request, d.result);
  if (d.result.isCollision()) {
    ++d.colliding;
    d.pairs.emplace_back(std::min(index_of(a), index_of(b)), std::max(index_of(a), index_of(b)));
  }
  return false;
}

// One FCL frame: every object moved to its pose at `frame`, the manager updated, then all pairs
// collided into `data` (the same per-frame work as World::set_poses + collide_all).
void fcl_frame(const std::vector<std::unique_ptr<fcl::CollisionObjectd>>& objects,
               fcl::BroadPhaseCollisionManagerd& manager, const Motion& motion, std::size_t frame,
               FclData& data) {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    objects[i]->setTransform(to_fcl(motion.pose(i, frame)));
    objects[i]->computeAABB();
  }
  manager.update();
  manager.collide(&data, fcl_callback);
}

// The first pair on which FCL's sorted pairs differ from antcd's, described with antcd's exact
// distance of that pair at this frame (an empty string when they agree).
std::string first_difference(const IndexPairs& fcl_pairs, const IndexPairs& antcd_pairs,
                             const Motion& motion, std::size_t frame) {
  IndexPairs only_fcl;
  IndexPairs only_antcd;
  std::set_difference(fcl_pairs.begin(), fcl_pairs.end(), antcd_pairs.begin(), antcd_pairs.end(),
                      std::back_inserter(only_fcl));
  std::set_difference(antcd_pairs.begin(), antcd_pairs.end(), fcl_pairs.begin(), fcl_pairs.end(),
                      std::back_inserter(only_antcd));
  if (only_fcl.empty() && only_antcd.empty()) return {};
  const bool fcl_side = !only_fcl.empty();
  const auto [i, j] = fcl_side ? only_fcl.front() : only_antcd.front();
  const Model a(small_meshes()[i % 2]);
  const Model b(small_meshes()[j % 2]);
  const DistanceResult d = distance(a, motion.pose(i, frame), b, motion.pose(j, frame));
  std::ostringstream msg;
  msg.precision(17);
  msg << "frame " << frame << ": " << only_fcl.size() << " pairs only FCL reports, "
      << only_antcd.size() << " only antcd; first: objects " << i << " and " << j << " (only "
      << (fcl_side ? "FCL" : "antcd") << "), antcd distance " << d.distance
      << (d.intersecting ? " (intersecting)" : "");
  return msg.str();
}

void world_frame_fcl(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>>> models;
  for (const Mesh& m : small_meshes()) models.push_back(fcl_model(m));
  const Motion motion(n, side_for(n), 42);
  const std::size_t before = heap_in_use();
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  auto manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
  for (std::size_t i = 0; i < n; ++i) {
    objects.push_back(
        std::make_unique<fcl::CollisionObjectd>(models[i % 2], to_fcl(motion.pose(i, 0))));
    objects.back()->computeAABB();
    objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
    raw.push_back(objects.back().get());
  }
  manager->registerObjects(raw);
  manager->setup();
  const std::size_t bytes = heap_in_use() - before;
  std::size_t frame = 0;
  std::size_t colliding = 0;
  std::size_t tested = 0;
  const auto& expected = expected_pairs(n);
  std::size_t checked =
      0;  // frames compared with antcd's pairs (none when antcd's run was filtered out)
  for (auto _ : state) {
    ++frame;
    FclData data;
    fcl_frame(objects, *manager, motion, frame, data);
    colliding += data.colliding;
    tested += data.tested;
    if (frame <= expected.size()) {
      state.PauseTiming();
      std::sort(data.pairs.begin(), data.pairs.end());
      const std::string difference =
          first_difference(data.pairs, expected[frame - 1], motion, frame);
      ++checked;
      state.ResumeTiming();
      if (!difference.empty()) {
        std::cerr << "world_frame_fcl/" << n << ": " << difference << "\n";
        state.SkipWithError(
            "FCL and antcd disagree on the colliding pairs of a frame (see stderr)");
        break;
      }
    }
  }
  state.counters["colliding_per_frame"] =
      static_cast<double>(colliding) / static_cast<double>(frame);
  state.counters["frames_checked"] = static_cast<double>(checked);
  state.counters["broadphase_pairs_per_frame"] =
      static_cast<double>(tested) / static_cast<double>(frame);
  state.counters["world_heap_MB"] = static_cast<double>(bytes) / 1e6;
}

// ---- both engines frame by frame in turn ----

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// world_interleaved/<objects>: one frame of antcd (in an arena of one thread, so that all of its
// work runs on this thread) then the same frame of FCL, in turn, on the same motion: a change of
// the machine's load hits both engines alike, which separate rows on a shared machine do not
// guarantee. Counters: per-frame medians of each engine's wall time and of this thread's CPU time,
// and their ratios antcd / FCL; the colliding pairs of every frame must agree.
void world_interleaved(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const Motion motion(n, side_for(n), 42);
  std::vector<std::shared_ptr<const Model>> models;
  for (const Mesh& m : small_meshes()) models.push_back(std::make_shared<const Model>(m));
  std::vector<std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>>> fcl_models;
  for (const Mesh& m : small_meshes()) fcl_models.push_back(fcl_model(m));
  World world;
  std::vector<ObjectId> ids;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  for (std::size_t i = 0; i < n; ++i) {
    ids.push_back(world.add(models[i % 2], motion.pose(i, 0)));
    objects.push_back(
        std::make_unique<fcl::CollisionObjectd>(fcl_models[i % 2], to_fcl(motion.pose(i, 0))));
    objects.back()->computeAABB();
    objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
    raw.push_back(objects.back().get());
  }
  auto manager = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
  manager->registerObjects(raw);
  manager->setup();
  tbb::task_arena one(1);
  std::vector<Transform> poses(n);
  std::vector<double> antcd_wall, antcd_cpu, fcl_wall, fcl_cpu;
  std::size_t frame = 0;
  for (auto _ : state) {
    ++frame;
    const auto w0 = std::chrono::steady_clock::now();
    const double c0 = thread_seconds();
    for (std::size_t i = 0; i < n; ++i) poses[i] = motion.pose(i, frame);
    const std::vector<PairContacts> pairs = one.execute([&] {
      world.set_poses(ids, poses);
      return world.collide_all();
    });
    const auto w1 = std::chrono::steady_clock::now();
    const double c1 = thread_seconds();
    FclData data;
    fcl_frame(objects, *manager, motion, frame, data);
    const auto w2 = std::chrono::steady_clock::now();
    const double c2 = thread_seconds();
    antcd_wall.push_back(std::chrono::duration<double>(w1 - w0).count());
    fcl_wall.push_back(std::chrono::duration<double>(w2 - w1).count());
    antcd_cpu.push_back(c1 - c0);
    fcl_cpu.push_back(c2 - c1);
    state.PauseTiming();
    IndexPairs mine;
    for (const PairContacts& p : pairs) {  // ids were handed out in order: slot = index
      mine.emplace_back(p.a.slot, p.b.slot);
    }
    std::sort(data.pairs.begin(), data.pairs.end());
    const std::string difference = first_difference(data.pairs, mine, motion, frame);
    state.ResumeTiming();
    if (!difference.empty()) {
      std::cerr << "world_interleaved/" << n << ": " << difference << "\n";
      state.SkipWithError("FCL and antcd disagree on the colliding pairs of a frame (see stderr)");
      break;
    }
  }
  state.counters["antcd_wall_ms"] = 1e3 * median(antcd_wall);
  state.counters["fcl_wall_ms"] = 1e3 * median(fcl_wall);
  state.counters["antcd_cpu_ms"] = 1e3 * median(antcd_cpu);
  state.counters["fcl_cpu_ms"] = 1e3 * median(fcl_cpu);
  state.counters["ratio_wall"] = median(antcd_wall) / median(fcl_wall);
  state.counters["ratio_cpu"] = median(antcd_cpu) / median(fcl_cpu);
}

// ---- two-thread scaling on a dense world of real meshes ----

std::vector<std::shared_ptr<const Model>> dense_models() {
  std::vector<std::shared_ptr<const Model>> out;
  const std::filesystem::path root = "/usr/share/assimp/models";
  for (const char* f : {"OBJ/spider.obj", "PLY/Wuson.ply"}) {
    if (!std::filesystem::exists(root / f)) continue;
    Mesh m = load_mesh(root / f);
    const Aabb b = m.bounds();
    const Vec3 c = 0.5 * (b.min + b.max);
    const Scalar r = 0.5 * (b.max - b.min).norm();
    for (Vec3& v : m.vertices) v = (v - c) / r;  // radius 1
    out.push_back(std::make_shared<const Model>(std::move(m)));
  }
  if (out.empty()) out.push_back(std::make_shared<const Model>(make_torus(0.8, 0.2, 96, 48)));
  return out;
}

// The machine's own two-thread ratio in the same run: a loop of independent arithmetic of about
// the same length and task count as dense_threads, no memory traffic, no serial part. On a machine
// shared with other work (Linux groups a session's threads into one scheduling entity), this
// ratio falls towards 1 whatever the program does; dense_threads can only be judged against it.
void parallel_control(benchmark::State& state) {
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  std::vector<double> out(256);
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t i) {
        double s = 0;
        for (int k = 0; k < 3000; ++k) s += std::sqrt(static_cast<double>(k + i));
        out[i] = s;
      });
    });
    benchmark::DoNotOptimize(out.data());
  }
}

void dense_threads(benchmark::State& state) {
  const auto threads = static_cast<int>(state.range(0));
  static const auto models = dense_models();
  constexpr std::size_t kObjects = 200;
  const Motion motion(kObjects, std::cbrt(4.0 * kObjects), 7);
  World world;
  std::vector<ObjectId> ids;
  for (std::size_t i = 0; i < kObjects; ++i) {
    ids.push_back(world.add(models[i % models.size()], motion.pose(i, 0)));
  }
  tbb::task_arena arena(threads);
  std::size_t colliding = 0;
  for (auto _ : state) {
    const std::vector<PairContacts> pairs = arena.execute([&] { return world.collide_all(); });
    colliding = pairs.size();
  }
  state.counters["colliding"] = static_cast<double>(colliding);
  state.counters["candidates"] = static_cast<double>(world.candidate_pairs(0).size());
}

// ---- nearest pair: the World's branch and bound against brute force ----

// The closest pair over every pair (i < j) in id order, each distance() bounded by the best so far
// (the brute force: n (n - 1) / 2 distance calls, most of them stopped early by the bound).
Scalar nearest_scan(const World& world, const NearestRequest& request) {
  const std::vector<ObjectId> ids = world.objects();
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      const Model& a = world.model(ids[i]);
      const Model& b = world.model(ids[j]);
      DistanceRequest r;
      r.upper_bound = std::max<Scalar>(best, 0);
      const DistanceResult d =
          request.signed_distance && a.is_closed() && b.is_closed()
              ? signed_distance(a, world.pose(ids[i]), b, world.pose(ids[j]), r)
              : distance(a, world.pose(ids[i]), b, world.pose(ids[j]), r);
      if (!d.beyond_upper_bound) best = std::min(best, d.distance);
    }
  }
  return best;
}

// nearest/<objects>/<signed>: the world of world_frame_<engine> (N small meshes, a few percent
// touching) at frame 0, one closest-pair query per iteration by each method in turn:
// World::nearest_pair, then nearest_scan (both on this thread). Counters: each one's median CPU
// time of this thread (ms) and their ratio;
// the two answers must be equal (else the run stops with an error).
void nearest(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const NearestRequest request{state.range(1) != 0};
  std::vector<std::shared_ptr<const Model>> models;
  for (const Mesh& m : small_meshes()) models.push_back(std::make_shared<const Model>(m));
  const Motion motion(n, side_for(n), 42);
  World world;
  for (std::size_t i = 0; i < n; ++i) world.add(models[i % 2], motion.pose(i, 0));
  std::vector<double> tree_ms;
  std::vector<double> scan_ms;
  Scalar found = 0;
  for (auto _ : state) {
    const double t0 = thread_seconds();
    const std::optional<NearestPair> best = world.nearest_pair(request);
    const double t1 = thread_seconds();
    const Scalar scanned = nearest_scan(world, request);
    const double t2 = thread_seconds();
    if (!best || best->result.distance != scanned) {
      state.SkipWithError("World::nearest_pair and the scan disagree");
      return;
    }
    found = scanned;
    tree_ms.push_back(1e3 * (t1 - t0));
    scan_ms.push_back(1e3 * (t2 - t1));
  }
  state.counters["distance"] = found;
  state.counters["world_ms"] = median(tree_ms);
  state.counters["scan_ms"] = median(scan_ms);
  state.counters["scan_over_world"] = median(scan_ms) / median(tree_ms);
}

}  // namespace

BENCHMARK(nearest)->Args({1000, 0})->Args({1000, 1})->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(world_frame_antcd)
    ->Args({10000, 0})
    ->Args({100000, 0})
    ->Args({10000, 1})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(8)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(world_frame_fcl)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(8)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(world_interleaved)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(15);
BENCHMARK(dense_threads)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseRealTime();
BENCHMARK(parallel_control)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseRealTime();

BENCHMARK_MAIN();
