// The Embree back-end of a build without Embree: every entry point says so. Linked instead of embree_backend.cpp.
#include "accel/embree_backend.h"

namespace lueur {

struct EmbreeScene {};

bool embree_available() { return false; }

std::shared_ptr<const EmbreeScene> build_embree_scene(const std::vector<Vec3>&, const HitFilter&) {
  throw AccelError("--accel embree: this build has no Embree (install libembree-dev and rebuild)");
}

Hit embree_intersect_closest(const EmbreeScene&, const Ray&) { return Hit{}; }
Hit embree_intersect_closest_raw(const EmbreeScene&, const Ray&) { return Hit{}; }
bool embree_intersect_any(const EmbreeScene&, const Ray&) { return false; }
size_t embree_bytes(const EmbreeScene&) { return 0; }
size_t embree_resident_bytes(const EmbreeScene&) { return 0; }
double embree_commit_seconds(const EmbreeScene&) { return 0.0; }

}  // namespace lueur
