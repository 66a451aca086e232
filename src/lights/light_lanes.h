// Weighing a fixed number of light-bound lanes at a shaded point (the clusters', or a tree node's children's), and
// the tree nodes' weighing in code built for AVX2 beside the baseline build. Internal to the `importance` light
// choice (light_clusters.cpp, light_lanes_avx2.cpp). Both builds give the same bits: the same IEEE operations on each
// lane (no fused multiply-add: -mavx2 does not enable FMA), only more lanes at once.
#pragma once

#include <cstddef>

#include "lights/light_bounds.h"
#include "lights/light_clusters.h"

namespace lueur {

/// Weighs lanes [0, kLanes) of a set of bound arrays at the point. kLanes is a multiple of four: a fixed trip count
/// without branches, which the compiler weighs four (eight with AVX) at a time. Always inlined, so that each build
/// keeps its own code (an out-of-line copy would be merged with the other build's at link time).
template <size_t kLanes, typename Arrays>
[[gnu::always_inline]] inline void weigh_lanes(const Arrays& a, const ImportanceQuery& q, float* __restrict out) {
  for (size_t k = 0; k < kLanes; ++k) {
    LightBounds b;
    b.cx = a.cx[k], b.cy = a.cy[k], b.cz = a.cz[k], b.radius = a.radius[k];
    b.ax = a.ax[k], b.ay = a.ay[k], b.az = a.az[k], b.cos_spread = a.cos_spread[k];
    b.ex = a.ex[k], b.ey = a.ey[k], b.ez = a.ez[k];
    b.lowest = a.lowest[k], b.tilt = a.tilt[k], b.power = a.power[k];
    out[k] = light_importance(q, b);
  }
}

/// A tree node's children's weights at the point, from the baseline build and from the AVX2 build (call the latter
/// only where the CPU has AVX2); `weigh_tree_children` calls whichever the CPU runs.
void weigh_tree_children_baseline(const LightTreeNode& node, const ImportanceQuery& q, float* out);
void weigh_tree_children_avx2(const LightTreeNode& node, const ImportanceQuery& q, float* out);
void weigh_tree_children(const LightTreeNode& node, const ImportanceQuery& q, float* out);

}  // namespace lueur
