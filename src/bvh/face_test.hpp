// Private: the six face axes of the node box test (BoxTest::faces, src/bvh/traverse.hpp) in
// 4-lane single precision (SSE2), a rounding-safe filter at half the instructions of the double
// test per node pair. The WebAssembly build has it too (Emscripten maps these SSE2 intrinsics
// onto SIMD128, -msse2 in wasm/CMakeLists.txt). Without SSE2 FloatFaceAxes::kAvailable is false
// and the traversal keeps the double test.
//
// What it decides. The double face test (geometry::detail::obb_face_separated) reports A's axis i
// when |t_i| > ea_i + sum_j q_ij eb_j and B's axis j when |sum_i t_i r_ij| > eb_j + sum_i q_ij
// ea_i, with r_ij = a_i . b_j, t_i = a_i . d, q_ij = |r_ij| + 1e-12, ea = A's half extents + margin
// and eb = B's. This test reports an axis only when those exact inequalities (of the double values
// of the axes, d, extents and margin) hold, so it culls a subset of what the double test culls,
// itself a filter in front of exact triangle tests: contacts and their order never depend on it.
//
// Rounding (u = 2^-24, axis components |x| <= 1): r_ij in float from float-rounded axes is within
// 11u of r_ij, so qf_ij = |rf_ij| + 32u >= q_ij; a float sum of the nonnegative products of the
// right-hand sides is at least (1 - 6u) times the same sum of real products, so the real
// right-hand side is at most rhs_f (1 + 7u) and the test asks |t| > rhs_f (1 + 32u) (t taken in
// double, rounded once to float). B's left-hand side sum_i t_i rf_ij is within 17u sum_i |t_i| of
// sum_i t_i r_ij; the test subtracts 32u sum_i |t_i|. Both slacks leave a few u to absorb the
// rounding of the comparisons' own operations. Float range: the argument is relative, so it needs
// no overflow and no subnormal operands that matter; PairFrame enables the test only for scenes
// whose scale (and margin) lie within [1e-20, 1e30], where every compared quantity is far inside
// float's normal range or exactly zero, and a subnormal product is far below the slack.
#pragma once

#include <antcd/bvh.hpp>

#include <cmath>
#include <cstddef>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace antcd::detail {

#if defined(__SSE2__)

/// A node's half extents as lanes (h0, h1, h2, 0).
inline __m128 half_lanes(const BvhNode& n) {
  static_assert(offsetof(BvhNode, half) + 16 <= sizeof(BvhNode), "the load stays in the node");
  const __m128 lanes_012 = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
  return _mm_and_ps(_mm_loadu_ps(n.half.data()), lanes_012);
}

/// B's node axes (in A's model frame) as float lanes: x = (b0.x, b1.x, b2.x, 0) and so on, and B's
/// half extents e = (eb0, eb1, eb2, 0). Kept per node of B, like PosedAxes.
struct FloatFaceAxes {
  static constexpr bool kAvailable = true;
  __m128 x = _mm_setzero_ps(), y = _mm_setzero_ps(), z = _mm_setzero_ps(), e = _mm_setzero_ps();

  FloatFaceAxes() = default;
  FloatFaceAxes(const Vec3& b0, const Vec3& b1, const Vec3& b2, const BvhNode& b)
      : e(half_lanes(b)) {
    // Each component rounded to float once; (x, y) pairs converted two at a time, then transposed.
    const __m128 p0 = _mm_cvtpd_ps(_mm_loadu_pd(b0.data()));  // b0.x b0.y 0 0
    const __m128 p1 = _mm_cvtpd_ps(_mm_loadu_pd(b1.data()));
    const __m128 p2 = _mm_cvtpd_ps(_mm_loadu_pd(b2.data()));
    const __m128 u01 = _mm_unpacklo_ps(p0, p1);  // b0.x b1.x b0.y b1.y
    x = _mm_shuffle_ps(u01, p2, _MM_SHUFFLE(3, 0, 1, 0));
    y = _mm_shuffle_ps(u01, p2, _MM_SHUFFLE(3, 1, 3, 2));
    z = _mm_movelh_ps(_mm_cvtpd_ps(_mm_set_pd(b1.z(), b0.z())), _mm_cvtpd_ps(_mm_set_sd(b2.z())));
  }
};

/// True when one of the six face axes separates A's node box (axes a.axis0, a.axis1, `a2`) from
/// B's (axes `fb`) by more than `margin_f` (the PairFrame margin rounded to float); `d` = B's
/// centre minus A's, A's model frame. See the header comment for the guarantee.
[[gnu::always_inline]] inline bool float_face_separated(const BvhNode& a, const Vec3& a2,
                                                        const FloatFaceAxes& fb, const Vec3& d,
                                                        float margin_f) {
  constexpr float kU = 0x1p-24f;
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 eps = _mm_set1_ps(32 * kU);
  const __m128 grow = _mm_set1_ps(1 + 32 * kU);
  const auto row = [&](const Vec3& ax) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(static_cast<float>(ax.x())), fb.x),
                                 _mm_mul_ps(_mm_set1_ps(static_cast<float>(ax.y())), fb.y)),
                      _mm_mul_ps(_mm_set1_ps(static_cast<float>(ax.z())), fb.z));
  };
  // Rows of r (lane j: r_ij; lane 3: 0) and of q.
  const __m128 r0 = row(a.axis0);
  const __m128 r1 = row(a.axis1);
  const __m128 r2 = row(a2);
  const __m128 q0 = _mm_add_ps(_mm_and_ps(r0, abs_mask), eps);
  const __m128 q1 = _mm_add_ps(_mm_and_ps(r1, abs_mask), eps);
  const __m128 q2 = _mm_add_ps(_mm_and_ps(r2, abs_mask), eps);
  const Scalar t0 = a.axis0.dot(d);
  const Scalar t1 = a.axis1.dot(d);
  const Scalar t2 = a2.dot(d);
  const __m128 t =
      _mm_set_ps(0, static_cast<float>(t2), static_cast<float>(t1), static_cast<float>(t0));
  const __m128 abs_t = _mm_and_ps(t, abs_mask);
  const __m128 ea = _mm_add_ps(half_lanes(a), _mm_set1_ps(margin_f));

  // A's axes: lane i compares |t_i| with ea_i + sum_j q_ij eb_j (rows times eb, transposed, added).
  const __m128 p0 = _mm_mul_ps(q0, fb.e);
  const __m128 p1 = _mm_mul_ps(q1, fb.e);
  const __m128 p2 = _mm_mul_ps(q2, fb.e);
  const __m128 zero = _mm_setzero_ps();
  const __m128 lo01 = _mm_unpacklo_ps(p0, p1);   // p0_0 p1_0 p0_1 p1_1
  const __m128 hi01 = _mm_unpackhi_ps(p0, p1);   // p0_2 p1_2 p0_3 p1_3
  const __m128 lo2 = _mm_unpacklo_ps(p2, zero);  // p2_0 0 p2_1 0
  const __m128 hi2 = _mm_unpackhi_ps(p2, zero);  // p2_2 0 p2_3 0
  const __m128 sum_a = _mm_add_ps(_mm_add_ps(_mm_movelh_ps(lo01, lo2), _mm_movehl_ps(lo2, lo01)),
                                  _mm_movelh_ps(hi01, hi2));
  const __m128 rhs_a = _mm_mul_ps(_mm_add_ps(ea, sum_a), grow);
  if ((_mm_movemask_ps(_mm_cmpgt_ps(abs_t, rhs_a)) & 7) != 0) return true;

  // B's axes: lane j compares |sum_i t_i r_ij| - slack with eb_j + sum_i q_ij ea_i.
  const auto lane = [](__m128 v, auto k) {
    return _mm_shuffle_ps(v, v,
                          _MM_SHUFFLE(decltype(k)::value, decltype(k)::value, decltype(k)::value,
                                      decltype(k)::value));
  };
  using L0 = std::integral_constant<int, 0>;
  using L1 = std::integral_constant<int, 1>;
  using L2 = std::integral_constant<int, 2>;
  const __m128 s =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(lane(t, L0{}), r0), _mm_mul_ps(lane(t, L1{}), r1)),
                 _mm_mul_ps(lane(t, L2{}), r2));
  const float slack = 32 * kU * static_cast<float>(std::abs(t0) + std::abs(t1) + std::abs(t2));
  const __m128 lhs_b = _mm_sub_ps(_mm_and_ps(s, abs_mask), _mm_set1_ps(slack));
  const __m128 sum_b =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(lane(ea, L0{}), q0), _mm_mul_ps(lane(ea, L1{}), q1)),
                 _mm_mul_ps(lane(ea, L2{}), q2));
  const __m128 rhs_b = _mm_mul_ps(_mm_add_ps(sum_b, fb.e), grow);
  return (_mm_movemask_ps(_mm_cmpgt_ps(lhs_b, rhs_b)) & 7) != 0;
}

#else

struct FloatFaceAxes {
  static constexpr bool kAvailable = false;
  FloatFaceAxes() = default;
  FloatFaceAxes(const Vec3&, const Vec3&, const Vec3&, const BvhNode&) {}
};

inline bool float_face_separated(const BvhNode&, const Vec3&, const FloatFaceAxes&, const Vec3&,
                                 float) {
  return false;
}

#endif

}  // namespace antcd::detail
