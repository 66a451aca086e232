// Collapses Lueur's BVH2 into the wide traversal form (4 or 8 children) at the lowest SAH cost the BVH2 allows
// (Ylitie, Karras and Laine, "Efficient incoherent ray traversal on GPUs through compressed wide BVHs", 2017): a
// bottom-up pass finds, for every BVH2 node and every number of slots up to the width, the cheapest way to hand its
// triangles to a wide node as that many children (leaves of up to kBvhMaxLeafSize triangles, or wide nodes of their
// own); the wide tree is then read off from the root. Leaves' triangles are packed four to a group,
// structure-of-arrays. Depends on bvh.h and core (the thread pool, freeing arrays) only.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "bvh/bvh.h"
#include "core/memory_budget.h"
#include "core/thread_pool.h"

namespace lueur {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Relative costs, in the SAH, of visiting an inner node and of testing one group of kBvhWidth triangles.
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;

/// The triangles under a BVH2 node: a contiguous range of the BVH's order.
struct Subtree {
  uint32_t first = 0, count = 0;
};

float area_of(const BvhNode& n) {
  Box3 box;
  box.lo = n.lo;
  box.hi = n.hi;
  return box.area();
}

/// One entry per BVH2 node.
HugePageVector<Subtree> describe_subtrees(const Bvh& bvh) {
  HugePageVector<Subtree> subtrees(bvh.nodes.size());
  // Children sit at higher indices than their parent: a backward pass meets them first.
  for (size_t i = bvh.nodes.size(); i-- > 0;) {
    const BvhNode& node = bvh.nodes[i];
    if (node.count > 0) {
      subtrees[i] = Subtree{node.first, node.count};
      continue;
    }
    // The build puts the left child's triangles first.
    subtrees[i] = Subtree{subtrees[node.first].first, subtrees[node.first].count + subtrees[node.first + 1].count};
  }
  return subtrees;
}

/// How to hand the triangles of one BVH2 node to a wide node of W children, for every number of slots up to W.
template <uint32_t W>
struct SlotPlan {
  /// choice[0]: 1 where the node is best one slot as a wide node of its own, 0 as a leaf. choice[i > 0]: 0 where
  /// i + 1 slots do no better than i (the plan for i slots is used), else how many of the i + 1 slots go to the
  /// left child (the rest to the right).
  uint8_t choice[W];
  /// How the W slots of this node's own wide node are shared between its children (left's share).
  uint8_t split;
};

/// The plans of all BVH2 nodes, children before parents (dynamic programming over the tree). costs[n][i] is the SAH
/// cost of the cheapest way node n takes at most i + 1 slots: a leaf costs its area times its triangle groups, a
/// wide node its area plus what its slots cost (plain areas: only comparisons matter). The costs are only needed
/// here and go with it: the plans the collapse reads are a fifth of their size.
template <uint32_t W>
HugePageVector<SlotPlan<W>> plan_slots(const Bvh& bvh, const HugePageVector<Subtree>& subtrees) {
  constexpr float kNever = std::numeric_limits<float>::infinity();
  HugePageVector<SlotPlan<W>> plans(bvh.nodes.size());
  HugePageVector<std::array<float, W>> costs(bvh.nodes.size());
  for (size_t n = bvh.nodes.size(); n-- > 0;) {
    const BvhNode& node = bvh.nodes[n];
    SlotPlan<W>& plan = plans[n];
    std::array<float, W>& cost = costs[n];
    const float area = area_of(node);
    const float leaf_cost = kIntersectionCost * static_cast<float>(bvh_group_count(subtrees[n].count)) * area;
    if (node.count > 0) {  // a BVH2 leaf cannot be opened
      for (uint32_t i = 0; i < W; ++i) {
        cost[i] = leaf_cost;
        plan.choice[i] = 0;
      }
      plan.split = 0;
      continue;
    }
    const std::array<float, W>& left = costs[node.first];
    const std::array<float, W>& right = costs[node.first + 1];
    // shared[j]: the cheapest way to give j slots to the two children together.
    float shared[W + 1];
    uint8_t left_share[W + 1];
    for (uint32_t j = 2; j <= W; ++j) {
      shared[j] = kNever;
      left_share[j] = 1;  // kept where every cost is infinite or NaN (coordinates near the float range)
      for (uint32_t k = 1; k < j; ++k) {
        const float both = left[k - 1] + right[j - k - 1];
        if (both < shared[j]) {
          shared[j] = both;
          left_share[j] = static_cast<uint8_t>(k);
        }
      }
    }
    plan.split = left_share[W];
    const float wide_cost = kTraversalCost * area + shared[W];
    const bool leaf = subtrees[n].count <= kBvhMaxLeafSize && leaf_cost <= wide_cost;
    cost[0] = leaf ? leaf_cost : wide_cost;
    plan.choice[0] = leaf ? 0 : 1;
    for (uint32_t i = 1; i < W; ++i) {
      const bool better = shared[i + 1] < cost[i - 1];
      cost[i] = better ? shared[i + 1] : cost[i - 1];
      plan.choice[i] = better ? left_share[i + 1] : 0;
    }
  }
  return plans;
}

/// Whether BVH2 node `n` taken as one slot is a leaf.
template <uint32_t W>
bool slot_is_leaf(const Bvh& bvh, const HugePageVector<SlotPlan<W>>& plans, uint32_t n) {
  return bvh.nodes[n].count > 0 || plans[n].choice[0] == 0;
}

/// Appends the slots BVH2 node `n` takes when given at most `budget` of them.
template <uint32_t W>
void collect_slots(const Bvh& bvh, const HugePageVector<SlotPlan<W>>& plans, uint32_t n, uint32_t budget,
                   std::array<uint32_t, W>& slots, uint32_t& used) {
  while (budget >= 2 && plans[n].choice[budget - 1] == 0) --budget;
  if (budget == 1) {
    slots[used++] = n;
    return;
  }
  const uint32_t left_share = plans[n].choice[budget - 1];
  collect_slots<W>(bvh, plans, bvh.nodes[n].first, left_share, slots, used);
  collect_slots<W>(bvh, plans, bvh.nodes[n].first + 1, budget - left_share, slots, used);
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

using TriangleAt = std::function<BvhTriangle(uint32_t place)>;

/// Packs the triangles of a subtree into groups of four at `groups[first]` on.
void pack_leaf(const Subtree& leaf, BvhTriangleGroup* groups, const TriangleAt& triangle_at) {
  const uint32_t group_count = bvh_group_count(leaf.count);
  for (uint32_t g = 0; g < group_count; ++g) {
    BvhTriangleGroup group{};
    for (uint32_t lane = 0; lane < kBvhWidth; ++lane) {
      const uint32_t i = g * kBvhWidth + lane;
      if (i >= leaf.count) {
        group.id[lane] = kNoHit;  // zero edges (from {}): never hit
        continue;
      }
      const BvhTriangle tri = triangle_at(leaf.first + i);
      for (int axis = 0; axis < 3; ++axis) {
        group.v0[axis][lane] = tri.v0[axis];
        group.e1[axis][lane] = tri.e1[axis];
        group.e2[axis][lane] = tri.e2[axis];
      }
      group.id[lane] = tri.id;
    }
    groups[g] = group;
  }
}

/// Wide nodes and triangle groups a part of the collapse makes.
struct Sizes {
  uint64_t nodes = 0, groups = 0;
};

/// A leaf of the wide tree whose triangles are still to be packed: its groups start at `group`.
struct LeafToPack {
  uint64_t group = 0;
  Subtree triangles;
};

/// The collapse into nodes of W children. The wide tree is read off the plans from the root, each wide node's
/// children made by a task; the top of the tree is made here, and subtrees of at most a 64th of the triangles are
/// set aside, counted, given their places after the top, and made on every thread. The leaves' triangles are packed
/// last, on every thread, once the BVH2 (with `release`) and the plans are freed. Where everything goes depends on
/// the tree only, not on the threads.
template <typename Node, uint32_t W>
class Collapse {
 public:
  Collapse(Bvh& bvh, const TriangleAt& triangle_at)
      : bvh_(bvh),
        triangle_at_(triangle_at),
        subtrees_(describe_subtrees(bvh)),
        plans_(plan_slots<W>(bvh, subtrees_)) {}

  void run(HugePageVector<Node>& nodes, HugePageVector<BvhTriangleGroup>& groups, bool release) {
    const Sizes total = count(0);
    nodes.resize(total.nodes);
    Part top{1, 0, {}};
    nodes[0] = empty_wide_node<Node, W>();
    std::vector<Task> tasks{{0, 0}}, deferred;
    const uint32_t grain = std::max<uint32_t>(32768, subtrees_[0].count / 64);
    while (!tasks.empty()) {
      const Task task = tasks.back();
      tasks.pop_back();
      if (task.wide != 0 && subtrees_[task.source].count <= grain) {
        deferred.push_back(task);
        continue;
      }
      fill(task, nodes, top, tasks);
    }
    // Each set-aside subtree's nodes and groups follow the top's, in the order they were set aside.
    std::vector<Part> parts(deferred.size());
    uint64_t next_node = top.next_node, next_group = top.next_group;
    for (size_t i = 0; i < deferred.size(); ++i) {
      const Sizes sizes = count(deferred[i].source);
      parts[i] = Part{next_node, next_group, {}};
      next_node += sizes.nodes - 1;  // its root is the task's node, made by the top
      next_group += sizes.groups;
    }
    ThreadPool pool(std::min(hardware_threads(), 64));
    pool.parallel_for(static_cast<int>(deferred.size()), [&](int i, int) {
      std::vector<Task> stack{deferred[i]};
      while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        fill(task, nodes, parts[i], stack);
      }
    });
    // Only the leaves' triangle ranges are needed from here on: the BVH2 and the plans go before the groups come.
    free_array(plans_);
    free_array(subtrees_);
    if (release) free_array(bvh_.nodes);
    parts.push_back(std::move(top));
    groups.resize(total.groups);
    pool.parallel_for(static_cast<int>(parts.size()), [&](int i, int) {
      for (const LeafToPack& leaf : parts[i].leaves)
        pack_leaf(leaf.triangles, groups.data() + leaf.group, triangle_at_);
      free_array(parts[i].leaves);
    });
  }

 private:
  /// Fills wide node `wide` from the BVH2 node `source`: an inner node, or a root that is a leaf.
  struct Task {
    uint32_t wide, source;
  };
  /// A part of the collapse: where it puts its next wide node and group, and its leaves to pack.
  struct Part {
    uint64_t next_node = 0, next_group = 0;
    std::vector<LeafToPack> leaves;
  };

  /// The BVH2 nodes that become the slots of the wide node made from `source`.
  uint32_t slots_of(uint32_t source, std::array<uint32_t, W>& slots) const {
    uint32_t used = 0;
    if (slot_is_leaf<W>(bvh_, plans_, source)) {
      slots[used++] = source;  // the whole BVH2 is one leaf: the root holds it as its only child
    } else {
      const BvhNode& node = bvh_.nodes[source];
      const uint32_t left_share = plans_[source].split;
      collect_slots<W>(bvh_, plans_, node.first, left_share, slots, used);
      collect_slots<W>(bvh_, plans_, node.first + 1, W - left_share, slots, used);
    }
    return used;
  }

  /// The wide nodes and groups made from `source` down (its own node included).
  Sizes count(uint32_t source) const {
    Sizes sizes;
    std::vector<uint32_t> stack{source};
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      ++sizes.nodes;
      std::array<uint32_t, W> slots{};
      const uint32_t used = slots_of(n, slots);
      for (uint32_t k = 0; k < used; ++k) {
        if (slot_is_leaf<W>(bvh_, plans_, slots[k]))
          sizes.groups += bvh_group_count(subtrees_[slots[k]].count);
        else
          stack.push_back(slots[k]);
      }
    }
    return sizes;
  }

  void fill(const Task& task, HugePageVector<Node>& nodes, Part& part, std::vector<Task>& tasks) const {
    std::array<uint32_t, W> slots{};
    const uint32_t used = slots_of(task.source, slots);
    Node& node = nodes[task.wide];
    for (uint32_t k = 0; k < used; ++k) {
      set_slot_box(node, k, bvh_.nodes[slots[k]]);
      if (slot_is_leaf<W>(bvh_, plans_, slots[k])) {
        const Subtree& leaf = subtrees_[slots[k]];
        node.child[k] = static_cast<uint32_t>(part.next_group);
        node.count[k] = bvh_group_count(leaf.count);
        part.leaves.push_back({part.next_group, leaf});
        part.next_group += node.count[k];
        continue;
      }
      const auto index = static_cast<uint32_t>(part.next_node++);
      node.child[k] = index;
      node.count[k] = 0;
      nodes[index] = empty_wide_node<Node, W>();
      tasks.push_back({index, slots[k]});
    }
  }

  Bvh& bvh_;
  const TriangleAt& triangle_at_;
  HugePageVector<Subtree> subtrees_;
  HugePageVector<SlotPlan<W>> plans_;
};

}  // namespace

bool bvh_avx2_enabled() {
  const char* isa = std::getenv("LUEUR_BVH_ISA");
  if (isa && std::strcmp(isa, "sse") == 0) return false;
  return __builtin_cpu_supports("avx2");
}

namespace {

void collapse(Bvh& bvh, const TriangleAt& triangle_at, bool release) {
  bvh.wide_nodes.clear();
  bvh.wide8_nodes.clear();
  bvh.groups.clear();
  if (bvh.nodes.empty()) return;
  if (bvh_avx2_enabled())
    Collapse<BvhWideNode8, kBvhWidth8>(bvh, triangle_at).run(bvh.wide8_nodes, bvh.groups, release);
  else
    Collapse<BvhWideNode, kBvhWidth>(bvh, triangle_at).run(bvh.wide_nodes, bvh.groups, release);
}

}  // namespace

void build_wide_bvh(Bvh& bvh) {
  collapse(
      bvh, [&bvh](uint32_t place) { return bvh.triangles[place]; }, false);
}

void build_wide_bvh(Bvh& bvh, const TriangleAt& triangle_at) { collapse(bvh, triangle_at, true); }

}  // namespace lueur
