// Builds two models from the public API only and checks one colliding and one separated pose.
#include <antcd/collide.hpp>
#include <antcd/error.hpp>
#include <antcd/method.hpp>
#include <antcd/version.hpp>

#include <cstdio>
#include <cstring>

int main() {
  using namespace antcd;
  const Model a(make_box(Vec3(1, 1, 1)));
  const Model b(make_sphere(0.5));
  const Transform near = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(1.2, 0, 0));
  const Transform far = Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(3, 0, 0));
  const bool touching = collide(a, Transform::identity(), b, near).colliding;
  const bool apart = collide(a, Transform::identity(), b, far).colliding;
  bool refused = false;
  try {
    (void)parse_method("no-such-method");
  } catch (const Error&) {  // ArgumentError, caught through the documented base
    refused = true;
  }
  const bool version_ok = std::strlen(kVersion) > 0;
  std::printf("antcd %s: touching %d, apart %d, bad method refused %d\n", kVersion, touching, apart,
              refused);
  return touching && !apart && refused && version_ok ? 0 : 1;
}
