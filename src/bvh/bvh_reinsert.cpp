// Insertion-based optimisation of the BVH2 (Bittner, Hapala and Havran 2013). The binned build decides each split
// from the top down, seeing only the node it splits; a poor early split leaves subtrees in places where their
// boxes inflate every ancestor. Here the nodes whose boxes are largest relative to their children's are taken out,
// and their two children are inserted again, each where the tree's total inner-node area (the SAH cost of
// traversal) grows least, found by a branch-and-bound search from the root. Depends on bvh.h only.
#include "bvh/bvh_reinsert.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lueur {
namespace {

constexpr uint32_t kNone = ~0u;

/// A node while the tree is rearranged. Leaves keep their first triangle in child[0].
struct Node {
  Vec3 lo;
  uint32_t parent = kNone;
  Vec3 hi;
  uint32_t count = 0;  ///< a leaf's triangles (count > 0)
  uint32_t child[2] = {kNone, kNone};
  bool leaf() const { return count > 0; }
};

float area_of(const Vec3& lo, const Vec3& hi) { return Box3{lo, hi}.area(); }

float area_of(const Node& n) { return area_of(n.lo, n.hi); }

float union_area(const Node& a, const Node& b) { return area_of(glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)); }

struct Tree {
  HugePageVector<Node> nodes;
  uint32_t root = 0;

  uint32_t sibling(uint32_t n) const {
    const Node& p = nodes[nodes[n].parent];
    return p.child[0] == n ? p.child[1] : p.child[0];
  }

  /// Makes `to` take `from`'s place under `from`'s parent (or as the root).
  void replace_child(uint32_t from, uint32_t to) {
    const uint32_t p = nodes[from].parent;
    nodes[to].parent = p;
    if (p == kNone) {
      root = to;
      return;
    }
    Node& parent = nodes[p];
    parent.child[parent.child[0] == from ? 0 : 1] = to;
  }

  /// Recomputes boxes from `n` up to the root, stopping where a box no longer changes (the ones above it are then
  /// already right).
  void refit_from(uint32_t n) {
    for (; n != kNone; n = nodes[n].parent) {
      Node& x = nodes[n];
      const Node& a = nodes[x.child[0]];
      const Node& b = nodes[x.child[1]];
      const Vec3 lo = glm::min(a.lo, b.lo), hi = glm::max(a.hi, b.hi);
      if (lo == x.lo && hi == x.hi) return;
      x.lo = lo;
      x.hi = hi;
    }
  }
};

/// Bittner's inefficiency of an inner node: its area, and how much larger it is than its children, which is what
/// removing it and placing its children better can win.
float inefficiency(const Tree& tree, uint32_t n) {
  const Node& node = tree.nodes[n];
  const float area = area_of(node);
  const float a = area_of(tree.nodes[node.child[0]]), b = area_of(tree.nodes[node.child[1]]);
  const float tiny = 1e-30f;
  const float m_sum = area / std::max(0.5f * (a + b), tiny);
  const float m_min = area / std::max(std::min(a, b), tiny);
  return m_sum * m_min * area;
}

struct Candidate {
  float bound;    ///< lower bound of the cost of inserting anywhere in the subtree of `node`
  float induced;  ///< area the ancestors of `node` gain from the insertion
  uint32_t node;
  bool operator<(const Candidate& o) const {  // std's heaps keep the largest on top: invert for the lowest bound
    if (bound != o.bound) return bound > o.bound;
    return node > o.node;
  }
};

// Nodes one search may look at. Real scenes need few (the bunny 17 on average, the conference room and the 2M
// spheres about 30, at most 92), but where many long triangles overlap (a star of slivers through one point) nothing
// can be pruned and each search would walk the whole tree, which makes the optimisation quadratic. The best place
// found so far is then taken.
constexpr size_t kMaxSearchVisits = 512;

/// The node whose sibling `n` (detached from the tree) should become: the one where the tree's inner-node area
/// grows least. Inserting next to x adds a parent of area area(x u n) and grows each ancestor a of x by
/// area(a u n) - area(a); since every node inside x costs at least area(n) plus what x's box already gains, whole
/// subtrees are skipped once that exceeds the best cost found.
uint32_t best_sibling(const Tree& tree, uint32_t n, std::vector<Candidate>& heap) {
  const Node& inserted = tree.nodes[n];
  const float own = area_of(inserted);
  heap.clear();
  heap.push_back({own, 0.0f, tree.root});
  uint32_t best = tree.root;
  float best_cost = std::numeric_limits<float>::infinity();
  for (size_t visits = 0; !heap.empty() && visits < kMaxSearchVisits; ++visits) {
    std::pop_heap(heap.begin(), heap.end());
    const Candidate c = heap.back();
    heap.pop_back();
    if (!(c.bound < best_cost)) break;
    const Node& x = tree.nodes[c.node];
    const float merged = union_area(x, inserted);
    const float cost = c.induced + merged;
    if (cost < best_cost) {
      best_cost = cost;
      best = c.node;
    }
    if (x.leaf()) continue;
    const float induced = c.induced + merged - area_of(x);
    if (induced + own < best_cost) {
      heap.push_back({induced + own, induced, x.child[0]});
      std::push_heap(heap.begin(), heap.end());
      heap.push_back({induced + own, induced, x.child[1]});
      std::push_heap(heap.begin(), heap.end());
    }
  }
  return best;
}

/// Inserts the detached subtree `n` next to the best sibling, using the free node `spare` as their new parent.
void insert(Tree& tree, uint32_t n, uint32_t spare, std::vector<Candidate>& heap_storage) {
  const uint32_t x = best_sibling(tree, n, heap_storage);
  tree.replace_child(x, spare);
  Node& p = tree.nodes[spare];
  p.child[0] = x;
  p.child[1] = n;
  p.count = 0;
  tree.nodes[x].parent = spare;
  tree.nodes[n].parent = spare;
  p.lo = glm::min(tree.nodes[x].lo, tree.nodes[n].lo);
  p.hi = glm::max(tree.nodes[x].hi, tree.nodes[n].hi);
  tree.refit_from(p.parent);
}

/// Takes the inner node `n` and its parent out of the tree (n's sibling takes the parent's place), then inserts n's
/// two children again, larger first, reusing n and its parent as their new parents.
void reinsert_children(Tree& tree, uint32_t n, std::vector<Candidate>& heap_storage) {
  const uint32_t parent = tree.nodes[n].parent;
  const uint32_t sibling = tree.sibling(n);
  tree.replace_child(parent, sibling);
  if (tree.nodes[sibling].parent != kNone) tree.refit_from(tree.nodes[sibling].parent);
  uint32_t a = tree.nodes[n].child[0], b = tree.nodes[n].child[1];
  if (area_of(tree.nodes[a]) < area_of(tree.nodes[b])) std::swap(a, b);
  tree.nodes[a].parent = kNone;
  tree.nodes[b].parent = kNone;
  insert(tree, a, n, heap_storage);
  insert(tree, b, parent, heap_storage);
}

/// Sum of the inner nodes' areas: the traversal term of the SAH cost (leaves never change here).
double inner_area(const Tree& tree) {
  double sum = 0.0;
  for (const Node& n : tree.nodes)
    if (!n.leaf()) sum += area_of(n);
  return sum;
}

/// The leaves' ranges of the unchanged tree, in triangle order.
void identity_ranges(const HugePageVector<BvhNode>& nodes, std::vector<LeafRange>& ranges) {
  ranges.clear();
  for (const BvhNode& b : nodes)
    if (b.count > 0) ranges.push_back({b.first, b.count});
  std::sort(ranges.begin(), ranges.end(), [](const LeafRange& a, const LeafRange& b) { return a.first < b.first; });
}

Tree make_tree(const HugePageVector<BvhNode>& nodes) {
  Tree tree;
  tree.nodes.resize(nodes.size());
  for (uint32_t i = 0; i < nodes.size(); ++i) {
    const BvhNode& b = nodes[i];
    Node& n = tree.nodes[i];
    n.lo = b.lo;
    n.hi = b.hi;
    n.child[0] = b.first;
    if (b.count > 0) {
      n.count = b.count;
    } else {
      n.child[1] = b.first + 1;
      tree.nodes[b.first].parent = i;  // children sit after their parent: their other fields are not written yet
      tree.nodes[b.first + 1].parent = i;
    }
  }
  return tree;
}

/// One pass: the `fraction` of inner nodes (at least one) of highest inefficiency, in decreasing order, each taken
/// out and its children inserted again.
void reinsert_pass(Tree& tree, float fraction, std::vector<Candidate>& heap) {
  std::vector<std::pair<float, uint32_t>> order;
  for (uint32_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    if (!n.leaf() && n.parent != kNone) order.push_back({inefficiency(tree, i), i});
  }
  if (order.empty()) return;
  const size_t take =
      std::clamp<size_t>(static_cast<size_t>(static_cast<double>(order.size()) * fraction), 1, order.size());
  const auto end = order.begin() + static_cast<std::ptrdiff_t>(take);
  std::partial_sort(order.begin(), end, order.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;  // ties by index: deterministic
  });
  for (auto it = order.begin(); it != end; ++it) {
    // Earlier moves reuse nodes as new parents: this one may now be the root. It is still an inner node.
    if (tree.nodes[it->second].parent != kNone) reinsert_children(tree, it->second, heap);
  }
}

/// Writes `tree` over `nodes` in the build's form: depth-first, left subtree first, children adjacent and after
/// their parent; each leaf's old range goes to `ranges`. Returns false, writing nothing, where a node would be
/// deeper than kBvhMaxDepth allows.
bool lay_out(const Tree& tree, HugePageVector<BvhNode>& nodes, std::vector<LeafRange>& ranges) {
  struct Visit {
    uint32_t node, depth;
  };
  std::vector<Visit> visits{{tree.root, 0}};
  size_t leaves = 0;
  while (!visits.empty()) {
    const Visit v = visits.back();
    visits.pop_back();
    if (v.depth >= kBvhMaxDepth) return false;
    const Node& n = tree.nodes[v.node];
    if (n.leaf()) {
      ++leaves;
      continue;
    }
    visits.push_back({n.child[0], v.depth + 1});
    visits.push_back({n.child[1], v.depth + 1});
  }
  ranges.clear();
  ranges.reserve(leaves);
  struct Place {
    uint32_t node, slot;
  };
  std::vector<Place> places{{tree.root, 0}};
  uint32_t next_slot = 1, next_triangle = 0;
  while (!places.empty()) {
    const Place p = places.back();
    places.pop_back();
    const Node& n = tree.nodes[p.node];
    BvhNode& out = nodes[p.slot];
    out.lo = n.lo;
    out.hi = n.hi;
    if (n.leaf()) {
      out.first = next_triangle;
      out.count = n.count;
      ranges.push_back({n.child[0], n.count});
      next_triangle += n.count;
      continue;
    }
    out.first = next_slot;
    out.count = 0;
    places.push_back({n.child[1], next_slot + 1});
    places.push_back({n.child[0], next_slot});
    next_slot += 2;
  }
  return true;
}

}  // namespace

void reinsert_subtrees(HugePageVector<BvhNode>& nodes, std::vector<LeafRange>& ranges,
                       const ReinsertSettings& settings) {
  Tree tree = make_tree(nodes);
  // Scenes whose extent nears the float range can give infinite or NaN areas, which no cost comparison can rank. A
  // finite root area bounds every other area and every sum the search forms, bar overflow to infinity.
  if (!std::isfinite(area_of(tree.nodes[tree.root]))) {
    identity_ranges(nodes, ranges);
    return;
  }
  const double before = inner_area(tree);
  std::vector<Candidate> heap;
  for (int pass = 0; pass < settings.passes; ++pass) reinsert_pass(tree, settings.fraction, heap);
  // Each move is greedy, so a pass could in principle end worse than it began; the binned tree is kept then.
  if (!(inner_area(tree) < before) || !lay_out(tree, nodes, ranges)) identity_ranges(nodes, ranges);
}

}  // namespace lueur
