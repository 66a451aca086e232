// Lueur's own bounding volume hierarchy: a binned-SAH BVH2 over triangles, improved by reinsertion, with
// closest-hit and any-hit queries.
// Depends on core only; knows triangles by their three vertex positions.
#pragma once

#include <functional>
#include <vector>

#include "core/huge_pages.h"
#include "core/ray.h"

namespace lueur {

/// Largest number of triangles in one leaf of the wide tree (the BVH2's leaves hold at most kBvhWidth).
inline constexpr uint32_t kBvhMaxLeafSize = 8;
/// Bound on the depth of any node (the root has depth 0); traversal stacks of this many entries cannot overflow.
inline constexpr uint32_t kBvhMaxDepth = 128;

/// 32 bytes: the box, and either the index of the first of two adjacent children (count == 0), which sit at higher
/// indices than their parent, or the first triangle of a leaf (count > 0) in the BVH's own triangle order. The
/// triangles under any node are a contiguous range of that order.
struct BvhNode {
  Vec3 lo;
  uint32_t first;
  Vec3 hi;
  uint32_t count;
};

/// A triangle prepared for intersection: v0 and the two edges, stored in BVH order.
struct BvhTriangle {
  Vec3 v0, e1, e2;
  uint32_t id;  ///< index of the triangle in the input (scene) order
};

/// Children per node of the traversal form, and triangles per leaf group: one SSE register of floats.
inline constexpr uint32_t kBvhWidth = 4;
static_assert(kBvhMaxLeafSize >= kBvhWidth, "a BVH2 leaf must fit in a leaf of the wide tree");

/// Triangle groups (tested together) that `count` triangles take.
inline constexpr uint32_t bvh_group_count(uint32_t count) { return (count + kBvhWidth - 1) / kBvhWidth; }

/// A node of the traversal form: the boxes of up to four children structure-of-arrays (lo[axis][child]), so that
/// one SSE slab test covers all four. An unused slot has NaN bounds, which no ray can enter.
struct alignas(64) BvhWideNode {
  float lo[3][kBvhWidth];
  float hi[3][kBvhWidth];
  uint32_t child[kBvhWidth];  ///< inner child: its node index; leaf: its first triangle group
  uint32_t count[kBvhWidth];  ///< 0: inner child (or unused slot); n > 0: a leaf of n triangle groups
};

/// The same with eight children, traversed with AVX2 when the CPU has it (bvh_avx2_enabled).
inline constexpr uint32_t kBvhWidth8 = 8;
struct alignas(64) BvhWideNode8 {
  float lo[3][kBvhWidth8];
  float hi[3][kBvhWidth8];
  uint32_t child[kBvhWidth8];
  uint32_t count[kBvhWidth8];
};

/// Four triangles structure-of-arrays (v0[axis][lane], ...), tested together. Unused lanes have zero edges (never
/// hit) and id kNoHit.
struct alignas(16) BvhTriangleGroup {
  float v0[3][kBvhWidth];
  float e1[3][kBvhWidth];
  float e2[3][kBvhWidth];
  uint32_t id[kBvhWidth];
};

struct Bvh {
  HugePageVector<BvhNode> nodes;          ///< the binned-SAH BVH2 after reinsertion; nodes[0] is the root
  HugePageVector<BvhTriangle> triangles;  ///< reordered once after the build so leaves read them directly
  /// What the queries traverse: the BVH2 collapsed into a 4-wide tree (wide_nodes[0] is the root), or an 8-wide one
  /// (wide8_nodes) when the CPU has AVX2, over leaves of triangle groups. The BVH2 above is kept as the build's
  /// record (tests check its invariants).
  HugePageVector<BvhWideNode> wide_nodes;
  HugePageVector<BvhWideNode8> wide8_nodes;
  HugePageVector<BvhTriangleGroup> groups;
  bool empty() const { return groups.empty(); }
  /// Bytes the queries read: the wide nodes and the triangle groups.
  size_t traversal_bytes() const {
    return wide_nodes.size() * sizeof(BvhWideNode) + wide8_nodes.size() * sizeof(BvhWideNode8) +
           groups.size() * sizeof(BvhTriangleGroup);
  }
  /// Bytes the tree keeps in memory while rays are traced: what the queries read, and the BVH2 and its triangles
  /// kept beside them as the build's record.
  size_t resident_bytes() const {
    return traversal_bytes() + nodes.size() * sizeof(BvhNode) + triangles.size() * sizeof(BvhTriangle);
  }
};

/// Collapses `bvh.nodes` into `bvh.wide8_nodes` (when bvh_avx2_enabled) or `bvh.wide_nodes`, and `bvh.groups`
/// (called by build_bvh).
void build_wide_bvh(Bvh& bvh);

/// The same, reading the triangle at each place of the BVH's triangle order from `triangle_at` rather than from
/// `bvh.triangles` (which a lean build never makes), and freeing `bvh.nodes` before the groups are packed.
void build_wide_bvh(Bvh& bvh, const std::function<BvhTriangle(uint32_t place)>& triangle_at);

/// Whether builds make the 8-wide AVX2 tree: the CPU has AVX2 and the environment does not say LUEUR_BVH_ISA=sse
/// (which tests use to check the 4-wide SSE kernels on any machine).
bool bvh_avx2_enabled();

/// Prepares triangle (a, b, c) for intersection: v0 = a, e1 = b - a, e2 = c - a. A zero-area triangle (edge cross
/// product exactly zero: repeated or collinear vertices) gets zero edges, so its determinant is exactly 0 for every
/// ray and it can never be hit, whatever the rounding of the determinant would otherwise have been.
BvhTriangle make_bvh_triangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t id);

/// The box that bounds where a hit on `tri` may lie: its vertices as the intersection test sees them (v0, v0 + e1,
/// v0 + e2), widened by a few ulps. Every node box of a BVH contains the boxes of its triangles exactly.
Box3 bvh_triangle_box(const BvhTriangle& tri);

/// Builds the hierarchy over triangles given as three vertex positions each (`corners.size() == 3 * count`).
/// Triangles that can never be hit are left out: zero-area ones (see make_bvh_triangle) and non-finite ones (a
/// non-finite vertex, or edges that overflow). The BVH2 and its triangles are kept beside the traversal form.
Bvh build_bvh(const std::vector<Vec3>& corners);

/// Triangles as indices into shared positions: triangle i's corners are positions[indices[i * stride + k]] for
/// k = 0, 1, 2 (stride counted in indices: a Scene's triangles start with their three vertex indices).
struct IndexedTriangles {
  const Vec3* positions = nullptr;
  const uint32_t* indices = nullptr;
  size_t stride = 3;
  size_t count = 0;
};

/// Told the share of a build done (0 to 1), from the thread that called it.
using BuildProgress = std::function<void(double done)>;

/// The same tree over indexed triangles, read where they are (no copy of their corners). With `keep_record` false
/// the BVH2 and its triangles are dropped once the traversal form is made, leaving only what queries read: about
/// half the memory of a large scene's tree.
Bvh build_bvh(const IndexedTriangles& triangles, bool keep_record = false, const BuildProgress& progress = {});

/// Closest intersection with t in (ray.tmin, ray.tmax). Ties in t go to the lowest input index, so the answer
/// does not depend on the traversal order.
Hit intersect_closest(const Bvh& bvh, const Ray& ray);

/// True if any triangle is hit with t in (ray.tmin, ray.tmax): the shadow-ray query.
bool intersect_any(const Bvh& bvh, const Ray& ray);

/// Which hits count, for surfaces with holes (alpha cutouts): a hit on triangle `id` (input index) at barycentrics
/// (u, v) of its corners b and c counts only if `accepts` says so. Queries taking a filter skip the hits it refuses
/// and go on to what lies behind them.
struct HitFilter {
  bool (*accepts)(const void* context, uint32_t id, float u, float v) = nullptr;
  const void* context = nullptr;
  bool operator()(uint32_t id, float u, float v) const { return accepts(context, id, u, v); }
};

/// intersect_closest and intersect_any counting only the hits `filter` accepts (whose `accepts` must be set).
Hit intersect_closest(const Bvh& bvh, const Ray& ray, const HitFilter& filter);
bool intersect_any(const Bvh& bvh, const Ray& ray, const HitFilter& filter);

/// What queries did, summed over many: judging a tree by its work per ray is steadier than by timings
/// (lueur-bench's traversal section). The counted queries are a separate instantiation of the traversals, so the
/// queries above stay as they were (callgrind: 1 instruction more per ray, a jump).
struct TraversalCounts {
  uint64_t queries = 0;
  uint64_t nodes = 0;   ///< wide nodes whose child boxes were tested
  uint64_t leaves = 0;  ///< leaves whose triangles were tested
  uint64_t groups = 0;  ///< triangle groups in those leaves
};

/// intersect_closest and intersect_any, adding what they did to `counts`.
Hit intersect_closest(const Bvh& bvh, const Ray& ray, TraversalCounts& counts);
bool intersect_any(const Bvh& bvh, const Ray& ray, TraversalCounts& counts);

/// Ray-triangle test shared by the BVH and the brute-force reference; on a hit inside (tmin, tmax) writes t, u, v.
/// Möller–Trumbore, where a determinant below the smallest normal float (zero included) or non-finite is never a
/// hit, and whose t must lie inside (tmin, tmax); that t is then clamped to the span of the ray inside
/// bvh_triangle_box (no span: no hit) and must still lie inside (tmin, tmax). Near-degenerate triangles and grazing
/// rays can give a Möller–Trumbore t far from the triangle; the clamp keeps every hit inside the node boxes above
/// it, so the BVH queries report exactly what a loop over all triangles with this function reports, bit for bit.
bool intersect_triangle(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t, float& u, float& v);

}  // namespace lueur
