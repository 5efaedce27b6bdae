// Primitive CCD with min_separation > 0 (antcd::ccd::vertex_face / edge_edge) against exact
// distances (CGAL's exact constructions kernel), and grazing queries recorded from a flexible
// scene.
//
// Truth. The queries have translational relative motion (the face's corners, or each edge's two
// ends, share one displacement), so the relative motion of the vertex (vertex-face) is a segment
// and that of edge a against edge b sweeps a parallelogram: the query comes within s at some
// t in [0, T] exactly when that segment (parallelogram), cut at T, is within s of the face (edge
// b). Distances of segments and triangles are taken exactly: 0 when they meet, else the least of
// the endpoint-triangle and segment-edge distances.
#include <antcd/ccd.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace antcd {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using P3 = K::Point_3;
using V3 = K::Vector_3;
using Seg = K::Segment_3;
using Tri = K::Triangle_3;

P3 to_cgal(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

FT squared_distance(const Seg& s, const Tri& t) {
  if (CGAL::do_intersect(s, t)) return FT(0);
  FT d = CGAL::min(CGAL::squared_distance(s.source(), t), CGAL::squared_distance(s.target(), t));
  for (int k = 0; k < 3; ++k) {
    d = CGAL::min(d, CGAL::squared_distance(s, Seg(t.vertex(k), t.vertex((k + 1) % 3))));
  }
  return d;
}

/// A translation-structured query: relative motion `rel` of the vertex (edge a) against the face
/// (edge b), which holds still in the relative frame.
struct Query {
  bool edge_edge = false;
  std::array<Vec3, 4> at_t0;
  std::array<Vec3, 4> at_t1;
};

/// Exact squared distance over t in [0, T] (T a double in [0, 1], exact as a rational).
FT squared_distance_until(const Query& q, double T) {
  const std::array<P3, 4> p0 = {to_cgal(q.at_t0[0]), to_cgal(q.at_t0[1]), to_cgal(q.at_t0[2]),
                                to_cgal(q.at_t0[3])};
  const std::array<P3, 4> p1 = {to_cgal(q.at_t1[0]), to_cgal(q.at_t1[1]), to_cgal(q.at_t1[2]),
                                to_cgal(q.at_t1[3])};
  if (!q.edge_edge) {
    const V3 rel = (p1[0] - p0[0]) - (p1[1] - p0[1]);
    const Tri face(p0[1], p0[2], p0[3]);
    if (T == 0) return CGAL::squared_distance(p0[0], face);
    return squared_distance(Seg(p0[0], p0[0] + FT(T) * rel), face);
  }
  const V3 rel = (p1[0] - p0[0]) - (p1[2] - p0[2]);
  const Seg b(p0[2], p0[3]);
  if (T == 0) return CGAL::squared_distance(Seg(p0[0], p0[1]), b);
  const V3 r = FT(T) * rel;
  return CGAL::min(squared_distance(b, Tri(p0[0], p0[1], p0[1] + r)),
                   squared_distance(b, Tri(p0[0], p0[1] + r, p0[0] + r)));
}

Vec3 random_point(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

/// Random translation-structured queries; a third of the edge-edge ones have parallel edges.
Query random_query(std::mt19937_64& rng, bool edge_edge) {
  Query q;
  q.edge_edge = edge_edge;
  for (Vec3& p : q.at_t0) p = random_point(rng, 1);
  const Vec3 w0 = random_point(rng, 1.5);
  const Vec3 w1 = random_point(rng, 0.5);
  if (edge_edge && rng() % 3 == 0) q.at_t0[3] = q.at_t0[2] + 0.5 * (q.at_t0[1] - q.at_t0[0]);
  for (std::size_t k = 0; k < 4; ++k) {
    const bool first = edge_edge ? k < 2 : k == 0;
    q.at_t1[k] = q.at_t0[k] + (first ? w0 : w1);
  }
  return q;
}

ccd::PrimitiveResult run(const Query& q, double sep, double tol) {
  return q.edge_edge ? ccd::edge_edge(q.at_t0, q.at_t1, sep, tol)
                     : ccd::vertex_face(q.at_t0, q.at_t1, sep, tol);
}

TEST(CcdSeparation, NoFalseNegativeNorLateHitAgainstExactDistances) {
  std::mt19937_64 rng(20261203);
  // Separations at the exact least distance d, and a relative step from it either way.
  const std::array<double, 9> offsets = {0, 1e-15, -1e-15, 1e-9, -1e-9, 1e-4, -1e-4, 0.05, -0.05};
  int queries = 0, positives = 0, false_positives = 0, exhausted = 0;
  for (int n = 0; n < 240; ++n) {
    const Query q = random_query(rng, n % 2 == 1);
    const FT d2 = squared_distance_until(q, 1);
    const double d = std::sqrt(CGAL::to_double(d2));
    if (!(d > 1e-3)) continue;  // a contact at separation 0: not this test's subject
    for (const double offset : offsets) {
      const double sep = d * (1 + offset);
      const double tol = 1e-6;
      const ccd::PrimitiveResult r = run(q, sep, tol);
      const bool truth = d2 <= FT(sep) * FT(sep);
      ++queries;
      positives += truth ? 1 : 0;
      exhausted += r.budget_exhausted ? 1 : 0;
      const std::string name = std::string(q.edge_edge ? "edge-edge " : "vertex-face ") +
                               std::to_string(n) + " offset " + std::to_string(offset);
      if (truth) {
        EXPECT_TRUE(r.hit) << name << ": contact missed";
      }
      if (!r.hit) continue;
      false_positives += truth ? 0 : 1;
      // Never late: nothing closer than the separation before toi (continuity: at toi = t* the
      // distance is the separation).
      if (r.toi > 0) {
        EXPECT_GE(squared_distance_until(q, r.toi), FT(sep) * FT(sep)) << name << ": toi " << r.toi;
      }
      if (!r.tolerance_decided) {
        EXPECT_TRUE(truth) << name << ": a proven hit must come within the separation";
      }
      // The tolerance's reach: within sep + 3W by toi + tolerance (Euclidean: the separation
      // search accepts on the Euclidean distance).
      double move = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        move = std::max(move, (q.at_t1[k] - q.at_t0[k]).cwiseAbs().maxCoeff());
      }
      const double reach = sep + 3 * (tol * 2 * move) + 1e-12;
      EXPECT_LE(squared_distance_until(q, std::min(1.0, r.toi + tol)), FT(reach) * FT(reach))
          << name;
    }
  }
  std::cout << queries << " queries, " << positives << " within the separation, " << false_positives
            << " false positives\n";
  EXPECT_GT(queries, 1500);
  EXPECT_GT(positives, queries / 3);
  EXPECT_EQ(exhausted, 0);
  // Only separations within the tolerance's reach of the least distance may be false positives.
  EXPECT_LE(false_positives, queries / 4) << false_positives << " of " << queries;
}

/// Least distance at time t of the primitives (floating point, for sampling).
double distance_at(const std::array<Vec3, 4>& a, const std::array<Vec3, 4>& b, bool edge_edge,
                   double t, int grid) {
  std::array<Vec3, 4> p;
  for (std::size_t k = 0; k < 4; ++k) p[k] = a[k] + t * (b[k] - a[k]);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= grid; ++i) {
    for (int j = 0; j <= grid; ++j) {
      const double u = double(i) / grid;
      const double v = double(j) / grid;
      if (edge_edge) {
        best = std::min(best, ((p[0] + u * (p[1] - p[0])) - (p[2] + v * (p[3] - p[2]))).norm());
      } else if (u + v <= 1) {
        best = std::min(best, (p[0] - (p[1] + u * (p[2] - p[1]) + v * (p[3] - p[1]))).norm());
      }
    }
  }
  return best;
}

TEST(CcdSeparation, GrazingAndCoplanarQueriesOfFlexibleScenesEndWithinTheBudget) {
  std::ifstream in(std::string(ANTCD_CCD_DATA) + "/grazing_separation.txt");
  ASSERT_TRUE(in) << "tests/ccd/data/grazing_separation.txt";
  std::string line;
  int count = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> f;
    std::string word;
    while (fields >> word) f.push_back(std::strtod(word.c_str(), nullptr));
    ASSERT_EQ(f.size(), 28u) << line;
    const bool edge_edge = f[0] == 1;
    std::array<Vec3, 4> a, b;
    for (std::size_t k = 0; k < 4; ++k) {
      a[k] = Vec3(f[3 + 3 * k], f[4 + 3 * k], f[5 + 3 * k]);
      b[k] = Vec3(f[15 + 3 * k], f[16 + 3 * k], f[17 + 3 * k]);
    }
    const double sep = f[1];
    const auto r = edge_edge ? ccd::edge_edge(a, b, sep, f[2]) : ccd::vertex_face(a, b, sep, f[2]);
    EXPECT_FALSE(r.budget_exhausted) << "query " << count;
    EXPECT_LT(r.boxes, 5000u) << "query " << count;
    // Sampled: no time before toi (or in [0, 1] for a miss) closer than the separation (a margin
    // of 1e-9 for the sampling's rounding), and a hit near a sampled distance within reach.
    const double end = r.hit ? r.toi : 1.0;
    for (int s = 0; s < (r.hit ? 200 : 201); ++s) {
      const double t = end * s / 200;
      EXPECT_GT(distance_at(a, b, edge_edge, t, 48), sep * (1 - 1e-9))
          << "query " << count << " closer than the separation at t " << t << " < toi " << end;
    }
    ++count;
  }
  EXPECT_GT(count, 140);
}

}  // namespace
}  // namespace antcd
