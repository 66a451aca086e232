// The Embree 3 back-end: one device and one triangle geometry per scene, traced with rtcIntersect1/rtcOccluded1.
// The only file that includes Embree's headers.
#include "accel/embree_backend.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <string>

#include "bvh/bvh.h"

namespace lueur {

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<float> vertices;         ///< 3 floats per corner, plus one float of padding Embree may read
  std::vector<uint32_t> indices;       ///< 0, 1, 2, 3, ...: triangle i uses corners 3i, 3i + 1, 3i + 2
  std::vector<BvhTriangle> triangles;  ///< Lueur's form of each triangle, in input order, for the exact hit
  std::atomic<long long> bytes{0};     ///< Embree's live allocations, from its memory monitor
  std::string error;                   ///< the first error Embree reported
  HitFilter filter;                    ///< hits to pass through (alpha cutouts), when set
  double commit_seconds = 0.0;         ///< rtcCommitScene's wall time

  EmbreeScene() = default;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

bool monitor_memory(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<EmbreeScene*>(user)->bytes.fetch_add(static_cast<long long>(bytes), std::memory_order_relaxed);
  return true;
}

void record_error(void* user, RTCError /*code*/, const char* message) {
  auto* s = static_cast<EmbreeScene*>(user);
  if (s->error.empty()) s->error = message ? message : "unknown error";
}

RTCRay to_embree(const Ray& ray) {
  RTCRay r;
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.tnear = ray.tmin;
  r.dir_x = ray.dir.x;
  r.dir_y = ray.dir.y;
  r.dir_z = ray.dir.z;
  r.time = 0.0f;
  r.tfar = ray.tmax;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  return r;
}

/// rtcIntersect1 on one ray; the hit's primitive id is the input triangle index.
RTCRayHit trace(const EmbreeScene& scene, const Ray& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = to_embree(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene.scene, &context, &rh);
  return rh;
}

/// Embree's filter function (intersect and occluded alike): refuses the hits the scene's HitFilter refuses. The
/// barycentrics are recomputed with Lueur's triangle test, as embree_intersect_closest does, so that a hole is the
/// same hole in both back-ends.
void filter_hits(const RTCFilterFunctionNArguments* args) {
  const auto* s = static_cast<const EmbreeScene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t id = RTCHitN_primID(args->hit, args->N, i);
    float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    Ray ray;
    ray.origin = Vec3(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                      RTCRayN_org_z(args->ray, args->N, i));
    ray.dir = Vec3(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                   RTCRayN_dir_z(args->ray, args->N, i));
    ray.tmin = RTCRayN_tnear(args->ray, args->N, i);
    ray.tmax = std::numeric_limits<float>::infinity();
    const BvhTriangle& tri = s->triangles[id];
    float t = 0.0f, uu = 0.0f, vv = 0.0f;
    if (intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, uu, vv)) u = uu, v = vv;
    if (!s->filter(id, u, v)) args->valid[i] = 0;
  }
}

}  // namespace

bool embree_available() { return true; }

std::shared_ptr<const EmbreeScene> build_embree_scene(const std::vector<Vec3>& corners, const HitFilter& filter) {
  const size_t count = corners.size() / 3;
  if (count >= kNoHit) throw AccelError("Embree: too many triangles for 32-bit indices");
  auto s = std::make_shared<EmbreeScene>();
  s->device = rtcNewDevice(nullptr);
  if (!s->device) throw AccelError("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(s->device, record_error, s.get());
  rtcSetDeviceMemoryMonitorFunction(s->device, monitor_memory, s.get());

  s->vertices.resize(9 * count + 1, 0.0f);
  s->indices.resize(3 * count);
  s->triangles.reserve(count);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t i = 0; i < count; ++i) {
    const Vec3& a = corners[3 * i];
    const Vec3& b = corners[3 * i + 1];
    const Vec3& c = corners[3 * i + 2];
    const BvhTriangle tri = make_bvh_triangle(a, b, c, static_cast<uint32_t>(i));
    s->triangles.push_back(tri);
    // build_bvh drops these; a NaN vertex makes Embree drop them as well.
    const bool kept = is_finite(a) && is_finite(b) && is_finite(c) && is_finite(tri.e1) && is_finite(tri.e2);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corners[3 * i + static_cast<size_t>(k)];
      for (int axis = 0; axis < 3; ++axis)
        s->vertices[9 * i + 3 * static_cast<size_t>(k) + axis] = kept ? p[axis] : nan;
      s->indices[3 * i + static_cast<size_t>(k)] = static_cast<uint32_t>(3 * i + static_cast<size_t>(k));
    }
  }

  s->scene = rtcNewScene(s->device);
  rtcSetSceneBuildQuality(s->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, s->vertices.data(), 0,
                             3 * sizeof(float), 3 * count);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, s->indices.data(), 0,
                             3 * sizeof(uint32_t), count);
  if (filter.accepts) {
    s->filter = filter;
    rtcSetGeometryUserData(geometry, s.get());
    rtcSetGeometryIntersectFilterFunction(geometry, filter_hits);
    rtcSetGeometryOccludedFilterFunction(geometry, filter_hits);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(s->scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  // Only the BVH's own allocations count towards its size.
  s->bytes.store(0);
  const auto commit_start = std::chrono::steady_clock::now();
  rtcCommitScene(s->scene);
  s->commit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - commit_start).count();
  if (!s->error.empty()) throw AccelError("Embree: " + s->error);
  return s;
}

Hit embree_intersect_closest_raw(const EmbreeScene& scene, const Ray& ray) {
  const RTCRayHit rh = trace(scene, ray);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rh.ray.tfar;
  hit.triangle = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  return hit;
}

Hit embree_intersect_closest(const EmbreeScene& scene, const Ray& ray) {
  Hit hit = embree_intersect_closest_raw(scene, ray);
  if (!hit.found()) return hit;
  const BvhTriangle& tri = scene.triangles[hit.triangle];
  float t = 0.0f, u = 0.0f, v = 0.0f;
  if (intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v)) {
    hit.t = t;
    hit.u = u;
    hit.v = v;
  }
  return hit;
}

bool embree_intersect_any(const EmbreeScene& scene, const Ray& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray);
  rtcOccluded1(scene.scene, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

size_t embree_bytes(const EmbreeScene& scene) {
  const long long bytes = scene.bytes.load();
  return bytes > 0 ? static_cast<size_t>(bytes) : 0;
}

size_t embree_resident_bytes(const EmbreeScene& scene) {
  return embree_bytes(scene) + scene.vertices.size() * sizeof(float) + scene.indices.size() * sizeof(uint32_t);
}

double embree_commit_seconds(const EmbreeScene& scene) { return scene.commit_seconds; }

}  // namespace lueur
