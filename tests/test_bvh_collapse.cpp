// Tests for the collapse of the BVH2 into the wide tree (bvh_wide.cpp): on small scenes its SAH cost must equal
// the lowest that any collapse of the same BVH2 reaches, found here by enumerating every choice; and the scenes must
// be ones where that lowest cost is worth finding (the greedy collapse it replaced costs more on most of them).
// Depends on bvh only.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "bvh/bvh.h"
#include "test_support.h"

namespace lueur {
namespace {

// The collapse's cost model: visiting a wide node costs its area, testing a leaf its area per group of triangles.
constexpr double kNodeCost = 1.0, kGroupCost = 1.0;

double area_of(const Vec3& lo, const Vec3& hi) {
  Box3 box;
  box.lo = lo;
  box.hi = hi;
  return box.area();
}

double area_of(const BvhNode& n) { return area_of(n.lo, n.hi); }

/// The lowest cost of any collapse of a BVH2, by exhaustive search: every node may be a slot of its parent wide
/// node (as a leaf of at most kBvhMaxLeafSize triangles, or as a wide node of its own), or be opened so that its two
/// children take its place, as long as a wide node has at most `width` slots. BVH2 leaves cannot be opened.
struct Exhaustive {
  const Bvh& bvh;
  uint32_t width;
  std::vector<uint32_t> triangles;         // under each BVH2 node
  mutable std::vector<double> slot_costs;  // slot(n), once computed (NaN before)

  explicit Exhaustive(const Bvh& b, uint32_t w)
      : bvh(b),
        width(w),
        triangles(b.nodes.size(), 0),
        slot_costs(b.nodes.size(), std::numeric_limits<double>::quiet_NaN()) {
    for (size_t i = bvh.nodes.size(); i-- > 0;) {
      const BvhNode& n = bvh.nodes[i];
      triangles[i] = n.count > 0 ? n.count : triangles[n.first] + triangles[n.first + 1];
    }
  }

  double leaf_cost(uint32_t n) const { return kGroupCost * bvh_group_count(triangles[n]) * area_of(bvh.nodes[n]); }

  /// Node n as one slot.
  double slot(uint32_t n) const {
    if (!std::isnan(slot_costs[n])) return slot_costs[n];
    const BvhNode& node = bvh.nodes[n];
    double cost = leaf_cost(n);
    if (node.count == 0) cost = triangles[n] <= kBvhMaxLeafSize ? std::min(cost, wide_node(n)) : wide_node(n);
    return slot_costs[n] = cost;
  }

  /// Node n (inner) as a wide node.
  double wide_node(uint32_t n) const {
    const BvhNode& node = bvh.nodes[n];
    return kNodeCost * area_of(node) + frontier({node.first, node.first + 1}, width);
  }

  /// The cheapest way to turn `pending` into at most `budget` slots.
  double frontier(std::vector<uint32_t> pending, uint32_t budget) const {
    if (pending.empty()) return 0.0;
    if (pending.size() > budget) return std::numeric_limits<double>::infinity();
    const uint32_t first = pending.front();
    std::vector<uint32_t> rest(pending.begin() + 1, pending.end());
    double best = slot(first) + frontier(rest, budget - 1);
    const BvhNode& node = bvh.nodes[first];
    if (node.count == 0) {
      std::vector<uint32_t> opened{node.first, node.first + 1};
      opened.insert(opened.end(), rest.begin(), rest.end());
      best = std::min(best, frontier(opened, budget));
    }
    return best;
  }
};

/// The cost of the greedy collapse Lueur used before the optimal one (as Embree's wide builders shape their trees):
/// a wide node takes the two children of its BVH2 node and keeps opening the inner one of largest area until it is
/// full; a slot is then a leaf where it is a BVH2 leaf, or holds at most kBvhMaxLeafSize triangles and testing them
/// all costs no more than one split, else a wide node of its own. A collapse the exhaustive search also considers,
/// so never cheaper than its lowest.
struct Greedy {
  const Exhaustive& exhaustive;

  bool leaf(uint32_t n) const {
    const BvhNode& node = exhaustive.bvh.nodes[n];
    if (node.count > 0) return true;
    if (exhaustive.triangles[n] > kBvhMaxLeafSize) return false;
    const double split =
        kNodeCost * area_of(node) + exhaustive.leaf_cost(node.first) + exhaustive.leaf_cost(node.first + 1);
    return !(split < exhaustive.leaf_cost(n));
  }

  double slot(uint32_t n) const { return leaf(n) ? exhaustive.leaf_cost(n) : wide_node(n); }

  double wide_node(uint32_t n) const {
    const Bvh& bvh = exhaustive.bvh;
    std::vector<uint32_t> slots{bvh.nodes[n].first, bvh.nodes[n].first + 1};
    while (slots.size() < exhaustive.width) {
      auto largest = slots.end();
      for (auto s = slots.begin(); s != slots.end(); ++s)
        if (bvh.nodes[*s].count == 0 &&
            (largest == slots.end() || area_of(bvh.nodes[*s]) > area_of(bvh.nodes[*largest])))
          largest = s;
      if (largest == slots.end()) break;
      const uint32_t opened = bvh.nodes[*largest].first;
      *largest = opened;
      slots.push_back(opened + 1);
    }
    double cost = kNodeCost * area_of(bvh.nodes[n]);
    for (const uint32_t s : slots) cost += slot(s);
    return cost;
  }
};

/// The cost of the wide tree the build made, under the same model.
template <typename Node, uint32_t W>
double wide_tree_cost(const HugePageVector<Node>& nodes) {
  double cost = 0.0;
  std::vector<uint32_t> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes[stack.back()];
    stack.pop_back();
    Vec3 lo(kInfinity), hi(-kInfinity);
    for (uint32_t k = 0; k < W; ++k) {
      const Vec3 slot_lo(node.lo[0][k], node.lo[1][k], node.lo[2][k]);
      const Vec3 slot_hi(node.hi[0][k], node.hi[1][k], node.hi[2][k]);
      if (std::isnan(slot_lo.x)) continue;
      lo = glm::min(lo, slot_lo);
      hi = glm::max(hi, slot_hi);
      if (node.count[k] > 0)
        cost += kGroupCost * node.count[k] * area_of(slot_lo, slot_hi);
      else
        stack.push_back(node.child[k]);
    }
    cost += kNodeCost * area_of(lo, hi);
  }
  return cost;
}

void add_random_triangle(std::mt19937& rng, std::vector<Vec3>& corners, float spread, float size) {
  std::uniform_real_distribution<float> place(-spread, spread), offset(-size, size);
  const Vec3 a(place(rng), place(rng), place(rng));
  corners.push_back(a);
  corners.push_back(a + Vec3(offset(rng), offset(rng), offset(rng)));
  corners.push_back(a + Vec3(offset(rng), offset(rng), offset(rng)));
}

void check_optimal_collapses(bool sse) {
  // Restored however the test ends: a failed ASSERT below must not leave later tests on the 4-wide tree.
  std::optional<test::ScopedEnv> isa;
  if (sse) isa.emplace("LUEUR_BVH_ISA", "sse");
  constexpr int kScenes = 40;
  std::mt19937 rng(21);
  int greedy_costlier = 0;
  for (int scene = 0; scene < kScenes; ++scene) {
    // Clusters of small triangles among a few large ones: leaves and openings both have something to win.
    std::vector<Vec3> corners;
    const int count = 24 + scene % 48;
    for (int i = 0; i < count; ++i) add_random_triangle(rng, corners, 10.0f, i % 5 == 0 ? 6.0f : 0.5f);
    const Bvh bvh = build_bvh(corners);
    ASSERT_GT(bvh.triangles.size(), kBvhMaxLeafSize);  // the root is then a wide node, whatever the plan
    const bool eight = !bvh.wide8_nodes.empty();
    ASSERT_EQ(eight, !sse && bvh_avx2_enabled());
    const Exhaustive exhaustive(bvh, eight ? kBvhWidth8 : kBvhWidth);
    const double best = exhaustive.wide_node(0);
    const double built = eight ? wide_tree_cost<BvhWideNode8, kBvhWidth8>(bvh.wide8_nodes)
                               : wide_tree_cost<BvhWideNode, kBvhWidth>(bvh.wide_nodes);
    EXPECT_NEAR(built, best, 1e-5 * best) << "scene " << scene << ", " << count << " triangles";
    const double greedy = Greedy{exhaustive}.wide_node(0);
    EXPECT_GE(greedy, best * (1.0 - 1e-9)) << "the enumeration missed the greedy collapse in scene " << scene;
    // Well beyond the rounding of float boxes that the tolerance above allows.
    if (greedy > best * (1.0 + 1e-3)) ++greedy_costlier;
  }
  // Matching the lowest cost only proves something where a plainer collapse misses it. With 24 triangles and more
  // the greedy collapse costs more on about half to three quarters of these scenes (fewer on small ones, where the
  // root holds nearly everything): a collapse that fell back to it would fail the check above on each scene
  // counted here.
  EXPECT_GE(greedy_costlier, kScenes / 3)
      << "only " << greedy_costlier << " of " << kScenes << " scenes tell the lowest-cost collapse from the greedy one";
  std::cout << "[ collapse ] " << (!sse && bvh_avx2_enabled() ? "8-wide" : "4-wide")
            << ": the greedy collapse costs more on " << greedy_costlier << " of " << kScenes << " scenes\n";
}

TEST(BvhCollapse, ReachesTheLowestCostOfAnyCollapse) { check_optimal_collapses(false); }

TEST(BvhCollapse, ReachesTheLowestCostOfAnyCollapseFourWide) { check_optimal_collapses(true); }

}  // namespace
}  // namespace lueur
