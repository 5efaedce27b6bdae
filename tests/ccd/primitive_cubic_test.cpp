// The coplanarity-cubic filter of primitive CCD (src/ccd/primitive_cubic.hpp) against exact
// rational arithmetic, and the primitive queries on the cases that stress it: contact exactly at
// t = 0 or 1 with rounded determinants, a double root (tangency), a cubic identically zero, and
// huge, tiny and far-offset coordinates.
#include <antcd/ccd.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>
#include <vector>

#include "ccd/exact_truth.hpp"
#include "ccd/primitive_cubic.hpp"

namespace antcd {
namespace {

using ccd::coplanar::CubicPiece;
using ccd::coplanar::CubicSign;
using test::CcdKind;
using test::CcdQuery;
using Q = mpq_class;
using QCubic = std::array<Q, 4>;

const std::array<std::size_t, 3>& hi_of(CcdKind kind) {
  return kind == CcdKind::VertexFace ? ccd::coplanar::kVertexFaceHi : ccd::coplanar::kEdgeEdgeHi;
}
const std::array<std::size_t, 3>& lo_of(CcdKind kind) {
  return kind == CcdKind::VertexFace ? ccd::coplanar::kVertexFaceLo : ccd::coplanar::kEdgeEdgeLo;
}

/// Exact Bernstein coefficients of the coplanarity cubic on [0, 1]: c(t) expanded exactly.
QCubic exact_cubic(const CcdQuery& q) {
  std::array<std::array<std::array<Q, 3>, 3>, 2> e;  // e[time][k][axis]
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < 3; ++i) {
      e[0][k][i] = Q(q.at_t0[hi_of(q.kind)[k]][static_cast<Eigen::Index>(i)]) -
                   Q(q.at_t0[lo_of(q.kind)[k]][static_cast<Eigen::Index>(i)]);
      e[1][k][i] = Q(q.at_t1[hi_of(q.kind)[k]][static_cast<Eigen::Index>(i)]) -
                   Q(q.at_t1[lo_of(q.kind)[k]][static_cast<Eigen::Index>(i)]);
    }
  }
  QCubic sum = {0, 0, 0, 0};
  for (unsigned mask = 0; mask < 8; ++mask) {
    const auto& a = e[mask & 1u][0];
    const auto& b = e[(mask >> 1) & 1u][1];
    const auto& c = e[(mask >> 2) & 1u][2];
    const Q det = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]);
    sum[static_cast<std::size_t>(std::popcount(mask))] += det;
  }
  return {sum[0], sum[1] / 3, sum[2] / 3, sum[3]};
}

void exact_split(const QCubic& b, QCubic& left, QCubic& right) {
  const Q m01 = (b[0] + b[1]) / 2, m12 = (b[1] + b[2]) / 2, m23 = (b[2] + b[3]) / 2;
  const Q m012 = (m01 + m12) / 2, m123 = (m12 + m23) / 2;
  const Q mid = (m012 + m123) / 2;
  left = {b[0], m01, m012, mid};
  right = {mid, m123, m23, b[3]};
}

/// Every computed coefficient within the piece's error of the exact one, and a certified sign
/// matching the exact coefficients; then the same for both halves, down to `depth` more levels.
/// Returns the number of pieces checked.
int check_piece(const CubicPiece& piece, const QCubic& exact, int depth, const std::string& name) {
  for (std::size_t k = 0; k < 4; ++k) {
    const Q gap = abs(Q(piece.b[k]) - exact[k]);
    EXPECT_LE(gap, Q(piece.error))
        << name << ": coefficient " << k << " on [" << piece.t0 << ", " << piece.t1 << "] off by "
        << gap.get_d() << " > bound " << piece.error;
  }
  const CubicSign sign = ccd::coplanar::classify(piece);
  for (std::size_t k = 0; k < 4; ++k) {
    if (sign == CubicSign::Positive) {
      EXPECT_GT(sgn(exact[k]), 0) << name;
    }
    if (sign == CubicSign::Negative) {
      EXPECT_LT(sgn(exact[k]), 0) << name;
    }
  }
  if (depth == 0) return 1;
  CubicPiece left, right;
  ccd::coplanar::split(piece, left, right);
  QCubic exact_left, exact_right;
  exact_split(exact, exact_left, exact_right);
  return 1 + check_piece(left, exact_left, depth - 1, name) +
         check_piece(right, exact_right, depth - 1, name);
}

/// A coordinate 2^20 + k 2^-30 (k < 2^30): 51 significant bits, so differences are exact but
/// products of three differences round.
Scalar rounded_coordinate(std::mt19937_64& rng) {
  return 0x1p20 + static_cast<Scalar>(rng() >> 34) * 0x1p-30;
}
Vec3 rounded_point(std::mt19937_64& rng) {
  return Vec3(rounded_coordinate(rng), rounded_coordinate(rng), rounded_coordinate(rng));
}

/// Queries that touch exactly at t = 0 (at_start) or exactly at t = 1, with far-offset coordinates
/// whose coplanarity determinants round: the exact cubic is 0 there, the computed one is not.
std::vector<CcdQuery> touching_at_an_end(CcdKind kind, bool at_start, int count,
                                         std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> small(-8, 8);
  std::vector<CcdQuery> out;
  for (int i = 0; i < count; ++i) {
    CcdQuery q;
    q.kind = kind;
    q.name = std::string(kind == CcdKind::VertexFace ? "vf" : "ee") +
             (at_start ? "_touch_at_0_" : "_touch_at_1_") + std::to_string(i);
    // Away from the plane: a small dyadic motion with a nonzero third component.
    const Vec3 away(small(rng) * 0.125, small(rng) * 0.125, (1 + std::abs(small(rng))) * 0.25);
    std::array<Vec3, 4> contact;
    if (kind == CcdKind::VertexFace) {
      const Vec3 f0 = rounded_point(rng), f1 = rounded_point(rng), f2 = rounded_point(rng);
      contact = {(2 * f0 + f1 + f2) / 4, f0, f1, f2};  // the vertex at barycentre (1/2, 1/4, 1/4)
    } else {
      const Vec3 a0 = rounded_point(rng), a1 = rounded_point(rng);
      const Vec3 m = (a0 + a1) / 2;
      const Vec3 r = rounded_point(rng) - Vec3::Constant(0x1p20);
      contact = {a0, a1, m + r, m - r};  // edge b crosses edge a at its midpoint
    }
    std::array<Vec3, 4> moved = contact;
    const std::size_t first_moving = kind == CcdKind::VertexFace ? 0 : 2;
    for (std::size_t k = first_moving; k < (kind == CcdKind::VertexFace ? 1u : 4u); ++k) {
      moved[k] += at_start ? away : -away;
    }
    q.at_t0 = at_start ? contact : moved;
    q.at_t1 = at_start ? moved : contact;
    out.push_back(q);
  }
  return out;
}

/// The plane z = x / 2 + y / 4 + 2^20 holds every corner at both times: the cubic is 0 exactly,
/// while its computed determinants round. The vertex (or edge b) slides into the other primitive.
std::vector<CcdQuery> coplanar_all_along(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto on_plane = [&](Scalar x, Scalar y) { return Vec3(x, y, x / 2 + y / 4 + 0x1p20); };
  const auto random_on_plane = [&] {
    return on_plane(static_cast<Scalar>(rng() >> 34) * 0x1p-30,
                    static_cast<Scalar>(rng() >> 34) * 0x1p-30);
  };
  std::vector<CcdQuery> out;
  for (int i = 0; i < count; ++i) {
    CcdQuery q;
    q.kind = i % 2 == 0 ? CcdKind::VertexFace : CcdKind::EdgeEdge;
    q.name = "coplanar_all_along_" + std::to_string(i);
    for (std::size_t k = 0; k < 4; ++k) q.at_t0[k] = random_on_plane();
    q.at_t1 = q.at_t0;
    // Translate the vertex (or edge b) within the plane by up to about 2: often through the other.
    const Vec3 shift = on_plane(static_cast<Scalar>(static_cast<int>(rng() % 33) - 16) / 8,
                                static_cast<Scalar>(static_cast<int>(rng() % 33) - 16) / 8) -
                       on_plane(0, 0);
    for (std::size_t k = q.kind == CcdKind::VertexFace ? 0 : 2;
         k < (q.kind == CcdKind::VertexFace ? 1u : 4u); ++k) {
      q.at_t1[k] += shift;
    }
    out.push_back(q);
  }
  return out;
}

CcdQuery transformed(const CcdQuery& q, Scalar scale, const Vec3& offset, const char* suffix) {
  CcdQuery out = q;
  out.name += suffix;
  for (std::size_t k = 0; k < 4; ++k) {
    out.at_t0[k] = q.at_t0[k] * scale + offset;
    out.at_t1[k] = q.at_t1[k] * scale + offset;
  }
  return out;
}

ccd::PrimitiveResult run(const CcdQuery& q) {
  return q.kind == CcdKind::VertexFace ? ccd::vertex_face(q.at_t0, q.at_t1)
                                       : ccd::edge_edge(q.at_t0, q.at_t1);
}

/// No contact missed and none reported late, against the exact truth; returns the false
/// positives.
int expect_conservative(const std::vector<CcdQuery>& queries) {
  int false_positives = 0;
  for (const CcdQuery& q : queries) {
    const auto truth = test::ccd_truth(q);
    EXPECT_TRUE(truth.has_value()) << q.name;
    if (!truth) continue;
    const auto r = run(q);
    if (*truth) {
      EXPECT_TRUE(r.hit) << q.name << ": contact missed";
    }
    if (!*truth && r.hit) ++false_positives;
    if (r.hit && !r.tolerance_decided) {
      EXPECT_TRUE(*truth) << q.name << ": proven but apart";
    }
    if (const auto first = test::ccd_first_time_upper(q); first && r.hit) {
      EXPECT_LE(r.toi, *first) << q.name << ": later than the exact first contact";
    }
  }
  return false_positives;
}

TEST(CcdCoplanarityCubic, ErrorBoundCoversTheExactCoefficients) {
  std::vector<CcdQuery> queries = test::degenerate_corpus();
  for (const CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
    for (const CcdQuery& q : test::near_miss_queries(kind, 100, 5)) queries.push_back(q);
    for (const bool at_start : {true, false}) {
      for (const CcdQuery& q : touching_at_an_end(kind, at_start, 50, 9)) queries.push_back(q);
    }
  }
  for (const CcdQuery& q : coplanar_all_along(50, 4)) queries.push_back(q);
  const std::size_t plain = queries.size();
  for (std::size_t i = 0; i < plain; ++i) {
    queries.push_back(transformed(queries[i], 0x1p-600, Vec3::Zero(), "*2^-600"));
    queries.push_back(transformed(queries[i], 0x1p300, Vec3::Zero(), "*2^300"));
    queries.push_back(transformed(queries[i], 0x1p400, Vec3::Zero(), "*2^400"));
  }
  int pieces = 0;
  int filtered = 0;
  for (const CcdQuery& q : queries) {
    CubicPiece piece;
    if (!ccd::coplanar::coplanarity_cubic(q.at_t0, q.at_t1, hi_of(q.kind), lo_of(q.kind), piece)) {
      continue;  // not finite (the 2^400 copies): the filter stays off
    }
    ++filtered;
    pieces += check_piece(piece, exact_cubic(q), 3, q.name);
  }
  std::cout << "cubic pieces checked against exact rationals: " << pieces << " of " << filtered
            << " queries (" << queries.size() - static_cast<std::size_t>(filtered)
            << " with the filter off)\n";
  EXPECT_GT(filtered, 2 * static_cast<int>(plain));
}

TEST(CcdCoplanarityCubic, IdenticallyZeroCubicIsNeverCertified) {
  for (const CcdQuery& q : coplanar_all_along(40, 8)) {
    const QCubic exact = exact_cubic(q);
    for (const Q& b : exact) ASSERT_EQ(sgn(b), 0) << q.name << ": not coplanar all along";
    CubicPiece piece;
    ASSERT_TRUE(
        ccd::coplanar::coplanarity_cubic(q.at_t0, q.at_t1, hi_of(q.kind), lo_of(q.kind), piece));
    // Down four levels: never a certified sign.
    std::function<void(const CubicPiece&, int)> walk = [&](const CubicPiece& p, int depth) {
      const CubicSign sign = ccd::coplanar::classify(p);
      EXPECT_TRUE(sign == CubicSign::Flat || sign == CubicSign::Uncertain) << q.name;
      if (depth == 0) return;
      CubicPiece left, right;
      ccd::coplanar::split(p, left, right);
      walk(left, depth - 1);
      walk(right, depth - 1);
    };
    walk(piece, 4);
  }
}

TEST(CcdPrimitive, ContactExactlyAtAnEndWithRoundedCubicIsFound) {
  int queries = 0;
  for (const CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
    for (const bool at_start : {true, false}) {
      const auto set = touching_at_an_end(kind, at_start, 100, at_start ? 21 : 22);
      for (const CcdQuery& q : set) ASSERT_EQ(test::ccd_truth(q), true) << q.name;
      EXPECT_EQ(expect_conservative(set), 0);
      queries += static_cast<int>(set.size());
      if (at_start) {
        for (const CcdQuery& q : set) EXPECT_EQ(run(q).toi, 0) << q.name;
      }
    }
  }
  EXPECT_EQ(queries, 400);
}

TEST(CcdPrimitive, CoplanarMotionsAreSearchedAllAlong) {
  const auto set = coplanar_all_along(200, 12);
  int touching = 0;
  for (const CcdQuery& q : set) touching += test::ccd_truth(q).value_or(false) ? 1 : 0;
  const int false_positives = expect_conservative(set);
  std::cout << "coplanar all along: " << set.size() << " queries, " << touching
            << " touching, false positives " << false_positives << '\n';
  EXPECT_GT(touching, 20);
  EXPECT_LT(false_positives, static_cast<int>(set.size()) - touching);
}

TEST(CcdPrimitive, DoubleRootTangencyIsFound) {
  // The face tilts about its edge f0 f1 (f2.z from 1 to -1) while the vertex moves so that
  // c(t) = pz - z py = (t - 1/2)^2 >= 0: the vertex touches the plane only at t = 1/2, at
  // (x, 1/2, 0). Inside the face for x = 1/4, outside (0.18 from it) for x = 3/4.
  for (const Scalar offset : {0.0, 0x1p20}) {
    for (const Scalar x : {0.25, 0.75}) {
      const Vec3 o = Vec3::Constant(offset);
      const std::array<Vec3, 4> t0 = {Vec3(x, 0.25, 0.5) + o, o, Vec3(1, 0, 0) + o,
                                      Vec3(0, 1, 1) + o};
      const std::array<Vec3, 4> t1 = {Vec3(x, 0.75, -0.5) + o, o, Vec3(1, 0, 0) + o,
                                      Vec3(0, 1, -1) + o};
      const auto r = ccd::vertex_face(t0, t1);
      if (x == 0.25) {
        ASSERT_TRUE(r.hit) << "offset " << offset;
        EXPECT_LE(r.toi, 0.5);
        EXPECT_GE(r.toi, 0.5 - 1e-6);
      } else {
        EXPECT_FALSE(r.hit) << "offset " << offset;
      }
    }
  }
}

TEST(CcdPrimitive, HugeTinyAndFarOffsetCoordinatesKeepEveryContact) {
  const auto corpus = test::degenerate_corpus();
  for (const auto& [scale, offset, suffix] :
       {std::tuple{0x1p-600, 0.0, "*2^-600"}, std::tuple{0x1p-30, 0.0, "*2^-30"},
        std::tuple{0x1p300, 0.0, "*2^300"}, std::tuple{0x1p400, 0.0, "*2^400"},
        std::tuple{1.0, 0x1p20, "+2^20"}}) {
    std::vector<CcdQuery> set;
    for (const CcdQuery& q : corpus)
      set.push_back(transformed(q, scale, Vec3::Constant(offset), suffix));
    const int false_positives = expect_conservative(set);
    std::cout << "degenerate corpus " << suffix << ": false positives " << false_positives << '\n';
  }
}

}  // namespace
}  // namespace antcd
