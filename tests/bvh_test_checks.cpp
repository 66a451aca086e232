// Checks shared by the BVH suites: see bvh_test_checks.h.
#include "bvh_test_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace lueur::test {
namespace {

/// The wide tree the queries traverse (8-wide or 4-wide, whichever was built): every inner slot's node lies inside
/// the slot's box, every leaf holds at most kBvhMaxLeafSize triangles inside its box, and every kept triangle is in
/// exactly one leaf.
template <typename Node, uint32_t W>
void check_wide_tree(const Bvh& bvh, const HugePageVector<Node>& nodes, const Corners& corners) {
  size_t failures = 0;
  auto fail = [&](const std::string& what) {
    if (++failures <= 5) ADD_FAILURE() << what;
  };
  std::vector<int> id_visits(corners.size() / 3, 0);
  auto inside = [](const Vec3& p, const Vec3& lo, const Vec3& hi) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
  };
  struct Item {
    uint32_t node;
    Vec3 lo, hi;
  };
  std::vector<Item> stack{{0, Vec3(-kInfinity), Vec3(kInfinity)}};
  size_t visited = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node >= nodes.size() || ++visited > nodes.size()) {
      fail("wide node " + std::to_string(item.node) + " out of range or reached twice");
      continue;
    }
    const Node& node = nodes[item.node];
    uint32_t used = 0;
    for (uint32_t k = 0; k < W; ++k) {
      const Vec3 lo(node.lo[0][k], node.lo[1][k], node.lo[2][k]), hi(node.hi[0][k], node.hi[1][k], node.hi[2][k]);
      if (std::isnan(lo.x)) continue;  // an unused slot
      ++used;
      if (!inside(lo, item.lo, item.hi) || !inside(hi, item.lo, item.hi)) fail("wide slot outside its parent's box");
      if (node.count[k] == 0) {
        stack.push_back({node.child[k], lo, hi});
        continue;
      }
      if (node.count[k] > bvh_group_count(kBvhMaxLeafSize)) fail("wide leaf with too many groups");
      uint32_t triangles = 0;
      for (uint32_t g = node.child[k]; g < node.child[k] + node.count[k] && g < bvh.groups.size(); ++g) {
        for (uint32_t lane = 0; lane < kBvhWidth; ++lane) {
          const uint32_t id = bvh.groups[g].id[lane];
          if (id == kNoHit) continue;
          ++triangles;
          if (id >= id_visits.size()) {
            fail("wide leaf triangle id out of range");
            continue;
          }
          ++id_visits[id];
          for (int corner = 0; corner < 3; ++corner)
            if (!inside(corners[3 * id + corner], lo, hi)) fail("triangle " + std::to_string(id) + " outside its leaf");
        }
      }
      if (triangles == 0 || triangles > kBvhMaxLeafSize)
        fail("wide leaf of " + std::to_string(triangles) + " triangles");
    }
    if (used == 0) fail("wide node " + std::to_string(item.node) + " has no children");
  }
  for (size_t i = 0; i < id_visits.size(); ++i) {
    const int expected = triangle_kept(corners, i) ? 1 : 0;
    if (id_visits[i] != expected)
      fail("input triangle " + std::to_string(i) + " is in " + std::to_string(id_visits[i]) + " wide leaves");
  }
  EXPECT_EQ(failures, 0u);
}

void check_wide_invariants(const Bvh& bvh, const Corners& corners) {
  if (!bvh.wide8_nodes.empty())
    check_wide_tree<BvhWideNode8, kBvhWidth8>(bvh, bvh.wide8_nodes, corners);
  else
    check_wide_tree<BvhWideNode, kBvhWidth>(bvh, bvh.wide_nodes, corners);
}

/// What a query of one ray may count, derived from the wide tree's boxes alone (no traversal code): at most the
/// nodes, leaves and groups whose boxes, widened a little, the ray's segment (tmin, tmax) crosses, their ancestors'
/// too; and when nothing is hit, at least those whose boxes, narrowed a little, it crosses plainly (with no hit to
/// prune by distance, both queries must test every one of them). The root counts as a node whenever there is one.
struct VisitRange {
  uint64_t nodes_max = 0, leaves_max = 0, groups_max = 0;
  uint64_t nodes_min = 0, leaves_min = 0;
};

/// The wide tree (either width) in double precision, with, for each input triangle, the wide nodes from the root
/// down to the one that holds its leaf: a closest hit on it must have visited all of them.
class VisitBounds {
 public:
  VisitBounds(const Bvh& bvh, size_t triangle_count) : nodes_on_path_(triangle_count, 0) {
    if (!bvh.wide8_nodes.empty())
      flatten<BvhWideNode8, kBvhWidth8>(bvh, bvh.wide8_nodes);
    else
      flatten<BvhWideNode, kBvhWidth>(bvh, bvh.wide_nodes);
  }

  /// Wide nodes from the root to the one holding triangle `id`'s leaf, both included (0: in no leaf).
  uint32_t nodes_on_path(uint32_t id) const { return id < nodes_on_path_.size() ? nodes_on_path_[id] : 0; }

  VisitRange for_ray(const Ray& ray) const {
    VisitRange range;
    if (nodes_.empty()) return range;
    range.nodes_max = range.nodes_min = 1;
    // A NaN limit (the test's rays get one where their length overflows) leaves the span undefined: the upper bound
    // then takes the whole line, and nothing is certain.
    Ray line = ray;
    if (std::isnan(line.tmin)) line.tmin = -kInfinity;
    if (std::isnan(line.tmax)) line.tmax = kInfinity;
    visit(0, line, line.tmin == ray.tmin && line.tmax == ray.tmax, range);
    return range;
  }

 private:
  struct Slot {
    double lo[3], hi[3];
    uint32_t child, groups;  ///< groups == 0: an inner slot, `child` its node
  };
  struct Node {
    uint32_t first, count;  ///< its used slots in slots_
  };

  template <typename WideNode, uint32_t W>
  void flatten(const Bvh& bvh, const HugePageVector<WideNode>& nodes) {
    for (const WideNode& node : nodes) {
      Node flat{static_cast<uint32_t>(slots_.size()), 0};
      for (uint32_t k = 0; k < W; ++k) {
        if (std::isnan(node.lo[0][k])) continue;  // an unused slot
        Slot slot{};
        for (int a = 0; a < 3; ++a) {
          slot.lo[a] = node.lo[a][k];
          slot.hi[a] = node.hi[a][k];
        }
        slot.child = node.child[k];
        slot.groups = node.count[k];
        slots_.push_back(slot);
        ++flat.count;
      }
      nodes_.push_back(flat);
    }
    if (nodes_.empty()) return;  // an empty BVH: no query visits anything
    // The slack covers the float rounding of the kernels' slab test (a few ulps of the coordinates and of the ray's
    // origin, which lies within the scene's box and a margin of about its size) with a wide margin.
    double scale = 0.0;
    for (uint32_t s = nodes_[0].first; s < nodes_[0].first + nodes_[0].count; ++s)
      for (int a = 0; a < 3; ++a) scale = std::max({scale, std::fabs(slots_[s].lo[a]), std::fabs(slots_[s].hi[a])});
    slack_ = 1e-4 * scale;
    // Depths of the leaves, by a walk from the root.
    std::vector<std::pair<uint32_t, uint32_t>> stack{{0, 1}};
    while (!stack.empty()) {
      const auto [n, depth] = stack.back();
      stack.pop_back();
      for (uint32_t s = nodes_[n].first; s < nodes_[n].first + nodes_[n].count; ++s) {
        const Slot& slot = slots_[s];
        if (slot.groups == 0) {
          stack.push_back({slot.child, depth + 1});
          continue;
        }
        for (uint32_t g = slot.child; g < slot.child + slot.groups; ++g)
          for (const uint32_t id : bvh.groups[g].id)
            if (id < nodes_on_path_.size()) nodes_on_path_[id] = depth;
      }
    }
  }

  /// Whether the segment (tmin, tmax) of the ray meets the slot's box grown by `grow` on every side (negative:
  /// shrunk), the ends of the span included.
  static bool crosses(const Slot& slot, const Ray& ray, double grow) {
    double entry = ray.tmin, exit = ray.tmax;
    for (int a = 0; a < 3; ++a) {
      const double lo = slot.lo[a] - grow, hi = slot.hi[a] + grow;
      if (lo > hi) return false;
      const double o = ray.origin[a], d = ray.dir[a];
      if (d == 0.0) {
        if (o < lo || o > hi) return false;
        continue;
      }
      const double t0 = (lo - o) / d, t1 = (hi - o) / d;
      entry = std::max(entry, std::min(t0, t1));
      exit = std::min(exit, std::max(t0, t1));
    }
    return entry <= exit;
  }

  void visit(uint32_t n, const Ray& ray, bool certain, VisitRange& range) const {
    for (uint32_t s = nodes_[n].first; s < nodes_[n].first + nodes_[n].count; ++s) {
      const Slot& slot = slots_[s];
      if (!crosses(slot, ray, slack_)) continue;
      const bool certainly = certain && crosses(slot, ray, -slack_);
      if (slot.groups > 0) {
        ++range.leaves_max;
        range.groups_max += slot.groups;
        if (certainly) ++range.leaves_min;
        continue;
      }
      ++range.nodes_max;
      if (certainly) ++range.nodes_min;
      visit(slot.child, ray, certainly, range);
    }
  }

  std::vector<Node> nodes_;
  std::vector<Slot> slots_;
  std::vector<uint32_t> nodes_on_path_;
  double slack_ = 0.0;
};

/// Checks what one counted query (`counts`, fresh) says it did against what the tree allows for its ray; `hit` is
/// the triangle a closest-hit query found (kNoHit for any-hit queries and misses). Returns what is wrong, or "".
std::string check_counts(const TraversalCounts& counts, const VisitRange& range, bool found, uint32_t hit,
                         uint32_t nodes_to_hit) {
  std::ostringstream wrong;
  if (counts.queries != 1) wrong << " counted " << counts.queries << " queries for one;";
  if (counts.nodes > range.nodes_max || counts.leaves > range.leaves_max || counts.groups > range.groups_max)
    wrong << " visited more than the ray's segment reaches;";
  if (counts.groups < counts.leaves) wrong << " fewer groups than leaves;";
  if (found && counts.leaves == 0) wrong << " a hit without a leaf tested;";
  if (hit != kNoHit && counts.nodes < nodes_to_hit) wrong << " skipped a node above the hit's leaf;";
  if (!found && (counts.nodes < range.nodes_min || counts.leaves < range.leaves_min))
    wrong << " missed a node or leaf the ray plainly crosses;";
  if (wrong.str().empty()) return "";
  std::ostringstream out;
  out << "counted nodes " << counts.nodes << ", leaves " << counts.leaves << ", groups " << counts.groups
      << "; the ray's segment reaches nodes " << range.nodes_max << ", leaves " << range.leaves_max << ", groups "
      << range.groups_max;
  if (!found) out << "; a miss must test nodes " << range.nodes_min << ", leaves " << range.leaves_min;
  if (hit != kNoHit) out << "; the hit's leaf is " << nodes_to_hit << " nodes down";
  out << ":" << wrong.str();
  return out.str();
}

}  // namespace

RayStats compare_with_brute_force(const Corners& corners, const Bvh& bvh, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  const Box3 bounds = bounds_of(corners);
  const VisitBounds visits(bvh, corners.size() / 3);
  RayStats stats;
  for (size_t i = 0; i < count; ++i) {
    const Ray ray = random_ray(rng, corners, bounds);
    const Hit expected = brute_force_closest(corners, ray);
    const Hit got = intersect_closest(bvh, ray);
    const bool any = intersect_any(bvh, ray);
    ++stats.rays;
    if (expected.found()) ++stats.hits;
    const bool same = got.found() == expected.found() &&
                      (!expected.found() || (got.triangle == expected.triangle && got.t == expected.t &&
                                             got.u == expected.u && got.v == expected.v));
    if (!same || any != expected.found()) {
      if (++stats.mismatches <= 5) {
        ADD_FAILURE() << "ray " << i << ": " << describe(ray) << "\n  bvh:   " << describe(got)
                      << "\n  brute: " << describe(expected) << "\n  any:   " << any;
      }
    }
    // The counted queries give the same answers, and their counts of work stay within what the tree's boxes allow
    // for this ray: a query that visited nodes its ray cannot reach, skipped ones it must test, or miscounted,
    // fails here.
    TraversalCounts closest_counts, any_counts;
    const Hit counted = intersect_closest(bvh, ray, closest_counts);
    const bool counted_any = intersect_any(bvh, ray, any_counts);
    const VisitRange range = visits.for_ray(ray);
    const uint32_t hit = got.found() ? got.triangle : kNoHit;
    std::string wrong;
    if (counted.triangle != got.triangle || counted.t != got.t || counted_any != any)
      wrong = "the counted queries answer differently";
    else if (const std::string w = check_counts(closest_counts, range, got.found(), hit, visits.nodes_on_path(hit));
             !w.empty())
      wrong = "closest hit: " + w;
    else if (const std::string v = check_counts(any_counts, range, any, kNoHit, 0); !v.empty())
      wrong = "any hit: " + v;
    if (!wrong.empty() && ++stats.miscounted <= 5)
      ADD_FAILURE() << "ray " << i << ": " << describe(ray) << "\n  " << wrong;
    if (!expected.found() && range.nodes_min > 1) ++stats.misses_bounded_below;
  }
  EXPECT_EQ(stats.mismatches, 0u);
  EXPECT_EQ(stats.miscounted, 0u);
  return stats;
}

uint32_t check_invariants(const Bvh& bvh, const Corners& corners) {
  size_t kept_count = 0;
  for (size_t i = 0; i < corners.size() / 3; ++i) kept_count += triangle_kept(corners, i) ? 1 : 0;
  EXPECT_EQ(bvh.triangles.size(), kept_count);
  if (kept_count == 0) {
    EXPECT_TRUE(bvh.empty());
    return 0;
  }
  EXPECT_FALSE(bvh.nodes.empty());
  if (bvh.nodes.empty()) return 0;

  std::vector<int> node_visits(bvh.nodes.size(), 0);
  std::vector<int> slot_visits(bvh.triangles.size(), 0);
  std::vector<int> id_visits(corners.size() / 3, 0);
  struct Item {
    uint32_t node, depth;
  };
  std::vector<Item> stack{{0, 0}};
  uint32_t max_depth = 0;
  size_t failures = 0;
  auto fail = [&](const std::string& what) {
    if (++failures <= 5) ADD_FAILURE() << what;
  };
  auto inside = [](const Vec3& p, const BvhNode& n) {
    return p.x >= n.lo.x && p.y >= n.lo.y && p.z >= n.lo.z && p.x <= n.hi.x && p.y <= n.hi.y && p.z <= n.hi.z;
  };
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    max_depth = std::max(max_depth, item.depth);
    if (++node_visits[item.node] != 1) fail("node " + std::to_string(item.node) + " reached twice");
    const BvhNode& node = bvh.nodes[item.node];
    if (!(node.lo.x <= node.hi.x && node.lo.y <= node.hi.y && node.lo.z <= node.hi.z)) {
      fail("node " + std::to_string(item.node) + " has an inverted box");
    }
    if (node.count == 0) {
      // An inner node at depth d leaves d + 1 entries on a traversal stack of kBvhMaxDepth.
      if (item.depth + 1 > kBvhMaxDepth) fail("inner node too deep: " + std::to_string(item.depth));
      if (node.first == 0 || static_cast<size_t>(node.first) + 1 >= bvh.nodes.size()) {
        fail("inner node " + std::to_string(item.node) + " has children out of range");
        continue;
      }
      for (uint32_t c = node.first; c <= node.first + 1; ++c) {
        const BvhNode& child = bvh.nodes[c];
        if (!inside(child.lo, node) || !inside(child.hi, node)) {
          fail("child " + std::to_string(c) + " is not inside its parent " + std::to_string(item.node));
        }
        stack.push_back({c, item.depth + 1});
      }
    } else {
      if (node.count > kBvhWidth) fail("leaf " + std::to_string(item.node) + " holds more than one group");
      if (static_cast<size_t>(node.first) + node.count > bvh.triangles.size()) {
        fail("leaf " + std::to_string(item.node) + " reaches past the triangles");
        continue;
      }
      for (uint32_t s = node.first; s < node.first + node.count; ++s) {
        ++slot_visits[s];
        const BvhTriangle& tri = bvh.triangles[s];
        if (tri.id >= id_visits.size()) {
          fail("triangle id out of range");
          continue;
        }
        ++id_visits[tri.id];
        const Vec3& a = corners[3 * tri.id];
        const Vec3& b = corners[3 * tri.id + 1];
        const Vec3& c = corners[3 * tri.id + 2];
        if (!inside(a, node) || !inside(b, node) || !inside(c, node)) {
          fail("triangle " + std::to_string(tri.id) + " is not inside its leaf " + std::to_string(item.node));
        }
        const BvhTriangle expected = make_bvh_triangle(a, b, c, tri.id);
        if (tri.v0 != expected.v0 || tri.e1 != expected.e1 || tri.e2 != expected.e2) {
          fail("triangle " + std::to_string(tri.id) + " is stored with other vertices");
        }
        // Hits are clamped into this box; agreement with brute force needs every node to contain it.
        const Box3 clamp_box = bvh_triangle_box(tri);
        if (!inside(clamp_box.lo, node) || !inside(clamp_box.hi, node)) {
          fail("triangle " + std::to_string(tri.id) + "'s clamp box is not inside its leaf");
        }
      }
    }
  }
  for (size_t n = 0; n < node_visits.size(); ++n) {
    if (node_visits[n] != 1) fail("node " + std::to_string(n) + " is unreachable");
  }
  for (size_t s = 0; s < slot_visits.size(); ++s) {
    if (slot_visits[s] != 1)
      fail("triangle slot " + std::to_string(s) + " is in " + std::to_string(slot_visits[s]) + " leaves");
  }
  for (size_t i = 0; i < id_visits.size(); ++i) {
    const int expected = triangle_kept(corners, i) ? 1 : 0;
    if (id_visits[i] != expected)
      fail("input triangle " + std::to_string(i) + " appears " + std::to_string(id_visits[i]) + " times");
  }
  EXPECT_EQ(failures, 0u);
  check_wide_invariants(bvh, corners);
  return max_depth;
}

}  // namespace lueur::test
