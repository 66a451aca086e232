// Collapses Lueur's binned-SAH BVH2 into the 4-wide traversal form: each wide node takes the two children of a
// BVH2 node and keeps opening its largest inner child until it has four, and each leaf's triangles are packed
// four to a group, structure-of-arrays. Depends on bvh.h only.
#include <array>
#include <cstdlib>
#include <cstring>

#include "bvh/bvh.h"

namespace lueur {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

template <typename Node>
void set_slot_box(Node& node, uint32_t slot, const BvhNode& child) {
  for (int axis = 0; axis < 3; ++axis) {
    node.lo[axis][slot] = child.lo[axis];
    node.hi[axis][slot] = child.hi[axis];
  }
}

template <typename Node, uint32_t W>
Node empty_wide_node() {
  Node node;
  for (int axis = 0; axis < 3; ++axis)
    for (uint32_t k = 0; k < W; ++k) node.lo[axis][k] = node.hi[axis][k] = kNaN;
  for (uint32_t k = 0; k < W; ++k) node.child[k] = node.count[k] = 0;
  return node;
}

/// Packs the triangles of a BVH2 leaf into groups of four; returns the first group.
uint32_t pack_leaf(Bvh& bvh, const BvhNode& leaf, uint32_t& group_count) {
  const auto first = static_cast<uint32_t>(bvh.groups.size());
  group_count = (leaf.count + kBvhWidth - 1) / kBvhWidth;
  for (uint32_t g = 0; g < group_count; ++g) {
    BvhTriangleGroup group{};
    for (uint32_t lane = 0; lane < kBvhWidth; ++lane) {
      const uint32_t i = g * kBvhWidth + lane;
      if (i >= leaf.count) {
        group.id[lane] = kNoHit;  // zero edges (from {}): never hit
        continue;
      }
      const BvhTriangle& tri = bvh.triangles[leaf.first + i];
      for (int axis = 0; axis < 3; ++axis) {
        group.v0[axis][lane] = tri.v0[axis];
        group.e1[axis][lane] = tri.e1[axis];
        group.e2[axis][lane] = tri.e2[axis];
      }
      group.id[lane] = tri.id;
    }
    bvh.groups.push_back(group);
  }
  return first;
}

/// The collapse into nodes of W children.
template <typename Node, uint32_t W>
void collapse(Bvh& bvh, HugePageVector<Node>& wide_nodes) {
  wide_nodes.reserve(bvh.nodes.size() / (W / 2) + 1);
  bvh.groups.reserve(bvh.triangles.size() / 2 + 1);

  // Each task fills wide node `wide` from the BVH2 node `source` (an inner node, or a leaf root).
  struct Task {
    uint32_t wide, source;
  };
  std::vector<Task> tasks{{0, 0}};
  wide_nodes.push_back(empty_wide_node<Node, W>());
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    const BvhNode& source = bvh.nodes[task.source];
    std::array<uint32_t, W> slots{};
    uint32_t used = 0;
    if (source.count > 0) {
      slots[used++] = task.source;  // a BVH2 that is one leaf: the root holds it as its only child
    } else {
      slots[used++] = source.first;
      slots[used++] = source.first + 1;
      // Open the inner child of largest area: the one a ray is most likely to enter.
      while (used < W) {
        int best = -1;
        float best_area = -1.0f;
        for (uint32_t k = 0; k < used; ++k) {
          const BvhNode& n = bvh.nodes[slots[k]];
          if (n.count > 0) continue;
          Box3 box;
          box.lo = n.lo;
          box.hi = n.hi;
          if (box.area() > best_area) {
            best_area = box.area();
            best = static_cast<int>(k);
          }
        }
        if (best < 0) break;
        const uint32_t opened = bvh.nodes[slots[static_cast<uint32_t>(best)]].first;
        slots[static_cast<uint32_t>(best)] = opened;
        slots[used++] = opened + 1;
      }
    }
    for (uint32_t k = 0; k < used; ++k) {
      const BvhNode& child = bvh.nodes[slots[k]];
      Node& node = wide_nodes[task.wide];  // taken again each time: the push below may move it
      set_slot_box(node, k, child);
      if (child.count > 0) {
        node.child[k] = pack_leaf(bvh, child, node.count[k]);
        continue;
      }
      const auto index = static_cast<uint32_t>(wide_nodes.size());
      node.child[k] = index;
      node.count[k] = 0;
      tasks.push_back({index, slots[k]});
      wide_nodes.push_back(empty_wide_node<Node, W>());
    }
  }
}

}  // namespace

bool bvh_avx_enabled() {
  const char* isa = std::getenv("LUEUR_BVH_ISA");
  if (isa && std::strcmp(isa, "sse") == 0) return false;
  return __builtin_cpu_supports("avx");
}

void build_wide_bvh(Bvh& bvh) {
  bvh.wide_nodes.clear();
  bvh.wide8_nodes.clear();
  bvh.groups.clear();
  if (bvh.nodes.empty()) return;
  if (bvh_avx_enabled())
    collapse<BvhWideNode8, kBvhWidth8>(bvh, bvh.wide8_nodes);
  else
    collapse<BvhWideNode, kBvhWidth>(bvh, bvh.wide_nodes);
}

}  // namespace lueur
