#include "peers/pairs.hpp"

#include "peers/adapters/fcl.hpp"
#include "peers/adapters/peer_mesh.hpp"
#include "peers/stopwatch.hpp"

#include <antcd/collide.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

namespace antcd::experiments::peers_bench {

using TrianglePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

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

/// The pair protocol at one size: torus A fixed, torus B tumbling past it. For pose i of P
/// (t = i / (P - 1)) B is rotated by 4πt about a fixed tilted axis (two full turns) and placed at
/// s·d(t) from A, d(t) sweeping half a turn around A (from −y through +x to +y, 0.35 up). s* is the
/// largest s at which the two touch (scan inward from the bounding spheres' contact, then
/// bisection to ~1e-13 relative); each clearance class places B from s* (clearance_rule).
std::vector<PairCell> run_pairs_at(std::size_t size, std::size_t poses, std::ostream& log) {
  const Mesh mesh = peers::benchmark_torus(size);
  const Model model(mesh);
  const peers::PeerMesh pm = peers::peer_mesh(mesh);
  const auto fcl_model = peers::build_fcl<fcl::OBBRSSd>(pm);
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
  const fcl::CollisionRequestd fcl_all(peers::kFclAllContacts, false);
  const fcl::Transform3d fcl_a = peers::to_fcl(pose_a);
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
      const fcl::Transform3d fcl_b = peers::to_fcl(b);

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

}  // namespace antcd::experiments::peers_bench
