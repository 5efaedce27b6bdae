// Solid angle of a triangle seen from a point (geometry::solid_angle): the winding number's term.
#include <antcd/geometry.hpp>

#include <cmath>
#include <numbers>

namespace antcd::geometry {

Scalar solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Van Oosterom and Strackee (1983): tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| +
  // (c·a)|b|) with a, b, c relative to p; atan2 keeps the sign and the quadrant.
  const Vec3 u = a - p;
  const Vec3 v = b - p;
  const Vec3 w = c - p;
  const Scalar lu = u.norm();
  const Scalar lv = v.norm();
  const Scalar lw = w.norm();
  const Scalar num = u.dot(v.cross(w));
  const Scalar den = lu * lv * lw + u.dot(v) * lw + v.dot(w) * lu + w.dot(u) * lv;
  return 2 * std::atan2(num, den);
}

}  // namespace antcd::geometry
