// Tests for the BVH2's insertion-based optimisation (bvh_reinsert.h): it must keep the build's form (children
// adjacent and after their parent, leaves over contiguous ranges, boxes that are the exact union of their children)
// while lowering the tree's inner-node area, and move what a top-down build misplaces. Depends on bvh only.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_reinsert.h"

namespace lueur {
namespace {

BvhNode leaf(const Vec3& lo, const Vec3& hi, uint32_t first, uint32_t count) { return BvhNode{lo, first, hi, count}; }

BvhNode inner(uint32_t first, const BvhNode& a, const BvhNode& b) {
  return BvhNode{glm::min(a.lo, b.lo), first, glm::max(a.hi, b.hi), 0};
}

/// The BVH2 ((a, b), (c, d)) over four leaves, in the build's form.
HugePageVector<BvhNode> two_pairs(const BvhNode& a, const BvhNode& b, const BvhNode& c, const BvhNode& d) {
  HugePageVector<BvhNode> nodes(7);
  nodes[3] = a;
  nodes[4] = b;
  nodes[5] = c;
  nodes[6] = d;
  nodes[1] = inner(3, a, b);
  nodes[2] = inner(5, c, d);
  nodes[0] = inner(1, nodes[1], nodes[2]);
  return nodes;
}

/// Checks that reinsertion left the tree as it was: every node unchanged, and the leaves' ranges in their old order.
void expect_left_as_built(const HugePageVector<BvhNode>& before, const HugePageVector<BvhNode>& after,
                          const std::vector<LeafRange>& ranges) {
  ASSERT_EQ(after.size(), before.size());
  for (size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].lo, before[i].lo);
    EXPECT_EQ(after[i].hi, before[i].hi);
    EXPECT_EQ(after[i].first, before[i].first);
    EXPECT_EQ(after[i].count, before[i].count);
  }
  uint32_t next = 0;
  for (const LeafRange& r : ranges) {
    EXPECT_EQ(r.first, next);
    next += r.count;
  }
}

double inner_area(const HugePageVector<BvhNode>& nodes) {
  double sum = 0.0;
  for (const BvhNode& n : nodes) {
    if (n.count > 0) continue;
    Box3 box;
    box.lo = n.lo;
    box.hi = n.hi;
    sum += box.area();
  }
  return sum;
}

/// Checks the build's form on `after`, and that its leaves are `before`'s, moved as `ranges` says: leaf k of the
/// new triangle order holds old range ranges[k], with the same box.
void check_form(const HugePageVector<BvhNode>& before, const HugePageVector<BvhNode>& after,
                const std::vector<LeafRange>& ranges) {
  ASSERT_EQ(before.size(), after.size());
  std::vector<int> reached(after.size(), 0);
  std::vector<uint32_t> stack{0};
  uint32_t next_triangle = 0;
  size_t leaf_index = 0;
  // Depth-first, left first: leaves must come in triangle order, one after another.
  while (!stack.empty()) {
    const uint32_t i = stack.back();
    stack.pop_back();
    ++reached[i];
    const BvhNode& n = after[i];
    if (n.count > 0) {
      ASSERT_LT(leaf_index, ranges.size());
      EXPECT_EQ(n.first, next_triangle);
      EXPECT_EQ(n.count, ranges[leaf_index].count);
      // The old leaf over this range had the same box.
      const auto old = std::find_if(before.begin(), before.end(), [&](const BvhNode& b) {
        return b.count > 0 && b.first == ranges[leaf_index].first;
      });
      ASSERT_NE(old, before.end());
      EXPECT_EQ(old->lo, n.lo);
      EXPECT_EQ(old->hi, n.hi);
      EXPECT_EQ(old->count, n.count);
      next_triangle += n.count;
      ++leaf_index;
      continue;
    }
    ASSERT_GT(n.first, i);
    ASSERT_LT(n.first + 1, after.size());
    const BvhNode& a = after[n.first];
    const BvhNode& b = after[n.first + 1];
    EXPECT_EQ(n.lo, glm::min(a.lo, b.lo)) << "node " << i;
    EXPECT_EQ(n.hi, glm::max(a.hi, b.hi)) << "node " << i;
    stack.push_back(n.first + 1);
    stack.push_back(n.first);
  }
  EXPECT_EQ(leaf_index, ranges.size());
  for (size_t i = 0; i < reached.size(); ++i) EXPECT_EQ(reached[i], 1) << "node " << i;
  // The ranges are the old leaves', each once.
  std::vector<LeafRange> sorted = ranges;
  std::sort(sorted.begin(), sorted.end(), [](const LeafRange& x, const LeafRange& y) { return x.first < y.first; });
  uint32_t expected_first = 0;
  for (const LeafRange& r : sorted) {
    EXPECT_EQ(r.first, expected_first);
    expected_first += r.count;
  }
  EXPECT_EQ(expected_first, next_triangle);
}

TEST(BvhReinsert, PairsTheLeavesThatBelongTogether) {
  // Four unit cubes: a and c overlap near the origin, b and d near x = 10. A top-down build that paired a with b
  // and c with d gives two inner boxes spanning the whole scene; pairing a with c and b with d gives two small
  // ones.
  const Vec3 one(1.0f);
  const BvhNode a = leaf(Vec3(0.0f), one, 0, 1), b = leaf(Vec3(10.0f, 0.0f, 0.0f), Vec3(11.0f, 1.0f, 1.0f), 1, 1);
  const BvhNode c = leaf(Vec3(0.2f), Vec3(1.2f), 2, 1),
                d = leaf(Vec3(10.2f, 0.2f, 0.2f), Vec3(11.2f, 1.2f, 1.2f), 3, 1);
  HugePageVector<BvhNode> nodes = two_pairs(a, b, c, d);
  const HugePageVector<BvhNode> before = nodes;

  std::vector<LeafRange> ranges;
  reinsert_subtrees(nodes, ranges, ReinsertSettings{2, 1.0f});
  check_form(before, nodes, ranges);
  EXPECT_LT(inner_area(nodes), 0.5 * inner_area(before));
  // Each of the root's children now holds one near pair: old triangles {0, 2} and {1, 3}.
  for (uint32_t child = nodes[0].first; child <= nodes[0].first + 1; ++child) {
    const BvhNode& pair = nodes[child];
    ASSERT_EQ(pair.count, 0u);
    uint32_t old_firsts[2];
    for (uint32_t k = 0; k < 2; ++k) {
      const BvhNode& l = nodes[pair.first + k];
      ASSERT_GT(l.count, 0u);
      old_firsts[k] = ranges[l.first].first;  // one triangle per leaf: the new first is the leaf's index
    }
    EXPECT_EQ(std::max(old_firsts[0], old_firsts[1]) - std::min(old_firsts[0], old_firsts[1]), 2u);
  }
}

TEST(BvhReinsert, LeavesAGoodTreeAsItIs) {
  const BvhNode a = leaf(Vec3(0.0f), Vec3(1.0f), 0, 3), b = leaf(Vec3(5.0f), Vec3(6.0f), 3, 2);
  const BvhNode c = leaf(Vec3(20.0f), Vec3(21.0f), 5, 4);
  HugePageVector<BvhNode> nodes(5);
  nodes[3] = a;
  nodes[4] = b;
  nodes[2] = c;
  nodes[1] = inner(3, a, b);
  nodes[0] = inner(1, nodes[1], c);
  const HugePageVector<BvhNode> before = nodes;
  std::vector<LeafRange> ranges;
  reinsert_subtrees(nodes, ranges, ReinsertSettings{3, 1.0f});
  ASSERT_EQ(ranges.size(), 3u);
  expect_left_as_built(before, nodes, ranges);
}

TEST(BvhReinsert, LeavesTreesWithoutFiniteAreasAlone) {
  // The root spans the float range: its area overflows, so no cost can be compared.
  const float big = 3.0e38f;
  const BvhNode a = leaf(Vec3(-big), Vec3(-big + 1.0e32f), 0, 1), b = leaf(Vec3(0.0f), Vec3(1.0f), 1, 1);
  const BvhNode c = leaf(Vec3(big - 1.0e32f), Vec3(big), 2, 1), d = leaf(Vec3(0.5f), Vec3(1.5f), 3, 1);
  HugePageVector<BvhNode> nodes = two_pairs(a, b, c, d);
  const HugePageVector<BvhNode> before = nodes;
  std::vector<LeafRange> ranges;
  reinsert_subtrees(nodes, ranges, ReinsertSettings{2, 1.0f});
  ASSERT_EQ(ranges.size(), 4u);
  expect_left_as_built(before, nodes, ranges);
}

/// A BVH2 over `count` random boxes split at random (the worst kind of top-down build), in the build's form.
HugePageVector<BvhNode> random_tree(std::mt19937& rng, uint32_t count) {
  std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f), size(0.01f, 3.0f);
  std::vector<BvhNode> leaves(count);
  for (uint32_t i = 0; i < count; ++i) {
    const Vec3 lo(coordinate(rng), coordinate(rng), coordinate(rng));
    leaves[i] = leaf(lo, lo + Vec3(size(rng), size(rng), size(rng)), 0, 1 + i % 4);
  }
  HugePageVector<BvhNode> nodes(1);
  struct Task {
    uint32_t slot, begin, end;
  };
  std::vector<Task> tasks{{0, 0, count}};
  uint32_t next_triangle = 0;
  std::vector<uint32_t> order;
  // Depth-first, left first, so leaves take consecutive triangle ranges; boxes are filled in afterwards.
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    if (t.end - t.begin == 1) {
      BvhNode l = leaves[t.begin];
      l.first = next_triangle;
      next_triangle += l.count;
      nodes[t.slot] = l;
      continue;
    }
    const uint32_t mid = t.begin + 1 + static_cast<uint32_t>(rng() % (t.end - t.begin - 1));
    const auto first = static_cast<uint32_t>(nodes.size());
    nodes[t.slot] = BvhNode{Vec3(0.0f), first, Vec3(0.0f), 0};
    nodes.resize(nodes.size() + 2);
    tasks.push_back({first + 1, mid, t.end});
    tasks.push_back({first, t.begin, mid});
  }
  for (size_t i = nodes.size(); i-- > 0;) {
    if (nodes[i].count > 0) continue;
    nodes[i] = inner(nodes[i].first, nodes[nodes[i].first], nodes[nodes[i].first + 1]);
  }
  return nodes;
}

TEST(BvhReinsert, RandomTreesKeepTheirFormAndLoseArea) {
  std::mt19937 rng(7);
  for (const uint32_t count : {2u, 3u, 17u, 200u, 3000u}) {
    HugePageVector<BvhNode> nodes = random_tree(rng, count);
    const HugePageVector<BvhNode> before = nodes;
    std::vector<LeafRange> ranges;
    reinsert_subtrees(nodes, ranges, ReinsertSettings{3, 0.2f});
    check_form(before, nodes, ranges);
    if (count > 3) {
      EXPECT_LT(inner_area(nodes), 0.8 * inner_area(before)) << count << " leaves";
    }
    // The same input gives the same tree.
    HugePageVector<BvhNode> again = before;
    std::vector<LeafRange> ranges_again;
    reinsert_subtrees(again, ranges_again, ReinsertSettings{3, 0.2f});
    for (size_t i = 0; i < nodes.size(); ++i) {
      EXPECT_EQ(again[i].lo, nodes[i].lo);
      EXPECT_EQ(again[i].hi, nodes[i].hi);
      EXPECT_EQ(again[i].first, nodes[i].first);
    }
    ASSERT_EQ(ranges_again.size(), ranges.size());
    for (size_t k = 0; k < ranges.size(); ++k) EXPECT_EQ(ranges_again[k].first, ranges[k].first);
  }
}

}  // namespace
}  // namespace lueur
