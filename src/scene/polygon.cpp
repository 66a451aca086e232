// Face triangulation (see polygon.h): the quad rule and ear clipping on the polygon's projection.
#include "scene/polygon.h"

#include <cmath>

namespace lueur {
namespace {

using Point2 = glm::dvec2;

/// Twice the signed area of triangle (a, b, c): positive when it turns counter-clockwise.
double turn(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Whether `q` lies inside or on the counter-clockwise triangle (a, b, c).
bool inside(const Point2& a, const Point2& b, const Point2& c, const Point2& q) {
  return turn(a, b, q) >= 0.0 && turn(b, c, q) >= 0.0 && turn(c, a, q) >= 0.0;
}

/// The polygon projected along its Newell normal's largest axis, turned so that it runs counter-clockwise; empty
/// when the polygon has no area to project (all corners on a line, or not finite).
std::vector<Point2> project(const std::vector<Vec3>& points) {
  glm::dvec3 normal(0.0);
  const size_t k = points.size();
  for (size_t i = 0; i < k; ++i) normal += glm::cross(glm::dvec3(points[i]), glm::dvec3(points[(i + 1) % k]));
  const glm::dvec3 size = glm::abs(normal);
  if (!(size.x > 0.0 || size.y > 0.0 || size.z > 0.0) || !std::isfinite(size.x + size.y + size.z)) return {};
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  // (y, z), (z, x) and (x, y) turn counter-clockwise about +x, +y and +z.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double flip = normal[axis] < 0.0 ? -1.0 : 1.0;
  std::vector<Point2> projected(k);
  for (size_t i = 0; i < k; ++i) projected[i] = Point2(points[i][u], flip * points[i][v]);
  return projected;
}

void clip_ears(const std::vector<Point2>& p, std::vector<std::array<uint32_t, 3>>& out) {
  const auto k = static_cast<uint32_t>(p.size());
  std::vector<uint32_t> prev(k), next(k);
  for (uint32_t i = 0; i < k; ++i) prev[i] = (i + k - 1) % k, next[i] = (i + 1) % k;
  std::vector<uint8_t> reflex(k);
  const auto classify = [&](uint32_t i) { reflex[i] = turn(p[prev[i]], p[i], p[next[i]]) <= 0.0; };
  for (uint32_t i = 0; i < k; ++i) classify(i);
  const auto is_ear = [&](uint32_t i) {
    if (reflex[i]) return false;
    const uint32_t a = prev[i], c = next[i];
    // A corner inside would be cut off; one on an edge or at a corner (a repeated position) means the polygon
    // touches or retraces itself there.
    for (uint32_t j = next[c]; j != a; j = next[j])
      if (inside(p[a], p[i], p[c], p[j])) return false;
    return true;
  };
  uint32_t remaining = k, i = 0, tried = 0;
  while (remaining > 3) {
    if (tried > remaining) return;  // a whole turn without an ear: none is left to find
    if (is_ear(i)) {
      const uint32_t a = prev[i], c = next[i];
      out.push_back({a, i, c});
      next[a] = c, prev[c] = a;
      classify(a);
      classify(c);
      --remaining, tried = 0;
      i = a;
    } else {
      i = next[i], ++tried;
    }
  }
  out.push_back({prev[i], i, next[i]});
}

}  // namespace

void triangulate_face(const std::vector<Vec3>& points, std::vector<std::array<uint32_t, 3>>& out) {
  const auto k = static_cast<uint32_t>(points.size());
  if (k < 3) return;
  if (k == 3) {
    out.push_back({0, 1, 2});
    return;
  }
  if (k == 4) {
    // In float, as the diagonals' squared lengths have always been compared here (ties split 1-3).
    const Vec3 e02 = points[2] - points[0], e13 = points[3] - points[1];
    const float d02 = e02.x * e02.x + e02.y * e02.y + e02.z * e02.z;
    const float d13 = e13.x * e13.x + e13.y * e13.y + e13.z * e13.z;
    if (d02 < d13) {
      out.push_back({0, 1, 2});
      out.push_back({0, 2, 3});
    } else {
      out.push_back({0, 1, 3});
      out.push_back({1, 2, 3});
    }
    return;
  }
  const std::vector<Point2> projected = project(points);
  if (projected.empty()) {
    for (uint32_t i = 1; i + 1 < k; ++i) out.push_back({0, i, i + 1});  // no area: a fan, every triangle of zero area
    return;
  }
  clip_ears(projected, out);
}

}  // namespace lueur
