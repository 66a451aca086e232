// Sampling a triangle by the solid angle it subtends from a point (Arvo 1995, "Stratified Sampling of Spherical
// Triangles"): every direction toward the triangle equally likely, pdf 1 / solid angle. Area sampling's weight
// cos_light area / d^2 grows without bound for a point close to the triangle's plane (at the edge where an emitting
// face meets a lit one), an estimator of infinite variance; this one's weight is the solid angle, at most 2 pi.
// Depends on core/math.h only.
#pragma once

#include "core/math.h"

namespace lueur {

/// A triangle as seen from a point: the unit directions to its corners, and the quantities Arvo's warp needs.
struct SphericalTriangle {
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};
  double solid_angle = 0.0;                 ///< 0 when the triangle is seen edge-on or from one of its corners
  double cos_alpha = 1.0, sin_alpha = 0.0;  ///< of the angle at corner a between the arcs to b and to c
  double cos_ab = 1.0;                      ///< cosine of the arc from a to b
};

/// The triangle p0 p1 p2 as seen from `from`.
SphericalTriangle make_spherical_triangle(const Vec3& from, const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// A unit direction uniform over the spherical triangle for (u1, u2) in [0, 1)^2, a warp that keeps the
/// stratification of the numbers. Only for a triangle with a positive solid angle.
glm::dvec3 sample_spherical_triangle(const SphericalTriangle& t, double u1, double u2);

/// The numbers (u1, u2) for sample_spherical_triangle warped so that directions come about in proportion to the
/// cosine with `normal` (pbrt-v4's warp product sampling): a bilinear density over [0, 1]^2 whose corners hold the
/// cosines toward the corners the warp maps them to ((0, 0) and (1, 0) to b, (0, 1) to a, (1, 1) to c), each at
/// least 0.01 so that no direction is left out. Returns the density of the warped numbers, by which the estimate
/// divides; 1 with no warp.
double warp_toward_cosine(const SphericalTriangle& t, const glm::dvec3& normal, double& u1, double& u2);

}  // namespace lueur
