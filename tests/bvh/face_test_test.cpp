// The float face-axes box test (src/bvh/face_test.hpp): never a separation the double test
// (geometry::detail::obb_face_separated) does not report, boxes within the margin never culled, and
// clear separations still found.
#include <antcd/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bvh/node_store.hpp"
#include "bvh/traverse.hpp"
#include "geometry/obb_sat.hpp"

namespace antcd {
namespace {

#if defined(__SSE2__)

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<Scalar> g;
  return Eigen::Quaternion<Scalar>(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// A node with the given box (axes made storable, extents rounded up as the build stores them).
BvhNode node(const Vec3& center, const Mat3& axes, const Vec3& half) {
  BvhNode n;
  detail::store_volumes(n, Obb{center, detail::storable_axes(axes), half}, half.norm());
  return n;
}

struct Verdicts {
  bool float_sep;
  bool double_sep;
};

// Both tests on A's box and B's (B's axes and centre in B's model frame, placed by `rot`).
Verdicts verdicts(const BvhNode& a, const BvhNode& b, const Mat3& rot, Scalar margin) {
  const Vec3 a2 = a.axis0.cross(a.axis1);
  const detail::PosedAxes<true> rb(b, rot);
  const Vec3 d = rot * b.center - a.center;
  const bool f = detail::float_face_separated(a, a2, rb.f, d, static_cast<float>(margin));
  Mat3 axes_a;
  axes_a << a.axis0, a.axis1, a2;
  Mat3 axes_b;
  axes_b << rb.b0, rb.b1, rb.b2;
  const Mat3 r = axes_a.transpose() * axes_b;
  const Vec3 t = axes_a.transpose() * d;
  const Vec3 ea = a.half_extents().array() + margin;
  const bool ds = geometry::detail::obb_face_separated(ea, b.half_extents(), r,
                                                       geometry::detail::obb_abs_rotation(r), t);
  return {f, ds};
}

TEST(FloatFaceTest, SeparatesOnlyWhatTheDoubleTestSeparates) {
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  std::uniform_real_distribution<Scalar> ext(0.01, 1);
  std::size_t float_count = 0;
  std::size_t double_count = 0;
  for (const Scalar scale : {1e-6, 1.0, 1e4}) {
    for (int k = 0; k < 20000; ++k) {
      const Vec3 ha(ext(rng), ext(rng), ext(rng));
      const Vec3 hb(ext(rng), ext(rng), ext(rng));
      const BvhNode a =
          node(scale * Vec3(unit(rng), unit(rng), unit(rng)), random_rotation(rng), scale * ha);
      const BvhNode b =
          node(scale * Vec3(unit(rng), unit(rng), unit(rng)), random_rotation(rng), scale * hb);
      const Mat3 rot = random_rotation(rng);
      const Scalar margin = 1e-9 * scale * (k % 3 == 0 ? 1 : 1e3);
      const Verdicts v = verdicts(a, b, rot, margin);
      ASSERT_TRUE(!v.float_sep || v.double_sep) << "scale " << scale << " sample " << k;
      float_count += v.float_sep;
      double_count += v.double_sep;
    }
  }
  // The float test loses only separations within a few 1e-6 of the boxes' size.
  EXPECT_GT(double_count, 10000u);
  EXPECT_GE(float_count, double_count - double_count / 500);
}

TEST(FloatFaceTest, KeepsBoxesWithinTheMarginAndCullsClearGaps) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Scalar> ext(0.05, 1);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 ra = random_rotation(rng);
    const BvhNode a = node(Vec3(0.3, -0.2, 0.1), ra, Vec3(ext(rng), ext(rng), ext(rng)));
    const BvhNode b0 = node(Vec3::Zero(), random_rotation(rng), Vec3(ext(rng), ext(rng), ext(rng)));
    const Mat3 axes_a = a.axes();
    const Mat3 axes_b = b0.axes();
    // A corner of one box on the centre of a face of the other, moved `gap` out along the face's
    // normal `dir`: the boxes touch at that corner (gap 0), or the face's axis separates them by
    // exactly gap.
    const int i = k % 6;
    const Vec3 dir = i < 3 ? Vec3(axes_a.col(i)) : Vec3(axes_b.col(i - 3));
    const auto b_center = [&](Scalar gap) -> Vec3 {
      Vec3 corner =
          Vec3::Zero();  // i < 3: B's corner least along dir; else A's corner most along it
      for (int c = 0; c < 3; ++c) {
        if (i < 3) {
          corner -= std::copysign(Scalar{b0.half[c]}, axes_b.col(c).dot(dir)) * axes_b.col(c);
        } else {
          corner += std::copysign(Scalar{a.half[c]}, axes_a.col(c).dot(dir)) * axes_a.col(c);
        }
      }
      if (i < 3) return a.center + (a.half[i] + gap) * dir - corner;
      return a.center + corner + (gap + b0.half[i - 3]) * dir;
    };
    const Scalar margin = 1e-9;
    for (const Scalar gap : {0.0, 0.5 * margin, 1e-4}) {
      BvhNode b = b0;
      b.center = b_center(gap);
      const Verdicts v = verdicts(a, b, Mat3::Identity(), margin);
      if (gap <= margin) {
        EXPECT_FALSE(v.float_sep) << "sample " << k << " gap " << gap;
      } else {
        EXPECT_TRUE(v.float_sep) << "sample " << k << " gap " << gap;
      }
    }
  }
}

#endif

}  // namespace
}  // namespace antcd
