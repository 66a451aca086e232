// Scenes and rays for the BVH suites: see bvh_test_scenes.h.
#include "bvh_test_scenes.h"

#include <cmath>
#include <sstream>

namespace lueur::test {
namespace {

/// A point of triangle i that stresses the edges: a vertex, an edge midpoint or a random interior point.
Vec3 target_point(std::mt19937& rng, const Corners& corners, size_t i) {
  const Vec3& a = corners[3 * i];
  const Vec3& b = corners[3 * i + 1];
  const Vec3& c = corners[3 * i + 2];
  switch (rng() % 4) {
    case 0:
      return (rng() % 3 == 0) ? a : (rng() % 2 == 0 ? b : c);
    case 1:
      return 0.5f * (a + b);
    default: {
      float u = uniform(rng, 0.0f, 1.0f), v = uniform(rng, 0.0f, 1.0f);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      return a + u * (b - a) + v * (c - a);
    }
  }
}

}  // namespace

bool triangle_finite(const Corners& corners, size_t i) {
  const Vec3& a = corners[3 * i];
  const Vec3& b = corners[3 * i + 1];
  const Vec3& c = corners[3 * i + 2];
  return is_finite(a) && is_finite(b) && is_finite(c) && is_finite(b - a) && is_finite(c - a);
}

bool triangle_kept(const Corners& corners, size_t i) {
  const Vec3& a = corners[3 * i];
  return triangle_finite(corners, i) && glm::cross(corners[3 * i + 1] - a, corners[3 * i + 2] - a) != Vec3(0.0f);
}

Hit brute_force_closest(const Corners& corners, const Ray& ray) {
  Hit best;
  for (size_t i = 0; i < corners.size() / 3; ++i) {
    if (!triangle_finite(corners, i)) continue;
    const auto id = static_cast<uint32_t>(i);
    const BvhTriangle tri = make_bvh_triangle(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2], id);
    float t = 0.0f, u = 0.0f, v = 0.0f;
    if (!intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v)) continue;
    if (t < best.t || (t == best.t && id < best.triangle)) {
      best.t = t;
      best.triangle = id;
      best.u = u;
      best.v = v;
    }
  }
  return best;
}

Box3 bounds_of(const Corners& corners) {
  Box3 box;
  for (size_t i = 0; i < corners.size() / 3; ++i) {
    if (!triangle_finite(corners, i)) continue;
    for (int k = 0; k < 3; ++k) box.expand(corners[3 * i + k]);
  }
  return box;
}

float uniform(std::mt19937& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }

Vec3 uniform_in(std::mt19937& rng, const Vec3& lo, const Vec3& hi) {
  return Vec3(uniform(rng, lo.x, hi.x), uniform(rng, lo.y, hi.y), uniform(rng, lo.z, hi.z));
}

Vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  for (;;) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    const float len = glm::length(d);
    if (len > 1e-3f) return d / len;
  }
}

Ray random_ray(std::mt19937& rng, const Corners& corners, const Box3& bounds) {
  const Vec3 margin = 0.2f * bounds.extent() + Vec3(0.1f);
  const Vec3 lo = bounds.lo - margin;
  const Vec3 hi = bounds.hi + margin;
  Ray ray;
  ray.origin = uniform_in(rng, lo, hi);
  const size_t count = corners.size() / 3;
  size_t target = rng() % count;
  for (size_t tries = 0; tries < 16 && !triangle_finite(corners, target); ++tries) target = rng() % count;
  const bool can_target = triangle_finite(corners, target);

  const unsigned kind = rng() % 10;
  if (kind <= 2 || !can_target) {
    ray.dir = random_direction(rng);
  } else if (kind == 3) {
    ray.dir = Vec3(0.0f);
    ray.dir[static_cast<int>(rng() % 3)] = (rng() % 2 == 0) ? 1.0f : -1.0f;
  } else if (kind == 4) {
    ray.dir = random_direction(rng);
    ray.dir[static_cast<int>(rng() % 3)] = (rng() % 2 == 0) ? 0.0f : -0.0f;
    if (ray.dir == Vec3(0.0f)) ray.dir = Vec3(1.0f, 0.0f, 0.0f);
  } else if (kind <= 7) {
    ray.dir = target_point(rng, corners, target) - ray.origin;
    if (ray.dir == Vec3(0.0f)) ray.dir = random_direction(rng);
  } else {
    // Axis-aligned through a vertex or edge point: exact zero components meeting shared edges.
    const Vec3 point = target_point(rng, corners, target);
    const int axis = static_cast<int>(rng() % 3);
    const bool positive = rng() % 2 == 0;
    ray.origin = point;
    ray.origin[axis] = positive ? lo[axis] : hi[axis];
    ray.dir = Vec3(0.0f);
    ray.dir[axis] = positive ? 1.0f : -1.0f;
  }
  if (rng() % 4 == 0) ray.dir *= std::exp(uniform(rng, std::log(0.01f), std::log(100.0f)));

  const float scale = glm::length(hi - lo) / glm::length(ray.dir);
  if (rng() % 4 == 0) ray.tmax = uniform(rng, 0.0f, 1.5f * scale);
  if (rng() % 5 == 0) ray.tmin = uniform(rng, 0.0f, 0.3f * scale);
  return ray;
}

std::string describe(const Ray& ray) {
  std::ostringstream out;
  out << std::hexfloat << "origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir ("
      << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ") tmin " << ray.tmin << " tmax " << ray.tmax;
  return out.str();
}

std::string describe(const Hit& hit) {
  if (!hit.found()) return "miss";
  std::ostringstream out;
  out << "triangle " << hit.triangle << std::hexfloat << " t " << hit.t << " u " << hit.u << " v " << hit.v;
  return out.str();
}

void add_triangle(Corners& corners, const Vec3& a, const Vec3& b, const Vec3& c) {
  corners.push_back(a);
  corners.push_back(b);
  corners.push_back(c);
}

Corners make_soup(std::mt19937& rng, size_t count) {
  Corners corners;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 center = uniform_in(rng, Vec3(-10.0f), Vec3(10.0f));
    const float size = std::exp(uniform(rng, std::log(0.02f), std::log(8.0f)));
    add_triangle(corners, center + size * uniform_in(rng, Vec3(-1.0f), Vec3(1.0f)),
                 center + size * uniform_in(rng, Vec3(-1.0f), Vec3(1.0f)),
                 center + size * uniform_in(rng, Vec3(-1.0f), Vec3(1.0f)));
  }
  for (size_t i = 0; i < count / 20; ++i) {
    const size_t src = rng() % count;
    add_triangle(corners, corners[3 * src], corners[3 * src + 1], corners[3 * src + 2]);
  }
  return corners;
}

Corners make_grid(int n, bool flat) {
  const float h = 0.25f;
  auto vertex = [&](int i, int j) {
    const float z =
        flat ? 0.0f : 0.7f * std::sin(0.31f * static_cast<float>(i)) * std::cos(0.23f * static_cast<float>(j));
    return Vec3(h * static_cast<float>(i), h * static_cast<float>(j), z);
  };
  Corners corners;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      add_triangle(corners, vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      add_triangle(corners, vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  }
  return corners;
}

Corners make_slivers(std::mt19937& rng) {
  Corners corners;
  auto point = [&] { return uniform_in(rng, Vec3(-4.0f), Vec3(4.0f)); };
  for (int i = 0; i < 300; ++i) {
    const Vec3 a = point();
    add_triangle(corners, a, a + uniform_in(rng, Vec3(-1.0f), Vec3(1.0f)),
                 a + uniform_in(rng, Vec3(-1.0f), Vec3(1.0f)));
  }
  for (int i = 0; i < 300; ++i) {  // almost collinear: the third vertex a hair off the edge
    const Vec3 a = point(), b = point();
    const float w = uniform(rng, 0.0f, 1.0f);
    const Vec3 off = random_direction(rng) * (glm::length(b - a) * std::pow(10.0f, uniform(rng, -7.0f, -3.0f)));
    add_triangle(corners, a, b, a + w * (b - a) + off);
  }
  for (int i = 0; i < 100; ++i) {  // needles: long and very narrow
    const Vec3 a = point(), b = point();
    add_triangle(corners, a, b, b + 1e-4f * random_direction(rng));
  }
  for (int i = 0; i < 60; ++i) {
    const Vec3 a = point(), b = point();
    add_triangle(corners, a, a, b);
    add_triangle(corners, a, b, b);
    add_triangle(corners, b, a, b);
    add_triangle(corners, a, a, a);
    // Exactly collinear: small integer coordinates make b - a and c - a exact multiples.
    const Vec3 base(static_cast<float>(rng() % 7) - 3.0f, static_cast<float>(rng() % 7) - 3.0f,
                    static_cast<float>(rng() % 7) - 3.0f);
    const Vec3 step(static_cast<float>(rng() % 3) - 1.0f, static_cast<float>(rng() % 3) - 1.0f, 0.5f);
    add_triangle(corners, base, base + step, base + 3.0f * step);
  }
  return corners;
}

Corners make_star(std::mt19937& rng, int count) {
  Corners corners;
  for (int i = 0; i < count; ++i) {
    const Vec3 d = random_direction(rng);
    const Vec3 side = glm::normalize(glm::cross(d, random_direction(rng)));
    const float length = 3.0f * static_cast<float>(1 + i % 5);
    const Vec3 centre = 0.05f * random_direction(rng);
    add_triangle(corners, centre - length * d, centre + length * d, centre + length * d + 0.02f * side);
  }
  return corners;
}

Corners make_sphere(int stacks, int slices, float radius) {
  auto vertex = [&](int i, int j) {
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(stacks);
    const float phi = 2.0f * kPi * static_cast<float>(j % slices) / static_cast<float>(slices);
    if (i == 0) return Vec3(0.0f, 0.0f, radius);
    if (i == stacks) return Vec3(0.0f, 0.0f, -radius);
    return radius * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  Corners corners;
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      add_triangle(corners, vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      add_triangle(corners, vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  }
  return corners;
}

size_t count_zero_area(const Corners& corners) {
  size_t n = 0;
  for (size_t i = 0; i < corners.size() / 3; ++i) {
    const Vec3 e1 = corners[3 * i + 1] - corners[3 * i];
    const Vec3 e2 = corners[3 * i + 2] - corners[3 * i];
    n += glm::cross(e1, e2) == Vec3(0.0f) ? 1 : 0;
  }
  return n;
}

}  // namespace lueur::test
