// antcd against FCL on the protocol of FCL's own mesh–mesh test (Google Benchmark): a large
// environment mesh at the identity, a small robot mesh at many random poses (uniform random
// rotation, translation uniform in a cube around the environment), boolean and all-contacts
// queries on each pose, antcd's Model against FCL's BVHModel<OBBRSS> over the same triangles.
//
// Meshes: assimp's test models (Debian assimp-testmodels). Pair "wuson_spider": Wuson (3 732
// triangles) scaled to bounding radius 1 as the environment, spider (1 368) scaled to radius 0.25
// as the robot; pair "spider_wuson": the other way round. The cube's half side is chosen (bisection
// on 200 seeded poses, antcd's boolean verdict) so that about 40 % of the poses collide, as in
// FCL's test; then 1 000 other seeded poses are used.
//
// protocol/<pair>: one iteration runs every pose once, and on each pose, in turn, antcd boolean,
// FCL boolean, antcd all contacts, FCL all contacts (interleaved: a change of the machine's load
// hits both engines alike). Counters: the colliding fraction; per engine and query the total wall
// time over the poses (ms) and the median per query (µs); the ratios antcd / FCL of the totals. On
// every pose the boolean verdicts must agree and the all-contacts sets of (environment triangle,
// robot triangle) pairs must be equal, otherwise the row stops with an error naming the pose.
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>

#include <benchmark/benchmark.h>

#include "peers/adapters/fcl.hpp"
#include "peers/adapters/peer_mesh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "scaled_mesh.hpp"

namespace {

using namespace antcd;
using bench::scaled;

constexpr std::size_t kCalibrationPoses = 200;
constexpr std::size_t kPoses = 1000;
constexpr double kTargetColliding = 0.4;

// Seeded poses: a uniform random rotation (normalized Gaussian quaternion) and a translation
// uniform in [-half, half]^3.
std::vector<Transform> random_poses(std::size_t n, Scalar half, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<Scalar> g(0, 1);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  std::vector<Transform> out(n);
  for (Transform& t : out) {
    t.rotation = Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    t.translation = Vec3(half * u(rng), half * u(rng), half * u(rng));
  }
  return out;
}

struct Protocol {
  std::string name;
  Mesh env_mesh;
  Mesh rob_mesh;
  std::unique_ptr<Model> env;
  std::unique_ptr<Model> rob;
  peers::PeerMesh env_peer;
  peers::PeerMesh rob_peer;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> env_fcl;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> rob_fcl;
  Scalar half = 0;  // the cube's half side
  std::vector<Transform> poses;
};

// nullptr when the models are not installed.
const Protocol* protocol(const char* env_file, const char* rob_file) {
  static std::vector<std::unique_ptr<Protocol>> made;
  const std::string name = std::string(env_file) + "+" + rob_file;
  for (const auto& p : made) {
    if (p->name == name) return p.get();
  }
  const std::filesystem::path root = "/usr/share/assimp/models";
  if (!std::filesystem::exists(root / env_file) || !std::filesystem::exists(root / rob_file)) {
    return nullptr;
  }
  auto p = std::make_unique<Protocol>();
  p->name = name;
  p->env_mesh = scaled(load_mesh(root / env_file), 1.0);
  p->rob_mesh = scaled(load_mesh(root / rob_file), 0.25);
  p->env = std::make_unique<Model>(p->env_mesh);
  p->rob = std::make_unique<Model>(p->rob_mesh);
  p->env_peer = peers::peer_mesh(p->env_mesh);
  p->rob_peer = peers::peer_mesh(p->rob_mesh);
  p->env_fcl = peers::build_fcl<fcl::OBBRSSd>(p->env_peer);
  p->rob_fcl = peers::build_fcl<fcl::OBBRSSd>(p->rob_peer);
  // The colliding fraction falls as the cube grows: bisect its half side for ~40 %.
  const auto fraction = [&](Scalar half) {
    CollisionResult r;
    std::size_t hits = 0;
    for (const Transform& t : random_poses(kCalibrationPoses, half, 1)) {
      hits += collide(*p->env, Transform{}, *p->rob, t, CollisionRequest{0, false, 0}, r) ? 1 : 0;
    }
    return static_cast<double>(hits) / kCalibrationPoses;
  };
  Scalar lo = 0.1;
  Scalar hi = 4;
  for (int it = 0; it < 20; ++it) {
    const Scalar mid = 0.5 * (lo + hi);
    (fraction(mid) > kTargetColliding ? lo : hi) = mid;
  }
  p->half = 0.5 * (lo + hi);
  p->poses = random_poses(kPoses, p->half, 2);
  made.push_back(std::move(p));
  return made.back().get();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

void protocol_run(benchmark::State& state, const char* env_file, const char* rob_file) {
  const Protocol* p = protocol(env_file, rob_file);
  if (p == nullptr) {
    state.SkipWithError("assimp test models not installed");
    return;
  }
  using Clock = std::chrono::steady_clock;
  const auto us = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::micro>(b - a).count();
  };
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  const fcl::CollisionRequestd fcl_bool(1, false);
  const fcl::CollisionRequestd fcl_all(peers::kFclAllContacts, false);
  std::vector<double> ab, fb, aa, fa;  // per query, µs
  CollisionResult r_bool;
  CollisionResult r_all;
  fcl::CollisionResultd f_bool;
  fcl::CollisionResultd f_all;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> xa, xf;
  std::size_t colliding = 0;
  std::size_t triangle_pairs = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < p->poses.size(); ++i) {
      const Transform& t = p->poses[i];
      const fcl::Transform3d ft = peers::to_fcl(t);
      const auto t0 = Clock::now();
      const bool hit =
          collide(*p->env, Transform{}, *p->rob, t, CollisionRequest{0, false, 0}, r_bool);
      const auto t1 = Clock::now();
      f_bool.clear();
      fcl::collide(p->env_fcl.get(), identity, p->rob_fcl.get(), ft, fcl_bool, f_bool);
      const auto t2 = Clock::now();
      collide(*p->env, Transform{}, *p->rob, t, CollisionRequest{0, true, 0}, r_all);
      const auto t3 = Clock::now();
      f_all.clear();
      fcl::collide(p->env_fcl.get(), identity, p->rob_fcl.get(), ft, fcl_all, f_all);
      const auto t4 = Clock::now();
      ab.push_back(us(t0, t1));
      fb.push_back(us(t1, t2));
      aa.push_back(us(t2, t3));
      fa.push_back(us(t3, t4));
      state.PauseTiming();
      xa.clear();
      for (const Contact& c : r_all.contacts) xa.emplace_back(c.triangle_a, c.triangle_b);
      xf.clear();
      for (std::size_t k = 0; k < f_all.numContacts(); ++k) {
        const auto& c = f_all.getContact(k);
        xf.emplace_back(p->env_peer.mesh_index[static_cast<std::size_t>(c.b1)],
                        p->rob_peer.mesh_index[static_cast<std::size_t>(c.b2)]);
      }
      std::sort(xa.begin(), xa.end());
      std::sort(xf.begin(), xf.end());
      const bool agree = hit == f_bool.isCollision() && r_all.colliding == hit && xa == xf;
      colliding += hit ? 1 : 0;
      triangle_pairs += xa.size();
      state.ResumeTiming();
      if (!agree) {
        state.SkipWithError(("pose " + std::to_string(i) + ": antcd and FCL disagree (boolean " +
                             std::to_string(hit) + " / " + std::to_string(f_bool.isCollision()) +
                             ", triangle pairs " + std::to_string(xa.size()) + " / " +
                             std::to_string(xf.size()) + ")")
                                .c_str());
        return;
      }
    }
  }
  const auto total = [](const std::vector<double>& v) {
    double s = 0;
    for (const double x : v) s += x;
    return s;
  };
  const double n = static_cast<double>(ab.size());
  state.counters["half_side"] = p->half;
  state.counters["colliding_fraction"] = static_cast<double>(colliding) / n;
  state.counters["triangle_pairs_per_pose"] = static_cast<double>(triangle_pairs) / n;
  state.counters["bool_antcd_med_us"] = median(ab);
  state.counters["bool_fcl_med_us"] = median(fb);
  state.counters["all_antcd_med_us"] = median(aa);
  state.counters["all_fcl_med_us"] = median(fa);
  state.counters["bool_ratio_total"] = total(ab) / total(fb);
  state.counters["all_ratio_total"] = total(aa) / total(fa);
  state.counters["bool_ratio_median"] = median(ab) / median(fb);
  state.counters["all_ratio_median"] = median(aa) / median(fa);
}

}  // namespace

BENCHMARK_CAPTURE(protocol_run, wuson_spider, "PLY/Wuson.ply", "OBJ/spider.obj")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(protocol_run, spider_wuson, "OBJ/spider.obj", "PLY/Wuson.ply")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

BENCHMARK_MAIN();
