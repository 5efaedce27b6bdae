// Primitive CCD (antcd::ccd::vertex_face / edge_edge) against exact rational truth.
#include <antcd/ccd.hpp>
#include <antcd/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>

#include "ccd/exact_truth.hpp"

namespace antcd {
namespace {

using test::CcdKind;
using test::CcdQuery;

ccd::PrimitiveResult run(const CcdQuery& q, Scalar min_separation = 0, Scalar tol = 1e-6) {
  return q.kind == CcdKind::VertexFace ? ccd::vertex_face(q.at_t0, q.at_t1, min_separation, tol)
                                       : ccd::edge_edge(q.at_t0, q.at_t1, min_separation, tol);
}

struct Tally {
  int queries = 0, positives = 0, false_negatives = 0, false_positives = 0, late = 0;
  int budget_exhausted = 0;
  std::uint32_t max_boxes = 0;
};

Tally check(const std::vector<CcdQuery>& queries) {
  Tally tally;
  for (const CcdQuery& q : queries) {
    const auto truth = test::ccd_truth(q);
    EXPECT_TRUE(truth.has_value()) << q.name << ": no exact truth for this structure";
    if (!truth) continue;
    const auto r = run(q);
    ++tally.queries;
    tally.budget_exhausted += r.budget_exhausted ? 1 : 0;
    if (r.budget_exhausted) std::cout << "budget stop: " << q.name << '\n';
    tally.max_boxes = std::max(tally.max_boxes, r.boxes);
    tally.positives += *truth ? 1 : 0;
    if (*truth && !r.hit) {
      ++tally.false_negatives;
      ADD_FAILURE() << q.name << ": contact missed";
    }
    if (!*truth && r.hit) ++tally.false_positives;
    if (r.hit && !r.tolerance_decided) {
      EXPECT_TRUE(*truth) << q.name << ": a proven hit must touch";
    }
    if (const auto first = test::ccd_first_time_upper(q); first && r.hit && r.toi > *first) {
      ++tally.late;
      ADD_FAILURE() << q.name << ": toi " << r.toi << " after the exact first contact " << *first;
    }
    EXPECT_GE(r.toi, 0);
    EXPECT_LE(r.toi, 1);
  }
  return tally;
}

TEST(CcdPrimitive, DegenerateCorpusHasNoFalseNegative) {
  const auto corpus = test::degenerate_corpus();
  ASSERT_GE(corpus.size(), 100u);
  const Tally t = check(corpus);
  std::cout << "degenerate corpus: " << t.queries << " queries, " << t.positives
            << " touching, false negatives " << t.false_negatives << ", false positives "
            << t.false_positives << ", most boxes " << t.max_boxes << ", budget stops "
            << t.budget_exhausted << '\n';
  EXPECT_EQ(t.false_negatives, 0);
  EXPECT_EQ(t.late, 0);
  // The corpus mixes both verdicts: a solver answering "hit" everywhere is caught below.
  EXPECT_GT(t.positives, 40);
  EXPECT_LT(t.false_positives, t.queries - t.positives);
}

TEST(CcdPrimitive, RandomNearMissesHaveNoFalseNegative) {
  for (const CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
    const auto queries = test::near_miss_queries(kind, 3000, kind == CcdKind::EdgeEdge ? 7 : 3);
    const Tally t = check(queries);
    std::cout << (kind == CcdKind::VertexFace ? "vf" : "ee") << " near misses: " << t.queries
              << " queries, " << t.positives << " touching, false negatives " << t.false_negatives
              << ", false positives " << t.false_positives << ", most boxes " << t.max_boxes
              << ", budget stops " << t.budget_exhausted << '\n';
    EXPECT_EQ(t.false_negatives, 0);
    EXPECT_GT(t.positives, 100);
    EXPECT_GT(t.queries - t.positives, 100);
  }
}

TEST(CcdPrimitive, TimeOfImpactIsTightForTransversalHits) {
  // Spike crossing the face at exactly t = 0.375.
  const std::array<Vec3, 4> t0 = {Vec3(0.25, 0.25, 3), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  std::array<Vec3, 4> t1 = t0;
  t1[0].z() = -5;
  const auto r = ccd::vertex_face(t0, t1, 0, 1e-6);
  ASSERT_TRUE(r.hit);
  EXPECT_LE(r.toi, 0.375);
  EXPECT_GE(r.toi, 0.375 - 1e-6);
  // With a separation of 1 the first time is (3 - 1) / 8 = 0.25, and the hit is proven there.
  const auto s = ccd::vertex_face(t0, t1, 1, 1e-6);
  ASSERT_TRUE(s.hit);
  EXPECT_LE(s.toi, 0.25);
  EXPECT_GE(s.toi, 0.25 - 1e-6);
}

TEST(CcdPrimitive, MinSeparationIsHonoured) {
  // Edges passing 0.5 apart: a hit with min_separation 0.5, none with 0.49.
  const std::array<Vec3, 4> t0 = {Vec3(-1, 0, 0.5), Vec3(1, 0, 0.5), Vec3(0, -1, 0), Vec3(0, 1, 0)};
  std::array<Vec3, 4> t1 = t0;
  t1[0].x() += 4;
  t1[1].x() += 4;  // slides along x: the closest approach stays 0.5 while they cross
  EXPECT_TRUE(ccd::edge_edge(t0, t1, 0.5).hit);
  EXPECT_FALSE(ccd::edge_edge(t0, t1, 0.49).hit);
  EXPECT_FALSE(ccd::edge_edge(t0, t1, 0).hit);
}

TEST(CcdPrimitive, RejectsBadArguments) {
  std::array<Vec3, 4> p = {Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW((void)ccd::vertex_face(p, p, -1), ArgumentError);
  EXPECT_THROW((void)ccd::vertex_face(p, p, 0, 0), ArgumentError);
  EXPECT_THROW((void)ccd::edge_edge(p, p, std::nan("")), ArgumentError);
  auto bad = p;
  bad[2].x() = std::nan("");
  try {
    (void)ccd::edge_edge(p, bad);
    FAIL() << "no throw";
  } catch (const ArgumentError& e) {
    EXPECT_NE(std::string(e.what()).find("at_t1[2]"), std::string::npos) << e.what();
  }
}

/// The query with every coordinate times 2^e, or nullopt when a product is not exact (a result
/// below DBL_MIN would lose bits and change the truth) or overflows.
std::optional<CcdQuery> scaled_query(const CcdQuery& q, int e) {
  CcdQuery out = q;
  out.name = q.name + " * 2^" + std::to_string(e);
  for (auto* points : {&out.at_t0, &out.at_t1}) {
    for (Vec3& p : *points) {
      for (int k = 0; k < 3; ++k) {
        const Scalar x = std::ldexp(p[k], e);
        if (!std::isfinite(x) || std::ldexp(x, -e) != p[k]) return std::nullopt;
        p[k] = x;
      }
    }
  }
  return out;
}

// Issue 41 asked whether the primitives, like the mesh sweeps, miss contacts at huge coordinates:
// they do not (this passed before the mesh sweeps' fix too). Pass-throughs at +-1e154 .. +-DBL_MAX
// and the degenerate corpus scaled to huge and tiny coordinates keep their exact truth.
TEST(CcdPrimitive, HugeAndTinyCoordinatesKeepEveryContact) {
  const Scalar big = std::numeric_limits<Scalar>::max();
  for (const Scalar s : {1e154, 1e155, 1e200, 1e300, big / 2, big}) {
    // A vertex from x = -s to x = +s through the face x = 0 at t = 0.5.
    const std::array<Vec3, 4> t0 = {Vec3(-s, 0.25, 0.25), Vec3(0, 0, 0), Vec3(0, 1, 0),
                                    Vec3(0, 0, 1)};
    std::array<Vec3, 4> t1 = t0;
    t1[0].x() = s;
    const ccd::PrimitiveResult vf = ccd::vertex_face(t0, t1);
    EXPECT_TRUE(vf.hit) << "vertex-face at +-" << s;
    EXPECT_LE(vf.toi, 0.5) << "vertex-face at +-" << s;
    EXPECT_TRUE(ccd::vertex_face(t0, t1, 1e-3).hit) << "vertex-face, separation, +-" << s;
    // An edge along y from x = -s to x = +s through an edge along z at the origin.
    const std::array<Vec3, 4> e0 = {Vec3(-s, -1, 0), Vec3(-s, 1, 0), Vec3(0, 0, -1), Vec3(0, 0, 1)};
    std::array<Vec3, 4> e1 = e0;
    e1[0].x() = s;
    e1[1].x() = s;
    const ccd::PrimitiveResult ee = ccd::edge_edge(e0, e1);
    EXPECT_TRUE(ee.hit) << "edge-edge at +-" << s;
    EXPECT_LE(ee.toi, 0.5) << "edge-edge at +-" << s;
  }
  // The degenerate corpus scaled to huge and to tiny coordinates keeps its exact truth.
  std::vector<CcdQuery> scaled;
  for (const CcdQuery& q : test::degenerate_corpus()) {
    Scalar largest = 0;
    for (const auto* points : {&q.at_t0, &q.at_t1}) {
      for (const Vec3& p : *points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
    }
    if (largest == 0) continue;
    for (const int target : {1020, 600, 300, -300, -600, -900}) {
      if (auto s = scaled_query(q, target - std::ilogb(largest))) scaled.push_back(*s);
    }
  }
  ASSERT_GT(scaled.size(), 100U);
  const Tally tally = check(scaled);
  EXPECT_EQ(tally.false_negatives, 0);
  EXPECT_EQ(tally.late, 0);
  std::cout << "scaled corpus: " << tally.queries << " queries, " << tally.positives
            << " touching, " << tally.false_positives << " false positives\n";
}

}  // namespace
}  // namespace antcd
