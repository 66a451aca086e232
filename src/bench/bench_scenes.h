// The scenes lueur-bench measures: the default scene, the real scenes in ../shared/scenes when present, and a
// procedural field of spheres of about 2 million triangles, each with a view and the lights its shadow rays aim at.
// Depends on the scene and camera layers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "scene/scene.h"

namespace lueur::bench {

struct BenchScene {
  std::string name;
  Scene scene;
  CameraSpec view;
  std::vector<uint32_t> lights;  ///< emitter triangles the shadow rays aim at (uniform by area)
  std::string path;              ///< the OBJ file it was read from; empty for a built-in scene
};

/// A field of `spheres` random UV spheres (64 x 32, 3,968 triangles each) over a ground quad, lit from above,
/// seen from above one corner.
BenchScene make_sphere_field(int spheres, uint32_t seed);

/// A closed room (4 x 3 x 6, a block on its floor) seen from inside facing its far wall from close by, lit by a
/// ceiling panel behind the camera: nearly every bounce ray from the wall the camera sees lands on a surface it does
/// not see (issue 51's test of the L1 store).
BenchScene make_room_facing_wall();

/// Spheres for about `triangles` triangles.
int spheres_for(size_t triangles);

/// The default scene with its view.
BenchScene make_default_bench_scene();

/// One of the shared scenes by its benchmark name (cornell-water, stanford-bunny, conference, cornell-original), or
/// nothing where it is missing (the reason appended to `skipped`) or not one of them.
std::optional<BenchScene> load_shared_bench_scene(const std::string& name, const std::string& shared_dir,
                                                  std::vector<std::string>& skipped);

/// The benchmark's scene list. `quick`: the default scene, the bunny, and a 100k-triangle sphere field; otherwise
/// every scene named in the README's table that is present, and the 2M-triangle field. `shared_dir` may be empty
/// or missing: those scenes are then left out (and named in `skipped`).
std::vector<BenchScene> load_bench_scenes(bool quick, const std::string& shared_dir, std::vector<std::string>& skipped);

}  // namespace lueur::bench
