// A program of a user of the installed package: the core alone (antcd::antcd), plus antcd::io and
// antcd::random when built with ANTCD_CONSUMER_FULL (consumer_full.cpp).
//
// Besides a few checks it prints a digest of answers from every parallel path of the core (a
// hierarchy build past the task threshold, a World's set_poses / candidate pairs / collide_all past
// theirs, distance, point queries over many blocks). `--write-digest FILE` stores it;
// `--expect-digest FILE` fails unless this build gives the same digest: the consumer_core_serial
// test builds the core without oneTBB and compares with the oneTBB build's digest.
#include <antcd/collide.hpp>
#include <antcd/distance.hpp>
#include <antcd/error.hpp>
#include <antcd/mesh.hpp>
#include <antcd/points.hpp>
#include <antcd/version.hpp>
#include <antcd/world.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#if defined(ANTCD_CONSUMER_FULL)
bool full_checks();  // consumer_full.cpp
#endif

namespace {

using namespace antcd;

// FNV-1a over the bytes of each value.
struct Digest {
  std::uint64_t h = 1469598103934665603ULL;
  template <class T>
  void add(const T& value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (const unsigned char b : bytes) h = (h ^ b) * 1099511628211ULL;
  }
  void add(const Vec3& v) {
    add(v.x());
    add(v.y());
    add(v.z());
  }
};

// A fixed pseudo-random sequence in [0, 1) (no <random>: its distributions differ by library).
struct Sequence {
  std::uint64_t state = 0x853c49e6748fea9bULL;
  double next() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  }
};

bool basic_checks() {
  const Model a(make_box(Vec3(1, 1, 1)));
  const Model b(make_sphere(0.5));
  const Transform near = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(1.2, 0, 0));
  const Transform far = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(3, 0, 0));
  const bool touching = collide(a, Transform::identity(), b, near).colliding;
  const bool apart = collide(a, Transform::identity(), b, far).colliding;
  bool refused = false;
  try {
    (void)make_sphere(-1);
  } catch (const Error&) {  // ArgumentError, caught through the documented base
    refused = true;
  }
  std::printf("antcd %s: touching %d, apart %d, bad argument refused %d\n", kVersion, touching,
              apart, refused);
  return touching && !apart && refused && std::strlen(kVersion) > 0;
}

std::uint64_t parallel_paths_digest() {
  Digest d;
  Sequence seq;
  // Two models of 2 * 256 * 96 = 49152 triangles: built by tasks (more than 16384 triangles).
  const auto big = std::make_shared<const Model>(make_torus(1.0, 0.3, 256, 96));
  const auto ball = std::make_shared<const Model>(make_sphere(0.6, 160, 80));
  // The hierarchy itself: same nodes, same leaf order.
  d.add(big->nodes().size());
  for (const std::uint32_t t : big->leaf_triangles()) d.add(t);
  const Transform pose_b =
      Transform::from_axis_angle(Vec3(1, 2, 3).normalized(), 0.7, Vec3(0.9, 0.2, 0.1));
  CollisionRequest all;
  all.all_contacts = true;
  const CollisionResult hit = collide(*big, Transform::identity(), *ball, pose_b, all);
  d.add(hit.contacts.size());
  const DistanceResult gap =
      distance(*big, Transform::identity(), *ball,
               Transform::from_axis_angle(Vec3::UnitX(), 0.3, Vec3(0, 0, 2)));
  d.add(gap.distance);
  d.add(gap.point_a);

  // 3000 points: 47 blocks of 64, spread over tasks.
  std::vector<Vec3> points;
  for (int i = 0; i < 3000; ++i) {
    points.emplace_back(3 * seq.next() - 1.5, 3 * seq.next() - 1.5, seq.next() - 0.5);
  }
  for (const std::uint8_t in : contains(*big, Transform::identity(), points)) d.add(in);
  for (const PointDistance& p : signed_distance(*ball, pose_b, points).points) {
    d.add(p.distance);
    d.add(p.triangle);
  }

  // A World of 3000 small boxes: set_poses past its batch threshold, pairs and narrow phase past
  // theirs.
  World world;
  const auto box = std::make_shared<const Model>(make_box(Vec3(0.5, 0.5, 0.5)));
  std::vector<ObjectId> ids;
  std::vector<Transform> poses;
  for (int i = 0; i < 3000; ++i) {
    ids.push_back(world.add(box, Transform::identity()));
    poses.push_back(Transform::from_axis_angle(
        Vec3(seq.next() + 0.1, seq.next(), seq.next()).normalized(), 6 * seq.next(),
        Vec3(40 * seq.next(), 40 * seq.next(), 4 * seq.next())));
  }
  world.set_poses(ids, poses);
  for (const ObjectPair& p : world.candidate_pairs()) {
    d.add(p.a.slot);
    d.add(p.b.slot);
  }
  for (const PairContacts& p : world.collide_all(all)) {
    d.add(p.a.slot);
    d.add(p.b.slot);
    d.add(p.contacts.size());
  }
  return d.h;
}

}  // namespace

int main(int argc, char** argv) {
  bool ok = basic_checks();
#if defined(ANTCD_CONSUMER_FULL)
  ok = full_checks() && ok;
#endif
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx",
                static_cast<unsigned long long>(parallel_paths_digest()));
  std::printf("digest of the parallel paths' answers: %s\n", digest);
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--write-digest") {
      std::ofstream(argv[i + 1]) << digest << "\n";
    } else if (option == "--expect-digest") {
      std::ifstream in(argv[i + 1]);
      std::string expected;
      in >> expected;
      if (expected != digest) {
        std::printf("error: digest %s differs from %s's %s\n", digest, argv[i + 1],
                    expected.c_str());
        ok = false;
      }
    } else {
      std::printf("error: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  return ok ? 0 : 1;
}
