// The `importance` light choice: the emitters grouped into a few clusters, each bounded (a sphere around it, a cone
// around its normals, its power), so that L1 weighs every cluster at the point it shades by a bound on what the
// cluster can send there (power x the best cosine at the surface x the best cosine at the emitter / distance^2),
// chooses one by that weight, then one of its emitters by power. The angular bounds are those of pbrt-v4's light BVH
// (LightBounds::Importance). Besides, a cluster wholly below the point's horizon (its box) or with the point behind
// every one of its emitters' planes weighs nothing, however close: no shadow ray is spent on a ceiling light from the
// ceiling it hangs under, or on a wall lamp from the wall behind it. The weight is positive wherever an emitter of
// the cluster can light the point, so the estimate stays unbiased, but for points within a few ulps of an emitter's
// plane and clusters whose best cosine at the surface is below 1e-5 (an emitter in the surface's own plane). The
// clusters are a cut of at most kMaxLightClusters nodes of a tree over the emitters, so that the weighing costs a
// fixed few operations per point however many emitters the scene has.
// Depends on lights/emitter.h only.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lights/emitter.h"
#include "lights/light_bounds.h"

namespace lueur {

inline constexpr size_t kMaxLightClusters = 16;
/// A cluster of at most this many emitters chooses among them by power; a larger one by a tree over them.
inline constexpr size_t kMaxMembersByPower = 16;
inline constexpr uint32_t kNoTreeNode = 0xffffffffu;

/// Children of a tree node, weighed at a point all at once (like the clusters): a node halves its emitters three
/// times over.
inline constexpr size_t kLightTreeWidth = 8;
/// Marks a node's child that is one emitter (the rest of the number is its slot in `members`), not another node.
inline constexpr uint32_t kLeafChild = 0x80000000u;

/// A node of a tree over a large cluster's emitters: up to kLightTreeWidth children, each another node or one
/// emitter, with their bounds in one array per field (as the clusters keep theirs). Lanes past `count` weigh nothing.
struct alignas(32) LightTreeNode {
  using PerChild = std::array<float, kLightTreeWidth>;
  PerChild cx{}, cy{}, cz{};
  PerChild radius{1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};  ///< positive in unused lanes too
  PerChild ax{}, ay{}, az{};
  PerChild cos_spread{-1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f};
  PerChild ex{}, ey{}, ez{};
  PerChild lowest{}, tilt{}, power{};
  std::array<uint32_t, kLightTreeWidth> child{};  ///< a node's index in `tree`, or kLeafChild | a slot in `members`
  uint32_t count = 0;
};
static_assert(kLightTreeWidth == 8, "LightTreeNode's initialisers hold eight lanes");

struct LightClusters {
  /// Per cluster, in fixed arrays so that weighing them all at a point is one loop of known length without branches
  /// (the compiler weighs several at once); entries past `count` weigh nothing (power 0).
  using PerCluster = std::array<float, kMaxLightClusters>;
  size_t count = 0;
  PerCluster cx{}, cy{}, cz{};       ///< centre of the bounding sphere of its triangles
  PerCluster radius{};               ///< that sphere's radius (positive)
  PerCluster ax{}, ay{}, az{};       ///< unit axis of the cone holding its emitters' normals
  PerCluster cos_spread{};           ///< cosine of that cone's half-angle; -1: they face every way
  PerCluster ex{}, ey{}, ez{};       ///< half extents of the box around its triangles (centred on the sphere's centre)
  PerCluster lowest{};               ///< the least of axis . corner over its triangles' corners
  PerCluster tilt{};                 ///< the largest |normal - axis| over its emitters (0: all face along the axis)
  PerCluster power{};                ///< sum of its emitters' power, relative to the brightest cluster's
  std::vector<uint32_t> first;       ///< cluster c holds members[first[c], first[c + 1])
  std::vector<uint32_t> members;     ///< light-table indices, grouped by cluster
  std::vector<double> member_cdf;    ///< per member: running power within its cluster
  std::vector<uint32_t> cluster_of;  ///< per light-table index: its cluster
  std::vector<float> share;          ///< per light-table index: its power / its cluster's power
  /// Clusters of more than kMaxMembersByPower emitters choose one by descending a tree over them, weighing a node's
  /// children at the point (pbrt-v4's light BVH below the cut, eight children a node instead of two).
  std::array<uint32_t, kMaxLightClusters> root;  ///< per cluster: its tree's root, or kNoTreeNode
  std::vector<LightTreeNode> tree;               ///< every cluster's tree nodes
  /// Where each node and each emitter of a tree hangs: node x kLightTreeWidth + lane of its parent's child, or
  /// kNoTreeNode (a root; an emitter outside the trees).
  std::vector<uint32_t> parent;   ///< per tree node
  std::vector<uint32_t> leaf_of;  ///< per light-table index
  LightClusters() { root.fill(kNoTreeNode); }
  size_t size() const { return count; }
};

/// Clusters over the light table's emitters (`records`, table order): top-down, each time splitting the cluster of
/// largest power x radius at the middle of its longest extent (of the triangles' centroids), until there are
/// kMaxLightClusters or every cluster holds one emitter. Emitters of zero power (none when any has power) are
/// weighed by area instead.
LightClusters build_light_clusters(const std::vector<EmitterRecord>& records);

/// Every cluster's weight at one shaded point, as a running sum.
struct LightWeights {
  std::array<float, kMaxLightClusters> weight{};
  std::array<float, kMaxLightClusters> cdf{};
  float total = 0.0f;  ///< 0: no emitter can light the point (or the weights overflowed)
  /// The weights passed a float's range (a point absurdly close to an absurdly small emitter): the caller chooses by
  /// power instead.
  bool overflowed = false;
  Vec3 position{0.0f}, normal{0.0f};  ///< the point weighed (the trees inside large clusters weigh there again)
};

/// Weighs the clusters at `position`, whose light must arrive on the side of the unit `normal`.
void weigh_light_clusters(const LightClusters& clusters, const Vec3& position, const Vec3& normal,
                          LightWeights& weights);

/// One emitter for u in [0, 1): a cluster by weight, then, with u rescaled inside the cluster's share (which keeps
/// the numbers' stratification), one of its emitters by power, or, in a cluster with a tree, by descending it. pmf 0
/// when no cluster (or no node of the tree) weighs anything.
LightChoice choose_weighted_light(const LightClusters& clusters, const LightWeights& weights, float u);

/// Probability that `choose_weighted_light` returns light-table index `index` with these weights.
float weighted_light_pmf(const LightClusters& clusters, const LightWeights& weights, uint32_t index);

}  // namespace lueur
