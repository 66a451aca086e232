// Clusters of emitters with bounds, weighed per shaded point (the `importance` light choice).
#include "lights/light_clusters.h"

#include <algorithm>
#include <bit>
#include <numeric>

#include "lights/light_bounds.h"
#include "lights/light_lanes.h"

namespace lueur {
namespace {

struct Box {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  void grow(const Vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  Vec3 centre() const { return 0.5f * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
};

Vec3 centroid(const EmitterRecord& e) { return (e.p0 + e.p1 + e.p2) * (1.0f / 3.0f); }

/// A range of `order` (light-table indices) being clustered, with what the split choice needs.
struct Range {
  size_t begin = 0, end = 0;
  double power = 0.0;
  float radius = 0.0f;
};

/// The weight each emitter is chosen by within its cluster: its power, or its area when no emitter has power.
std::vector<double> emitter_weights(const std::vector<EmitterRecord>& records) {
  std::vector<double> weights(records.size());
  double total = 0.0;
  for (size_t i = 0; i < records.size(); ++i) total += weights[i] = emitter_power(records[i]);
  if (!(total > 0.0))
    for (size_t i = 0; i < records.size(); ++i) weights[i] = records[i].area;
  return weights;
}

Range measure(const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
              const std::vector<uint32_t>& order, size_t begin, size_t end) {
  Range r{begin, end, 0.0, 0.0f};
  Box box;
  for (size_t k = begin; k < end; ++k) {
    const EmitterRecord& e = records[order[k]];
    box.grow(e.p0), box.grow(e.p1), box.grow(e.p2);
    r.power += weights[order[k]];
  }
  r.radius = 0.5f * glm::length(box.extent());
  return r;
}

/// Splits [begin, end) of `order` in two non-empty parts: at the middle of the centroids' longest extent, or, where
/// that leaves one side empty (centroids bunched at one end) or `median_only` says so, at the median. Returns the
/// first index of the second.
size_t split(const std::vector<EmitterRecord>& records, std::vector<uint32_t>& order, size_t begin, size_t end,
             bool median_only = false) {
  Box box;
  for (size_t k = begin; k < end; ++k) box.grow(centroid(records[order[k]]));
  const Vec3 extent = box.extent();
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const float middle = box.centre()[axis];
  const auto first = order.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = order.begin() + static_cast<std::ptrdiff_t>(end);
  if (!median_only) {
    // stable_partition: the same clusters whatever the standard library's unstable algorithms do.
    const auto cut =
        std::stable_partition(first, last, [&](uint32_t i) { return centroid(records[i])[axis] < middle; });
    if (cut != first && cut != last) return static_cast<size_t>(cut - order.begin());
  }
  // The sort's order is total (ties by index), so whatever the partition left, the median is the same.
  const auto mid = first + static_cast<std::ptrdiff_t>((end - begin) / 2);
  std::stable_sort(first, last, [&](uint32_t a, uint32_t b) {
    const float ca = centroid(records[a])[axis], cb = centroid(records[b])[axis];
    return ca < cb || (ca == cb && a < b);
  });
  return static_cast<size_t>(mid - order.begin());
}

/// Past this depth a tree splits at the median only, so that its depth stays logarithmic whatever the emitters' layout.
constexpr int kMaxMiddleSplitDepth = 40;

/// The largest double below 1: a rescaled number stays in [0, 1).
constexpr double kOneBelowOne = 1.0 - 0x1p-53;

/// Sets lane `lane` of a node's (or the clusters') bound arrays.
template <typename Arrays>
void set_lane(Arrays& a, size_t lane, const LightBounds& b) {
  a.cx[lane] = b.cx, a.cy[lane] = b.cy, a.cz[lane] = b.cz, a.radius[lane] = b.radius;
  a.ax[lane] = b.ax, a.ay[lane] = b.ay, a.az[lane] = b.az, a.cos_spread[lane] = b.cos_spread;
  a.ex[lane] = b.ex, a.ey[lane] = b.ey, a.ez[lane] = b.ez;
  a.lowest[lane] = b.lowest, a.tilt[lane] = b.tilt, a.power[lane] = b.power;
}

/// Fills tree node `node` over `order[begin, end)` (at least two emitters) and, below it, the nodes of its subtree:
/// the range halved three times over (a part of one emitter stays whole), each part a child, down to one emitter per
/// child. Such a child holds its emitter's slot in `members`: `slot_base` plus its place in the cluster.
void build_tree(LightClusters& c, const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
                std::vector<uint32_t>& order, size_t cluster_begin, uint32_t slot_base, double power_scale,
                uint32_t node, size_t begin, size_t end, int depth) {
  std::vector<std::pair<size_t, size_t>> parts = {{begin, end}};
  for (int round = 0; (size_t{2} << round) <= kLightTreeWidth; ++round) {
    std::vector<std::pair<size_t, size_t>> halves;
    for (const auto& [b, e] : parts) {
      if (e - b == 1) {
        halves.emplace_back(b, e);
        continue;
      }
      const size_t cut = split(records, order, b, e, depth + round >= kMaxMiddleSplitDepth);
      halves.emplace_back(b, cut);
      halves.emplace_back(cut, e);
    }
    parts = std::move(halves);
  }
  // Every part's bounds first: building a child's subtree reorders its part (not its bounds, but its sums' order).
  for (size_t lane = 0; lane < parts.size(); ++lane) {
    const auto [b, e] = parts[lane];
    set_lane(c.tree[node], lane, bound_emitters(records, weights, order.data() + b, e - b, power_scale));
  }
  c.tree[node].count = static_cast<uint32_t>(parts.size());
  for (size_t lane = 0; lane < parts.size(); ++lane) {
    const auto [b, e] = parts[lane];
    const auto place = static_cast<uint32_t>(node * kLightTreeWidth + lane);
    if (e - b == 1) {
      c.tree[node].child[lane] = kLeafChild | (slot_base + static_cast<uint32_t>(b - cluster_begin));
      c.leaf_of[order[b]] = place;
      continue;
    }
    const auto child = static_cast<uint32_t>(c.tree.size());
    c.tree.emplace_back();
    c.parent.push_back(place);
    c.tree[node].child[lane] = child;
    build_tree(c, records, weights, order, cluster_begin, slot_base, power_scale, child, b, e,
               depth + static_cast<int>(std::countr_zero(kLightTreeWidth)));
  }
}

/// Appends the cluster holding `order[r.begin, r.end)`: its bounds and members, and, when it holds more than
/// kMaxMembersByPower emitters, the tree that chooses among them (which reorders the range).
void add_cluster(LightClusters& c, const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
                 std::vector<uint32_t>& order, const Range& r, double power_scale) {
  const size_t cluster = c.count++;
  set_lane(c, cluster, bound_emitters(records, weights, order.data() + r.begin, r.end - r.begin, power_scale));
  const auto slot_base = static_cast<uint32_t>(c.members.size());
  c.first.push_back(slot_base);
  if (r.end - r.begin > kMaxMembersByPower) {
    const auto root = static_cast<uint32_t>(c.tree.size());
    c.root[cluster] = root;
    c.tree.emplace_back();
    c.parent.push_back(kNoTreeNode);
    build_tree(c, records, weights, order, r.begin, slot_base, power_scale, root, r.begin, r.end, 0);
  }
  double running = 0.0;
  for (size_t k = r.begin; k < r.end; ++k) {
    const uint32_t i = order[k];
    c.members.push_back(i);
    running += weights[i];
    c.member_cdf.push_back(running);
    c.cluster_of[i] = static_cast<uint32_t>(cluster);
    c.share[i] = static_cast<float>(weights[i] / r.power);
  }
}

}  // namespace

LightClusters build_light_clusters(const std::vector<EmitterRecord>& records) {
  LightClusters clusters;
  clusters.radius.fill(1.0f);  // entries past the count: finite arithmetic, weight 0
  clusters.cos_spread.fill(-1.0f);
  if (records.empty()) return clusters;
  const std::vector<double> weights = emitter_weights(records);
  std::vector<uint32_t> order(records.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<Range> ranges = {measure(records, weights, order, 0, order.size())};
  while (ranges.size() < kMaxLightClusters) {
    // The cluster whose bounds say least about its emitters: the most power spread over the largest sphere.
    size_t widest = ranges.size();
    double widest_score = -1.0;
    for (size_t k = 0; k < ranges.size(); ++k) {
      const double score = ranges[k].power * static_cast<double>(ranges[k].radius);
      if (ranges[k].end - ranges[k].begin > 1 && score > widest_score) widest = k, widest_score = score;
    }
    if (widest == ranges.size()) break;  // every cluster is one emitter
    const Range r = ranges[widest];
    const size_t cut = split(records, order, r.begin, r.end);
    ranges[widest] = measure(records, weights, order, r.begin, cut);
    ranges.insert(ranges.begin() + static_cast<std::ptrdiff_t>(widest) + 1,
                  measure(records, weights, order, cut, r.end));
  }
  clusters.cluster_of.resize(records.size());
  clusters.leaf_of.assign(records.size(), kNoTreeNode);
  clusters.share.resize(records.size());
  // Powers relative to the brightest cluster's: a scene of absurd Ke stays within a float.
  double brightest = 0.0;
  for (const Range& r : ranges) brightest = std::max(brightest, r.power);
  for (const Range& r : ranges) add_cluster(clusters, records, weights, order, r, 1.0 / brightest);
  clusters.first.push_back(static_cast<uint32_t>(clusters.members.size()));
  return clusters;
}

template <size_t kLanes>
void weigh_clusters(const LightClusters& c, const ImportanceQuery& q, LightWeights& weights) {
  LightClusters::PerCluster out{};
  weigh_lanes<kLanes>(c, q, out.data());
  weights.weight = out;
  float running = 0.0f;
  for (size_t k = 0; k < kLanes; ++k) weights.cdf[k] = running += weights.weight[k];
  weights.overflowed = !std::isfinite(running);
  weights.total = weights.overflowed ? 0.0f : running;
}

void weigh_light_clusters(const LightClusters& c, const Vec3& position, const Vec3& normal, LightWeights& weights) {
  // A scene with one or two emitters weighs four lanes, not sixteen.
  static_assert(kMaxLightClusters == 16);
  weights.position = position, weights.normal = normal;
  // Copies, so that the compiler need not fear that writing the weights changes them.
  const ImportanceQuery q(position, normal);
  if (c.count <= 4) return weigh_clusters<4>(c, q, weights);
  if (c.count <= 8) return weigh_clusters<8>(c, q, weights);
  weigh_clusters<16>(c, q, weights);
}

void weigh_tree_children_baseline(const LightTreeNode& node, const ImportanceQuery& q, float* out) {
  weigh_lanes<kLightTreeWidth>(node, q, out);
}

void weigh_tree_children(const LightTreeNode& node, const ImportanceQuery& q, float* out) {
  // Decided once: the AVX2 build weighs a node's eight children in one pass (1.18x the frames of an L1 render under
  // a sphere lamp of 960 triangles), with the same bits.
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2)
    weigh_tree_children_avx2(node, q, out);
  else
    weigh_tree_children_baseline(node, q, out);
}

namespace {

/// A tree node's children weighed at the point, as running sums (the last is the total); their powers where the
/// weights pass a float's range. False when none weighs anything: no emitter below the node can light the point.
bool weigh_children(const LightTreeNode& n, const ImportanceQuery& q, std::array<float, kLightTreeWidth>& cdf) {
  std::array<float, kLightTreeWidth> weight;
  weigh_tree_children(n, q, weight.data());
  float running = 0.0f;
  for (size_t k = 0; k < kLightTreeWidth; ++k) cdf[k] = running += weight[k];
  if (!std::isfinite(running)) {
    running = 0.0f;
    for (size_t k = 0; k < kLightTreeWidth; ++k) cdf[k] = running += n.power[k];
  }
  return running > 0.0f;
}

/// The entry of running weights `cdf` (`count` in use of an array of kWidth) that x falls in: the first whose running
/// weight exceeds x, the last if none does. Found without a branch on x: the running weights never fall, so the
/// entries before it are exactly those at or below x. Branches on a random x missed about once per choice, which
/// made the clusters' choice 5% of a frame.
template <size_t kWidth, typename Number>
size_t entry_of(const float* cdf, size_t count, Number x) {
  size_t k = 0;
  for (size_t i = 0; i + 1 < kWidth; ++i) k += static_cast<size_t>((i + 1 < count) & !(cdf[i] > x));
  return k;
}

/// A node's child `lane` as its running weights `cdf` give it: the weight below it and its own. The descent and
/// weighted_light_pmf both take a child's share from here, so that their products agree to the bit.
struct LaneShare {
  float below, weight;
};
LaneShare share_of(const std::array<float, kLightTreeWidth>& cdf, size_t lane) {
  const float below = lane > 0 ? cdf[lane - 1] : 0.0f;
  return {below, cdf[lane] - below};
}

/// The member of cluster k (which has a tree) for v in [0, 1]: down from the root, a child by its share of its
/// node's children's weights at the point, with v rescaled inside that share.
LightChoice choose_in_tree(const LightClusters& c, const LightWeights& weights, size_t k, double v) {
  const ImportanceQuery q(weights.position, weights.normal);
  float pmf = weights.weight[k] / weights.total;
  uint32_t node = c.root[k];
  std::array<float, kLightTreeWidth> cdf;
  for (;;) {
    const LightTreeNode& n = c.tree[node];
    if (!weigh_children(n, q, cdf)) return LightChoice{};  // no child can light the point: no shadow ray
    const float total = cdf[kLightTreeWidth - 1];
    size_t lane = entry_of<kLightTreeWidth>(cdf.data(), n.count, v * total);
    while (lane > 0 && !(cdf[lane] > cdf[lane - 1])) --lane;  // x rounded up to the total: the last that weighs
    const auto [below, weight] = share_of(cdf, lane);
    pmf *= weight / total;
    v = std::clamp((v * total - below) / weight, 0.0, kOneBelowOne);
    if (n.child[lane] & kLeafChild) return LightChoice{c.members[n.child[lane] & ~kLeafChild], pmf};
    node = n.child[lane];
  }
}

}  // namespace

LightChoice choose_weighted_light(const LightClusters& c, const LightWeights& weights, float u) {
  LightChoice choice;
  if (!(weights.total > 0.0f)) return choice;
  const size_t n = c.size();
  const float x = u * weights.total;
  size_t k = entry_of<kMaxLightClusters>(weights.cdf.data(), n, x);
  while (!(weights.weight[k] > 0.0f)) --k;  // x rounded up to the total: the last cluster that weighs anything
  const float below = weights.cdf[k] - weights.weight[k];
  const double v = std::clamp(static_cast<double>((x - below) / weights.weight[k]), 0.0, 1.0);
  if (c.root[k] != kNoTreeNode) return choose_in_tree(c, weights, k, v);
  // The member: the first whose running power within the cluster exceeds v x the cluster's power (std::upper_bound,
  // but halving the range with a conditional move instead of a branch).
  const double* base = c.member_cdf.data() + c.first[k];
  size_t length = c.first[k + 1] - c.first[k];
  const double target = v * base[length - 1];
  const double* const last = base + length - 1;
  while (length > 1) {
    const size_t half = length / 2;
    base = base[half] <= target ? base + half : base;
    length -= half;
  }
  const double* at = std::min(base + (*base <= target ? 1 : 0), last);
  choice.index = c.members[static_cast<size_t>(at - c.member_cdf.data())];
  choice.pmf = weights.weight[k] / weights.total * c.share[choice.index];
  return choice;
}

float weighted_light_pmf(const LightClusters& c, const LightWeights& weights, uint32_t index) {
  if (!(weights.total > 0.0f)) return 0.0f;
  const uint32_t k = c.cluster_of[index];
  if (c.root[k] == kNoTreeNode) return weights.weight[k] / weights.total * c.share[index];
  // The path from the root to the emitter, then the same products as choose_in_tree, in the same order.
  std::vector<uint32_t> path;  // node x kLightTreeWidth + lane, from the emitter up
  for (uint32_t place = c.leaf_of[index]; place != kNoTreeNode; place = c.parent[place / kLightTreeWidth])
    path.push_back(place);
  const ImportanceQuery q(weights.position, weights.normal);
  float pmf = weights.weight[k] / weights.total;
  std::array<float, kLightTreeWidth> cdf;
  for (size_t i = path.size(); i-- > 0;) {
    if (!weigh_children(c.tree[path[i] / kLightTreeWidth], q, cdf)) return 0.0f;
    pmf *= share_of(cdf, path[i] % kLightTreeWidth).weight / cdf[kLightTreeWidth - 1];
  }
  return pmf;
}

}  // namespace lueur
