// Builds Lueur's BVH: a binned-SAH BVH2 of 32-byte nodes over triangles, split down to leaves of one triangle group
// and improved by reinsertion (bvh_reinsert.cpp), then lays the triangles out in leaf order. Which subtrees become
// leaves of the wide tree the queries traverse is the collapse's decision (bvh_wide.cpp). Depends on core (math, ray,
// box) only; must not know about scenes, materials or rendering.

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_reinsert.h"
#include "core/memory_budget.h"

namespace lueur {
namespace {

// 32 bins keep the split quality close to a full sweep while a node costs one pass over its triangles.
constexpr int kBinCount = 32;
/// Triangle groups a leaf of `count` triangles takes: the unit of the SAH's cost (one SIMD test: 1 or 4 triangles
/// cost the same).
inline float group_cost(uint32_t count) { return static_cast<float>(bvh_group_count(count)); }
// From this depth on nodes are split by object median only. Median splits halve the count, so leaves are
// reached within 32 more levels even for 2^32 triangles, which keeps every node shallower than kBvhMaxDepth.
constexpr uint32_t kSahDepthLimit = kBvhMaxDepth - 32;
// Subtrees this small (in triangles) are built in parallel once the top of the tree is done.
constexpr uint32_t kParallelGrain = 4096;
// Above the subtrees, a node's bounds and bins are computed by several threads, each over a slice of at least this
// many triangles (below it, starting the threads costs more than it saves).
constexpr uint32_t kParallelSlice = 32768;

/// Threads for the build: every hardware thread, within reason (asked once: the query reads a file on Linux).
unsigned build_threads() {
  static const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 64u));
  return threads;
}

/// How many slices of at least kParallelSlice triangles a range of `count` is cut into (1: work serially).
unsigned slice_count(uint32_t count) {
  return static_cast<unsigned>(std::min<uint32_t>(build_threads(), std::max(1u, count / kParallelSlice)));
}

/// Cuts [begin, end) into `slices` consecutive slices and calls work(slice, slice_begin, slice_end) for each on
/// its own thread. Callers merge the slices' results in slice order with exact operations (box min / max, integer
/// counts), so the result does not depend on the slicing.
template <class Work>
void for_each_slice(uint32_t begin, uint32_t end, unsigned slices, Work&& work) {
  const uint64_t count = end - begin;
  auto slice_begin = [&](unsigned k) { return begin + static_cast<uint32_t>(count * k / slices); };
  std::vector<std::thread> helpers;
  for (unsigned k = 1; k < slices; ++k) helpers.emplace_back([&, k] { work(k, slice_begin(k), slice_begin(k + 1)); });
  work(0u, begin, slice_begin(1));
  for (std::thread& t : helpers) t.join();
}

/// A box in two SSE registers (x, y, z, unused): the binning's inner loop grows boxes with one min and one max.
struct SseBox {
  __m128 lo = _mm_set1_ps(kInfinity);
  __m128 hi = _mm_set1_ps(-kInfinity);
  void expand(__m128 point_lo, __m128 point_hi) {
    lo = _mm_min_ps(lo, point_lo);
    hi = _mm_max_ps(hi, point_hi);
  }
  void expand(const SseBox& b) { expand(b.lo, b.hi); }
  Box3 box() const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    return Box3{Vec3(l[0], l[1], l[2]), Vec3(h[0], h[1], h[2])};
  }
};

/// A triangle during the build: its box, with its input index in the fourth lane of `lo`. Its centroid (the
/// binned position) is 0.5 lo + 0.5 hi, computed where needed: halving before adding cannot overflow.
struct PrimRef {
  __m128 lo, hi;
  uint32_t index() const { return static_cast<uint32_t>(_mm_extract_ps(lo, 3)); }
  __m128 centroid() const {
    // The index's bits read as a float are a denormal for any index below 2^23; Intel cores take a microcode
    // assist (over 100 cycles) for every multiply that reads one, which made the binning 4x slower there. The
    // fourth lane is cleared first: bit operations take no assist.
    const __m128 xyz = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
    const __m128 half = _mm_set1_ps(0.5f);
    return _mm_add_ps(_mm_mul_ps(half, _mm_and_ps(lo, xyz)), _mm_mul_ps(half, hi));
  }
  float centroid(int axis) const {
    alignas(16) float l[4], h[4];
    _mm_store_ps(l, lo);
    _mm_store_ps(h, hi);
    return 0.5f * l[axis] + 0.5f * h[axis];
  }
};

struct Bin {
  SseBox box;
  uint32_t count = 0;
};
using Bins = std::array<std::array<Bin, kBinCount>, 3>;

struct Split {
  int axis = -1;  ///< -1: no usable split
  int bin = 0;    ///< first bin of the right side
  float cost = kInfinity;
};

/// A node whose box and children are still to be decided, covering prims[begin, end).
struct BuildTask {
  uint32_t node, begin, end, depth;
};

/// Bin of a centroid coordinate. Written so that no input (NaN, infinite offsets) reaches an undefined float-to-int
/// conversion, and used by both the binning and the partition so the two always agree.
int bin_of(float c, float lo, float scale) {
  const float f = (c - lo) * scale;
  if (!(f < static_cast<float>(kBinCount - 1))) return kBinCount - 1;
  return f > 0.0f ? static_cast<int>(f) : 0;
}

/// Surface area of a non-empty box, as Box3::area computes it.
float area_of(const SseBox& b) {
  alignas(16) float e[4];
  _mm_store_ps(e, _mm_sub_ps(b.hi, b.lo));
  return 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
}

/// Adds prims[begin, end) to `bins` along every usable axis.
void bin_prims(const HugePageVector<PrimRef>& prims, uint32_t begin, uint32_t end, const Box3& centroids,
               const std::array<float, 3>& scale, const std::array<bool, 3>& usable, Bins& bins) {
  // bin_of for three axes at once, with the same operations (so the partition, which uses bin_of, agrees):
  // min(f, 31) also maps NaN to 31, max(., 0) maps negatives to 0, then truncation.
  const __m128 lo = _mm_setr_ps(centroids.lo.x, centroids.lo.y, centroids.lo.z, 0.0f);
  const __m128 scales = _mm_setr_ps(scale[0], scale[1], scale[2], 0.0f);
  const __m128 last_bin = _mm_set1_ps(static_cast<float>(kBinCount - 1));
  for (uint32_t i = begin; i < end; ++i) {
    const PrimRef& p = prims[i];
    const __m128 f = _mm_mul_ps(_mm_sub_ps(p.centroid(), lo), scales);
    alignas(16) int32_t bin[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(bin),
                    _mm_cvttps_epi32(_mm_max_ps(_mm_min_ps(f, last_bin), _mm_setzero_ps())));
    for (int axis = 0; axis < 3; ++axis) {
      if (!usable[axis]) continue;
      Bin& b = bins[axis][bin[axis]];
      b.box.expand(p.lo, p.hi);
      ++b.count;
    }
  }
}

/// Best binned-SAH split of prims[begin, end) over all three axes; cost is sum(area * groups) of the two sides.
Split find_sah_split(const HugePageVector<PrimRef>& prims, uint32_t begin, uint32_t end, const Box3& centroids) {
  std::array<float, 3> scale{};
  std::array<bool, 3> usable{};
  for (int axis = 0; axis < 3; ++axis) {
    const float extent = centroids.hi[axis] - centroids.lo[axis];
    scale[axis] = static_cast<float>(kBinCount) / extent;
    // All centroids on one plane, or an extent so small (or large) that binning would be meaningless.
    usable[axis] = extent > 0.0f && std::isfinite(scale[axis]) && scale[axis] > 0.0f;
  }
  Bins bins{};
  if (const unsigned slices = slice_count(end - begin); slices == 1) {
    bin_prims(prims, begin, end, centroids, scale, usable, bins);
  } else {  // the top of the tree: each slice bins into its own array, merged exactly
    std::vector<Bins> slice_bins(slices);
    for_each_slice(begin, end, slices, [&](unsigned k, uint32_t b, uint32_t e) {
      bin_prims(prims, b, e, centroids, scale, usable, slice_bins[k]);
    });
    for (const Bins& slice : slice_bins)
      for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < kBinCount; ++i) {
          bins[axis][i].box.expand(slice[axis][i].box);
          bins[axis][i].count += slice[axis][i].count;
        }
  }

  Split best;
  for (int axis = 0; axis < 3; ++axis) {
    if (!usable[axis]) continue;
    // right_cost[k]: area * count of bins k..end, the right side of a split before bin k.
    std::array<float, kBinCount> right_cost{};
    std::array<uint32_t, kBinCount> right_count{};
    SseBox right;
    uint32_t count = 0;
    for (int k = kBinCount - 1; k > 0; --k) {
      right.expand(bins[axis][k].box);
      count += bins[axis][k].count;
      right_cost[k] = area_of(right) * group_cost(count);
      right_count[k] = count;
    }
    SseBox left;
    count = 0;
    for (int k = 1; k < kBinCount; ++k) {
      left.expand(bins[axis][k - 1].box);
      count += bins[axis][k - 1].count;
      if (count == 0 || right_count[k] == 0) continue;
      const float cost = area_of(left) * group_cost(count) + right_cost[k];
      if (cost < best.cost) best = Split{axis, k, cost};  // NaN or infinite costs (overflowing boxes) never win
    }
  }
  return best;
}

/// Splits prims[begin, end) at the median centroid along the widest centroid axis; both halves are non-empty.
uint32_t median_split(HugePageVector<PrimRef>& prims, uint32_t begin, uint32_t end, const Box3& centroids) {
  const Vec3 extent = centroids.extent();
  int axis = 0;
  if (extent.y > extent[axis]) axis = 1;
  if (extent.z > extent[axis]) axis = 2;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + begin, prims.begin() + mid, prims.begin() + end,
                   [axis](const PrimRef& a, const PrimRef& b) { return a.centroid(axis) < b.centroid(axis); });
  return mid;
}

/// Decides one node: its box, and either a leaf or a split whose two children are appended to `nodes` and
/// pushed on `tasks`.
void build_node(HugePageVector<PrimRef>& prims, HugePageVector<BvhNode>& nodes, const BuildTask& task,
                std::vector<BuildTask>& tasks) {
  SseBox sse_box, sse_centroids;
  auto bound = [&](uint32_t b, uint32_t e, SseBox& slice_box, SseBox& slice_centroids) {
    for (uint32_t i = b; i < e; ++i) {
      slice_box.expand(prims[i].lo, prims[i].hi);
      const __m128 c = prims[i].centroid();
      slice_centroids.expand(c, c);
    }
  };
  if (const unsigned slices = slice_count(task.end - task.begin); slices == 1) {
    bound(task.begin, task.end, sse_box, sse_centroids);
  } else {
    std::vector<std::pair<SseBox, SseBox>> slice_bounds(slices);
    for_each_slice(task.begin, task.end, slices, [&](unsigned k, uint32_t b, uint32_t e) {
      bound(b, e, slice_bounds[k].first, slice_bounds[k].second);
    });
    for (const auto& [slice_box, slice_centroids] : slice_bounds) {
      sse_box.expand(slice_box);
      sse_centroids.expand(slice_centroids);
    }
  }
  const Box3 box = sse_box.box(), centroids = sse_centroids.box();
  const uint32_t count = task.end - task.begin;

  // Nodes of at most kBvhWidth triangles (one group test) are leaves; larger ones are always split, at the best
  // binned-SAH split, so that the collapse can open any subtree of more than one group to fill a wide node.
  bool split = false;
  uint32_t mid = 0;
  if (count > kBvhWidth) {
    if (task.depth < kSahDepthLimit) {
      const Split s = find_sah_split(prims, task.begin, task.end, centroids);
      if (s.axis >= 0) {
        const int axis = s.axis;
        const float lo = centroids.lo[axis];
        const float scale = static_cast<float>(kBinCount) / (centroids.hi[axis] - lo);
        const auto it = std::partition(prims.begin() + task.begin, prims.begin() + task.end,
                                       [&](const PrimRef& p) { return bin_of(p.centroid(axis), lo, scale) < s.bin; });
        mid = static_cast<uint32_t>(it - prims.begin());
        // The bin counts promise two non-empty sides; should rounding ever disagree, fall back to the median.
        split = mid != task.begin && mid != task.end;
      }
    }
    // All centroids coincide, no SAH split is finite, or the depth budget for SAH is spent.
    if (!split) {
      mid = median_split(prims, task.begin, task.end, centroids);
      split = true;
    }
  }

  BvhNode& node = nodes[task.node];
  node.lo = box.lo;
  node.hi = box.hi;
  if (!split) {
    node.first = task.begin;
    node.count = count;
    return;
  }
  const auto left = static_cast<uint32_t>(nodes.size());
  node.first = left;
  node.count = 0;
  nodes.push_back(BvhNode{});  // may invalidate `node`, which is not used past this point
  nodes.push_back(BvhNode{});
  // Left last so it is built next: a node's subtree then tends to sit close to it in memory.
  tasks.push_back({left + 1, mid, task.end, task.depth + 1});
  tasks.push_back({left, task.begin, mid, task.depth + 1});
}

}  // namespace

BvhTriangle make_bvh_triangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t id) {
  BvhTriangle tri{a, b - a, c - a, id};
  if (glm::cross(tri.e1, tri.e2) == Vec3(0.0f)) {
    tri.e1 = Vec3(0.0f);
    tri.e2 = Vec3(0.0f);
  }
  return tri;
}

namespace {

/// The build over triangles read by `corners(i, a, b, c)`; `keep_record`: see build_bvh(IndexedTriangles).
template <typename Corners>
Bvh build(size_t input_count, const Corners& corners, bool keep_record, const BuildProgress& progress) {
  // Reported at the end of each step, by the rough share of a large build's time up to there: the boxes, the top,
  // the subtrees (one by one), reinsertion and the collapse.
  const auto report = [&](double done) {
    if (progress) progress(done);
  };
  Bvh bvh;
  if (input_count >= kNoHit) throw std::length_error("build_bvh: too many triangles for 32-bit indices");

  // Only the kept triangles' boxes are held during the build; their prepared form (edges) is made once, in leaf
  // order, at the end, rather than kept in input order and copied (a 2M-triangle scene would write 96 MB twice).
  // Made on every thread, each slice from its own start, then closed up in order (where triangles were left out).
  HugePageVector<PrimRef> prims(input_count);
  const unsigned slices = slice_count(static_cast<uint32_t>(input_count));
  std::vector<uint32_t> kept(slices, 0);
  for_each_slice(0, static_cast<uint32_t>(input_count), slices, [&](unsigned slice, uint32_t begin, uint32_t end) {
    uint32_t out = begin;
    for (uint32_t i = begin; i < end; ++i) {
      Vec3 a, b, c;
      corners(i, a, b, c);
      if (!is_finite(a) || !is_finite(b) || !is_finite(c)) continue;
      const BvhTriangle tri = make_bvh_triangle(a, b, c, i);
      // Edges that overflow could never be hit (non-finite determinant) and would give infinite boxes.
      if (!is_finite(tri.e1) || !is_finite(tri.e2)) continue;
      // Nor can a zero-area triangle (make_bvh_triangle gave it zero edges): it would only fill leaf lanes. Real
      // meshes have many (the conference room: 16% of its triangles).
      if (tri.e1 == Vec3(0.0f) && tri.e2 == Vec3(0.0f)) continue;
      // Hits are clamped into bvh_triangle_box, so node boxes must contain it exactly; the input vertices too
      // (v0 + e1 can round away from b).
      Box3 box = bvh_triangle_box(tri);
      box.expand(a);
      box.expand(b);
      box.expand(c);
      float index_bits;
      std::memcpy(&index_bits, &i, sizeof index_bits);
      prims[out++] = PrimRef{_mm_setr_ps(box.lo.x, box.lo.y, box.lo.z, index_bits),
                             _mm_setr_ps(box.hi.x, box.hi.y, box.hi.z, 0.0f)};
    }
    kept[slice] = out - begin;
  });
  size_t filled = 0;
  for (unsigned slice = 0; slice < slices; ++slice) {
    const size_t begin = input_count * slice / slices;
    if (filled != begin) std::copy(prims.begin() + begin, prims.begin() + begin + kept[slice], prims.begin() + filled);
    filled += kept[slice];
  }
  prims.resize(filled);
  report(0.15);
  if (prims.empty()) return bvh;

  const auto prim_count = static_cast<uint32_t>(prims.size());
  bvh.nodes.reserve(2 * static_cast<size_t>(prim_count) - 1);
  bvh.nodes.push_back(BvhNode{});
  // The top of the tree is built here; subtrees of at most kParallelGrain triangles (or a 32nd of the scene) are
  // set aside and built independently on all hardware threads, each into its own node array, then appended in a
  // fixed order: the tree is the same whatever the number of threads.
  const uint32_t grain = std::max(kParallelGrain, prim_count / 32);
  std::vector<BuildTask> deferred;
  std::vector<BuildTask> tasks{{0, 0, prim_count, 0}};
  while (!tasks.empty()) {
    const BuildTask task = tasks.back();
    tasks.pop_back();
    if (task.end - task.begin <= grain && task.node != 0) {
      deferred.push_back(task);
      continue;
    }
    build_node(prims, bvh.nodes, task, tasks);
  }
  report(0.3);
  std::vector<HugePageVector<BvhNode>> subtrees(deferred.size());
  std::atomic<size_t> next{0}, finished{0};
  auto worker = [&](bool reports) {
    for (size_t i; (i = next.fetch_add(1)) < deferred.size();) {
      HugePageVector<BvhNode>& local = subtrees[i];
      local.push_back(BvhNode{});
      std::vector<BuildTask> stack{{0, deferred[i].begin, deferred[i].end, deferred[i].depth}};
      while (!stack.empty()) {
        const BuildTask task = stack.back();
        stack.pop_back();
        build_node(prims, local, task, stack);
      }
      const size_t done = finished.fetch_add(1) + 1;
      if (reports) report(0.3 + 0.35 * static_cast<double>(done) / static_cast<double>(deferred.size()));
    }
  };
  const unsigned threads = build_threads();
  std::vector<std::thread> helpers;
  for (unsigned t = 1; t < threads && t < deferred.size(); ++t) helpers.emplace_back(worker, false);
  worker(true);  // the calling thread reports, as progress callers expect
  for (std::thread& t : helpers) t.join();
  // Local node 0 becomes the deferred node itself; local node k > 0 goes to base + k - 1.
  for (size_t i = 0; i < deferred.size(); ++i) {
    const HugePageVector<BvhNode>& local = subtrees[i];
    const auto base = static_cast<uint32_t>(bvh.nodes.size());
    auto place = [&](BvhNode n) {
      if (n.count == 0) n.first = base + n.first - 1;
      return n;
    };
    bvh.nodes[deferred[i].node] = place(local[0]);
    for (size_t k = 1; k < local.size(); ++k) bvh.nodes.push_back(place(local[k]));
    free_array(subtrees[i]);  // a large scene's nodes are held twice only one subtree at a time
  }

  // A few top-down decisions of the binned build leave subtrees where they inflate every ancestor's box; moving
  // them cuts the conference room's traversal cost by a quarter (bvh_reinsert.h). The triangles are then laid out
  // in the new leaf order, once, in their prepared form.
  // Only the prims' indices are needed from here on: the boxes go before reinsertion makes its own tree.
  std::vector<uint32_t> ids(prims.size());
  for (size_t k = 0; k < prims.size(); ++k) ids[k] = prims[k].index();
  free_array(prims);
  std::vector<LeafRange> ranges;
  reinsert_subtrees(bvh.nodes, ranges);
  report(0.7);
  std::vector<uint32_t> order;  // the input index at each place of the new leaf order
  order.reserve(ids.size());
  for (const LeafRange& range : ranges)
    for (uint32_t k = 0; k < range.count; ++k) order.push_back(ids[range.first + k]);
  free_array(ids);
  free_array(ranges);
  const auto triangle_at = [&](uint32_t place) {
    Vec3 a, b, c;
    corners(order[place], a, b, c);
    return make_bvh_triangle(a, b, c, order[place]);
  };
  if (keep_record) {
    bvh.triangles.reserve(order.size());
    for (uint32_t place = 0; place < order.size(); ++place) bvh.triangles.push_back(triangle_at(place));
    build_wide_bvh(bvh);
  } else {
    build_wide_bvh(bvh, triangle_at);  // which frees the BVH2 as soon as it can
  }
  report(1.0);
  return bvh;
}

}  // namespace

Bvh build_bvh(const std::vector<Vec3>& corners) {
  return build(corners.size() / 3,
               [&](size_t i, Vec3& a, Vec3& b, Vec3& c) {
                 a = corners[3 * i];
                 b = corners[3 * i + 1];
                 c = corners[3 * i + 2];
               },
               true, {});
}

Bvh build_bvh(const IndexedTriangles& triangles, bool keep_record, const BuildProgress& progress) {
  return build(
      triangles.count,
      [&](size_t i, Vec3& a, Vec3& b, Vec3& c) {
        const uint32_t* v = triangles.indices + i * triangles.stride;
        a = triangles.positions[v[0]];
        b = triangles.positions[v[1]];
        c = triangles.positions[v[2]];
      },
      keep_record, progress);
}

}  // namespace lueur
