// Scenes and rays for the BVH suites (test_bvh_*.cpp): triangle soups, grids, slivers, stars and spheres given as
// corner lists, random rays that stress edges and vertices, the brute-force reference the BVH must agree with, and
// descriptions of rays and hits for failure messages. Depends on bvh and core only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "bvh/bvh.h"

namespace lueur::test {

/// Triangles as three corners each, the form build_bvh takes.
using Corners = std::vector<Vec3>;

/// Whether input triangle i has finite vertices and edges (the brute-force reference skips the others).
bool triangle_finite(const Corners& corners, size_t i);

/// What build_bvh keeps: finite triangles of nonzero area (the others can never be hit).
bool triangle_kept(const Corners& corners, size_t i);

/// The reference: every triangle through the same preparation and test as the BVH, ties to the lowest index.
Hit brute_force_closest(const Corners& corners, const Ray& ray);

/// The box of the finite triangles.
Box3 bounds_of(const Corners& corners);

float uniform(std::mt19937& rng, float lo, float hi);
Vec3 uniform_in(std::mt19937& rng, const Vec3& lo, const Vec3& hi);
Vec3 random_direction(std::mt19937& rng);

/// Rays of several kinds: random, exactly axis-aligned, with one zero component, and aimed at triangle vertices,
/// edges and interiors (some of those axis-aligned too); random lengths of direction, finite tmax, positive tmin.
Ray random_ray(std::mt19937& rng, const Corners& corners, const Box3& bounds);

/// Exact (hexadecimal) descriptions for failure messages.
std::string describe(const Ray& ray);
std::string describe(const Hit& hit);

void add_triangle(Corners& corners, const Vec3& a, const Vec3& b, const Vec3& c);

/// Triangles of mixed sizes scattered in a box, some overlapping, with a few exact duplicates appended so that
/// equal distances also happen between triangles in different leaves.
Corners make_soup(std::mt19937& rng, size_t count);

/// An n x n grid of quads, two triangles each, sharing exact vertices; flat (z == 0) or a height field.
Corners make_grid(int n, bool flat);

/// Normal triangles mixed with slivers, needles and zero-area triangles (repeated and collinear vertices).
Corners make_slivers(std::mt19937& rng);

/// Long slivers through one point, in every direction, of a few lengths: every box overlaps every other, the case
/// where reinsertion's search can prune nothing (bvh_reinsert.cpp caps it).
Corners make_star(std::mt19937& rng, int count);

/// A closed UV sphere with shared vertices (pole triangles with two equal vertices included).
Corners make_sphere(int stacks, int slices, float radius);

/// Triangles whose edge cross product is exactly zero.
size_t count_zero_area(const Corners& corners);

}  // namespace lueur::test
