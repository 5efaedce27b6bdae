// bench/core_bench.cpp — antcd against FCL in one binary: hierarchy build time and exact
// mesh–mesh query time (boolean and all contacts), on generated meshes of about 1k, 10k, 100k and
// 1M triangles. FCL (fcl::BVHModel<fcl::OBBRSSd>) gets the very same triangles and poses.
//
// Benchmarks (name/shape/nominal triangle count, e.g. "all_antcd/torus/100000"):
//   build_antcd, build_fcl          one hierarchy over the mesh (manual time: construction only)
//   boolean_antcd, boolean_fcl      stop at the first contact (antcd CollisionRequest{0, false},
//                                   FCL num_max_contacts = 1)
//   all_antcd, all_fcl              every colliding triangle pair (antcd all_contacts = true,
//                                   FCL num_max_contacts = 10^7, enable_contact = false)
//   all_fcl_points                  as all_fcl but enable_contact = true (FCL also computes contact
//                                   points, normal and depth, up to two contacts per pair)
// Shapes: "sphere" (UV sphere, convex) and "torus" (non-convex); both models of a pair are the
// same mesh, placed by two different poses.
//
// Every query benchmark runs the same 64 seeded pose pairs per iteration (22 deep overlaps, 21
// shallow or grazing contacts, 21 just separated) and reports the counter `per_query` (time of one
// query, averaged over the 64). Before timing, each pose is checked: antcd and FCL must give the
// same boolean verdict and the same set of colliding triangle pairs, otherwise the benchmark is
// skipped with an error naming the pose.
//
// Medians: --benchmark_repetitions=5. With the console output (the default), a Markdown summary
// table of medians and antcd/FCL ratios is printed after the run (docs/performance.md).
#include <antcd/bvh.hpp>
#include <antcd/collide.hpp>
#include <antcd/math.hpp>
#include <antcd/mesh.hpp>

#include <benchmark/benchmark.h>

#include "peers/adapters/fcl.hpp"
#include "peers/adapters/peer_mesh.hpp"
#include "shared/rng.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <iterator>
#include <map>
#include <memory>
#include <numbers>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace {

using antcd::Scalar;
using antcd::Vec3;

// ---------------------------------------------------------------------------------------------
// Meshes

enum class Shape { Sphere, Torus };

const char* shape_name(Shape shape) { return shape == Shape::Sphere ? "sphere" : "torus"; }

antcd::Mesh make_mesh(Shape shape, std::int64_t nominal) {
  const int k = antcd::peers::tessellation_for(static_cast<std::size_t>(nominal));
  return shape == Shape::Sphere ? antcd::make_sphere(1.0, 2 * k, k)
                                : antcd::make_torus(1.0, 0.4, 2 * k, k);
}

/// Generated meshes, made once per (shape, size) and kept for the whole run.
const antcd::Mesh& mesh_for(Shape shape, std::int64_t nominal) {
  static std::map<std::pair<Shape, std::int64_t>, std::unique_ptr<antcd::Mesh>> cache;
  auto& slot = cache[{shape, nominal}];
  if (!slot) slot = std::make_unique<antcd::Mesh>(make_mesh(shape, nominal));
  return *slot;
}

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

// ---------------------------------------------------------------------------------------------
// Poses

/// SplitMix64 (shared/rng.hpp): its output is the same on every platform (the standard
/// distributions are not), so the pose set is reproducible everywhere.
class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  /// Uniform in [0, 1).
  double uniform() { return rng_.uniform(); }

  /// Uniformly distributed rotation (unit quaternion from three uniforms, Shoemake 1992).
  antcd::Mat3 rotation() {
    const double u1 = uniform();
    const double a = 2 * std::numbers::pi * uniform();
    const double b = 2 * std::numbers::pi * uniform();
    const double s1 = std::sqrt(1 - u1);
    const double s2 = std::sqrt(u1);
    return antcd::Quat(s2 * std::cos(b), s1 * std::sin(a), s1 * std::cos(a), s2 * std::sin(b))
        .normalized()
        .toRotationMatrix();
  }

  /// Uniformly distributed unit vector.
  Vec3 direction() {
    const double z = 2 * uniform() - 1;
    const double phi = 2 * std::numbers::pi * uniform();
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  antcd::shared::SplitMix64 rng_;
};

enum class Category { Deep, Shallow, Separated };

const char* category_name(Category c) {
  switch (c) {
    case Category::Deep:
      return "deep";
    case Category::Shallow:
      return "shallow";
    default:
      return "separated";
  }
}

struct PosePair {
  Category category = Category::Deep;
  antcd::Transform a;
  antcd::Transform b;
  fcl::Transform3d fcl_a = fcl::Transform3d::Identity();
  fcl::Transform3d fcl_b = fcl::Transform3d::Identity();
};

using antcd::peers::to_fcl;

constexpr int kPoses = 64;
constexpr std::uint64_t kPoseSeed = 0x616e746364ULL;  // fixed: identical draws at every size

/// 64 pose pairs for two copies of `model`. Pose i draws a rotation for each copy, an offset for A
/// and a direction d; B sits at A's position + s·d. The contact distance s* along d (the largest s
/// at which the copies still touch, to ~1e-13 relative) is found with antcd's boolean query: a
/// scan inward from the bounding spheres' contact, then bisection. Then
///   deep:      s = s*·(0.4 .. 0.9)
///   shallow:   s = s* - r·10^(-7 .. -2)   (penetration 1e-7 to 1e-2 of the bounding radius r,
///              log-uniform: below the tessellation sag of the largest meshes, ~5e-6 r, as well)
///   separated: s = s* + r·10^(-7 .. -2)   (same distribution of gaps)
/// The labels describe the construction; the verification below reports what each pose gives.
std::vector<PosePair> make_poses(const antcd::Model& model) {
  Scalar radius = 0;
  for (const Vec3& v : model.mesh().vertices) radius = std::max(radius, v.norm());
  const Scalar far = 2 * radius * (1 + 1e-6);

  Random rng(kPoseSeed);
  antcd::CollisionResult result;
  std::vector<PosePair> poses;
  poses.reserve(kPoses);
  for (int i = 0; i < kPoses; ++i) {
    PosePair p;
    p.category = static_cast<Category>(i % 3);
    p.a.rotation = rng.rotation();
    p.a.translation = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2 - Vec3::Ones();
    p.b.rotation = rng.rotation();
    const double u = rng.uniform();
    auto touches = [&](const Vec3& d, Scalar s) {
      antcd::Transform b = p.b;
      b.translation = p.a.translation + s * d;
      return antcd::collide(model, p.a, model, b, antcd::CollisionRequest{0, false, 0}, result);
    };
    Vec3 d;
    Scalar inside = -1;  // a colliding distance
    Scalar outside = far;
    while (inside < 0) {  // a direction with no contact at all is redrawn (not seen in practice)
      d = rng.direction();
      constexpr int kSteps = 64;
      for (int k = 1; k <= kSteps; ++k) {
        const Scalar s = far * (1 - static_cast<Scalar>(k) / kSteps);
        if (touches(d, s)) {
          inside = s;
          outside = far * (1 - static_cast<Scalar>(k - 1) / kSteps);
          break;
        }
      }
    }
    for (int it = 0; it < 200 && outside - inside > 1e-13 * far; ++it) {
      const Scalar mid = 0.5 * (inside + outside);
      (touches(d, mid) ? inside : outside) = mid;
    }
    const Scalar contact = 0.5 * (inside + outside);
    const Scalar small = radius * std::pow(10.0, -7 + 5 * u);
    Scalar s = contact;
    switch (p.category) {
      case Category::Deep:
        s = contact * (0.4 + 0.5 * u);
        break;
      case Category::Shallow:
        s = contact - small;
        break;
      case Category::Separated:
        s = contact + small;
        break;
    }
    p.b.translation = p.a.translation + s * d;
    p.fcl_a = to_fcl(p.a);
    p.fcl_b = to_fcl(p.b);
    poses.push_back(p);
  }
  return poses;
}

// ---------------------------------------------------------------------------------------------
// Queries (the code that is timed)

using antcd::peers::kFclAllContacts;

const antcd::CollisionRequest kAntcdBoolean{0, false, 0};
const antcd::CollisionRequest kAntcdAll{0, true, 0};
const fcl::CollisionRequestd kFclBoolean(1, false);
const fcl::CollisionRequestd kFclAll(kFclAllContacts, false);
const fcl::CollisionRequestd kFclAllPoints(kFclAllContacts, true);

bool fcl_query(const FclModel& model, const PosePair& p, const fcl::CollisionRequestd& request,
               fcl::CollisionResultd& result) {
  result.clear();
  fcl::collide(&model, p.fcl_a, &model, p.fcl_b, request, result);
  return result.isCollision();
}

// ---------------------------------------------------------------------------------------------
// Scenes: models, poses and the verification, made once per (shape, size)

using PairSet = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

PairSet antcd_pairs(const antcd::CollisionResult& r) {
  PairSet out;
  out.reserve(r.contacts.size());
  for (const auto& c : r.contacts) out.emplace_back(c.triangle_a, c.triangle_b);
  std::sort(out.begin(), out.end());
  return out;
}

/// FCL's colliding pairs, each once (with enable_contact one pair may give two contacts).
/// FCL's primitive ids index the peer mesh; `mesh_index` maps them back to antcd's triangles.
PairSet fcl_pairs(const fcl::CollisionResultd& r, const std::vector<std::uint32_t>& mesh_index) {
  PairSet out;
  out.reserve(r.numContacts());
  for (std::size_t i = 0; i < r.numContacts(); ++i) {
    const auto& c = r.getContact(i);
    out.emplace_back(mesh_index[static_cast<std::size_t>(c.b1)],
                     mesh_index[static_cast<std::size_t>(c.b2)]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string describe_difference(const PairSet& x, const PairSet& y) {
  PairSet only_x;
  PairSet only_y;
  std::set_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(only_x));
  std::set_difference(y.begin(), y.end(), x.begin(), x.end(), std::back_inserter(only_y));
  std::ostringstream os;
  os << only_x.size() << " pair(s) only in antcd, " << only_y.size() << " only in FCL";
  if (!only_x.empty())
    os << "; e.g. antcd-only (" << only_x[0].first << ", " << only_x[0].second << ")";
  if (!only_y.empty())
    os << "; e.g. FCL-only (" << only_y[0].first << ", " << only_y[0].second << ")";
  return os.str();
}

struct Scene {
  Shape shape = Shape::Sphere;
  std::size_t triangles = 0;
  std::unique_ptr<antcd::Model> model;
  std::vector<std::uint32_t> fcl_to_mesh;  // FCL primitive id → antcd triangle
  std::shared_ptr<FclModel> fcl_model;
  std::vector<PosePair> poses;
  std::string error;         // first disagreement antcd vs FCL (empty: all agree)
  std::string points_error;  // same, against FCL with enable_contact = true
  std::string summary;       // one line: what the poses give
};

/// Builds both models and the poses, then runs every pose through every query kind once and
/// compares: boolean verdicts (antcd boolean, antcd all, FCL boolean, FCL all must agree) and the
/// sets of colliding triangle pairs (antcd all == FCL all; FCL with contact points, deduplicated).
std::unique_ptr<Scene> make_scene(Shape shape, std::int64_t nominal) {
  auto scene = std::make_unique<Scene>();
  scene->shape = shape;
  const antcd::Mesh& mesh = mesh_for(shape, nominal);
  scene->triangles = mesh.triangles.size();
  scene->model = std::make_unique<antcd::Model>(mesh);
  const antcd::peers::PeerMesh peer = antcd::peers::peer_mesh(mesh);
  scene->fcl_to_mesh = peer.mesh_index;
  scene->fcl_model = antcd::peers::build_fcl<fcl::OBBRSSd>(peer);
  scene->poses = make_poses(*scene->model);

  antcd::CollisionResult ab;
  antcd::CollisionResult aa;
  fcl::CollisionResultd fb;
  fcl::CollisionResultd fa;
  fcl::CollisionResultd fp;
  int colliding[3] = {0, 0, 0};
  int per_category[3] = {0, 0, 0};
  std::size_t pairs = 0;
  std::size_t fcl_point_contacts = 0;
  for (int i = 0; i < kPoses; ++i) {
    const PosePair& p = scene->poses[static_cast<std::size_t>(i)];
    const auto cat = static_cast<std::size_t>(p.category);
    ++per_category[cat];
    const bool antcd_bool =
        antcd::collide(*scene->model, p.a, *scene->model, p.b, kAntcdBoolean, ab);
    const bool antcd_all = antcd::collide(*scene->model, p.a, *scene->model, p.b, kAntcdAll, aa);
    const bool fcl_bool = fcl_query(*scene->fcl_model, p, kFclBoolean, fb);
    const bool fcl_all = fcl_query(*scene->fcl_model, p, kFclAll, fa);
    const bool fcl_points = fcl_query(*scene->fcl_model, p, kFclAllPoints, fp);
    const PairSet xa = antcd_pairs(aa);
    const PairSet xf = fcl_pairs(fa, scene->fcl_to_mesh);
    const PairSet xp = fcl_pairs(fp, scene->fcl_to_mesh);
    colliding[cat] += antcd_bool ? 1 : 0;
    pairs += xa.size();
    fcl_point_contacts += fp.numContacts();

    std::ostringstream where;
    where << shape_name(shape) << " " << scene->triangles << " triangles, pose " << i << " ("
          << category_name(p.category) << "): ";
    if (scene->error.empty()) {
      if (antcd_bool != fcl_bool || antcd_all != fcl_all || antcd_bool != antcd_all) {
        std::ostringstream os;
        os << where.str() << "verdicts differ: antcd boolean " << antcd_bool << ", antcd all "
           << antcd_all << ", FCL boolean " << fcl_bool << ", FCL all " << fcl_all;
        scene->error = os.str();
      } else if (fa.numContacts() != aa.contacts.size() || xa != xf) {
        std::ostringstream os;
        os << where.str() << "contact pairs differ: antcd " << aa.contacts.size() << ", FCL "
           << fa.numContacts() << "; " << describe_difference(xa, xf);
        scene->error = os.str();
      }
    }
    if (scene->points_error.empty() && (fcl_points != antcd_all || xp != xa)) {
      std::ostringstream os;
      os << where.str() << "FCL with contact points: verdict " << fcl_points << ", " << xp.size()
         << " distinct pairs vs antcd " << xa.size() << "; " << describe_difference(xa, xp);
      scene->points_error = os.str();
    }
  }
  std::ostringstream os;
  os << shape_name(shape) << " " << scene->triangles << " triangles: colliding poses deep "
     << colliding[0] << "/" << per_category[0] << ", shallow " << colliding[1] << "/"
     << per_category[1] << ", separated " << colliding[2] << "/" << per_category[2] << "; " << pairs
     << " colliding triangle pairs over the 64 poses (FCL with points: " << fcl_point_contacts
     << " contacts); antcd vs FCL: "
     << (scene->error.empty() ? "verdicts and pair sets identical" : "MISMATCH: " + scene->error);
  if (!scene->points_error.empty()) os << "; FCL with points: MISMATCH: " << scene->points_error;
  scene->summary = os.str();
  std::fprintf(stderr, "[verify] %s\n", scene->summary.c_str());
  return scene;
}

std::map<std::pair<Shape, std::int64_t>, std::unique_ptr<Scene>>& scenes() {
  static std::map<std::pair<Shape, std::int64_t>, std::unique_ptr<Scene>> cache;
  return cache;
}

const Scene& scene_for(Shape shape, std::int64_t nominal) {
  auto& slot = scenes()[{shape, nominal}];
  if (!slot) slot = make_scene(shape, nominal);
  return *slot;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks

/// CPU time of the calling thread in seconds. The builds are timed with it (manual time), as the
/// queries are by Google Benchmark's default CPU timer: both libraries run single-threaded here,
/// and on a shared machine the thread's CPU time is far less disturbed by other load than wall
/// time.
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Per-operation time counter: `ops` operations per iteration, reported as seconds per operation.
benchmark::Counter per_op(double ops) {
  return benchmark::Counter(
      ops, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void build_antcd(benchmark::State& state, Shape shape) {
  const antcd::Mesh& mesh = mesh_for(shape, state.range(0));
  std::size_t nodes = 0;
  for (auto _ : state) {
    antcd::Mesh copy = mesh;  // Model takes its mesh by value; the copy is not timed
    const double start = thread_seconds();
    const antcd::Model model(std::move(copy));
    state.SetIterationTime(thread_seconds() - start);
    nodes = model.nodes().size();
    benchmark::DoNotOptimize(nodes);
  }  // destruction not timed (manual time)
  state.counters["tris"] = static_cast<double>(mesh.triangles.size());
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["per_build"] = per_op(1);
}

void build_fcl(benchmark::State& state, Shape shape) {
  const antcd::Mesh& mesh = mesh_for(shape, state.range(0));
  const antcd::peers::FclInput in = antcd::peers::fcl_input(antcd::peers::peer_mesh(mesh));
  int nodes = 0;
  for (auto _ : state) {
    const double start = thread_seconds();
    const auto model = antcd::peers::build_fcl<fcl::OBBRSSd>(in);  // copies them, like antcd
    state.SetIterationTime(thread_seconds() - start);
    nodes = model->getNumBVs();
    benchmark::DoNotOptimize(nodes);
  }
  state.counters["tris"] = static_cast<double>(mesh.triangles.size());
  state.counters["nodes"] = nodes;
  state.counters["per_build"] = per_op(1);
}

enum class Query { Boolean, All, AllPoints };

void query_antcd(benchmark::State& state, Shape shape, Query query) {
  const Scene& scene = scene_for(shape, state.range(0));
  if (!scene.error.empty()) {
    state.SkipWithError(scene.error.c_str());
    return;
  }
  const antcd::CollisionRequest& request = query == Query::Boolean ? kAntcdBoolean : kAntcdAll;
  antcd::CollisionResult result;
  std::size_t hits = 0;
  std::size_t contacts = 0;
  for (auto _ : state) {
    for (const PosePair& p : scene.poses) {
      hits += antcd::collide(*scene.model, p.a, *scene.model, p.b, request, result) ? 1 : 0;
      contacts += result.contacts.size();
    }
  }
  benchmark::DoNotOptimize(hits);
  state.counters["tris"] = static_cast<double>(scene.triangles);
  state.counters["contacts"] = benchmark::Counter(static_cast<double>(contacts) / kPoses,
                                                  benchmark::Counter::kAvgIterations);
  state.counters["per_query"] = per_op(kPoses);
}

void query_fcl(benchmark::State& state, Shape shape, Query query) {
  const Scene& scene = scene_for(shape, state.range(0));
  const std::string& error = query == Query::AllPoints ? scene.points_error : scene.error;
  if (!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const fcl::CollisionRequestd& request = query == Query::Boolean ? kFclBoolean
                                          : query == Query::All   ? kFclAll
                                                                  : kFclAllPoints;
  fcl::CollisionResultd result;
  std::size_t hits = 0;
  std::size_t contacts = 0;
  for (auto _ : state) {
    for (const PosePair& p : scene.poses) {
      hits += fcl_query(*scene.fcl_model, p, request, result) ? 1 : 0;
      contacts += result.numContacts();
    }
  }
  benchmark::DoNotOptimize(hits);
  state.counters["tris"] = static_cast<double>(scene.triangles);
  state.counters["contacts"] = benchmark::Counter(static_cast<double>(contacts) / kPoses,
                                                  benchmark::Counter::kAvgIterations);
  state.counters["per_query"] = per_op(kPoses);
}

void boolean_antcd(benchmark::State& state, Shape shape) {
  query_antcd(state, shape, Query::Boolean);
}
void boolean_fcl(benchmark::State& state, Shape shape) { query_fcl(state, shape, Query::Boolean); }
void all_antcd(benchmark::State& state, Shape shape) { query_antcd(state, shape, Query::All); }
void all_fcl(benchmark::State& state, Shape shape) { query_fcl(state, shape, Query::All); }
void all_fcl_points(benchmark::State& state, Shape shape) {
  query_fcl(state, shape, Query::AllPoints);
}

/// Nominal sizes; the 1M builds take seconds each, so Google Benchmark runs them once per
/// repetition by itself (min time 0.5 s).
void sizes(benchmark::internal::Benchmark* b) {
  for (const std::int64_t n : {1'000, 10'000, 100'000, 1'000'000}) b->Arg(n);
}

void build_config(benchmark::internal::Benchmark* b) {
  sizes(b);
  b->UseManualTime()->Unit(benchmark::kMillisecond);
}

void query_config(benchmark::internal::Benchmark* b) {
  sizes(b);
  b->Unit(benchmark::kMillisecond);  // CPU time (the default timer)
}

BENCHMARK_CAPTURE(build_antcd, sphere, Shape::Sphere)->Apply(build_config);
BENCHMARK_CAPTURE(build_fcl, sphere, Shape::Sphere)->Apply(build_config);
BENCHMARK_CAPTURE(build_antcd, torus, Shape::Torus)->Apply(build_config);
BENCHMARK_CAPTURE(build_fcl, torus, Shape::Torus)->Apply(build_config);
BENCHMARK_CAPTURE(boolean_antcd, sphere, Shape::Sphere)->Apply(query_config);
BENCHMARK_CAPTURE(boolean_fcl, sphere, Shape::Sphere)->Apply(query_config);
BENCHMARK_CAPTURE(boolean_antcd, torus, Shape::Torus)->Apply(query_config);
BENCHMARK_CAPTURE(boolean_fcl, torus, Shape::Torus)->Apply(query_config);
BENCHMARK_CAPTURE(all_antcd, sphere, Shape::Sphere)->Apply(query_config);
BENCHMARK_CAPTURE(all_fcl, sphere, Shape::Sphere)->Apply(query_config);
BENCHMARK_CAPTURE(all_fcl_points, sphere, Shape::Sphere)->Apply(query_config);
BENCHMARK_CAPTURE(all_antcd, torus, Shape::Torus)->Apply(query_config);
BENCHMARK_CAPTURE(all_fcl, torus, Shape::Torus)->Apply(query_config);
BENCHMARK_CAPTURE(all_fcl_points, torus, Shape::Torus)->Apply(query_config);

// ---------------------------------------------------------------------------------------------
// Summary table

std::string format_time(double seconds) {
  char buf[32];
  if (seconds < 1e-3) {
    std::snprintf(buf, sizeof buf, "%.3g µs", seconds * 1e6);
  } else if (seconds < 1) {
    std::snprintf(buf, sizeof buf, "%.3g ms", seconds * 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g s", seconds);
  }
  return buf;
}

/// The console output plus, at the end, one Markdown table per size with the medians (the single
/// run without --benchmark_repetitions) and the ratio antcd/FCL.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.run_type == Run::RT_Aggregate && !median) continue;
      Entry& e = entries_[run.run_name.function_name + "/" + run.run_name.args];
      if (run.error_occurred) {
        e.error = true;
        continue;
      }
      double value = -1;
      for (const char* key : {"per_query", "per_build"}) {
        const auto it = run.counters.find(key);
        if (it != run.counters.end()) value = it->second.value;
      }
      if (median) {
        e.value = value;
        e.from_median = true;
      } else if (!e.from_median) {
        e.value = value;
        ++e.runs;
      }
      const auto tris = run.counters.find("tris");
      if (tris != run.counters.end()) e.triangles = static_cast<std::size_t>(tris->second.value);
    }
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::ostream& out = GetOutputStream();
    out << "\n";
    for (const std::int64_t n : {1'000, 10'000, 100'000, 1'000'000}) {
      const std::string size = std::to_string(n);
      bool any = false;
      for (const auto& [name, e] : entries_) {
        any = any || name.ends_with("/" + size);
      }
      if (!any) continue;
      out << "Nominal " << size << " triangles\n\n";
      out << "| shape (triangles) | measure | antcd | FCL | antcd/FCL |\n";
      out << "| --- | --- | --- | --- | --- |\n";
      for (const char* shape : {"sphere", "torus"}) {
        const std::string suffix = std::string("/") + shape + "/" + size;
        row(out, shape, "build", "build_antcd" + suffix, "build_fcl" + suffix);
        row(out, shape, "boolean query", "boolean_antcd" + suffix, "boolean_fcl" + suffix);
        row(out, shape, "all-contacts query", "all_antcd" + suffix, "all_fcl" + suffix);
        row(out, shape, "all-contacts query, FCL with contact points", "all_antcd" + suffix,
            "all_fcl_points" + suffix);
      }
      out << "\n";
    }
  }

 private:
  struct Entry {
    double value = -1;
    bool from_median = false;
    bool error = false;
    int runs = 0;
    std::size_t triangles = 0;
  };

  [[nodiscard]] std::string cell(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end()) return "not run";
    if (it->second.error) return "error";
    if (!it->second.from_median && it->second.runs > 1) return "no median";
    return format_time(it->second.value);
  }

  void row(std::ostream& out, const char* shape, const char* measure, const std::string& antcd,
           const std::string& fcl) const {
    const auto a = entries_.find(antcd);
    const auto f = entries_.find(fcl);
    if (a == entries_.end() && f == entries_.end()) return;
    std::size_t triangles = 0;
    if (a != entries_.end()) triangles = a->second.triangles;
    if (f != entries_.end() && triangles == 0) triangles = f->second.triangles;
    std::string ratio = "—";
    const auto usable = [](const Entry& e) {
      return !e.error && e.value > 0 && (e.from_median || e.runs == 1);
    };
    if (a != entries_.end() && f != entries_.end() && usable(a->second) && usable(f->second)) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", a->second.value / f->second.value);
      ratio = buf;
    }
    out << "| " << shape << " (" << triangles << ") | " << measure << " | " << cell(antcd) << " | "
        << cell(fcl) << " | " << ratio << " |\n";
  }

  std::map<std::string, Entry> entries_;
};

}  // namespace

int main(int argc, char** argv) {
  // The summary table rides on the console reporter; with another --benchmark_format the
  // library's own reporter is used unchanged.
  bool console = true;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg.starts_with("--benchmark_format=") && arg != "--benchmark_format=console") {
      console = false;
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  if (console) {
    SummaryReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
  } else {
    benchmark::RunSpecifiedBenchmarks();
  }
  benchmark::Shutdown();
  // Every scene's verification result, so a run's log states what was compared.
  for (const auto& [key, scene] : scenes()) {
    if (scene) std::fprintf(stderr, "[verify] %s\n", scene->summary.c_str());
  }
  return 0;
}
