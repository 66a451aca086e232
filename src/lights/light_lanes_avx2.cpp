// A light tree node's children weighed in code built for AVX2: eight lanes in one pass instead of two. Called only on
// CPUs that have AVX2 (light_clusters.cpp decides).
//
// Only this function is built for AVX2 (a target attribute), not the file (no -mavx2): the inline helpers it uses
// from headers (std::max, the bounds' helpers) keep their baseline code wherever the compiler leaves an out-of-line
// copy of them, so the copy the linker keeps for the whole program never holds an AVX instruction
// (tests/check_avx_objects.sh).
#include "lights/light_lanes.h"

namespace lueur {

[[gnu::target("avx2")]] void weigh_tree_children_avx2(const LightTreeNode& node, const ImportanceQuery& q, float* out) {
  weigh_lanes<kLightTreeWidth>(node, q, out);
}

}  // namespace lueur
