// Checks shared by the BVH suites (test_bvh_*.cpp): the BVH2's and the wide tree's invariants, the BVH's answers
// against the brute-force loop on random rays, and the work its counted queries report against what the tree's
// boxes allow for each ray. Depends on bvh, core and bvh_test_scenes.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bvh/bvh.h"
#include "bvh_test_scenes.h"

namespace lueur::test {

struct RayStats {
  size_t rays = 0;
  size_t hits = 0;
  size_t mismatches = 0;            ///< rays where the BVH and the brute-force loop disagree
  size_t miscounted = 0;            ///< rays whose counted queries did work their ray's segment does not allow
  size_t misses_bounded_below = 0;  ///< missing rays that plainly cross nodes below the root, which must be tested
};

/// Fires `count` rays at the scene and compares the BVH with the brute-force loop on every one; checks on each that
/// the counted queries answer the same and count work within what the tree's boxes allow for that ray.
RayStats compare_with_brute_force(const Corners& corners, const Bvh& bvh, size_t count, uint32_t seed);

/// Walks the BVH2 from the root and checks its structure, then the wide tree's; returns the deepest node depth.
uint32_t check_invariants(const Bvh& bvh, const Corners& corners);

}  // namespace lueur::test
