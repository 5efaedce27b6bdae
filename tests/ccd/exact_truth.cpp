// Tests only: exact rational truth for translation-structured CCD queries (see exact_truth.hpp).
#include "ccd/exact_truth.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace antcd::test {
namespace {

using Q = mpq_class;
using QVec = std::array<Q, 3>;

QVec exact(const Vec3& v) { return {Q(v.x()), Q(v.y()), Q(v.z())}; }
QVec sub(const QVec& a, const QVec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
QVec add(const QVec& a, const QVec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
QVec scale(const QVec& a, const Q& s) { return {a[0] * s, a[1] * s, a[2] * s}; }
QVec cross(const QVec& a, const QVec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Q dot(const QVec& a, const QVec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
bool is_zero(const QVec& a) { return sgn(a[0]) == 0 && sgn(a[1]) == 0 && sgn(a[2]) == 0; }
int orient3d(const QVec& a, const QVec& b, const QVec& c, const QVec& d) {
  return sgn(dot(cross(sub(b, a), sub(c, a)), sub(d, a)));
}

/// Index of the largest |component| of n (n != 0).
int dominant_axis(const QVec& n) {
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (abs(n[static_cast<std::size_t>(i)]) > abs(n[static_cast<std::size_t>(k)])) k = i;
  }
  return k;
}

struct Q2 {
  Q x, y;
};
Q2 project(const QVec& p, int drop) {
  const int i = (drop + 1) % 3;
  const int j = (drop + 2) % 3;
  return {p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)]};
}
int orient2d(const Q2& a, const Q2& b, const Q2& c) {
  return sgn((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
/// c collinear with a, b: is it within the segment's bounding box (hence on the segment)?
bool on_segment(const Q2& a, const Q2& b, const Q2& c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}
bool segments_meet_2d(const Q2& p, const Q2& q, const Q2& r, const Q2& s) {
  const int d1 = orient2d(r, s, p);
  const int d2 = orient2d(r, s, q);
  const int d3 = orient2d(p, q, r);
  const int d4 = orient2d(p, q, s);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && on_segment(r, s, p)) || (d2 == 0 && on_segment(r, s, q)) ||
         (d3 == 0 && on_segment(p, q, r)) || (d4 == 0 && on_segment(p, q, s));
}

/// Closed segments [p, q] and [r, s] in 3D share a point.
bool segments_meet(const QVec& p, const QVec& q, const QVec& r, const QVec& s) {
  if (orient3d(p, q, r, s) != 0) return false;
  // Coplanar: a normal of the common plane, or the line's direction when all are collinear.
  const std::array<QVec, 3> dirs = {sub(q, p), sub(s, r), sub(r, p)};
  QVec normal = {0, 0, 0};
  for (std::size_t i = 0; i < 3 && is_zero(normal); ++i) {
    for (std::size_t j = i + 1; j < 3 && is_zero(normal); ++j) normal = cross(dirs[i], dirs[j]);
  }
  if (is_zero(normal)) normal = cross(sub(s, p), sub(q, r));
  int drop = 0;
  if (!is_zero(normal)) {
    drop = dominant_axis(normal);
  } else {
    // All four points on one line (or equal): drop an axis the line does not run along.
    QVec dir = {0, 0, 0};
    for (const QVec& d : {sub(q, p), sub(s, r), sub(r, p), sub(s, p)}) {
      if (!is_zero(d)) dir = d;
    }
    if (is_zero(dir)) return true;  // all the same point
    drop = (dominant_axis(dir) + 1) % 3;
  }
  return segments_meet_2d(project(p, drop), project(q, drop), project(r, drop), project(s, drop));
}

/// x coplanar with the non-degenerate triangle (a, b, c) with normal n: inside or on it.
bool in_triangle(const QVec& x, const QVec& a, const QVec& b, const QVec& c, const QVec& n) {
  return sgn(dot(cross(sub(b, a), sub(x, a)), n)) >= 0 &&
         sgn(dot(cross(sub(c, b), sub(x, b)), n)) >= 0 &&
         sgn(dot(cross(sub(a, c), sub(x, c)), n)) >= 0;
}

/// Closed segment [p, q] and closed triangle (a, b, c) share a point; `first` (optional) receives
/// the segment parameter of the meeting point when the segment crosses the plane transversally.
bool segment_meets_triangle(const QVec& p, const QVec& q, const QVec& a, const QVec& b,
                            const QVec& c, Q* first = nullptr) {
  const QVec n = cross(sub(b, a), sub(c, a));
  if (is_zero(n)) {
    return segments_meet(p, q, a, b) || segments_meet(p, q, b, c) || segments_meet(p, q, a, c);
  }
  const Q op = dot(n, sub(p, a));
  const Q oq = dot(n, sub(q, a));
  if (sgn(op) * sgn(oq) > 0) return false;
  if (sgn(op) == 0 && sgn(oq) == 0) {
    return in_triangle(p, a, b, c, n) || in_triangle(q, a, b, c, n) || segments_meet(p, q, a, b) ||
           segments_meet(p, q, b, c) || segments_meet(p, q, a, c);
  }
  const Q s = op / (op - oq);
  if (!in_triangle(add(p, scale(sub(q, p), s)), a, b, c, n)) return false;
  if (first != nullptr) *first = s;
  return true;
}

bool same(const QVec& a, const QVec& b) { return a == b; }

struct Relative {
  QVec p, q;                  // segment of the relative motion
  std::array<QVec, 4> shape;  // triangle (3 used) or parallelogram corners at t = 0
  bool parallelogram = false;
};

std::optional<Relative> relative_motion(const CcdQuery& query) {
  std::array<QVec, 4> x0;
  std::array<QVec, 4> d;
  for (std::size_t k = 0; k < 4; ++k) {
    x0[k] = exact(query.at_t0[k]);
    d[k] = sub(exact(query.at_t1[k]), x0[k]);
  }
  Relative r;
  if (query.kind == CcdKind::VertexFace) {
    if (!same(d[1], d[2]) || !same(d[1], d[3])) return std::nullopt;
    r.p = x0[0];
    r.q = add(x0[0], sub(d[0], d[1]));
    r.shape = {x0[1], x0[2], x0[3], x0[3]};
    return r;
  }
  if (!same(d[0], d[1]) || !same(d[2], d[3])) return std::nullopt;
  const QVec m = sub(d[0], d[2]);  // a relative to b
  r.p = x0[2];
  r.q = x0[3];
  r.shape = {x0[0], x0[1], add(x0[1], m), add(x0[0], m)};
  r.parallelogram = true;
  return r;
}

}  // namespace

std::optional<bool> ccd_truth(const CcdQuery& query) {
  const auto r = relative_motion(query);
  if (!r) return std::nullopt;
  const auto& s = r->shape;
  if (!r->parallelogram) return segment_meets_triangle(r->p, r->q, s[0], s[1], s[2]);
  return segment_meets_triangle(r->p, r->q, s[0], s[1], s[2]) ||
         segment_meets_triangle(r->p, r->q, s[0], s[2], s[3]);
}

std::optional<double> ccd_first_time_upper(const CcdQuery& query) {
  if (query.kind != CcdKind::VertexFace) return std::nullopt;  // edge–edge: b is the segment
  const auto r = relative_motion(query);
  if (!r) return std::nullopt;
  const auto& s = r->shape;
  const QVec n = cross(sub(s[1], s[0]), sub(s[2], s[0]));
  if (is_zero(n) || (sgn(dot(n, sub(r->p, s[0]))) == 0 && sgn(dot(n, sub(r->q, s[0]))) == 0)) {
    return std::nullopt;
  }
  Q first;
  if (!segment_meets_triangle(r->p, r->q, s[0], s[1], s[2], &first)) return std::nullopt;
  // The exact time rounded up to a double, so toi <= t* is checked without loss.
  double up = first.get_d();
  if (Q(up) < first) up = std::nextafter(up, 2.0);
  return up;
}

// ---- corpus ----------------------------------------------------------------------------------

namespace {

CcdQuery vf(std::string name, Vec3 v0, Vec3 v1, std::array<Vec3, 3> face, Vec3 w = Vec3::Zero()) {
  CcdQuery q;
  q.name = std::move(name);
  q.kind = CcdKind::VertexFace;
  q.at_t0 = {v0, face[0], face[1], face[2]};
  q.at_t1 = {v1, face[0] + w, face[1] + w, face[2] + w};
  return q;
}

CcdQuery ee(std::string name, std::array<Vec3, 2> a, Vec3 wa, std::array<Vec3, 2> b, Vec3 wb) {
  CcdQuery q;
  q.name = std::move(name);
  q.kind = CcdKind::EdgeEdge;
  q.at_t0 = {a[0], a[1], b[0], b[1]};
  q.at_t1 = {a[0] + wa, a[1] + wa, b[0] + wb, b[1] + wb};
  return q;
}

/// The same query with every point drifting by `drift` over the step and shifted by `offset`.
CcdQuery moved(const CcdQuery& q, const std::string& suffix, const Vec3& drift,
               const Vec3& offset) {
  CcdQuery out = q;
  out.name += suffix;
  for (std::size_t k = 0; k < 4; ++k) {
    out.at_t0[k] += offset;
    out.at_t1[k] += offset + drift;
  }
  return out;
}

}  // namespace

std::vector<CcdQuery> degenerate_corpus() {
  const std::array<Vec3, 3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const double h = 0x1p-40;  // a hair: far below any tolerance, exact in double
  const Vec3 z = Vec3::Zero();
  std::vector<CcdQuery> base = {
      // Spikes through the face, its cracks (edges), corners and holes next to them.
      vf("spike_interior", {0.25, 0.25, 1}, {0.25, 0.25, -1}, tri),
      vf("spike_edge_crack", {0.5, 0, 1}, {0.5, 0, -1}, tri),
      vf("spike_hypotenuse", {0.5, 0.5, 1}, {0.5, 0.5, -1}, tri),
      vf("spike_corner", {0, 0, 1}, {0, 0, -1}, tri),
      vf("spike_hole_beside_edge", {0.5, -h, 1}, {0.5, -h, -1}, tri),
      vf("spike_hole_beside_corner", {1 + h, 0, 1}, {1 + h, 0, -1}, tri),
      vf("spike_hole_beyond_hypotenuse", {0.5 + h, 0.5, 1}, {0.5 + h, 0.5, -1}, tri),
      vf("spike_stops_short", {0.25, 0.25, 1}, {0.25, 0.25, h}, tri),
      // Sliding spikes (in the face's plane) and the cube cliff (along an edge line).
      vf("slide_across", {-1, 0.25, 0}, {2, 0.25, 0}, tri),
      vf("slide_beside", {-1, -h, 0}, {2, -h, 0}, tri),
      vf("slide_along_edge", {-1, 0, 0}, {2, 0, 0}, tri),
      vf("cliff_reaches_corner_at_1", {-1, 0, 0}, {0, 0, 0}, tri),
      vf("cliff_short_of_corner", {-1, 0, 0}, {-h, 0, 0}, tri),
      vf("slide_above", {-1, 0.25, h}, {2, 0.25, h}, tri),
      // Contact at the ends of the step and without motion.
      vf("touch_at_t0", {0.25, 0.25, 0}, {0.25, 0.25, 1}, tri),
      vf("touch_at_t1", {0.25, 0.25, 1}, {0.25, 0.25, 0}, tri),
      vf("rest_on_face", {0.25, 0.25, 0}, {0.25, 0.25, 0}, tri),
      vf("rest_above", {0.25, 0.25, h}, {0.25, 0.25, h}, tri),
      vf("rest_on_corner", {1, 0, 0}, {1, 0, 0}, tri),
      // The face moves onto a resting vertex.
      vf("face_hits_vertex", {0.25, 0.25, 0.5}, {0.25, 0.25, 0.5}, tri, {0, 0, 1}),
      vf("face_misses_vertex", {0.25, 0.25, 0.5 + h}, {0.25, 0.25, 0.5 + h}, tri, {0, 0, 0.5}),
      // Edges: wedges crossing, parallel, collinear, coplanar, internal edges (shared ends).
      ee("wedge_cross", {Vec3(-1, 0, 1), Vec3(1, 0, 1)}, {0, 0, -2},
         {Vec3(0, -1, 0), Vec3(0, 1, 0)}, z),
      ee("wedge_miss_by_hair", {Vec3(-1, 0, 1), Vec3(1, 0, 1)}, {0, 0, -1 + h},
         {Vec3(0, -1, 0), Vec3(0, 1, 0)}, z),
      ee("wedge_end_touch", {Vec3(-1, 0, 1), Vec3(0, 0, 1)}, {0, 0, -2},
         {Vec3(0, 0, 0), Vec3(0, 1, 0)}, z),
      ee("wedge_end_miss", {Vec3(-1, 0, 1), Vec3(-h, 0, 1)}, {0, 0, -2},
         {Vec3(0, 0, 0), Vec3(0, 1, 0)}, z),
      ee("parallel_overlap", {Vec3(0, 0, 1), Vec3(1, 0, 1)}, {0, 0, -2},
         {Vec3(0.5, 0, 0), Vec3(2, 0, 0)}, z),
      ee("parallel_disjoint", {Vec3(0, 0, 1), Vec3(1, 0, 1)}, {0, 0, -2},
         {Vec3(1 + h, 0, 0), Vec3(2, 0, 0)}, z),
      ee("parallel_end_to_end", {Vec3(0, 0, 1), Vec3(1, 0, 1)}, {0, 0, -2},
         {Vec3(1, 0, 0), Vec3(2, 0, 0)}, z),
      ee("parallel_offset", {Vec3(0, h, 1), Vec3(1, h, 1)}, {0, 0, -2},
         {Vec3(0, 0, 0), Vec3(1, 0, 0)}, z),
      ee("coplanar_sweep_hit", {Vec3(0, 1, 0), Vec3(1, 1, 0)}, {0, -2, 0},
         {Vec3(0.5, 0, 0), Vec3(0.5, -1, 0)}, z),
      ee("coplanar_sweep_miss", {Vec3(0, 1, 0), Vec3(1, 1, 0)}, {0, -2, 0},
         {Vec3(1 + h, 0, 0), Vec3(2, 0, 0)}, z),
      ee("collinear_slide_hit", {Vec3(-2, 0, 0), Vec3(-1, 0, 0)}, {1, 0, 0},
         {Vec3(0, 0, 0), Vec3(1, 0, 0)}, z),
      ee("collinear_slide_miss", {Vec3(-2, 0, 0), Vec3(-1, 0, 0)}, {1 - h, 0, 0},
         {Vec3(0, 0, 0), Vec3(1, 0, 0)}, z),
      ee("internal_edge_shared_end", {Vec3(0, 0, 0), Vec3(1, 0, 0)}, {0, 0, 1},
         {Vec3(0, 0, 0), Vec3(0, 1, 0)}, {0, 0, 1}),
      ee("touch_at_t0", {Vec3(-1, 0, 0), Vec3(1, 0, 0)}, {0, 0, 1}, {Vec3(0, -1, 0), Vec3(0, 1, 0)},
         z),
      ee("touch_at_t1", {Vec3(-1, 0, 1), Vec3(1, 0, 1)}, {0, 0, -1},
         {Vec3(0, -1, 0), Vec3(0, 1, 0)}, z),
      ee("rest_crossing", {Vec3(-1, 0, 0), Vec3(1, 0, 0)}, z, {Vec3(0, -1, 0), Vec3(0, 1, 0)}, z),
      ee("rest_apart", {Vec3(-1, 0, h), Vec3(1, 0, h)}, z, {Vec3(0, -1, 0), Vec3(0, 1, 0)}, z),
      ee("both_move_meet", {Vec3(-1, 0, 1), Vec3(1, 0, 1)}, {0, 0, -1},
         {Vec3(0, -1, -1), Vec3(0, 1, -1)}, {0, 0, 1}),
      ee("degenerate_edge_point", {Vec3(0, 0, 1), Vec3(0, 0, 1)}, {0, 0, -2},
         {Vec3(-1, 0, 0), Vec3(1, 0, 0)}, z),
  };
  std::vector<CcdQuery> out = base;
  for (const CcdQuery& q : base) out.push_back(moved(q, "+drift", Vec3(3, -2, 0.5), Vec3::Zero()));
  for (const CcdQuery& q : base) {
    out.push_back(moved(q, "+far", Vec3(0.125, 0.25, -0.5), Vec3(1024, -512, 256)));
  }
  return out;
}

std::vector<CcdQuery> near_miss_queries(CcdKind kind, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // Coordinates are integers times 2^-10 (|x| <= 4), weights multiples of 2^-8, nudges multiples
  // of 2^-40: every sum below is exact in double.
  auto coord = [&] {
    return std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(-1024, 1024)(rng)),
                      -10);
  };
  auto point = [&] { return Vec3(coord(), coord(), coord()); };
  auto weight = [&] {
    return std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(0, 256)(rng)), -8);
  };
  auto nudge = [&] {
    return Vec3(
        std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(-4, 4)(rng)), -40),
        std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(-4, 4)(rng)), -40),
        std::ldexp(static_cast<double>(std::uniform_int_distribution<int>(-4, 4)(rng)), -40));
  };
  std::vector<CcdQuery> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const int aim = static_cast<int>(rng() % 3);  // 0: inside, 1: edge, 2: corner
    const Vec3 dir = point();
    const Scalar when = weight();  // contact time of the un-nudged motion
    const Vec3 drift = point();
    if (kind == CcdKind::VertexFace) {
      const std::array<Vec3, 3> tri = {point(), point(), point()};
      Scalar wu = weight();
      Scalar wv = aim == 0 ? std::ldexp(std::floor(std::ldexp((1 - wu) * weight(), 8)), -8) : 0;
      if (aim == 2) wu = 0;
      const Vec3 target = tri[0] + wu * (tri[1] - tri[0]) + wv * (tri[2] - tri[0]);
      const Vec3 v0 = target - when * dir + nudge();
      CcdQuery q = vf("near_vf_" + std::to_string(i), v0, v0 + dir, tri);
      out.push_back(moved(q, "", drift, Vec3::Zero()));
    } else {
      const std::array<Vec3, 2> a = {point(), point()};
      const std::array<Vec3, 2> b0 = {point(), point()};
      // Put a point of b (weight wb) onto a point of a (weight wa) at time `when`.
      const Scalar wa = aim == 2 ? 0 : weight();
      const Scalar wb = aim == 0 ? weight() : 0;
      const Vec3 pa = a[0] + wa * (a[1] - a[0]);
      const Vec3 pb = b0[0] + wb * (b0[1] - b0[0]);
      const Vec3 shift = pa - pb - when * dir + nudge();  // b at time `when` meets pa (un-nudged)
      const std::array<Vec3, 2> b = {b0[0] + shift, b0[1] + shift};
      CcdQuery q = ee("near_ee_" + std::to_string(i), a, Vec3::Zero(), b, dir);
      out.push_back(moved(q, "", drift, Vec3::Zero()));
    }
  }
  return out;
}

std::string to_rational_csv(const std::vector<CcdQuery>& queries) {
  std::ostringstream out;
  for (const CcdQuery& q : queries) {
    const bool truth = ccd_truth(q).value_or(false);
    for (const auto* set : {&q.at_t0, &q.at_t1}) {
      for (const Vec3& p : *set) {
        for (int c = 0; c < 3; ++c) {
          const Q x(p[c]);
          out << x.get_num().get_str() << ',' << x.get_den().get_str() << (c < 2 ? "," : "");
        }
        out << ',' << (truth ? 1 : 0) << '\n';
      }
    }
  }
  return out.str();
}

}  // namespace antcd::test
