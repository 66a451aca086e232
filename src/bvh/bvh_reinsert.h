// Improves a built BVH2 by moving badly placed subtrees to where they cost least (insertion-based optimisation,
// after Bittner, Hapala and Havran, "Fast insertion-based optimization of bounding volume hierarchies", 2013).
// Internal to src/bvh; depends on bvh.h only.
#pragma once

#include <vector>

#include "bvh/bvh.h"

namespace lueur {

/// A leaf's triangles in the order the tree had before the optimisation: where they start, and how many.
struct LeafRange {
  uint32_t first, count;
};

/// How much reinsertion to do. On the conference room (BENCHMARKS.md, session 9) these defaults cut the traversal
/// term of the SAH by 28% for about 5 ms; three times as many nodes per pass cut it 1.6% further (ten times: 2.7%)
/// and traced no faster. Most of the gain is in the first few hundred moves.
struct ReinsertSettings {
  int passes = 2;
  float fraction = 0.003f;  ///< of the inner nodes, the most inefficient, taken out and reinserted in each pass
};

/// Rewrites the BVH2 `nodes` (root at 0, each inner node's two children adjacent and after it, each leaf over a
/// contiguous range of the triangle order, left subtree's range first) into a tree of lower SAH cost, in the same
/// form. `ranges` receives the old range of every leaf in the new triangle order: the caller concatenates them to
/// reorder its triangles. Every node box is the exact union of its children's, so boxes still contain their
/// triangles exactly. Deterministic and serial. A result deeper than kBvhMaxDepth, or one whose traversal
/// term is not lower, is dropped: `nodes` then stays as it was and `ranges` is the identity.
void reinsert_subtrees(HugePageVector<BvhNode>& nodes, std::vector<LeafRange>& ranges,
                       const ReinsertSettings& settings = {});

}  // namespace lueur
