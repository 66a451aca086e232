// A light tree node's children weighed in code built for AVX2 (CMakeLists.txt gives this file -mavx2): eight lanes
// in one pass instead of two. Called only on CPUs that have AVX2 (light_clusters.cpp decides).
#include "lights/light_lanes.h"

namespace lueur {

void weigh_tree_children_avx2(const LightTreeNode& node, const ImportanceQuery& q, float* out) {
  weigh_lanes<kLightTreeWidth>(node, q, out);
}

}  // namespace lueur
