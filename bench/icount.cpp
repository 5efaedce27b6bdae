// antcd_icount: a fixed set of queries on fixed inputs, each section's instructions counted by
// valgrind's callgrind (scripts/icount.sh runs it and compares with bench/icount_baseline.txt).
//
// Instruction counts of a deterministic program on a fixed input do not depend on the machine's
// load, so a growth of a few percent is a real change of the code (or of the compiler), where
// wall-clock timings on a shared machine are not. Every input here is fixed: assimp's test models
// (Debian assimp-testmodels, the real meshes of the benchmarks), the library's shape generators,
// the production-line generator and a seeded antcd::Rng; one thread throughout.
//
// Sections (each one callgrind dump, named):
//   pair_boolean       boolean collide(), Wuson (radius 1) against spider (radius 0.25), 200 poses
//   pair_contacts      the same poses, all contacts
//   pair_distance      antcd::distance on 60 of those poses
//   world_frame        a World of 40 generated shapes: set_poses + collide_all, 12 frames
//   scene_exact_frame  Scene::run_frame (exact) over a 20-object scene of real meshes, 24 frames
//   world_static_frame a World of 32 static touching parts (spheres, boxes, tori on a grid) and 8
//                      moving shapes: set_poses of the moving ones + collide_all(all contacts),
//                      12 frames (static x static pairs answered from the World's kept answers,
//                      world.hpp "Unchanged pairs")
//   maco_frame         Scene::run_frame (MACO, one SceneMemory) over the generated line, 6 frames
//   model_load         Model::from_bytes of a saved 20 000-triangle torus and of Wuson (the
//                      reader's checks, most of all that every volume holds its subtree)
//
// Run alone (without valgrind) it runs the same work and prints each section's result checksum,
// so that a count change can be told apart from an answer change.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/load.hpp>
#include <antcd/rng.hpp>
#include <antcd/scene.hpp>
#include <antcd/world.hpp>

#include <tbb/task_arena.h>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "scaled_mesh.hpp"
#include "shared/production_line.hpp"

namespace {

using namespace antcd;
using bench::scaled;

const std::filesystem::path kModels = "/usr/share/assimp/models";

// A rotation uniform over SO(3) (a quaternion uniform in the unit ball, normalised) and a
// translation uniform in [-half, half]^3, from our own seeded stream (no library distribution).
Transform random_pose(Rng& rng, Scalar half) {
  Scalar w = 0, x = 0, y = 0, z = 0, n2 = 0;
  do {
    w = rng.uniform(-1, 1);
    x = rng.uniform(-1, 1);
    y = rng.uniform(-1, 1);
    z = rng.uniform(-1, 1);
    n2 = w * w + x * x + y * y + z * z;
  } while (n2 > 1 || n2 < 1e-6);
  const Vec3 t(rng.uniform(-half, half), rng.uniform(-half, half), rng.uniform(-half, half));
  return Transform::from_quaternion(t, w, x, y, z);
}

// One named section: run once untimed (first-use caches, page faults), then again with callgrind
// collecting, then dump its counts under `name`. Returns the counted run's checksum.
template <class F>
std::uint64_t section(const char* name, F&& body) {
  body();
  CALLGRIND_TOGGLE_COLLECT;
  const std::uint64_t sum = body();
  CALLGRIND_TOGGLE_COLLECT;
  CALLGRIND_DUMP_STATS_AT(name);
  std::printf("%-18s checksum %llu\n", name, static_cast<unsigned long long>(sum));
  return sum;
}

std::uint64_t scene_sum(const FrameResult& r) {
  std::uint64_t s = r.candidates.size() * 1000003u + r.pairs.size();
  for (const auto& [i, j] : r.pairs) s = s * 31 + i * 1009u + j;
  return s;
}

int run() {
  for (const char* f : {"PLY/Wuson.ply", "OBJ/spider.obj", "STL/sphereWithHole.stl"}) {
    if (!std::filesystem::exists(kModels / f)) {
      std::fprintf(stderr, "error: %s missing (install Debian's assimp-testmodels)\n",
                   (kModels / f).c_str());
      return 2;
    }
  }
  // Setup is not counted: callgrind starts with instrumentation off (--instr-atstart=no).
  const Model env(scaled(load_mesh(kModels / "PLY/Wuson.ply"), 1.0));
  const Model rob(scaled(load_mesh(kModels / "OBJ/spider.obj"), 0.25));
  Rng rng(25);
  std::vector<Transform> poses(200);
  for (Transform& t : poses) t = random_pose(rng, 0.65);

  // The World: 40 generated shapes in a 6 m cube, each with its own seeded drift and spin.
  World world;
  std::vector<ObjectId> ids;
  std::vector<Transform> world_start, world_step;
  World static_world;
  std::vector<ObjectId> static_movers;
  std::vector<Transform> static_start;
  {
    const std::vector<std::shared_ptr<const Model>> shapes = {
        std::make_shared<const Model>(make_sphere(0.5, 24, 12)),
        std::make_shared<const Model>(make_box({0.6, 0.3, 0.4}, 3)),
        std::make_shared<const Model>(make_torus(0.5, 0.15, 32, 12)),
        std::make_shared<const Model>(make_cylinder(0.3, 1.0, 24, 4))};
    for (std::size_t k = 0; k < 40; ++k) {
      world_start.push_back(random_pose(rng, 3.0));
      Transform step = random_pose(rng, 0.65);
      world_step.push_back(step);
      ids.push_back(world.add(shapes[k % shapes.size()], world_start.back()));
    }
    // Static parts on a 4 x 4 x 2 grid 0.9 apart (each touching its neighbours), turned at
    // random, and 8 of the shapes above moving through them with the first 8 steps.
    for (int k = 0; k < 32; ++k) {
      Transform pose = random_pose(rng, 0.0);
      pose.translation = Vec3(0.9 * (k % 4), 0.9 * (k / 4 % 4), 0.9 * (k / 16));
      static_world.add(shapes[k % 3], pose);
    }
    for (std::size_t k = 0; k < 8; ++k) {
      Transform pose = random_pose(rng, 1.5);
      pose.translation += Vec3(1.35, 1.35, 0.45);
      static_start.push_back(pose);
      static_movers.push_back(static_world.add(shapes[k % shapes.size()], pose));
    }
  }

  // Real meshes placed by the production-line generator (pairs meeting and parting).
  shared::ProductionLineOptions real;
  real.objects = 20;
  real.frames = 24;
  real.seed = 1;
  real.mesh_files = {kModels / "OBJ/spider.obj", kModels / "PLY/Wuson.ply",
                     kModels / "STL/sphereWithHole.stl"};
  const Scene real_scene = shared::make_scene(shared::generate_production_line(real));
  shared::ProductionLineOptions line;
  line.objects = 30;
  line.frames = 6;
  line.seed = 1;
  const Scene line_scene = shared::make_scene(shared::generate_production_line(line));

  const std::vector<std::vector<std::uint8_t>> saved = {
      Model(make_torus(1.0, 0.3, 200, 50)).to_bytes(), env.to_bytes()};

  CALLGRIND_START_INSTRUMENTATION;

  std::size_t colliding = 0;
  section("pair_boolean", [&] {
    std::uint64_t s = 0;
    colliding = 0;
    CollisionResult r;
    for (const Transform& t : poses) {
      const bool hit = collide(env, Transform{}, rob, t, CollisionRequest{}, r);
      colliding += hit ? 1 : 0;
      s = s * 31 + (hit ? 1 : 0);
    }
    return s;
  });
  std::printf("  (%zu of %zu poses colliding)\n", colliding, poses.size());
  section("pair_contacts", [&] {
    std::uint64_t s = 0;
    CollisionRequest request;
    request.all_contacts = true;
    CollisionResult r;
    for (const Transform& t : poses) {
      collide(env, Transform{}, rob, t, request, r);
      s = s * 31 + r.contacts.size();
    }
    return s;
  });
  section("pair_distance", [&] {
    std::uint64_t s = 0;
    for (std::size_t k = 0; k < 60; ++k) {
      const DistanceResult d = distance(env, Transform{}, rob, poses[k]);
      s = s * 31 + static_cast<std::uint64_t>(d.distance * 1e9);
    }
    return s;
  });
  section("world_frame", [&] {
    std::uint64_t s = 0;
    std::vector<Transform> now = world_start;
    for (int f = 0; f < 12; ++f) {
      for (std::size_t k = 0; k < now.size(); ++k) now[k] = now[k] * world_step[k];
      world.set_poses(ids, now);
      for (const PairContacts& p : world.collide_all()) s = s * 31 + p.a.slot * 1009u + p.b.slot;
    }
    world.set_poses(ids, world_start);  // the warm-up run and the counted run start alike
    return s;
  });
  section("scene_exact_frame", [&] {
    std::uint64_t s = 0;
    const SceneQuery exact;
    for (std::size_t f = 0; f < real_scene.description().frames; ++f) {
      s = s * 31 + scene_sum(real_scene.run_frame(f, exact));
    }
    return s;
  });
  section("world_static_frame", [&] {
    std::uint64_t s = 0;
    std::vector<Transform> now = static_start;
    CollisionRequest all;
    all.all_contacts = true;
    for (int f = 0; f < 12; ++f) {
      for (std::size_t k = 0; k < now.size(); ++k) now[k] = now[k] * world_step[k];
      static_world.set_poses(static_movers, now);
      for (const PairContacts& p : static_world.collide_all(all)) {
        s = s * 31 + p.a.slot * 1009u + p.b.slot + p.contacts.size();
      }
    }
    static_world.set_poses(static_movers, static_start);
    return s;
  });
  section("maco_frame", [&] {
    std::uint64_t s = 0;
    SceneQuery maco;
    maco.method = Method::Maco;
    SceneMemory memory;
    for (std::size_t f = 0; f < line_scene.description().frames; ++f) {
      s = s * 31 + scene_sum(line_scene.run_frame(f, maco, &memory));
    }
    return s;
  });
  section("model_load", [&] {
    std::uint64_t s = 0;
    for (const std::vector<std::uint8_t>& bytes : saved) {
      const Model m = Model::from_bytes(bytes);
      s = s * 31 + m.nodes().size() * 1009u + m.stats().depth;
    }
    return s;
  });
  return 0;
}

}  // namespace

int main() {
  // One thread: a World query spreads over the calling arena's workers otherwise.
  tbb::task_arena single(1);
  return single.execute(run);
}
