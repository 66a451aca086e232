// Collapses Lueur's binned-SAH BVH2 into the wide traversal form (4 or 8 children), as Embree's wide builders
// shape their trees: each wide node takes the two children of a BVH2 node and keeps opening its largest child of
// more than one triangle group until it is full; then each child becomes a leaf where the SAH prefers one test of
// all its triangles to a split, or a wide node of its own. Leaves' triangles are packed four to a group,
// structure-of-arrays. Depends on bvh.h only.
#include <array>
#include <cstdlib>
#include <cstring>

#include "bvh/bvh.h"

namespace lueur {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Relative costs, in the SAH, of visiting an inner node and of testing one group of kBvhWidth triangles.
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;

/// What the collapse knows of a BVH2 node: the triangles under it, and whether they are best tested as one leaf.
struct Subtree {
  uint32_t first = 0, count = 0;
  bool leaf = false;
};

float area_of(const BvhNode& n) {
  Box3 box;
  box.lo = n.lo;
  box.hi = n.hi;
  return box.area();
}

/// One entry per BVH2 node. An inner node is a leaf candidate when it holds at most kBvhMaxLeafSize triangles and
/// testing them all costs no more than a traversal step plus testing each child's (the SAH's leaf decision, made
/// here rather than in the build so that a wide node can still open such a node to fill its slots).
std::vector<Subtree> describe_subtrees(const Bvh& bvh) {
  std::vector<Subtree> subtrees(bvh.nodes.size());
  // Children sit at higher indices than their parent: a backward pass meets them first.
  for (size_t i = bvh.nodes.size(); i-- > 0;) {
    const BvhNode& node = bvh.nodes[i];
    Subtree& subtree = subtrees[i];
    if (node.count > 0) {
      subtree = Subtree{node.first, node.count, true};
      continue;
    }
    const Subtree& left = subtrees[node.first];
    const Subtree& right = subtrees[node.first + 1];
    subtree.first = left.first;  // the build puts the left child's triangles first
    subtree.count = left.count + right.count;
    if (subtree.count > kBvhMaxLeafSize) continue;
    const auto groups = [](uint32_t count) { return static_cast<float>(bvh_group_count(count)); };
    const float area = area_of(node);
    const float leaf_cost = kIntersectionCost * groups(subtree.count) * area;
    const float split_cost =
        kTraversalCost * area + kIntersectionCost * (groups(left.count) * area_of(bvh.nodes[node.first]) +
                                                     groups(right.count) * area_of(bvh.nodes[node.first + 1]));
    subtree.leaf = !(split_cost < leaf_cost);
  }
  return subtrees;
}

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

/// Packs the triangles of a subtree into groups of four; returns the first group.
uint32_t pack_leaf(Bvh& bvh, const Subtree& leaf, uint32_t& group_count) {
  const auto first = static_cast<uint32_t>(bvh.groups.size());
  group_count = bvh_group_count(leaf.count);
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

  const std::vector<Subtree> subtrees = describe_subtrees(bvh);
  // Each task fills wide node `wide` from the BVH2 node `source`: an inner node, or a root that is a leaf.
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
    if (subtrees[task.source].leaf) {
      slots[used++] = task.source;  // the whole BVH2 is one leaf: the root holds it as its only child
    } else {
      slots[used++] = source.first;
      slots[used++] = source.first + 1;
      // Open the inner child of largest area, the one a ray is most likely to enter, until the node is full.
      while (used < W) {
        int best = -1;
        float best_area = -1.0f;
        for (uint32_t k = 0; k < used; ++k) {
          const BvhNode& n = bvh.nodes[slots[k]];
          if (n.count > 0) continue;
          if (const float area = area_of(n); area > best_area) {
            best_area = area;
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
      Node& node = wide_nodes[task.wide];  // taken again each time: the push below may move it
      set_slot_box(node, k, bvh.nodes[slots[k]]);
      if (subtrees[slots[k]].leaf) {
        node.child[k] = pack_leaf(bvh, subtrees[slots[k]], node.count[k]);
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

bool bvh_avx2_enabled() {
  const char* isa = std::getenv("LUEUR_BVH_ISA");
  if (isa && std::strcmp(isa, "sse") == 0) return false;
  return __builtin_cpu_supports("avx2");
}

void build_wide_bvh(Bvh& bvh) {
  bvh.wide_nodes.clear();
  bvh.wide8_nodes.clear();
  bvh.groups.clear();
  if (bvh.nodes.empty()) return;
  if (bvh_avx2_enabled())
    collapse<BvhWideNode8, kBvhWidth8>(bvh, bvh.wide8_nodes);
  else
    collapse<BvhWideNode, kBvhWidth>(bvh, bvh.wide_nodes);
}

}  // namespace lueur
