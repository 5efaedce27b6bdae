// antcd against FCL 0.7 and Bullet 3.24, side by side (see peers_bench.hpp).
#include "peers_bench.hpp"

#include <antcd/collide.hpp>
#include <antcd/io.hpp>
#include <antcd/mesh.hpp>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/config.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletCollisionCommon.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <memory>
#include <numbers>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "production_line.hpp"

namespace antcd::experiments {

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Clocks, statistics, formatting

struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  timespec cpu{};
  timespec process{};
  Stopwatch() {
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &process);
  }
  /// CPU time of every thread of the process (the oneTBB workers included).
  [[nodiscard]] double process_ms() const {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec - process.tv_sec) * 1e3 +
           static_cast<double>(now.tv_nsec - process.tv_nsec) * 1e-6;
  }
  [[nodiscard]] double wall_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall)
        .count();
  }
  [[nodiscard]] double cpu_ms() const {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec - cpu.tv_sec) * 1e3 +
           static_cast<double>(now.tv_nsec - cpu.tv_nsec) * 1e-6;
  }
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  if (q == 0.5) {
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }
  // Nearest rank.
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}
double median(const std::vector<double>& v) { return quantile(v, 0.5); }
double p99(const std::vector<double>& v) { return quantile(v, 0.99); }
double mean(const std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

/// Three significant digits.
std::string num(double x) {
  if (!std::isfinite(x)) return "—";
  std::ostringstream os;
  const double a = std::abs(x);
  if (a >= 100) {
    os << std::fixed << std::setprecision(0) << x;
  } else if (a >= 10) {
    os << std::fixed << std::setprecision(1) << x;
  } else if (a >= 1) {
    os << std::fixed << std::setprecision(2) << x;
  } else if (a >= 0.1) {
    os << std::fixed << std::setprecision(3) << x;
  } else if (a == 0) {
    os << "0";
  } else {
    os << std::setprecision(3) << x;
  }
  return os.str();
}

std::string ratio(double a, double b) {
  if (!(b > 0) || !std::isfinite(a)) return "—";
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << a / b;
  return os.str();
}

std::string read_text(const char* path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string cpu_model() {
  std::istringstream in(read_text("/proc/cpuinfo"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string load_average() {
  std::istringstream in(read_text("/proc/loadavg"));
  std::string a;
  std::string b;
  std::string c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

/// Resident set size of this process now, in MiB (from /proc/self/statm).
double rss_mib() {
  std::istringstream in(read_text("/proc/self/statm"));
  long pages_total = 0;
  long pages_resident = 0;
  in >> pages_total >> pages_resident;
  return static_cast<double>(pages_resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

std::string today() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

// ---------------------------------------------------------------------------------------------
// Meshes as the peers get them: the triangles antcd keeps (non-degenerate), in mesh order.

struct PeerMesh {
  std::vector<Vec3> vertices;
  std::vector<TriangleIndices> triangles;
  std::vector<std::uint32_t> mesh_index;  ///< peer triangle → mesh triangle
};

PeerMesh peer_mesh(const Mesh& mesh) {
  PeerMesh out;
  out.vertices = mesh.vertices;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (geometry::is_degenerate_triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                         mesh.vertices[tri[2]])) {
      continue;
    }
    out.triangles.push_back(tri);
    out.mesh_index.push_back(t);
  }
  return out;
}

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> build_fcl(const PeerMesh& m) {
  std::vector<fcl::Vector3d> vertices;
  vertices.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices) vertices.emplace_back(v.x(), v.y(), v.z());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(m.triangles.size());
  for (const auto& t : m.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

template <class BV>
double fcl_bytes(const fcl::BVHModel<BV>& model) {
  // The brief's estimate: the BV node array, the vertices and the triangles (the permutation array
  // primitive_indices, one int per triangle, is left out).
  return static_cast<double>(model.getNumBVs()) * sizeof(fcl::BVNode<BV>) +
         static_cast<double>(model.num_vertices) * sizeof(fcl::Vector3d) +
         static_cast<double>(model.num_tris) * sizeof(fcl::Triangle);
}

fcl::Transform3d to_fcl(const Transform& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.rotation;
  out.translation() = t.translation;
  return out;
}

btTransform to_bullet(const Transform& t) {
  const Mat3& r = t.rotation;
  const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1),
                          r(2, 2));
  return btTransform(basis, btVector3(t.translation.x(), t.translation.y(), t.translation.z()));
}

/// A colliding triangle pair between two objects (object i < object j; triangle indices in their
/// meshes).
struct TriContact {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  std::uint32_t ta = 0;
  std::uint32_t tb = 0;
  auto operator<=>(const TriContact&) const = default;
};

// ---------------------------------------------------------------------------------------------
// The scene as every engine sees it

struct SceneObjects {
  const Scene* scene = nullptr;
  std::vector<const Model*> models;  ///< distinct
  std::vector<std::size_t> model_of;
  std::vector<PeerMesh> meshes;  ///< per distinct model
  std::vector<std::uint32_t> moving;
  std::size_t triangles = 0;  ///< summed over objects

  explicit SceneObjects(const Scene& s) : scene(&s) {
    std::map<const Model*, std::size_t> index;
    for (std::size_t i = 0; i < s.object_count(); ++i) {
      const Model* m = &s.model_of(i);
      auto it = index.find(m);
      if (it == index.end()) {
        it = index.emplace(m, models.size()).first;
        models.push_back(m);
        meshes.push_back(peer_mesh(m->mesh()));
      }
      model_of.push_back(it->second);
      triangles += meshes[it->second].triangles.size();
      if (s.description().objects[i].poses.size() > 1) {
        moving.push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  [[nodiscard]] const Transform& pose(std::size_t object, std::size_t frame) const {
    return scene->description().objects[object].pose(frame);
  }
};

// ---- FCL ----

struct FclCallbackData {
  const SceneObjects* objects = nullptr;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  ObjectPairs* pairs = nullptr;
  std::vector<TriContact>* contacts = nullptr;
  std::size_t candidates = 0;
};

std::uint32_t object_index(const fcl::CollisionObjectd* o) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(o->getUserData()));
}

bool fcl_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto& d = *static_cast<FclCallbackData*>(data);
  ++d.candidates;
  d.result.clear();
  fcl::collide(o1, o2, d.request, d.result);
  if (!d.result.isCollision()) return false;
  std::uint32_t i = object_index(o1);
  std::uint32_t j = object_index(o2);
  const bool swapped = i > j;
  if (swapped) std::swap(i, j);
  d.pairs->emplace_back(i, j);
  if (d.contacts != nullptr) {
    const auto& map_i = d.objects->meshes[d.objects->model_of[i]].mesh_index;
    const auto& map_j = d.objects->meshes[d.objects->model_of[j]].mesh_index;
    for (std::size_t k = 0; k < d.result.numContacts(); ++k) {
      const auto& c = d.result.getContact(k);
      auto b1 = static_cast<std::uint32_t>(c.b1);
      auto b2 = static_cast<std::uint32_t>(c.b2);
      if (swapped) std::swap(b1, b2);
      d.contacts->push_back({i, j, map_i[b1], map_j[b2]});
    }
  }
  return false;  // never stop: every pair is wanted
}

constexpr std::size_t kFclAllContacts = 10'000'000;

template <class BV>
class FclScene {
 public:
  explicit FclScene(const SceneObjects& objects) : objects_(objects) {
    for (const PeerMesh& m : objects.meshes) models_.push_back(build_fcl<BV>(m));
    std::vector<fcl::CollisionObjectd*> all;
    for (std::size_t i = 0; i < objects.model_of.size(); ++i) {
      auto o = std::make_unique<fcl::CollisionObjectd>(models_[objects.model_of[i]],
                                                       to_fcl(objects.pose(i, 0)));
      o->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
      o->computeAABB();
      all.push_back(o.get());
      objects_list_.push_back(std::move(o));
    }
    for (const std::uint32_t i : objects.moving) moving_.push_back(objects_list_[i].get());
    manager_.registerObjects(all);
    manager_.setup();
  }

  /// One frame: moves the moving objects, refits the broad phase, tests every overlapping pair.
  /// Returns the broad-phase pairs tested.
  std::size_t run(std::size_t frame, bool all_contacts, ObjectPairs& pairs,
                  std::vector<TriContact>* contacts) {
    pairs.clear();
    if (contacts != nullptr) contacts->clear();
    for (const std::uint32_t i : objects_.moving) {
      objects_list_[i]->setTransform(to_fcl(objects_.pose(i, frame)));
      objects_list_[i]->computeAABB();
    }
    manager_.update(moving_);
    FclCallbackData data;
    data.objects = &objects_;
    data.request = all_contacts ? fcl::CollisionRequestd(kFclAllContacts, false)
                                : fcl::CollisionRequestd(1, false);
    data.pairs = &pairs;
    data.contacts = contacts;
    manager_.collide(&data, fcl_callback);
    std::sort(pairs.begin(), pairs.end());
    if (contacts != nullptr) std::sort(contacts->begin(), contacts->end());
    return data.candidates;
  }

 private:
  const SceneObjects& objects_;
  std::vector<std::shared_ptr<fcl::BVHModel<BV>>> models_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_list_;
  std::vector<fcl::CollisionObjectd*> moving_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
};

// ---- Bullet ----

/// One GImpact mesh shape over a peer mesh (the arrays must outlive the shape).
struct BulletMesh {
  std::vector<int> indices;
  std::vector<btScalar> coords;
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::unique_ptr<btGImpactMeshShape> shape;

  explicit BulletMesh(const PeerMesh& m) {
    for (const auto& t : m.triangles) {
      for (int k = 0; k < 3; ++k) indices.push_back(static_cast<int>(t[k]));
    }
    for (const Vec3& v : m.vertices) {
      coords.push_back(v.x());
      coords.push_back(v.y());
      coords.push_back(v.z());
    }
    btIndexedMesh part;
    part.m_numTriangles = static_cast<int>(m.triangles.size());
    part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices.data());
    part.m_triangleIndexStride = 3 * static_cast<int>(sizeof(int));
    part.m_numVertices = static_cast<int>(m.vertices.size());
    part.m_vertexBase = reinterpret_cast<const unsigned char*>(coords.data());
    part.m_vertexStride = 3 * static_cast<int>(sizeof(btScalar));
    part.m_indexType = PHY_INTEGER;
    part.m_vertexType = sizeof(btScalar) == sizeof(double) ? PHY_DOUBLE : PHY_FLOAT;
    array = std::make_unique<btTriangleIndexVertexArray>();
    array->addIndexedMesh(part, PHY_INTEGER);
    shape = std::make_unique<btGImpactMeshShape>(array.get());
    // GImpact grows every triangle (its box and its clipping) by the margin; 0 makes the contact
    // test the closed triangles themselves, like antcd and FCL.
    shape->setMargin(0);
    shape->updateBound();
  }
};

class BulletScene {
 public:
  explicit BulletScene(const SceneObjects& objects) : objects_(objects) {
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    for (const PeerMesh& m : objects.meshes) meshes_.push_back(std::make_unique<BulletMesh>(m));
    for (std::size_t i = 0; i < objects.model_of.size(); ++i) {
      auto o = std::make_unique<btCollisionObject>();
      o->setCollisionShape(meshes_[objects.model_of[i]]->shape.get());
      o->setWorldTransform(to_bullet(objects.pose(i, 0)));
      o->setUserIndex(static_cast<int>(i));
      bodies_.push_back(std::move(o));
    }
    world_ =
        std::make_unique<btCollisionWorld>(dispatcher_.get(), broadphase_.get(), config_.get());
    for (auto& o : bodies_) world_->addCollisionObject(o.get());
  }
  ~BulletScene() {
    for (auto& o : bodies_) world_->removeCollisionObject(o.get());
  }
  BulletScene(const BulletScene&) = delete;
  BulletScene& operator=(const BulletScene&) = delete;

  /// One frame; returns the broad phase's overlapping pairs.
  std::size_t run(std::size_t frame, ObjectPairs& pairs) {
    pairs.clear();
    for (const std::uint32_t i : objects_.moving) {
      bodies_[i]->setWorldTransform(to_bullet(objects_.pose(i, frame)));
    }
    world_->performDiscreteCollisionDetection();
    const int manifolds = dispatcher_->getNumManifolds();
    for (int k = 0; k < manifolds; ++k) {
      const btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(k);
      bool touching = false;
      for (int c = 0; c < m->getNumContacts() && !touching; ++c) {
        touching = m->getContactPoint(c).getDistance() <= 0;
      }
      if (!touching) continue;
      auto i = static_cast<std::uint32_t>(m->getBody0()->getUserIndex());
      auto j = static_cast<std::uint32_t>(m->getBody1()->getUserIndex());
      if (i > j) std::swap(i, j);
      pairs.emplace_back(i, j);
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return static_cast<std::size_t>(world_->getPairCache()->getNumOverlappingPairs());
  }

 private:
  const SceneObjects& objects_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::vector<std::unique_ptr<BulletMesh>> meshes_;
  std::vector<std::unique_ptr<btCollisionObject>> bodies_;
  std::unique_ptr<btCollisionWorld> world_;
};

// ---- antcd all contacts on a scene ----

/// The scene's exact boolean frame (broad phase + first contact per pair), then every colliding
/// triangle pair of the colliding object pairs: what a user of the public API does to get all
/// contacts of a frame. Returns the boolean frame.
FrameResult antcd_all_contacts(const Scene& scene, std::size_t frame, const SceneQuery& query,
                               CollisionResult& scratch, std::vector<TriContact>& contacts) {
  contacts.clear();
  FrameResult r = scene.run_frame(frame, query);
  const CollisionRequest all{query.delta, true, 0};
  for (const auto& [i, j] : r.pairs) {
    const auto& oi = scene.description().objects[i];
    const auto& oj = scene.description().objects[j];
    collide(scene.model_of(i), oi.pose(frame), scene.model_of(j), oj.pose(frame), all, scratch);
    for (const Contact& c : scratch.contacts)
      contacts.push_back({i, j, c.triangle_a, c.triangle_b});
  }
  std::sort(contacts.begin(), contacts.end());
  return r;
}

// ---------------------------------------------------------------------------------------------
// Scenes: timed frames and the comparison

Disagreement disagreement(std::string_view scene, std::size_t frame,
                          std::pair<std::uint32_t, std::uint32_t> p, std::string other,
                          bool reference_says, bool other_says, std::string detail = {}) {
  Disagreement d;
  d.scene = std::string(scene);
  d.frame = frame;
  d.object_a = p.first;
  d.object_b = p.second;
  d.reference = "antcd";
  d.other = std::move(other);
  d.reference_says = reference_says;
  d.other_says = other_says;
  d.detail = std::move(detail);
  return d;
}

/// Appends one record per object pair on which `other` differs from `reference`.
void compare_pairs(const ObjectPairs& reference, const ObjectPairs& other, std::string_view scene,
                   std::size_t frame, std::string_view other_name, std::vector<Disagreement>& out) {
  ObjectPairs only_ref;
  ObjectPairs only_other;
  std::set_difference(reference.begin(), reference.end(), other.begin(), other.end(),
                      std::back_inserter(only_ref));
  std::set_difference(other.begin(), other.end(), reference.begin(), reference.end(),
                      std::back_inserter(only_other));
  for (const auto& p : only_ref) {
    out.push_back(disagreement(scene, frame, p, std::string(other_name), true, false));
  }
  for (const auto& p : only_other) {
    out.push_back(disagreement(scene, frame, p, std::string(other_name), false, true));
  }
}

/// Object pairs (both engines say colliding) whose colliding triangle pairs differ.
void compare_contacts(const std::vector<TriContact>& reference,
                      const std::vector<TriContact>& other, std::string_view scene,
                      std::size_t frame, std::string_view other_name,
                      std::vector<Disagreement>& out) {
  if (reference == other) return;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::array<std::size_t, 4>> per_pair;
  std::vector<TriContact> only_ref;
  std::vector<TriContact> only_other;
  std::set_difference(reference.begin(), reference.end(), other.begin(), other.end(),
                      std::back_inserter(only_ref));
  std::set_difference(other.begin(), other.end(), reference.begin(), reference.end(),
                      std::back_inserter(only_other));
  for (const auto& c : reference) ++per_pair[{c.i, c.j}][0];
  for (const auto& c : other) ++per_pair[{c.i, c.j}][1];
  for (const auto& c : only_ref) ++per_pair[{c.i, c.j}][2];
  for (const auto& c : only_other) ++per_pair[{c.i, c.j}][3];
  for (const auto& [p, n] : per_pair) {
    if (n[2] == 0 && n[3] == 0) continue;
    if (n[0] == 0 || n[1] == 0) continue;  // a verdict difference, reported by compare_pairs
    std::ostringstream os;
    os << "triangle pairs: antcd " << n[0] << ", " << other_name << " " << n[1] << " (" << n[2]
       << " only in antcd, " << n[3] << " only in " << other_name << ")";
    out.push_back(disagreement(scene, frame, p, std::string(other_name) + " all-contacts", true,
                               true, os.str()));
  }
}

struct Series {
  std::string engine;
  std::string query;
  std::vector<double> wall_ms;
  std::vector<double> cpu_ms;
  std::vector<double> process_ms;  ///< CPU time of all threads
  double candidates = 0;           ///< broad-phase pairs, summed over frames
};

struct SceneRun {
  std::string name;
  std::string description;
  std::size_t objects = 0;
  std::size_t moving = 0;
  std::size_t models = 0;
  std::size_t triangles = 0;
  std::size_t frames = 0;
  double colliding = 0;  ///< antcd colliding object pairs, summed over frames
  double contacts = 0;   ///< antcd colliding triangle pairs, summed over frames
  int threads = 1;
  std::vector<Series> series;
  std::vector<Disagreement> disagreements;

  Series& get(const std::string& engine, const std::string& query) {
    for (Series& s : series) {
      if (s.engine == engine && s.query == query) return s;
    }
    series.push_back({engine, query, {}, {}, {}, 0});
    return series.back();
  }
  [[nodiscard]] const Series* find(const std::string& engine, const std::string& query) const {
    for (const Series& s : series) {
      if (s.engine == engine && s.query == query) return &s;
    }
    return nullptr;
  }
};

struct SceneEngines {
  bool fcl_obb = true;
  bool bullet = true;
  bool all_contacts = true;
};

template <class F>
void timed(Series& s, F&& f) {
  const Stopwatch sw;
  const std::size_t candidates = f();
  s.cpu_ms.push_back(sw.cpu_ms());
  s.process_ms.push_back(sw.process_ms());
  s.wall_ms.push_back(sw.wall_ms());
  s.candidates += static_cast<double>(candidates);
}

SceneRun run_scene(const Scene& scene, std::string_view name, std::size_t frames, int threads,
                   const SceneEngines& engines, std::ostream* log) {
  SceneRun run;
  run.name = std::string(name);
  const SceneObjects objects(scene);
  run.objects = scene.object_count();
  run.moving = objects.moving.size();
  run.models = objects.models.size();
  run.triangles = objects.triangles;
  run.frames = frames;
  run.threads = threads;

  FclScene<fcl::OBBRSSd> fcl_obbrss(objects);
  std::unique_ptr<FclScene<fcl::OBBd>> fcl_obb;
  if (engines.fcl_obb) fcl_obb = std::make_unique<FclScene<fcl::OBBd>>(objects);
  std::unique_ptr<BulletScene> bullet;
  if (engines.bullet) bullet = std::make_unique<BulletScene>(objects);

  SceneQuery q1;
  q1.method = Method::Exact;
  q1.threads = 1;
  SceneQuery qt = q1;
  qt.threads = threads;
  CollisionResult scratch;
  std::vector<TriContact> antcd_contacts;
  std::vector<TriContact> peer_contacts;
  ObjectPairs pairs;
  std::vector<Disagreement>& dis = run.disagreements;

  for (std::size_t f = 0; f < frames; ++f) {
    FrameResult ref;
    timed(run.get("antcd exact", "boolean"), [&] {
      ref = scene.run_frame(f, q1);
      return ref.candidates.size();
    });
    run.colliding += static_cast<double>(ref.pairs.size());
    if (threads > 1) {
      FrameResult rt;
      timed(run.get("antcd exact, " + std::to_string(threads) + " threads", "boolean"), [&] {
        rt = scene.run_frame(f, qt);
        return rt.candidates.size();
      });
      compare_pairs(ref.pairs, rt.pairs, name, f, "antcd " + std::to_string(threads) + " threads",
                    dis);
    }
    if (engines.all_contacts) {
      FrameResult ra;
      timed(run.get("antcd exact", "all contacts"), [&] {
        ra = antcd_all_contacts(scene, f, q1, scratch, antcd_contacts);
        return ra.candidates.size();
      });
      run.contacts += static_cast<double>(antcd_contacts.size());
    }

    timed(run.get("FCL-OBBRSS", "boolean"),
          [&] { return fcl_obbrss.run(f, false, pairs, nullptr); });
    compare_pairs(ref.pairs, pairs, name, f, "FCL-OBBRSS", dis);
    if (engines.all_contacts) {
      timed(run.get("FCL-OBBRSS", "all contacts"),
            [&] { return fcl_obbrss.run(f, true, pairs, &peer_contacts); });
      compare_pairs(ref.pairs, pairs, name, f, "FCL-OBBRSS all-contacts", dis);
      compare_contacts(antcd_contacts, peer_contacts, name, f, "FCL-OBBRSS", dis);
    }
    if (fcl_obb) {
      timed(run.get("FCL-OBB", "boolean"), [&] { return fcl_obb->run(f, false, pairs, nullptr); });
      compare_pairs(ref.pairs, pairs, name, f, "FCL-OBB", dis);
      if (engines.all_contacts) {
        timed(run.get("FCL-OBB", "all contacts"),
              [&] { return fcl_obb->run(f, true, pairs, &peer_contacts); });
        compare_pairs(ref.pairs, pairs, name, f, "FCL-OBB all-contacts", dis);
        compare_contacts(antcd_contacts, peer_contacts, name, f, "FCL-OBB", dis);
      }
    }
    if (bullet) {
      timed(run.get("Bullet GImpact", "contact manifolds"), [&] { return bullet->run(f, pairs); });
      compare_pairs(ref.pairs, pairs, name, f, "Bullet", dis);
    }
    if (log != nullptr && (f + 1) % 50 == 0) {
      *log << "  " << name << ": frame " << (f + 1) << "/" << frames << '\n';
    }
  }
  for (Disagreement& d : dis) {
    d.name_a = scene.description().objects[d.object_a].name;
    d.name_b = scene.description().objects[d.object_b].name;
  }
  return run;
}

// ---------------------------------------------------------------------------------------------
// Generated scenes

/// A folder removed when it goes out of scope (only when we created it).
class WorkDir {
 public:
  explicit WorkDir(const fs::path& requested) {
    if (!requested.empty()) {
      path_ = requested;
      create_folders(path_);
      return;
    }
    path_ = fs::temp_directory_path() /
            ("antcd-peers-" + std::to_string(::getpid()) + "-" +
             std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    create_folders(path_);
    owned_ = true;
  }
  ~WorkDir() {
    if (owned_) {
      std::error_code ec;
      fs::remove_all(path_, ec);
    }
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool owned_ = false;
};

/// The dense variant: every translation's x (the line's direction) multiplied by `x_scale`, about
/// x = 0. Objects keep their size and motion, so neighbouring stations slide into each other.
void pack_along_line(GeneratedScene& g, Scalar x_scale) {
  for (SceneObject& o : g.scene.objects) {
    for (Transform& t : o.poses) t.translation.x() *= x_scale;
  }
}

std::unique_ptr<Scene> load_generated(const GeneratedScene& g, const fs::path& dir) {
  const fs::path file = write_scene(g, dir);
  return std::make_unique<Scene>(load_scene(file));
}

// ---------------------------------------------------------------------------------------------
// Pair protocol

enum class Clearance { Deep, Shallow, Touching, Separated };
constexpr std::array<Clearance, 4> kClearances = {Clearance::Deep, Clearance::Shallow,
                                                  Clearance::Touching, Clearance::Separated};

const char* clearance_name(Clearance c) {
  switch (c) {
    case Clearance::Deep:
      return "deep";
    case Clearance::Shallow:
      return "shallow";
    case Clearance::Touching:
      return "touching";
    case Clearance::Separated:
      return "separated";
  }
  return "?";
}

const char* clearance_rule(Clearance c) {
  switch (c) {
    case Clearance::Deep:
      return "s = 0.7 s*";
    case Clearance::Shallow:
      return "s = s* − 1e-3 R";
    case Clearance::Touching:
      return "s = s* − 1e-9 R";
    case Clearance::Separated:
      return "s = s* + 1e-6 R";
  }
  return "?";
}

/// Torus tessellation for a nominal triangle count (as bench/core_bench.cpp): 2k × k segments,
/// 4k² triangles.
int torus_k(std::size_t nominal) {
  switch (nominal) {
    case 1'000:
      return 16;
    case 10'000:
      return 50;
    case 100'000:
      return 158;
    case 1'000'000:
      return 500;
    default:
      return static_cast<int>(std::lround(std::sqrt(static_cast<double>(nominal) / 4.0)));
  }
}

struct PairCell {
  std::size_t size = 0;
  std::size_t triangles = 0;
  Clearance clearance = Clearance::Deep;
  std::size_t poses = 0;
  std::size_t colliding_antcd = 0;
  std::size_t colliding_fcl = 0;
  std::size_t triangle_pairs_antcd = 0;
  std::size_t triangle_pairs_fcl = 0;
  std::size_t disagreements = 0;
  std::string first_disagreement;
  std::vector<double> antcd_bool_us, fcl_bool_us, antcd_all_us, fcl_all_us;
};

struct BuildRow {
  std::size_t size = 0;
  std::size_t triangles = 0;
  double antcd_ms = 0;
  double fcl_obbrss_ms = 0;
  double fcl_obb_ms = 0;
  double antcd_bytes_per_tri = 0;
  double fcl_obbrss_bytes_per_tri = 0;
  double fcl_obb_bytes_per_tri = 0;
  std::size_t antcd_nodes = 0;
  int fcl_bvs = 0;
};

BuildRow measure_build(std::size_t size, const Mesh& mesh, int reps) {
  BuildRow row;
  row.size = size;
  row.triangles = mesh.triangles.size();
  std::unique_ptr<Model> model;
  // Time only the construction: the copy handed to Model is made outside the timed region.
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    Mesh copy = mesh;
    model.reset();
    const Stopwatch sw;
    model = std::make_unique<Model>(std::move(copy));
    t.push_back(sw.wall_ms());
  }
  row.antcd_ms = median(t);
  row.antcd_bytes_per_tri =
      static_cast<double>(model->stats().memory_bytes) / static_cast<double>(row.triangles);
  row.antcd_nodes = model->stats().nodes;
  model.reset();

  const PeerMesh pm = peer_mesh(mesh);
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> obbrss;
  std::vector<fcl::Vector3d> vertices;
  for (const Vec3& v : pm.vertices) vertices.emplace_back(v.x(), v.y(), v.z());
  std::vector<fcl::Triangle> triangles;
  for (const auto& tri : pm.triangles) triangles.emplace_back(tri[0], tri[1], tri[2]);
  t.clear();
  for (int r = 0; r < reps; ++r) {
    obbrss.reset();
    const Stopwatch sw;
    obbrss = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    obbrss->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
    obbrss->addSubModel(vertices, triangles);
    obbrss->endModel();
    t.push_back(sw.wall_ms());
  }
  row.fcl_obbrss_ms = median(t);
  row.fcl_obbrss_bytes_per_tri = fcl_bytes(*obbrss) / static_cast<double>(row.triangles);
  row.fcl_bvs = obbrss->getNumBVs();
  obbrss.reset();
  std::shared_ptr<fcl::BVHModel<fcl::OBBd>> obb;
  t.clear();
  for (int r = 0; r < reps; ++r) {
    obb.reset();
    const Stopwatch sw;
    obb = std::make_shared<fcl::BVHModel<fcl::OBBd>>();
    obb->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
    obb->addSubModel(vertices, triangles);
    obb->endModel();
    t.push_back(sw.wall_ms());
  }
  row.fcl_obb_ms = median(t);
  row.fcl_obb_bytes_per_tri = fcl_bytes(*obb) / static_cast<double>(row.triangles);
  return row;
}

using TrianglePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// The pair protocol at one size: torus A fixed, torus B tumbling past it. For pose i of P
/// (t = i / (P - 1)) B is rotated by 4πt about a fixed tilted axis (two full turns) and placed at
/// s·d(t) from A, d(t) sweeping half a turn around A (from −y through +x to +y, 0.35 up). s* is the
/// largest s at which the two touch (scan inward from the bounding spheres' contact, then
/// bisection to ~1e-13 relative); each clearance class places B from s* (clearance_rule).
std::vector<PairCell> run_pairs_at(std::size_t size, std::size_t poses, std::ostream& log) {
  const int k = torus_k(size);
  const Mesh mesh = make_torus(1.0, 0.4, 2 * k, k);
  const Model model(mesh);
  const PeerMesh pm = peer_mesh(mesh);
  const auto fcl_model = build_fcl<fcl::OBBRSSd>(pm);
  Scalar radius = 0;
  for (const Vec3& v : mesh.vertices) radius = std::max(radius, v.norm());
  const Scalar far = 2 * radius * (1 + 1e-6);

  Transform pose_a = Transform::from_axis_angle(Vec3(1, 1, 0), 0.3);
  const Vec3 tumble_axis = Vec3(0.3, 0.5, 0.8).normalized();
  const Mat3 start = Eigen::AngleAxis<Scalar>(0.7, Vec3::UnitX()).toRotationMatrix();

  std::vector<PairCell> cells(kClearances.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    cells[c].size = size;
    cells[c].triangles = mesh.triangles.size();
    cells[c].clearance = kClearances[c];
    cells[c].poses = poses;
  }
  CollisionResult scratch;
  CollisionResult ab;
  CollisionResult aa;
  fcl::CollisionResultd fb;
  fcl::CollisionResultd fa;
  const fcl::CollisionRequestd fcl_bool(1, false);
  const fcl::CollisionRequestd fcl_all(kFclAllContacts, false);
  const fcl::Transform3d fcl_a = to_fcl(pose_a);
  TrianglePairs xa;
  TrianglePairs xf;
  for (std::size_t i = 0; i < poses; ++i) {
    const Scalar t = poses > 1 ? static_cast<Scalar>(i) / static_cast<Scalar>(poses - 1) : 0;
    Transform pose_b;
    pose_b.rotation =
        Eigen::AngleAxis<Scalar>(4 * std::numbers::pi * t, tumble_axis).toRotationMatrix() * start;
    const Scalar phi = -std::numbers::pi / 2 + std::numbers::pi * t;
    const Vec3 d = Vec3(std::cos(phi), std::sin(phi), 0.35).normalized();
    auto touches = [&](Scalar s) {
      Transform b = pose_b;
      b.translation = s * d;
      return collide(model, pose_a, model, b, CollisionRequest{0, false, 0}, scratch);
    };
    Scalar inside = -1;
    Scalar outside = far;
    constexpr int kSteps = 32;
    for (int step = 1; step <= kSteps; ++step) {
      const Scalar s = far * (1 - static_cast<Scalar>(step) / kSteps);
      if (touches(s)) {
        inside = s;
        outside = far * (1 - static_cast<Scalar>(step - 1) / kSteps);
        break;
      }
    }
    if (inside < 0) continue;  // no contact along d at all (not seen with these shapes)
    for (int it = 0; it < 200 && outside - inside > 1e-13 * far; ++it) {
      const Scalar mid = 0.5 * (inside + outside);
      (touches(mid) ? inside : outside) = mid;
    }
    const Scalar contact = 0.5 * (inside + outside);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      PairCell& cell = cells[c];
      Scalar s = contact;
      switch (cell.clearance) {
        case Clearance::Deep:
          s = 0.7 * contact;
          break;
        case Clearance::Shallow:
          s = contact - 1e-3 * radius;
          break;
        case Clearance::Touching:
          s = contact - 1e-9 * radius;
          break;
        case Clearance::Separated:
          s = contact + 1e-6 * radius;
          break;
      }
      Transform b = pose_b;
      b.translation = s * d;
      const fcl::Transform3d fcl_b = to_fcl(b);

      Stopwatch sw;
      const bool antcd_bool = collide(model, pose_a, model, b, CollisionRequest{0, false, 0}, ab);
      cell.antcd_bool_us.push_back(sw.wall_ms() * 1e3);
      sw = Stopwatch();
      fb.clear();
      fcl::collide(fcl_model.get(), fcl_a, fcl_model.get(), fcl_b, fcl_bool, fb);
      cell.fcl_bool_us.push_back(sw.wall_ms() * 1e3);
      sw = Stopwatch();
      collide(model, pose_a, model, b, CollisionRequest{0, true, 0}, aa);
      cell.antcd_all_us.push_back(sw.wall_ms() * 1e3);
      sw = Stopwatch();
      fa.clear();
      fcl::collide(fcl_model.get(), fcl_a, fcl_model.get(), fcl_b, fcl_all, fa);
      cell.fcl_all_us.push_back(sw.wall_ms() * 1e3);

      const bool fcl_bool_hit = fb.isCollision();
      cell.colliding_antcd += antcd_bool ? 1 : 0;
      cell.colliding_fcl += fcl_bool_hit ? 1 : 0;
      xa.clear();
      for (const Contact& ct : aa.contacts) xa.emplace_back(ct.triangle_a, ct.triangle_b);
      std::sort(xa.begin(), xa.end());
      xf.clear();
      for (std::size_t q = 0; q < fa.numContacts(); ++q) {
        const auto& ct = fa.getContact(q);
        xf.emplace_back(pm.mesh_index[static_cast<std::size_t>(ct.b1)],
                        pm.mesh_index[static_cast<std::size_t>(ct.b2)]);
      }
      std::sort(xf.begin(), xf.end());
      cell.triangle_pairs_antcd += xa.size();
      cell.triangle_pairs_fcl += xf.size();
      if (antcd_bool != fcl_bool_hit || aa.colliding != antcd_bool || xa != xf) {
        if (cell.disagreements++ == 0) {
          std::ostringstream os;
          os << "pose " << i << ": antcd boolean " << antcd_bool << ", FCL boolean " << fcl_bool_hit
             << "; triangle pairs antcd " << xa.size() << ", FCL " << xf.size();
          cell.first_disagreement = os.str();
        }
      }
    }
  }
  log << "  pairs: " << mesh.triangles.size() << " triangles done\n";
  return cells;
}

// ---------------------------------------------------------------------------------------------
// Scale

struct ScaleRow {
  std::size_t objects = 0;
  std::size_t vertices_option = 0;
  std::size_t triangles = 0;
  std::size_t models = 0;
  std::size_t frames = 0;
  double candidates = 0;  ///< per frame, mean
  double colliding = 0;   ///< per frame, mean
  double median_ms = 0;
  double p99_ms = 0;
  double build_ms = 0;
  double model_mib = 0;
  double rss_mib = 0;
};

ScaleRow run_scale_row(std::size_t objects, std::size_t vertices, std::size_t frames,
                       const fs::path& dir, std::ostream& log) {
  ProductionLineOptions po;
  po.objects = objects;
  po.vertices = vertices;
  po.frames = frames;
  const GeneratedScene g = generate_production_line(po);
  const auto scene = load_generated(g, dir);
  ScaleRow row;
  row.objects = objects;
  row.vertices_option = vertices;
  row.models = scene->model_count();
  row.frames = frames;
  row.build_ms = scene->build_ms();
  std::map<const Model*, int> seen;
  for (std::size_t i = 0; i < scene->object_count(); ++i) {
    const Model& m = scene->model_of(i);
    row.triangles += m.leaf_triangles().size();
    if (seen.emplace(&m, 0).second) {
      row.model_mib += static_cast<double>(m.stats().memory_bytes) / (1024.0 * 1024.0);
    }
  }
  SceneQuery q;
  q.method = Method::Exact;
  std::vector<double> ms;
  for (std::size_t f = 0; f < frames; ++f) {
    const Stopwatch sw;
    const FrameResult r = scene->run_frame(f, q);
    ms.push_back(sw.wall_ms());
    row.candidates += static_cast<double>(r.candidates.size());
    row.colliding += static_cast<double>(r.pairs.size());
  }
  row.candidates /= static_cast<double>(frames);
  row.colliding /= static_cast<double>(frames);
  row.median_ms = median(ms);
  row.p99_ms = p99(ms);
  row.rss_mib = rss_mib();
  log << "  scale: " << objects << " objects done\n";
  return row;
}

// ---------------------------------------------------------------------------------------------
// Report

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

struct Target {
  std::string what;
  std::string measured;
  std::string verdict;  ///< "met", "missed", "not measured"
};

std::string verdict(bool ok) { return ok ? "met" : "MISSED"; }

}  // namespace

SceneCheck check_scene(const Scene& scene, std::string_view name, std::size_t frames,
                       bool with_bullet) {
  SceneEngines engines;
  engines.fcl_obb = false;
  engines.bullet = with_bullet;
  const SceneRun run = run_scene(scene, name, frames, 1, engines, nullptr);
  SceneCheck check;
  check.frames = frames;
  check.colliding_pairs = static_cast<std::size_t>(run.colliding);
  check.triangle_pairs = static_cast<std::size_t>(run.contacts);
  if (const Series* s = run.find("antcd exact", "boolean")) {
    check.candidate_pairs = static_cast<std::size_t>(s->candidates);
  }
  for (const Disagreement& d : run.disagreements) {
    (d.other == "Bullet" ? check.bullet : check.fcl).push_back(d);
  }
  return check;
}

PeersBenchResult run_peers_bench(const PeersBenchOptions& options, std::ostream& log) {
  if (options.threads < 1) throw antcd::ArgumentError("--threads must be at least 1");
  const auto total_start = std::chrono::steady_clock::now();
  const std::size_t frames_default = options.quick ? 30 : 300;
  const std::size_t frames_wanted = options.frames > 0 ? options.frames : frames_default;
  const std::string load_start = load_average();

  PeersBenchResult result;
  std::ostringstream md;
  std::vector<Target> targets;
  std::vector<Disagreement> all_disagreements;

  md << "# antcd vs FCL and Bullet (`antcd bench peers`)\n\n";
  md << "- run: " << today() << (options.quick ? ", --quick" : "") << ", --threads "
     << options.threads << ", frames per scene " << frames_wanted << "\n";
  md << "- machine: " << std::thread::hardware_concurrency() << " logical CPUs (nproc "
     << sysconf(_SC_NPROCESSORS_ONLN) << "), CPU \"" << cpu_model() << "\"\n";
  md << "- peers: FCL " << FCL_VERSION << ", Bullet " << BT_BULLET_VERSION / 100 << "."
     << BT_BULLET_VERSION % 100
     << (sizeof(btScalar) == sizeof(double) ? " (double precision build)"
                                            : " (single precision build)")
     << "; antcd default BuildOptions (leaf size 4, area-weighted covariance)\n";
  md << "- times: each frame (or pose) runs every engine in turn, so all see the same machine "
        "load. Scenes: CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID) and wall time "
        "(steady_clock) per frame; single-thread ratios and targets use the CPU medians (the "
        "machine is shared, and CPU time is much less disturbed by other work than wall time); "
        "the threaded run can only be judged by wall time. Pairs and builds: wall time per query "
        "or build, medians.\n\n";

  // ---- Scenes ----
  std::vector<SceneRun> scene_runs;
  if (options.run_scenes) {
    const WorkDir work(options.work_dir);
    std::vector<std::pair<std::string, std::unique_ptr<Scene>>> scenes;
    std::vector<std::string> descriptions;
    if (!options.scene_file.empty()) {
      auto scene = std::make_unique<Scene>(load_scene(options.scene_file));
      descriptions.push_back("scene file " + options.scene_file.string());
      scenes.emplace_back(options.scene_file.filename().string(), std::move(scene));
    } else {
      ProductionLineOptions paper;
      paper.frames = frames_wanted;
      log << "generating the paper scene (90 objects, 750 vertices, " << frames_wanted
          << " frames)\n";
      const GeneratedScene g = generate_production_line(paper);
      scenes.emplace_back("paper", load_generated(g, work.path() / "paper"));
      descriptions.push_back(
          "the paper's production line: experiments/production_line.hpp with default options "
          "(90 objects, ~750 vertices per mesh, seed 1)");
      ProductionLineOptions dense = paper;
      dense.objects = 180;
      GeneratedScene gd = generate_production_line(dense);
      pack_along_line(gd, 0.5);
      scenes.emplace_back("dense", load_generated(gd, work.path() / "dense"));
      descriptions.push_back(
          "dense: the same generator with 180 objects, then every translation's x (the line's "
          "direction) multiplied by 0.5, so neighbouring stations overlap");
    }
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const Scene& scene = *scenes[s].second;
      const std::size_t frames = std::min(frames_wanted, scene.description().frames);
      log << "scene " << scenes[s].first << ": " << scene.object_count() << " objects, " << frames
          << " frames\n";
      SceneRun run =
          run_scene(scene, scenes[s].first, frames, options.threads, SceneEngines{}, &log);
      run.description = descriptions[s];
      scene_runs.push_back(std::move(run));
    }
  }

  if (!scene_runs.empty()) {
    md << "## Scenes\n\n";
    md << "Per frame: poses → broad phase → narrow phase on every surviving pair. antcd: "
          "`Scene::run_frame` with `Method::Exact` (all contacts: that frame, then "
          "`collide(all_contacts)` on each colliding object pair). FCL: one `BVHModel` per mesh "
          "behind `DynamicAABBTreeCollisionManagerd` (moving objects re-posed and refitted each "
          "frame), `fcl::collide` per overlapping pair, boolean = `num_max_contacts` 1, all "
          "contacts = 10^7 without contact points. Bullet: `btGImpactMeshShape` (margin 0) in a "
          "`btCollisionWorld` with `btDbvtBroadphase`, `performDiscreteCollisionDetection`, a "
          "pair collides when its manifold has a point of distance ≤ 0 (Bullet keeps at most 4 "
          "points per pair, so it gives object pairs only).\n\n";
    for (const SceneRun& run : scene_runs) {
      const Series* base = run.find("antcd exact", "boolean");
      md << "### Scene `" << run.name << "`\n\n"
         << run.description << ". " << run.objects << " objects (" << run.moving << " moving), "
         << run.models << " distinct meshes, " << run.triangles << " triangles in all, "
         << run.frames
         << " frames; antcd: " << num(base->candidates / static_cast<double>(run.frames))
         << " candidate pairs and " << num(run.colliding / static_cast<double>(run.frames))
         << " colliding object pairs per frame (mean), "
         << num(run.contacts / static_cast<double>(run.frames))
         << " colliding triangle pairs per frame.\n\n";
      md << "| engine | query | broad-phase pairs / frame | median CPU ms | p99 CPU ms | median "
            "wall ms | p99 wall ms | antcd / engine (CPU medians) | antcd / engine (wall "
            "medians) |\n";
      md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
      for (const Series& s : run.series) {
        const Series* ref = run.find("antcd exact", s.query);
        if (s.query == "contact manifolds") ref = base;
        const bool threaded = s.engine.find("threads") != std::string::npos;
        const bool self = ref == nullptr || ref == &s;
        md << "| " << s.engine << " | " << s.query << " | "
           << num(s.candidates / static_cast<double>(run.frames)) << " | "
           << (threaded ? "—" : num(median(s.cpu_ms))) << " | "
           << (threaded ? "—" : num(p99(s.cpu_ms))) << " | " << num(median(s.wall_ms)) << " | "
           << num(p99(s.wall_ms)) << " | "
           << (self       ? "1"
               : threaded ? "—"
                          : ratio(median(ref->cpu_ms), median(s.cpu_ms)))
           << " | " << (self ? "1" : ratio(median(ref->wall_ms), median(s.wall_ms))) << " |\n";
      }
      md << "\n";
      if (run.threads > 1) {
        const Series* t =
            run.find("antcd exact, " + std::to_string(run.threads) + " threads", "boolean");
        if (t != nullptr) {
          md << "antcd boolean with " << run.threads
             << " threads (oneTBB): " << ratio(median(base->wall_ms), median(t->wall_ms))
             << "× the speed of 1 thread (wall medians " << num(median(base->wall_ms)) << " → "
             << num(median(t->wall_ms))
             << " ms). CPU time of all threads per frame: " << num(median(base->process_ms))
             << " ms with 1 thread, " << num(median(t->process_ms)) << " ms with " << run.threads
             << " (the work the threads share; wall time can only drop below it / threads when "
                "the cores are free).\n\n";
        }
      }
      std::map<std::string, std::size_t> by_engine;
      for (const Disagreement& d : run.disagreements) ++by_engine[d.other];
      std::vector<std::string> others;
      if (run.threads > 1) others.push_back("antcd " + std::to_string(run.threads) + " threads");
      for (const char* e :
           {"FCL-OBBRSS", "FCL-OBBRSS all-contacts", "FCL-OBB", "FCL-OBB all-contacts", "Bullet"}) {
        others.emplace_back(e);
      }
      md << "Agreement with antcd (1 thread) over " << run.frames
         << " frames, object pairs per frame (all-contacts runs: also the colliding triangle "
            "pairs of each object pair): ";
      for (std::size_t e = 0; e < others.size(); ++e) {
        const std::size_t n = by_engine[others[e]];
        md << (e == 0 ? "" : "; ") << others[e] << " "
           << (n == 0 ? "identical on every frame" : std::to_string(n) + " disagreement(s)");
      }
      md << ".\n\n";
      if (!run.disagreements.empty()) {
        md << "| frame | objects | pair | antcd | other | other says | detail |\n";
        md << "| --- | --- | --- | --- | --- | --- | --- |\n";
        std::size_t shown = 0;
        for (const Disagreement& d : run.disagreements) {
          if (shown++ == 40) {
            md << "| … | | | | | | " << run.disagreements.size() - 40
               << " more in disagreements.csv |\n";
            break;
          }
          md << "| " << d.frame << " | " << d.object_a << ", " << d.object_b << " | " << d.name_a
             << " – " << d.name_b << " | " << (d.reference_says ? "collide" : "apart") << " | "
             << d.other << " | " << (d.other_says ? "collide" : "apart") << " | " << d.detail
             << " |\n";
        }
        md << "\n";
      }
      for (const Disagreement& d : run.disagreements) {
        all_disagreements.push_back(d);
        if (d.other.rfind("FCL", 0) == 0 || d.other.rfind("antcd", 0) == 0) {
          result.antcd_fcl_agree = false;
        } else {
          ++result.bullet_disagreements;
        }
      }
    }
    // Scene targets.
    for (const SceneRun& run : scene_runs) {
      const Series* ab = run.find("antcd exact", "boolean");
      const Series* fb = run.find("FCL-OBBRSS", "boolean");
      const Series* aa = run.find("antcd exact", "all contacts");
      const Series* fa = run.find("FCL-OBBRSS", "all contacts");
      auto measured = [](const Series* x, const Series* y) {
        return "antcd/FCL " + ratio(median(x->cpu_ms), median(y->cpu_ms)) + " CPU (" +
               num(median(x->cpu_ms)) + " vs " + num(median(y->cpu_ms)) + " ms), " +
               ratio(median(x->wall_ms), median(y->wall_ms)) + " wall";
      };
      const double rb = median(ab->cpu_ms) / median(fb->cpu_ms);
      targets.push_back({"scene `" + run.name + "`: exact boolean ≤ 1/3 of FCL-OBBRSS per frame",
                         measured(ab, fb), verdict(rb <= 1.0 / 3.0)});
      const double ra = median(aa->cpu_ms) / median(fa->cpu_ms);
      targets.push_back({"scene `" + run.name + "`: all contacts ≤ 1/2 of FCL-OBBRSS per frame",
                         measured(aa, fa), verdict(ra <= 0.5)});
    }
    for (const SceneRun& run : scene_runs) {
      if (run.name != "dense" && scene_runs.size() > 1) continue;
      const Series* ab = run.find("antcd exact", "boolean");
      const Series* at =
          run.find("antcd exact, " + std::to_string(run.threads) + " threads", "boolean");
      if (at == nullptr) {
        targets.push_back({"scene `" + run.name + "`: 2 threads ≥ 1.6× faster than 1",
                           "not run (--threads 1)", "not measured"});
      } else {
        const double speedup = median(ab->wall_ms) / median(at->wall_ms);
        targets.push_back({"scene `" + run.name + "`: " + std::to_string(run.threads) +
                               " threads ≥ 1.6× faster than 1",
                           ratio(median(ab->wall_ms), median(at->wall_ms)) + "×",
                           verdict(speedup >= 1.6)});
      }
    }
  }

  // ---- Pairs, build, memory ----
  if (options.run_pairs) {
    const std::vector<std::size_t> sizes =
        options.quick ? std::vector<std::size_t>{1'000, 10'000}
                      : std::vector<std::size_t>{1'000, 10'000, 100'000, 1'000'000};
    const std::size_t poses = options.quick ? 100 : 1000;
    std::vector<PairCell> cells;
    std::vector<BuildRow> builds;
    for (const std::size_t size : sizes) {
      log << "pairs: nominal " << size << " triangles, " << poses << " poses\n";
      auto c = run_pairs_at(size, poses, log);
      cells.insert(cells.end(), c.begin(), c.end());
      const int k = torus_k(size);
      const Mesh mesh = make_torus(1.0, 0.4, 2 * k, k);
      const int reps = options.quick ? 3 : (size >= 1'000'000 ? 3 : 5);
      builds.push_back(measure_build(size, mesh, reps));
      log << "  build: " << size << " done\n";
    }
    md << "## Mesh pairs: torus tumbling past torus\n\n";
    md << "Both models are the torus `make_torus(1, 0.4, 2k, k)` (4k² triangles; k = 16, 50, 158, "
          "500). A is fixed; for pose i of "
       << poses
       << " B turns by 4π·i/(P−1) about a tilted axis (two full turns) and sits at s·d from A, "
          "the direction d sweeping half a turn around A. s* is the contact distance along d "
          "(scan and bisection with antcd's boolean query, to ~1e-13 relative), R the bounding "
          "radius (1.4). Clearances: "
       << "deep " << clearance_rule(Clearance::Deep) << ", shallow "
       << clearance_rule(Clearance::Shallow) << ", touching " << clearance_rule(Clearance::Touching)
       << ", just separated " << clearance_rule(Clearance::Separated)
       << ". Times: medians over the poses of one query, µs; FCL is `BVHModel<OBBRSSd>`; "
          "boolean = first contact, all = every colliding triangle pair (FCL without contact "
          "points). Every pose compares both verdicts and the sets of colliding triangle "
          "pairs.\n\n";
    md << "| triangles | clearance | colliding poses antcd / FCL | triangle pairs antcd / FCL | "
          "boolean antcd µs | boolean FCL µs | antcd/FCL | all antcd µs | all FCL µs | antcd/FCL "
          "| disagreements |\n";
    md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    double worst_bool = 0;
    double worst_all = 0;
    std::string worst_bool_at;
    std::string worst_all_at;
    for (const PairCell& c : cells) {
      const double rb = median(c.antcd_bool_us) / median(c.fcl_bool_us);
      const double ra = median(c.antcd_all_us) / median(c.fcl_all_us);
      if (rb > worst_bool) {
        worst_bool = rb;
        worst_bool_at = std::to_string(c.triangles) + " " + clearance_name(c.clearance);
      }
      if (ra > worst_all) {
        worst_all = ra;
        worst_all_at = std::to_string(c.triangles) + " " + clearance_name(c.clearance);
      }
      md << "| " << c.triangles << " | " << clearance_name(c.clearance) << " | "
         << c.colliding_antcd << " / " << c.colliding_fcl << " of " << c.poses << " | "
         << c.triangle_pairs_antcd << " / " << c.triangle_pairs_fcl << " | "
         << num(median(c.antcd_bool_us)) << " | " << num(median(c.fcl_bool_us)) << " | "
         << ratio(median(c.antcd_bool_us), median(c.fcl_bool_us)) << " | "
         << num(median(c.antcd_all_us)) << " | " << num(median(c.fcl_all_us)) << " | "
         << ratio(median(c.antcd_all_us), median(c.fcl_all_us)) << " | " << c.disagreements
         << (c.first_disagreement.empty() ? "" : " (" + c.first_disagreement + ")") << " |\n";
      if (c.disagreements > 0) result.antcd_fcl_agree = false;
    }
    md << "\n";
    targets.push_back({"pairs: boolean faster than FCL at every size and clearance",
                       "worst antcd/FCL " + num(worst_bool) + " (" + worst_bool_at + ")",
                       verdict(worst_bool < 1)});
    targets.push_back({"pairs: all contacts faster than FCL at every size and clearance",
                       "worst antcd/FCL " + num(worst_all) + " (" + worst_all_at + ")",
                       verdict(worst_all < 1)});

    md << "## Hierarchy build and memory\n\n";
    md << "Build: median wall time of " << (options.quick ? "3" : "5 (1M: 3)")
       << " constructions (antcd `Model(mesh)`, the mesh copy made before the clock; FCL "
          "`beginModel` / `addSubModel` / `endModel`, default splitter). Memory: antcd "
          "`BvhStats::memory_bytes` (its mesh copy, nodes, leaf triangle indices and packed leaf "
          "vertices); FCL estimated as getNumBVs() × sizeof(BVNode<BV>) ("
       << sizeof(fcl::BVNode<fcl::OBBRSSd>) << " B for OBBRSS, " << sizeof(fcl::BVNode<fcl::OBBd>)
       << " B for OBB) + vertices × 24 B + triangles × 24 B (its primitive index array, 4 B per "
          "triangle, is not counted). antcd nodes are "
       << sizeof(BvhNode) << " B.\n\n";
    md << "| triangles | antcd build ms | FCL-OBBRSS ms | antcd/FCL | FCL-OBB ms | antcd nodes | "
          "FCL BVs | antcd B/triangle | FCL-OBBRSS B/triangle | antcd/FCL | FCL-OBB B/triangle "
          "|\n";
    md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    double worst_build = 0;
    double worst_mem = 0;
    for (const BuildRow& b : builds) {
      worst_build = std::max(worst_build, b.antcd_ms / b.fcl_obbrss_ms);
      worst_mem = std::max(worst_mem, b.antcd_bytes_per_tri / b.fcl_obbrss_bytes_per_tri);
      md << "| " << b.triangles << " | " << num(b.antcd_ms) << " | " << num(b.fcl_obbrss_ms)
         << " | " << ratio(b.antcd_ms, b.fcl_obbrss_ms) << " | " << num(b.fcl_obb_ms) << " | "
         << b.antcd_nodes << " | " << b.fcl_bvs << " | " << num(b.antcd_bytes_per_tri) << " | "
         << num(b.fcl_obbrss_bytes_per_tri) << " | "
         << ratio(b.antcd_bytes_per_tri, b.fcl_obbrss_bytes_per_tri) << " | "
         << num(b.fcl_obb_bytes_per_tri) << " |\n";
    }
    md << "\n";
    targets.push_back({"build ≤ 1/2 of FCL-OBBRSS's time at every size",
                       "worst antcd/FCL " + num(worst_build), verdict(worst_build <= 0.5)});
    targets.push_back({"memory per triangle ≤ FCL-OBBRSS's at every size",
                       "worst antcd/FCL " + num(worst_mem), verdict(worst_mem <= 1)});

    std::ostringstream pc;
    pc << "triangles,clearance,poses,colliding_antcd,colliding_fcl,triangle_pairs_antcd,"
          "triangle_pairs_fcl,bool_antcd_us,bool_fcl_us,all_antcd_us,all_fcl_us,disagreements\n";
    for (const PairCell& c : cells) {
      pc << c.triangles << ',' << clearance_name(c.clearance) << ',' << c.poses << ','
         << c.colliding_antcd << ',' << c.colliding_fcl << ',' << c.triangle_pairs_antcd << ','
         << c.triangle_pairs_fcl << ',' << median(c.antcd_bool_us) << ',' << median(c.fcl_bool_us)
         << ',' << median(c.antcd_all_us) << ',' << median(c.fcl_all_us) << ',' << c.disagreements
         << '\n';
    }
    result.csv.emplace_back("pairs.csv", pc.str());
    std::ostringstream bc;
    bc << "triangles,antcd_build_ms,fcl_obbrss_build_ms,fcl_obb_build_ms,antcd_bytes_per_tri,"
          "fcl_obbrss_bytes_per_tri,fcl_obb_bytes_per_tri\n";
    for (const BuildRow& b : builds) {
      bc << b.triangles << ',' << b.antcd_ms << ',' << b.fcl_obbrss_ms << ',' << b.fcl_obb_ms << ','
         << b.antcd_bytes_per_tri << ',' << b.fcl_obbrss_bytes_per_tri << ','
         << b.fcl_obb_bytes_per_tri << '\n';
    }
    result.csv.emplace_back("build.csv", bc.str());
  }

  // ---- Scale ----
  if (options.run_scale) {
    const WorkDir work(options.work_dir.empty() ? fs::path() : options.work_dir / "scale");
    struct Spec {
      std::size_t objects;
      std::size_t vertices;
    };
    const std::vector<Spec> specs =
        options.quick ? std::vector<Spec>{{90, 750}, {1000, 200}}
                      : std::vector<Spec>{{90, 750}, {1000, 1000}, {3000, 333}, {10000, 100}};
    const std::size_t frames = options.quick ? 5 : 30;
    std::vector<ScaleRow> rows;
    for (const Spec& s : specs) {
      log << "scale: " << s.objects << " objects, " << s.vertices << " vertices per mesh\n";
      rows.push_back(run_scale_row(s.objects, s.vertices, frames,
                                   work.path() / ("line_" + std::to_string(s.objects)), log));
    }
    md << "## Scale: objects vs candidate pairs vs time per frame (antcd exact, 1 thread)\n\n";
    md << "The production-line generator with `--objects N --vertices V` (V lowered with N to "
          "keep about 2 million triangles in all at 1 000 and more objects), "
       << frames
       << " frames each, boolean exact. Resident memory is the whole process's after the run "
          "(it includes what earlier sections left allocated).\n\n";
    md << "| objects | --vertices | triangles in all | distinct meshes | hierarchy MiB | build ms "
          "| "
          "candidate pairs / frame | colliding pairs / frame | median ms / frame | p99 ms | µs "
          "per candidate pair | RSS MiB |\n";
    md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    std::ostringstream sc;
    sc << "objects,vertices_option,triangles,models,frames,candidates_per_frame,colliding_per_"
          "frame,median_ms,p99_ms,build_ms,model_mib,rss_mib\n";
    for (const ScaleRow& r : rows) {
      md << "| " << r.objects << " | " << r.vertices_option << " | " << r.triangles << " | "
         << r.models << " | " << num(r.model_mib) << " | " << num(r.build_ms) << " | "
         << num(r.candidates) << " | " << num(r.colliding) << " | " << num(r.median_ms) << " | "
         << num(r.p99_ms) << " | "
         << (r.candidates > 0 ? num(1e3 * r.median_ms / r.candidates) : "—") << " | "
         << num(r.rss_mib) << " |\n";
      sc << r.objects << ',' << r.vertices_option << ',' << r.triangles << ',' << r.models << ','
         << r.frames << ',' << r.candidates << ',' << r.colliding << ',' << r.median_ms << ','
         << r.p99_ms << ',' << r.build_ms << ',' << r.model_mib << ',' << r.rss_mib << '\n';
    }
    md << "\nPeak resident memory of the process: " << num(peak_rss_mib()) << " MiB.\n\n";
    result.csv.emplace_back("scale.csv", sc.str());
  }

  // ---- Targets ----
  if (!targets.empty()) {
    md << "## Targets (single thread unless stated)\n\n| target | measured | verdict |\n"
          "| --- | --- | --- |\n";
    for (const Target& t : targets) {
      md << "| " << t.what << " | " << t.measured << " | " << t.verdict << " |\n";
    }
    md << "\n";
  }
  md << "Agreement: "
     << (result.antcd_fcl_agree ? "antcd and FCL agreed on every frame and pose."
                                : "antcd and FCL DISAGREED (see above).")
     << " Bullet disagreements with antcd: " << result.bullet_disagreements << ".\n\n";
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - total_start).count();
  md << "Run time " << num(total_s) << " s; load average " << load_start << " at the start, "
     << load_average() << " at the end.\n";

  if (!scene_runs.empty()) {
    std::ostringstream sc;
    sc << "scene,engine,query,frames,candidates_per_frame,median_ms,p99_ms,mean_ms,median_cpu_"
          "ms\n";
    for (const SceneRun& run : scene_runs) {
      for (const Series& s : run.series) {
        sc << run.name << ',' << csv_escape(s.engine) << ',' << csv_escape(s.query) << ','
           << run.frames << ',' << s.candidates / static_cast<double>(run.frames) << ','
           << median(s.wall_ms) << ',' << p99(s.wall_ms) << ',' << mean(s.wall_ms) << ','
           << median(s.cpu_ms) << '\n';
      }
    }
    result.csv.emplace_back("scenes.csv", sc.str());
    std::ostringstream dc;
    dc << "scene,frame,object_a,object_b,name_a,name_b,antcd,engine,engine_says,detail\n";
    for (std::size_t s = 0; s < scene_runs.size(); ++s) {
      for (const Disagreement& d : scene_runs[s].disagreements) {
        dc << d.scene << ',' << d.frame << ',' << d.object_a << ',' << d.object_b << ','
           << csv_escape(d.name_a) << ',' << csv_escape(d.name_b) << ','
           << (d.reference_says ? "collide" : "apart") << ',' << csv_escape(d.other) << ','
           << (d.other_says ? "collide" : "apart") << ',' << csv_escape(d.detail) << '\n';
      }
    }
    result.csv.emplace_back("disagreements.csv", dc.str());
  }
  result.report_markdown = md.str();
  return result;
}

}  // namespace antcd::experiments
