// The closest-hit and any-hit traversals of Lueur's wide BVH, written once for both tree widths over the kernels of
// bvh_kernels.h: the traversal stack, the leaf loops, the order children are taken in and prefetched, and the
// counting of work. Internal to src/bvh, with internal linkage for the kernels' reason: bvh_traverse.cpp and the
// AVX2 translation unit (bvh_traverse_avx.cpp) each compile their own copy.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <utility>

#include "bvh/bvh.h"
#include "bvh/bvh_kernels.h"

namespace lueur {
namespace {

/// A node or leaf waiting on the traversal stack, with the distance at which the ray enters it.
struct StackEntry {
  uint32_t child, count;
  float entry;
};

// Each node of `Width` children visited pushes at most Width - 1 entries (sorting writes its nearest child one entry
// above them before taking it back), and no inner node is deeper than kBvhMaxDepth - 1.
template <uint32_t Width>
constexpr uint32_t kStackSize = (Width - 1) * kBvhMaxDepth + 1;

// ---- the pieces both wide traversals (4-wide SSE, 8-wide AVX2) share -------------------------------------------

/// The closest hit a traversal has found so far.
struct BestHit {
  float t;
  uint32_t id = kNoHit;
  float u = 0.0f, v = 0.0f;
};

/// Which hits count: every one (NoFilter, compiled away), or those a HitFilter accepts (alpha cutouts).
struct NoFilter {
  bool operator()(uint32_t, float, float) const { return true; }
};

/// Tests the `count` triangle groups of a leaf starting at `first`, keeping the closest hit in `best`. Equal
/// distances go to the lowest input index, whichever leaf was reached first.
template <typename Filter>
inline void intersect_leaf_closest(const BvhTriangleGroup* groups, uint32_t first, uint32_t count,
                                   const RayLanes& lanes, const ClampLanes& clamp_lanes, BestHit& best,
                                   const Filter& filter) {
  for (uint32_t g = 0; g < count; ++g) {
    const BvhTriangleGroup& group = groups[first + g];
    __m128 t4, u4, v4;
    int mask = moller_trumbore4(group, lanes, t4, u4, v4);
    if (mask == 0) continue;
    mask = clamp4(group, lanes, clamp_lanes, mask, t4);
    while (mask != 0) {
      const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
      mask &= mask - 1;
      const float t = lane(t4, k);
      const uint32_t id = group.id[k];
      if ((t < best.t || (t == best.t && id < best.id)) && filter(id, lane(u4, k), lane(v4, k))) {
        best.t = t;
        best.id = id;
        best.u = lane(u4, k);
        best.v = lane(v4, k);
      }
    }
  }
}

/// Whether any triangle of the leaf's `count` groups starting at `first` is hit inside the ray's interval.
template <typename Filter>
inline bool intersect_leaf_any(const BvhTriangleGroup* groups, uint32_t first, uint32_t count, const RayData& r,
                               const RayLanes& lanes, const Filter& filter) {
  for (uint32_t g = 0; g < count; ++g) {
    const BvhTriangleGroup& group = groups[first + g];
    __m128 t4, u4, v4;
    int mask = moller_trumbore4(group, lanes, t4, u4, v4);
    while (mask != 0) {
      const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
      mask &= mask - 1;
      float t = lane(t4, k);
      if (finish_lane(r, group, k, t) && filter(group.id[k], lane(u4, k), lane(v4, k))) return true;
    }
  }
  return false;
}

/// Where a node's children and leaves lie, and how to start loading one: as soon as a node test selects a child,
/// all its cache lines are requested (as Embree does), so that the load of the child visited next overlaps the
/// sorting and branching that choose it, and stacked siblings may arrive before they are popped. On scenes larger
/// than the caches this hides much of the memory latency. Closest-hit queries only: it gave any-hit nothing
/// measurable.
template <typename Node>
struct ChildMemory {
  const Node* nodes;
  const BvhTriangleGroup* groups;
  void prefetch(uint32_t child, uint32_t count) const {
    const char* p =
        count != 0 ? reinterpret_cast<const char*>(groups + child) : reinterpret_cast<const char*>(nodes + child);
    constexpr size_t kBytes = std::max(sizeof(Node), sizeof(BvhTriangleGroup));
    for (size_t offset = 0; offset < kBytes; offset += 64) _mm_prefetch(p + offset, _MM_HINT_T0);
  }
};

/// The children of `node` whose bits are set in `mask`, nearest first: all but the nearest go on the stack,
/// farthest deepest, so that hits in the nearer ones shrink the best distance and let the farther ones be dropped.
/// Returns the nearest, to visit next. One or two children (most nodes) take no loop; more are insertion-sorted
/// where they land on the stack, nearest on top, which is then popped. `mask` must not be 0.
template <typename Node>
inline StackEntry push_children_nearest_first(const Node& node, int mask, const float* entry,
                                              const ChildMemory<Node>& memory, StackEntry* stack, uint32_t& size) {
  auto next = [&] {
    const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
    mask &= mask - 1;
    memory.prefetch(node.child[k], node.count[k]);
    return StackEntry{node.child[k], node.count[k], entry[k]};
  };
  StackEntry nearest = next();
  if (mask == 0) return nearest;
  StackEntry other = next();
  if (other.entry < nearest.entry) std::swap(nearest, other);
  if (mask == 0) {
    stack[size++] = other;
    return nearest;
  }
  StackEntry* sorted = stack + size;  // farthest first
  sorted[0] = other;
  sorted[1] = nearest;
  uint32_t n = 2;
  while (mask != 0) {
    const StackEntry e = next();
    uint32_t j = n++;
    for (; j > 0 && sorted[j - 1].entry < e.entry; --j) sorted[j] = sorted[j - 1];
    sorted[j] = e;
  }
  size += n - 1;
  return sorted[n - 1];
}

/// The slots of the children set in `mask`, in slot order: the first is returned, the others pushed. For any-hit
/// queries, where no distance order pays. `mask` must not be 0.
struct NodeRef {
  uint32_t child, count;
};
template <typename Node>
inline NodeRef push_children_in_order(const Node& node, int mask, NodeRef* stack, uint32_t& size) {
  auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
  mask &= mask - 1;
  const NodeRef first{node.child[k], node.count[k]};
  while (mask != 0) {
    k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
    mask &= mask - 1;
    stack[size++] = {node.child[k], node.count[k]};
  }
  return first;
}

/// How a traversal counts its work: NoCounts compiles to nothing, Counting adds to a TraversalCounts.
struct NoCounts {
  void query() const {}
  void node() const {}
  void leaf(uint32_t) const {}
};
struct Counting {
  TraversalCounts& counts;
  void query() const { ++counts.queries; }
  void node() const { ++counts.nodes; }
  void leaf(uint32_t groups) const {
    ++counts.leaves;
    counts.groups += groups;
  }
};

inline Hit make_hit(const BestHit& best) {
  Hit hit;
  if (best.id != kNoHit) {
    hit.t = best.t;
    hit.triangle = best.id;
    hit.u = best.u;
    hit.v = best.v;
  }
  return hit;
}

// ---- the traversals, for either tree: Sse over `BvhWideNode`s, Avx over `BvhWideNode8`s ------------------------

/// The BVH's wide tree of `Node`s (root at 0).
template <typename Node>
const Node* wide_tree(const Bvh& bvh);
template <>
inline const BvhWideNode* wide_tree(const Bvh& bvh) {
  return bvh.wide_nodes.data();
}
template <>
inline const BvhWideNode8* wide_tree(const Bvh& bvh) {
  return bvh.wide8_nodes.data();
}

/// Closest hit in the BVH's wide tree of `Node`s, Simd::kWidth children each.
template <typename Simd, typename Node, typename Count, typename Filter = NoFilter>
Hit closest_hit(const Bvh& bvh, const Ray& ray, const Count& count, const Filter& filter = {}) {
  using V = typename Simd::V;
  constexpr uint32_t kWidth = Simd::kWidth;
  count.query();
  if (bvh.empty()) return Hit{};
  const RayData r(ray);
  const RayLanes lanes(r);
  const ClampLanes clamp_lanes(r);
  const BoxLanes<Simd> box_lanes(r);
  const Node* nodes = wide_tree<Node>(bvh);
  const BvhTriangleGroup* groups = bvh.groups.data();

  const ChildMemory<Node> memory{nodes, groups};
  BestHit best{r.tmax};
  StackEntry stack[kStackSize<kWidth>];
  uint32_t size = 0;
  StackEntry current{0, 0, 0.0f};  // the root, an inner node

  for (;;) {
    if (current.count == 0) {
      const Node& node = nodes[current.child];
      V entry_lanes;
      count.node();
      const int mask = hit_boxes(node, box_lanes, Simd::broadcast(best.t), entry_lanes);
      if (mask != 0) {
        alignas(sizeof(V)) float entry[kWidth];
        Simd::store(entry, entry_lanes);
        current = push_children_nearest_first(node, mask, entry, memory, stack, size);
        continue;
      }
    } else {
      count.leaf(current.count);
      intersect_leaf_closest(groups, current.child, current.count, lanes, clamp_lanes, best, filter);
    }
    // Next waiting node that can still hold a hit no farther than the best one.
    do {
      if (size == 0) return make_hit(best);
      current = stack[--size];
    } while (current.entry > best.t);
  }
}

/// Whether anything in the BVH's wide tree of `Node`s, Simd::kWidth children each, is hit.
template <typename Simd, typename Node, typename Count, typename Filter = NoFilter>
bool any_hit(const Bvh& bvh, const Ray& ray, const Count& count, const Filter& filter = {}) {
  using V = typename Simd::V;
  count.query();
  if (bvh.empty()) return false;
  const RayData r(ray);
  const RayLanes lanes(r);
  const BoxLanes<Simd> box_lanes(r);
  const V t_limit = Simd::broadcast(r.tmax);
  const Node* nodes = wide_tree<Node>(bvh);
  const BvhTriangleGroup* groups = bvh.groups.data();

  // Any hit ends the query, so children are taken in slot order, with no sorting and no distances kept.
  NodeRef stack[kStackSize<Simd::kWidth>];
  uint32_t size = 0;
  NodeRef current{0, 0};
  for (;;) {
    if (current.count == 0) {
      const Node& node = nodes[current.child];
      V entry;
      count.node();
      const int mask = hit_boxes(node, box_lanes, t_limit, entry);
      if (mask != 0) {
        current = push_children_in_order(node, mask, stack, size);
        continue;
      }
    } else {
      count.leaf(current.count);
      if (intersect_leaf_any(groups, current.child, current.count, r, lanes, filter)) return true;
    }
    if (size == 0) return false;
    current = stack[--size];
  }
}

}  // namespace

/// The traversals of the 8-wide tree (bvh_traverse_avx.cpp); intersect_closest / intersect_any call them when
/// the BVH has one.
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray);
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray);
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts);
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts);
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray, const HitFilter& filter);
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray, const HitFilter& filter);

}  // namespace lueur
