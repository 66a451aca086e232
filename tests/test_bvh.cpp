// Tests for Lueur's BVH: closest and any hit against a brute-force loop over several scenes and many rays, the
// tree invariants, and degenerate inputs. Depends on bvh and core only (no scene loading, no renderer).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "test_support.h"

namespace lueur {
namespace {

using Corners = std::vector<Vec3>;

/// Whether input triangle i has finite vertices and edges (the brute-force reference skips the others).
bool triangle_finite(const Corners& corners, size_t i) {
  const Vec3& a = corners[3 * i];
  const Vec3& b = corners[3 * i + 1];
  const Vec3& c = corners[3 * i + 2];
  return is_finite(a) && is_finite(b) && is_finite(c) && is_finite(b - a) && is_finite(c - a);
}

/// What build_bvh keeps: finite triangles of nonzero area (the others can never be hit).
bool triangle_kept(const Corners& corners, size_t i) {
  const Vec3& a = corners[3 * i];
  return triangle_finite(corners, i) && glm::cross(corners[3 * i + 1] - a, corners[3 * i + 2] - a) != Vec3(0.0f);
}

/// The reference: every triangle through the same preparation and test as the BVH, ties to the lowest index.
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

/// Rays of several kinds: random, exactly axis-aligned, with one zero component, and aimed at triangle vertices,
/// edges and interiors (some of those axis-aligned too); random lengths of direction, finite tmax, positive tmin.
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

struct RayStats {
  size_t rays = 0;
  size_t hits = 0;
  size_t mismatches = 0;
};

/// Fires `count` rays at the scene and compares the BVH with the brute-force loop on every one.
RayStats compare_with_brute_force(const Corners& corners, const Bvh& bvh, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  const Box3 bounds = bounds_of(corners);
  RayStats stats;
  for (size_t i = 0; i < count; ++i) {
    const Ray ray = random_ray(rng, corners, bounds);
    const Hit expected = brute_force_closest(corners, ray);
    const Hit got = intersect_closest(bvh, ray);
    const bool any = intersect_any(bvh, ray);
    ++stats.rays;
    if (expected.found()) ++stats.hits;
    const bool same = got.found() == expected.found() &&
                      (!expected.found() || (got.triangle == expected.triangle && got.t == expected.t &&
                                             got.u == expected.u && got.v == expected.v));
    if (!same || any != expected.found()) {
      if (++stats.mismatches <= 5) {
        ADD_FAILURE() << "ray " << i << ": " << describe(ray) << "\n  bvh:   " << describe(got)
                      << "\n  brute: " << describe(expected) << "\n  any:   " << any;
      }
    }
  }
  EXPECT_EQ(stats.rays, count);
  EXPECT_EQ(stats.mismatches, 0u);
  return stats;
}

/// Walks the tree from the root and checks its structure; returns the deepest node depth.
/// The wide tree the queries traverse (8-wide or 4-wide, whichever was built): every inner slot's node lies inside
/// the slot's box, every leaf holds at most kBvhMaxLeafSize triangles inside its box, and every kept triangle is in
/// exactly one leaf.
template <typename Node, uint32_t W>
void check_wide_tree(const Bvh& bvh, const HugePageVector<Node>& nodes, const Corners& corners) {
  size_t failures = 0;
  auto fail = [&](const std::string& what) {
    if (++failures <= 5) ADD_FAILURE() << what;
  };
  std::vector<int> id_visits(corners.size() / 3, 0);
  auto inside = [](const Vec3& p, const Vec3& lo, const Vec3& hi) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  };
  struct Item {
    uint32_t node;
    Vec3 lo, hi;
  };
  std::vector<Item> stack{{0, Vec3(-kInfinity), Vec3(kInfinity)}};
  size_t visited = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node >= nodes.size() || ++visited > nodes.size()) {
      fail("wide node " + std::to_string(item.node) + " out of range or reached twice");
      continue;
    }
    const Node& node = nodes[item.node];
    uint32_t used = 0;
    for (uint32_t k = 0; k < W; ++k) {
      const Vec3 lo(node.lo[0][k], node.lo[1][k], node.lo[2][k]), hi(node.hi[0][k], node.hi[1][k], node.hi[2][k]);
      if (std::isnan(lo.x)) continue;  // an unused slot
      ++used;
      if (!inside(lo, item.lo, item.hi) || !inside(hi, item.lo, item.hi)) fail("wide slot outside its parent's box");
      if (node.count[k] == 0) {
        stack.push_back({node.child[k], lo, hi});
        continue;
      }
      if (node.count[k] > bvh_group_count(kBvhMaxLeafSize)) fail("wide leaf with too many groups");
      uint32_t triangles = 0;
      for (uint32_t g = node.child[k]; g < node.child[k] + node.count[k] && g < bvh.groups.size(); ++g) {
        for (uint32_t lane = 0; lane < kBvhWidth; ++lane) {
          const uint32_t id = bvh.groups[g].id[lane];
          if (id == kNoHit) continue;
          ++triangles;
          if (id >= id_visits.size()) {
            fail("wide leaf triangle id out of range");
            continue;
          }
          ++id_visits[id];
          for (int corner = 0; corner < 3; ++corner)
            if (!inside(corners[3 * id + corner], lo, hi)) fail("triangle " + std::to_string(id) + " outside its leaf");
        }
      }
      if (triangles == 0 || triangles > kBvhMaxLeafSize)
        fail("wide leaf of " + std::to_string(triangles) + " triangles");
    }
    if (used == 0) fail("wide node " + std::to_string(item.node) + " has no children");
  }
  for (size_t i = 0; i < id_visits.size(); ++i) {
    const int expected = triangle_kept(corners, i) ? 1 : 0;
    if (id_visits[i] != expected)
      fail("input triangle " + std::to_string(i) + " is in " + std::to_string(id_visits[i]) + " wide leaves");
  }
  EXPECT_EQ(failures, 0u);
}

void check_wide_invariants(const Bvh& bvh, const Corners& corners) {
  if (!bvh.wide8_nodes.empty())
    check_wide_tree<BvhWideNode8, kBvhWidth8>(bvh, bvh.wide8_nodes, corners);
  else
    check_wide_tree<BvhWideNode, kBvhWidth>(bvh, bvh.wide_nodes, corners);
}

uint32_t check_invariants(const Bvh& bvh, const Corners& corners) {
  size_t kept_count = 0;
  for (size_t i = 0; i < corners.size() / 3; ++i) kept_count += triangle_kept(corners, i) ? 1 : 0;
  EXPECT_EQ(bvh.triangles.size(), kept_count);
  if (kept_count == 0) {
    EXPECT_TRUE(bvh.empty());
    return 0;
  }
  EXPECT_FALSE(bvh.nodes.empty());
  if (bvh.nodes.empty()) return 0;

  std::vector<int> node_visits(bvh.nodes.size(), 0);
  std::vector<int> slot_visits(bvh.triangles.size(), 0);
  std::vector<int> id_visits(corners.size() / 3, 0);
  struct Item {
    uint32_t node, depth;
  };
  std::vector<Item> stack{{0, 0}};
  uint32_t max_depth = 0;
  size_t failures = 0;
  auto fail = [&](const std::string& what) {
    if (++failures <= 5) ADD_FAILURE() << what;
  };
  auto inside = [](const Vec3& p, const BvhNode& n) {
    return p.x >= n.lo.x && p.y >= n.lo.y && p.z >= n.lo.z && p.x <= n.hi.x && p.y <= n.hi.y && p.z <= n.hi.z;
  };
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    max_depth = std::max(max_depth, item.depth);
    if (++node_visits[item.node] != 1) fail("node " + std::to_string(item.node) + " reached twice");
    const BvhNode& node = bvh.nodes[item.node];
    if (!(node.lo.x <= node.hi.x && node.lo.y <= node.hi.y && node.lo.z <= node.hi.z)) {
      fail("node " + std::to_string(item.node) + " has an inverted box");
    }
    if (node.count == 0) {
      // An inner node at depth d leaves d + 1 entries on a traversal stack of kBvhMaxDepth.
      if (item.depth + 1 > kBvhMaxDepth) fail("inner node too deep: " + std::to_string(item.depth));
      if (node.first == 0 || static_cast<size_t>(node.first) + 1 >= bvh.nodes.size()) {
        fail("inner node " + std::to_string(item.node) + " has children out of range");
        continue;
      }
      for (uint32_t c = node.first; c <= node.first + 1; ++c) {
        const BvhNode& child = bvh.nodes[c];
        if (!inside(child.lo, node) || !inside(child.hi, node)) {
          fail("child " + std::to_string(c) + " is not inside its parent " + std::to_string(item.node));
        }
        stack.push_back({c, item.depth + 1});
      }
    } else {
      if (node.count > kBvhWidth) fail("leaf " + std::to_string(item.node) + " holds more than one group");
      if (static_cast<size_t>(node.first) + node.count > bvh.triangles.size()) {
        fail("leaf " + std::to_string(item.node) + " reaches past the triangles");
        continue;
      }
      for (uint32_t s = node.first; s < node.first + node.count; ++s) {
        ++slot_visits[s];
        const BvhTriangle& tri = bvh.triangles[s];
        if (tri.id >= id_visits.size()) {
          fail("triangle id out of range");
          continue;
        }
        ++id_visits[tri.id];
        const Vec3& a = corners[3 * tri.id];
        const Vec3& b = corners[3 * tri.id + 1];
        const Vec3& c = corners[3 * tri.id + 2];
        if (!inside(a, node) || !inside(b, node) || !inside(c, node)) {
          fail("triangle " + std::to_string(tri.id) + " is not inside its leaf " + std::to_string(item.node));
        }
        const BvhTriangle expected = make_bvh_triangle(a, b, c, tri.id);
        if (tri.v0 != expected.v0 || tri.e1 != expected.e1 || tri.e2 != expected.e2) {
          fail("triangle " + std::to_string(tri.id) + " is stored with other vertices");
        }
        // Hits are clamped into this box; agreement with brute force needs every node to contain it.
        const Box3 clamp_box = bvh_triangle_box(tri);
        if (!inside(clamp_box.lo, node) || !inside(clamp_box.hi, node)) {
          fail("triangle " + std::to_string(tri.id) + "'s clamp box is not inside its leaf");
        }
      }
    }
  }
  for (size_t n = 0; n < node_visits.size(); ++n) {
    if (node_visits[n] != 1) fail("node " + std::to_string(n) + " is unreachable");
  }
  for (size_t s = 0; s < slot_visits.size(); ++s) {
    if (slot_visits[s] != 1)
      fail("triangle slot " + std::to_string(s) + " is in " + std::to_string(slot_visits[s]) + " leaves");
  }
  for (size_t i = 0; i < id_visits.size(); ++i) {
    const int expected = triangle_kept(corners, i) ? 1 : 0;
    if (id_visits[i] != expected)
      fail("input triangle " + std::to_string(i) + " appears " + std::to_string(id_visits[i]) + " times");
  }
  EXPECT_EQ(failures, 0u);
  check_wide_invariants(bvh, corners);
  return max_depth;
}

void add_triangle(Corners& corners, const Vec3& a, const Vec3& b, const Vec3& c) {
  corners.push_back(a);
  corners.push_back(b);
  corners.push_back(c);
}

/// Triangles of mixed sizes scattered in a box, some overlapping, with a few exact duplicates appended so that
/// equal distances also happen between triangles in different leaves.
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

/// An n x n grid of quads, two triangles each, sharing exact vertices; flat (z == 0) or a height field.
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

/// Normal triangles mixed with slivers, needles and zero-area triangles (repeated and collinear vertices).
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

/// Long slivers through one point, in every direction, of a few lengths: every box overlaps every other, the case
/// where reinsertion's search can prune nothing (bvh_reinsert.cpp caps it).
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

/// A closed UV sphere with shared vertices (pole triangles with two equal vertices included).
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

// ---- the ray-triangle test on its own -------------------------------------

TEST(IntersectTriangle, HitsInsideAndReportsBarycentrics) {
  Ray ray;
  ray.origin = Vec3(0.25f, 0.25f, -2.0f);
  ray.dir = Vec3(0.0f, 0.0f, 1.0f);
  float t = -1.0f, u = -1.0f, v = -1.0f;
  ASSERT_TRUE(intersect_triangle(ray, Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
  EXPECT_FLOAT_EQ(u, 0.25f);
  EXPECT_FLOAT_EQ(v, 0.25f);
}

TEST(IntersectTriangle, RespectsOpenIntervalAndRejectsMissesAndParallelRays) {
  const Vec3 v0(0.0f), e1(1.0f, 0.0f, 0.0f), e2(0.0f, 1.0f, 0.0f);
  float t = 0.0f, u = 0.0f, v = 0.0f;
  Ray ray;
  ray.origin = Vec3(0.25f, 0.25f, -2.0f);
  ray.tmax = 2.0f;  // the hit is exactly at tmax: outside the open interval
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.tmax = kInfinity;
  ray.tmin = 2.0f;
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.tmin = 0.0f;
  ray.origin = Vec3(0.75f, 0.75f, -2.0f);  // beyond the hypotenuse
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.origin = Vec3(0.25f, 0.25f, 0.0f);  // in the plane, moving along it
  ray.dir = Vec3(1.0f, 0.0f, 0.0f);
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.origin = Vec3(0.25f, 0.25f, 2.0f);  // from behind: both faces count
  ray.dir = Vec3(0.0f, 0.0f, -1.0f);
  EXPECT_TRUE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(IntersectTriangle, ZeroAreaTrianglesAreNeverHit) {
  // e1 == e2: the rounded determinant of Möller–Trumbore need not be zero, the prepared triangle makes it so.
  const Vec3 a(0.1f, 0.2f, 0.3f), b(0.7f, -0.4f, 1.3f);
  const BvhTriangle tri = make_bvh_triangle(a, b, b, 7);
  EXPECT_EQ(tri.id, 7u);
  EXPECT_EQ(tri.v0, a);
  std::mt19937 rng(5);
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.origin = uniform_in(rng, Vec3(-2.0f), Vec3(2.0f));
    ray.dir = glm::mix(a, b, uniform(rng, 0.0f, 1.0f)) - ray.origin;
    float t = 0.0f, u = 0.0f, v = 0.0f;
    ASSERT_FALSE(intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v)) << describe(ray);
  }
  const BvhTriangle normal = make_bvh_triangle(a, b, Vec3(1.0f, 1.0f, 1.0f), 0);
  EXPECT_EQ(normal.e1, b - a);
  EXPECT_EQ(normal.e2, Vec3(1.0f) - a);
}

// ---- counted queries ---------------------------------------------------------

TEST(Bvh, CountedQueriesAnswerTheSameAndCountTheirWork) {
  std::mt19937 rng(21);
  const Corners corners = make_soup(rng, 2000);
  const Bvh bvh = build_bvh(corners);
  const Box3 bounds = bounds_of(corners);
  TraversalCounts closest, any;
  constexpr int kRays = 2000;
  for (int i = 0; i < kRays; ++i) {
    const Ray ray = random_ray(rng, corners, bounds);
    const Hit expected = intersect_closest(bvh, ray);
    const Hit counted = intersect_closest(bvh, ray, closest);
    EXPECT_EQ(counted.triangle, expected.triangle);
    EXPECT_EQ(counted.t, expected.t);
    EXPECT_EQ(intersect_any(bvh, ray, any), intersect_any(bvh, ray));
  }
  for (const TraversalCounts& c : {closest, any}) {
    EXPECT_EQ(c.queries, static_cast<uint64_t>(kRays));
    EXPECT_GE(c.nodes, c.queries);  // the root at least
    EXPECT_GE(c.groups, c.leaves);
    EXPECT_GT(c.leaves, 0u);
  }

  // A ray that misses the scene's box tests the root's children and nothing else.
  TraversalCounts miss;
  Ray away;
  away.origin = bounds.hi + Vec3(1.0f);
  away.dir = Vec3(1.0f, 0.5f, 0.25f);
  EXPECT_FALSE(intersect_closest(bvh, away, miss).found());
  EXPECT_EQ(miss.nodes, 1u);
  EXPECT_EQ(miss.leaves, 0u);

  // A query on an empty tree is still a query, with no work.
  TraversalCounts empty;
  EXPECT_FALSE(intersect_closest(build_bvh({}), away, empty).found());
  EXPECT_FALSE(intersect_any(build_bvh({}), away, empty));
  EXPECT_EQ(empty.queries, 2u);
  EXPECT_EQ(empty.nodes, 0u);
}

// ---- empty and degenerate inputs -------------------------------------------

TEST(Bvh, EmptyInputGivesNoHits) {
  const Bvh bvh = build_bvh({});
  EXPECT_TRUE(bvh.empty());
  Ray ray;
  EXPECT_FALSE(intersect_closest(bvh, ray).found());
  EXPECT_EQ(intersect_closest(bvh, ray).t, kInfinity);
  EXPECT_FALSE(intersect_any(bvh, ray));
}

TEST(Bvh, NonFiniteTrianglesAreDropped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Corners only_bad;
  add_triangle(only_bad, Vec3(nan, 0.0f, 0.0f), Vec3(1.0f), Vec3(2.0f, 0.0f, 1.0f));
  add_triangle(only_bad, Vec3(0.0f), Vec3(kInfinity, 1.0f, 0.0f), Vec3(0.0f, 1.0f, 1.0f));
  const Bvh empty = build_bvh(only_bad);
  EXPECT_TRUE(empty.empty());
  EXPECT_FALSE(intersect_any(empty, Ray{}));

  std::mt19937 rng(11);
  Corners corners = make_soup(rng, 600);
  for (size_t i = 0; i < corners.size(); i += 37) corners[i][static_cast<int>(i % 3)] = (i % 2 == 0) ? nan : -kInfinity;
  const Bvh bvh = build_bvh(corners);
  check_invariants(bvh, corners);
  const RayStats stats = compare_with_brute_force(corners, bvh, 5000, 12);
  EXPECT_GT(stats.hits, stats.rays / 5);
}

TEST(Bvh, IdenticalTrianglesBuildAndTieToLowestIndex) {
  Corners corners;
  for (int i = 0; i < 100000; ++i) {
    add_triangle(corners, Vec3(-1.0f, -1.0f, 0.5f), Vec3(1.5f, -0.5f, 0.25f), Vec3(0.0f, 2.0f, -0.5f));
  }
  const Bvh bvh = build_bvh(corners);
  const uint32_t depth = check_invariants(bvh, corners);
  EXPECT_LE(depth, 20u);  // a median split halves each time
  std::mt19937 rng(3);
  size_t hits = 0;
  // Few rays: with every copy at the same distance, each hit has to look at all 100k triangles.
  for (int i = 0; i < 300; ++i) {
    Ray ray;
    ray.origin = uniform_in(rng, Vec3(-3.0f), Vec3(3.0f));
    ray.dir = Vec3(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), 0.0f) - ray.origin;
    const Hit hit = intersect_closest(bvh, ray);
    if (hit.found()) {
      ++hits;
      ASSERT_EQ(hit.triangle, 0u) << describe(ray);
    }
    float t = 0.0f, u = 0.0f, v = 0.0f;
    const BvhTriangle& tri = bvh.triangles.front();
    ASSERT_EQ(intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v), hit.found()) << describe(ray);
    if (hit.found()) {
      ASSERT_EQ(hit.t, t);
    }
    ASSERT_EQ(intersect_any(bvh, ray), hit.found());
  }
  EXPECT_GT(hits, 30u);
}

TEST(Bvh, PointTrianglesBuildAndAreNeverHit) {
  Corners corners;
  for (int i = 0; i < 100000; ++i) add_triangle(corners, Vec3(0.5f), Vec3(0.5f), Vec3(0.5f));
  const Bvh bvh = build_bvh(corners);
  check_invariants(bvh, corners);
  Ray ray;
  ray.origin = Vec3(0.5f, 0.5f, -1.0f);
  EXPECT_FALSE(intersect_closest(bvh, ray).found());
  EXPECT_FALSE(intersect_any(bvh, ray));
}

TEST(Bvh, GeometricallyGrowingTrianglesStayWithinTheDepthBound) {
  // Each triangle dwarfs all the previous ones, which invites SAH to peel them off one at a time.
  Corners corners;
  float s = 1.0f;
  for (int i = 0; i < 600; ++i, s *= 1.08f) {
    add_triangle(corners, Vec3(s, 0.0f, 0.0f), Vec3(1.5f * s, 0.3f * s, 0.1f * s), Vec3(1.2f * s, -0.2f * s, 0.4f * s));
  }
  const Bvh bvh = build_bvh(corners);
  const uint32_t depth = check_invariants(bvh, corners);
  std::cout << "[ depth    ] " << depth << "\n";
  EXPECT_LT(depth, kBvhMaxDepth);
  compare_with_brute_force(corners, bvh, 3000, 21);
}

// ---- the BVH against brute force -------------------------------------------

struct SceneCase {
  const char* name;
  Corners corners;
  size_t rays;
};

void run_scene(const SceneCase& scene, uint32_t seed) {
  const Bvh bvh = build_bvh(scene.corners);
  const uint32_t depth = check_invariants(bvh, scene.corners);
  const RayStats stats = compare_with_brute_force(scene.corners, bvh, scene.rays, seed);
  std::cout << "[ scene    ] " << scene.name << ": " << scene.corners.size() / 3 << " triangles, " << bvh.nodes.size()
            << " nodes, depth " << depth << ", " << stats.rays << " rays, " << stats.hits << " hits\n";
  // Both outcomes must be well represented, or the comparison proves little.
  EXPECT_GT(stats.hits, stats.rays / 10) << scene.name;
  EXPECT_LT(stats.hits, stats.rays - stats.rays / 20) << scene.name;
}

// Rays compared with brute force per scene. CTest runs each test in its own process, so the total is checked
// at compile time rather than by counting at run time (run_scene asserts that each scene traced its count).
constexpr size_t kSoupRays = 25000, kFlatGridRays = 15000, kHeightFieldRays = 15000, kSliverRays = 20000,
                 kCopiesRays = 10000, kSphereRays = 20000, kStarRays = 5000;
static_assert(kSoupRays + kFlatGridRays + kHeightFieldRays + kSliverRays + kCopiesRays + kSphereRays + kStarRays >=
                  100000,
              "the BVH must be checked against brute force on at least 100k rays");

TEST(BvhVersusBruteForce, RandomSoup) {
  std::mt19937 rng(1);
  run_scene({"soup", make_soup(rng, 2000), kSoupRays}, 101);
}

TEST(BvhVersusBruteForce, FlatGrid) { run_scene({"flat grid", make_grid(48, true), kFlatGridRays}, 102); }

TEST(BvhVersusBruteForce, HeightFieldGrid) { run_scene({"height field", make_grid(48, false), kHeightFieldRays}, 103); }

TEST(BvhVersusBruteForce, SliversAndDegenerates) {
  std::mt19937 rng(2);
  const Corners corners = make_slivers(rng);
  ASSERT_GE(count_zero_area(corners), 240u);
  run_scene({"slivers", corners, kSliverRays}, 104);
  // Zero-area triangles never win, even when rays are aimed straight at them.
  const Bvh bvh = build_bvh(corners);
  std::mt19937 ray_rng(5);
  const Box3 bounds = bounds_of(corners);
  for (int i = 0; i < 5000; ++i) {
    const Hit hit = intersect_closest(bvh, random_ray(ray_rng, corners, bounds));
    if (!hit.found()) continue;
    const size_t k = hit.triangle;
    ASSERT_NE(glm::cross(corners[3 * k + 1] - corners[3 * k], corners[3 * k + 2] - corners[3 * k]), Vec3(0.0f));
  }
}

TEST(BvhVersusBruteForce, ThousandCopiesOfOneTriangle) {
  Corners corners;
  for (int i = 0; i < 1000; ++i)
    add_triangle(corners, Vec3(-1.0f, -1.0f, 0.0f), Vec3(1.0f, -1.0f, 0.2f), Vec3(0.0f, 1.0f, -0.3f));
  run_scene({"copies", corners, kCopiesRays}, 105);
  const Bvh bvh = build_bvh(corners);
  std::mt19937 rng(6);
  const Box3 bounds = bounds_of(corners);
  for (int i = 0; i < 2000; ++i) {
    const Hit hit = intersect_closest(bvh, random_ray(rng, corners, bounds));
    if (hit.found()) {
      ASSERT_EQ(hit.triangle, 0u);
    }
  }
}

TEST(BvhVersusBruteForce, StarOfOverlappingSlivers) {
  std::mt19937 rng(12);
  run_scene({"star", make_star(rng, 3000), kStarRays}, 110);
}

TEST(BvhVersusBruteForce, ClosedSphere) { run_scene({"sphere", make_sphere(40, 80, 3.0f), kSphereRays}, 106); }

// Above 65536 triangles the top of the tree bins and bounds its nodes on several threads (one slice each): the
// slices' merged bins must give a correct tree.
TEST(BvhVersusBruteForce, LargeSphereBuiltWithParallelBinning) {
  const Corners corners = make_sphere(160, 320, 3.0f);
  ASSERT_GT(corners.size() / 3, 100000u);
  run_scene({"large sphere", corners, 2000}, 107);
}

// The tests above trace the tree this CPU gets (8-wide AVX2 when it has AVX2); these check the 4-wide SSE kernels,
// which CPUs without AVX2 run, against brute force on any machine.
TEST(BvhVersusBruteForce, SseKernelsOnAnyMachine) {
  std::mt19937 rng(7);
  const Corners soup = make_soup(rng, 2000);
  const Corners sphere = make_sphere(40, 80, 3.0f);
  const Bvh default_soup = build_bvh(soup);
  EXPECT_EQ(default_soup.wide8_nodes.empty(), !bvh_avx2_enabled());
  Bvh sse_soup, sse_sphere;
  {
    const test::ScopedEnv isa("LUEUR_BVH_ISA", "sse");  // restored even if a build throws
    sse_soup = build_bvh(soup);
    sse_sphere = build_bvh(sphere);
  }
  ASSERT_TRUE(sse_soup.wide8_nodes.empty());
  ASSERT_FALSE(sse_soup.wide_nodes.empty());
  const RayStats a = compare_with_brute_force(soup, sse_soup, 10000, 108);
  const RayStats b = compare_with_brute_force(sphere, sse_sphere, 10000, 109);
  EXPECT_GT(a.hits + b.hits, (a.rays + b.rays) / 10);
}

}  // namespace
}  // namespace lueur
