// The optional libraries of the installed package: antcd::io (load_mesh) and antcd::random (method
// names, random detection). Built into antcd_consumer when the package has them.
#include <antcd/bvh.hpp>
#include <antcd/error.hpp>
#include <antcd/load.hpp>
#include <antcd/mesh.hpp>
#include <antcd/method.hpp>
#include <antcd/random.hpp>

#include <cstdio>
#include <filesystem>

bool full_checks() {
  using namespace antcd;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "antcd_consumer_box.obj";
  save_obj(make_box(Vec3(1, 1, 1)), file);
  const Mesh loaded = load_mesh(file);
  std::filesystem::remove(file);
  bool refused = false;
  try {
    (void)parse_method("no-such-method");
  } catch (const Error&) {
    refused = true;
  }
  const Model a(loaded);
  const Model b(make_sphere(0.5));
  const SearchResult hit = random_collide(
      a, Transform::identity(), b, Transform::from_axis_angle(Vec3::UnitZ(), 0, Vec3(1.2, 0, 0)));
  std::printf("antcd::io loaded %zu triangles; antcd::random: bad method refused %d, found %d\n",
              loaded.triangles.size(), refused, hit.found);
  return loaded.triangles.size() == 12 && refused;
}
