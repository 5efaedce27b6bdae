# The core library's sources (antcd::antcd), relative to src/: one list for the native build
# (src/CMakeLists.txt) and the WebAssembly build (wasm/CMakeLists.txt). The broad-phase tree,
# world/aabb_tree.cpp, is listed apart (ANTCD_CORE_TREE_SOURCE): the native build compiles it once
# as an object library shared with world_tests.
set(ANTCD_CORE_SOURCES
  geometry/predicates.cpp
  geometry/intersection.cpp
  geometry/distance.cpp
  geometry/solid_angle.cpp
  geometry/penetration.cpp
  geometry/obb.cpp
  geometry/obb_fit.cpp
  mesh/mesh.cpp
  mesh/closed.cpp
  mesh/shapes.cpp
  bvh/split.cpp
  bvh/build.cpp
  bvh/traverse.cpp
  bvh/refit.cpp
  bvh/model_file.cpp
  bvh/model_check.cpp
  exact/exact.cpp
  exact/manifold.cpp
  distance/distance.cpp
  penetration/convex.cpp
  penetration/inside_point.cpp
  penetration/penetration.cpp
  penetration/signed_distance.cpp
  points/point_index.cpp
  points/point_tree.cpp
  points/solid_grid.cpp
  points/points.cpp
  util/file.cpp
  world/world.cpp
  world/query.cpp
  world/raycast.cpp
  world/nearest.cpp
  world/continuous.cpp
  world/deform_motion.cpp
  ccd/first_contact.cpp
  ccd/plane_step.cpp
  ccd/primitive.cpp
  ccd/sweep.cpp
  ccd/swept_proximity.cpp
  ccd/deform_bounds.cpp
  ccd/deform_sweep.cpp
  ccd/normal_cone.cpp
)
set(ANTCD_CORE_TREE_SOURCE world/aabb_tree.cpp)
# Self-collision of one Model (antcd/self.hpp).
list(APPEND ANTCD_CORE_SOURCES self/pair_test.cpp self/cone.cpp self/self.cpp self/proximity.cpp)
