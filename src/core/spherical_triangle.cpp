// Arvo's warp, in double precision: it runs only for the few light samples whose triangle is close to their point,
// where thin spherical triangles lose too much to rounding in floats.
#include "core/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace lueur {
namespace {

/// The unit vector along the part of `v` orthogonal to the unit vector `axis`, or zero if there is none.
glm::dvec3 orthogonal_direction(const glm::dvec3& v, const glm::dvec3& axis) {
  const glm::dvec3 w = v - glm::dot(v, axis) * axis;
  const double length = glm::length(w);
  return length > 0.0 ? w / length : glm::dvec3(0.0);
}

/// The cosine and sine of the angle at corner `at` between the great circles toward `to1` and `to2`, from the
/// normals of their planes (no inverse trigonometry); false where a side has no length.
bool corner_angle(const glm::dvec3& at, const glm::dvec3& to1, const glm::dvec3& to2, double& cos_angle,
                  double& sin_angle) {
  const glm::dvec3 n1 = glm::cross(at, to1), n2 = glm::cross(at, to2);
  const double lengths = glm::length(n1) * glm::length(n2);
  if (!(lengths > 0.0)) return false;
  cos_angle = std::clamp(glm::dot(n1, n2) / lengths, -1.0, 1.0);
  sin_angle = std::min(glm::length(glm::cross(n1, n2)) / lengths, 1.0);
  return true;
}

/// x in [0, 1) with density proportional to (1 - x) a + x b (a, b >= 0, not both 0), for u in [0, 1).
double sample_linear(double u, double a, double b) {
  if (u == 0.0 && a == 0.0) return 0.0;
  const double x = u * (a + b) / (a + std::sqrt((1.0 - u) * a * a + u * b * b));
  return std::min(x, std::nextafter(1.0, 0.0));
}

}  // namespace

double warp_toward_cosine(const SphericalTriangle& t, const glm::dvec3& normal, double& u1, double& u2) {
  const double at_b = std::max(0.01, glm::dot(normal, t.b)), at_a = std::max(0.01, glm::dot(normal, t.a)),
               at_c = std::max(0.01, glm::dot(normal, t.c));
  // Corners (u1, u2): (0, 0) and (1, 0) b, (0, 1) a, (1, 1) c. u2 from its marginal, then u1 given u2.
  u2 = sample_linear(u2, 2.0 * at_b, at_a + at_c);
  const double left = (1.0 - u2) * at_b + u2 * at_a, right = (1.0 - u2) * at_b + u2 * at_c;
  u1 = sample_linear(u1, left, right);
  const double value = (1.0 - u1) * left + u1 * right;
  return 4.0 * value / (2.0 * at_b + at_a + at_c);
}

SphericalTriangle make_spherical_triangle(const Vec3& from, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  SphericalTriangle t;
  const glm::dvec3 o(from);
  const glm::dvec3 da = glm::dvec3(p0) - o, db = glm::dvec3(p1) - o, dc = glm::dvec3(p2) - o;
  const double la = glm::length(da), lb = glm::length(db), lc = glm::length(dc);
  if (!(la > 0.0) || !(lb > 0.0) || !(lc > 0.0)) return t;
  t.a = da / la;
  t.b = db / lb;
  t.c = dc / lc;
  // The solid angle by Van Oosterom and Strackee's formula, which stays accurate for thin and small triangles
  // where the sum of the corner angles minus pi would cancel.
  const double triple = std::fabs(glm::dot(t.a, glm::cross(t.b, t.c)));
  const double denominator = 1.0 + glm::dot(t.a, t.b) + glm::dot(t.b, t.c) + glm::dot(t.c, t.a);
  const double solid_angle = 2.0 * std::atan2(triple, denominator);
  if (!(solid_angle > 1e-9) || !std::isfinite(solid_angle)) return t;
  if (!corner_angle(t.a, t.b, t.c, t.cos_alpha, t.sin_alpha)) return t;
  t.solid_angle = solid_angle;
  t.cos_ab = std::clamp(glm::dot(t.a, t.b), -1.0, 1.0);
  return t;
}

glm::dvec3 sample_spherical_triangle(const SphericalTriangle& t, double u1, double u2) {
  // Choose the sub-triangle a b c' of area u1 x solid_angle: its corner c' lies on the arc from a to c, found from
  // the spherical law of cosines (Arvo's steps 2-5). Then a direction on the arc from b to c', with the cosine
  // from b uniform so that area is (step 6-7).
  // The sine and cosine of area - alpha by the angle-difference identities: one sine and one cosine in all.
  const double area = u1 * t.solid_angle;
  const double sin_area = std::sin(area), cos_area = std::cos(area);
  const double s = sin_area * t.cos_alpha - cos_area * t.sin_alpha;
  const double c = cos_area * t.cos_alpha + sin_area * t.sin_alpha;
  const double u = c - t.cos_alpha;
  const double v = s + t.sin_alpha * t.cos_ab;
  const double q_denominator = (v * s + u * c) * t.sin_alpha;
  double q = q_denominator != 0.0 ? ((v * c - u * s) * t.cos_alpha - v) / q_denominator : 1.0;
  q = std::clamp(q, -1.0, 1.0);
  const glm::dvec3 c_prime = q * t.a + std::sqrt(std::max(0.0, 1.0 - q * q)) * orthogonal_direction(t.c, t.a);
  const double z = std::clamp(1.0 - u2 * (1.0 - glm::dot(c_prime, t.b)), -1.0, 1.0);
  return z * t.b + std::sqrt(std::max(0.0, 1.0 - z * z)) * orthogonal_direction(c_prime, t.b);
}

}  // namespace lueur
