#include "peers/scenes.hpp"

#include "peers/adapters/bullet.hpp"
#include "peers/adapters/fcl.hpp"
#include "peers/adapters/scene_objects.hpp"
#include "peers/stopwatch.hpp"

#include <antcd/collide.hpp>

#include <algorithm>
#include <array>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace antcd::experiments::peers_bench {
namespace {

using peers::BulletScene;
using peers::FclScene;
using peers::SceneObjects;
using peers::TriContact;

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

template <class F>
void timed(Series& s, F&& f) {
  const Stopwatch sw;
  const std::size_t candidates = f();
  s.cpu_ms.push_back(sw.cpu_ms());
  s.process_ms.push_back(sw.process_ms());
  s.wall_ms.push_back(sw.wall_ms());
  s.candidates += static_cast<double>(candidates);
}

}  // namespace

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

}  // namespace antcd::experiments::peers_bench

namespace antcd::experiments {

SceneCheck check_scene(const Scene& scene, std::string_view name, std::size_t frames,
                       bool with_bullet) {
  using namespace peers_bench;
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

}  // namespace antcd::experiments
