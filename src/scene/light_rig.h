// What a scene from the internet needs to be seen at first look: whether it is a closed room (a camera outside it
// sees only its walls), the view from inside such a room, and the default light rig for a scene without emitters,
// made of emissive triangles so that every pass and light strategy samples it like any other light.
// Depends on core and scene only: rays are cast through a function, over the model's triangles here (model_ray_cast) or
// by a BVH above.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/camera_spec.h"
#include "scene/scene.h"

namespace lueur {

/// Distance along the unit direction `dir` from `origin` to the nearest surface, or infinity; `front` tells whether
/// that surface was met on the side its winding faces.
using RayCast = std::function<float(const Vec3& origin, const Vec3& dir, bool& front)>;

/// What a loop over every triangle of `scene` (its light rig excluded) finds, for scenes not yet prepared for tracing;
/// runs of triangles whose box a ray misses are skipped. `scene` must outlive the function and keep its triangles.
RayCast model_ray_cast(const Scene& scene);

/// A closed room: a point inside it from which nearly every direction meets a wall, and what that point sees above
/// and below (the rig's ceiling panel hangs there).
struct Enclosure {
  Vec3 inside{0.0f};                 ///< a point of open space inside the room
  float up = 0.0f;                   ///< distance from `inside` to the ceiling
  float down = 0.0f;                 ///< distance from `inside` to the floor
  Vec3 long_axis{1.0f, 0.0f, 0.0f};  ///< the room's longer horizontal axis (x or z)
};

/// Whether the model inside `bounds` is a closed room, probed from a few points of its bounding box (30% of the way
/// along its longer horizontal axis at 60% of its height, where lueur-bench's camera stands in the conference
/// room; the centre; higher up): a point is inside a room when at least 62 of 64
/// directions meet a surface and most of them meet it on the side its winding faces (rooms face inwards; from
/// inside a closed solid, such as a scanned statue, the rays meet its back faces).
std::optional<Enclosure> find_enclosure(const Box3& bounds, const RayCast& cast);

/// The view from inside a closed room: from the enclosure's inside point along the room's longer axis, toward its
/// far end and a little down, 60 degrees tall.
CameraSpec inside_view(const Box3& bounds, const Enclosure& room);

/// Adds the default light rig to `scene` (which has no emitter), scaled by `scale`, and returns what it added in a
/// few words. The rig's triangles come after the model's (Scene::rig_begin), so that the model's bounds, which the
/// camera frames, leave them out.
/// - Outside a closed room: a sky, a closed box of 12 inward-facing emitting triangles four model radii around the
///   model, brightest on top (1.1), then behind the default camera (0.7, the key), at the sides and ahead (0.2:
///   the background the first view sees, with no seam where a wide image reaches the sides) and below (0.05): a
///   white surface facing up at its centre reads 1.1 x the top's form factor (0.554) + 1.3 x a quarter of the
///   rest, 0.754.
/// - Inside a closed room (`room`): a panel under the ceiling above the inside point, facing down, bright enough
///   that the white floor below it reads 1.
/// Far beyond float's reach (coordinates near 1e20) the rig's triangles may have no area; the caller checks.
std::string add_light_rig(Scene& scene, const std::optional<Enclosure>& room, float scale);

}  // namespace lueur
