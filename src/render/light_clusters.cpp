// Clusters of emitters with bounds, weighed per shaded point (the `importance` light choice).
#include "render/light_clusters.h"

#include <algorithm>
#include <numeric>

namespace lueur {
namespace {

struct Box {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  void grow(const Vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  Vec3 centre() const { return 0.5f * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
};

/// Below this cosine at the surface (relative to the distance to the farthest corner), a cluster counts as under the
/// horizon.
constexpr float kHorizonTolerance = 1e-5f;

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
/// that leaves one side empty (centroids bunched at one end), at the median. Returns the first index of the second.
size_t split(const std::vector<EmitterRecord>& records, std::vector<uint32_t>& order, size_t begin, size_t end) {
  Box box;
  for (size_t k = begin; k < end; ++k) box.grow(centroid(records[order[k]]));
  const Vec3 extent = box.extent();
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const float middle = box.centre()[axis];
  const auto first = order.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = order.begin() + static_cast<std::ptrdiff_t>(end);
  // stable_partition: the same clusters whatever the standard library's unstable algorithms do.
  const auto cut = std::stable_partition(first, last, [&](uint32_t i) { return centroid(records[i])[axis] < middle; });
  if (cut != first && cut != last) return static_cast<size_t>(cut - order.begin());
  const auto mid = first + static_cast<std::ptrdiff_t>((end - begin) / 2);
  std::stable_sort(first, last, [&](uint32_t a, uint32_t b) {
    const float ca = centroid(records[a])[axis], cb = centroid(records[b])[axis];
    return ca < cb || (ca == cb && a < b);
  });
  return static_cast<size_t>(mid - order.begin());
}

/// Appends the bounds of the cluster holding `order[r.begin, r.end)`.
void add_cluster(LightClusters& c, const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
                 const std::vector<uint32_t>& order, const Range& r, double power_scale) {
  Box box;
  glm::dvec3 normal_sum(0.0);
  double area_sum = 0.0;
  for (size_t k = r.begin; k < r.end; ++k) {
    const EmitterRecord& e = records[order[k]];
    box.grow(e.p0), box.grow(e.p1), box.grow(e.p2);
    normal_sum += static_cast<double>(e.area) * glm::dvec3(e.normal);
    area_sum += e.area;
  }
  const size_t cluster = c.count++;
  const Vec3 centre = box.centre();
  c.cx[cluster] = centre.x, c.cy[cluster] = centre.y, c.cz[cluster] = centre.z;
  // Half the diagonal, made a hair larger so that rounding never leaves a corner outside.
  c.radius[cluster] = std::max(r.radius * (1.0f + 1e-5f), std::numeric_limits<float>::min());
  const double length = glm::length(normal_sum);
  Vec3 axis(0.0f, 0.0f, 1.0f);
  float cos_spread = -1.0f;
  if (length > 1e-6 * area_sum) {
    axis = Vec3(normal_sum / length);
    cos_spread = 1.0f;
    for (size_t k = r.begin; k < r.end; ++k)
      cos_spread = std::min(cos_spread, glm::dot(axis, records[order[k]].normal));
    // Rounding must not narrow the cone: widen it by a hair, and to every direction once it is a half-space or more.
    cos_spread = cos_spread > 1e-3f ? std::min(cos_spread, 1.0f) - 1e-5f : -1.0f;
  }
  c.ax[cluster] = axis.x, c.ay[cluster] = axis.y, c.az[cluster] = axis.z;
  c.cos_spread[cluster] = cos_spread;
  const Vec3 half = 0.5f * box.extent() * (1.0f + 1e-5f);
  c.ex[cluster] = half.x, c.ey[cluster] = half.y, c.ez[cluster] = half.z;
  // Where the point must be for some emitter of the cluster to face it: in front of the plane through the lowest
  // corner along the axis, by up to tilt x (distance to the farthest corner) when the normals lean off the axis.
  float lowest = kInfinity;
  double tilt = 0.0;
  for (size_t k = r.begin; k < r.end; ++k) {
    const EmitterRecord& e = records[order[k]];
    lowest = std::min({lowest, glm::dot(axis, e.p0), glm::dot(axis, e.p1), glm::dot(axis, e.p2)});
    tilt = std::max(tilt, glm::length(glm::dvec3(e.normal) - glm::dvec3(axis)));
  }
  c.lowest[cluster] = lowest;
  c.tilt[cluster] = static_cast<float>(tilt) + 1e-6f;  // the normals' own rounding
  c.power[cluster] = static_cast<float>(r.power * power_scale);
  c.first.push_back(static_cast<uint32_t>(c.members.size()));
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

/// cos(max(0, a - b)) for angles a, b in [0, pi] given by their cosines and sines.
inline float cos_of_clamped_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
/// sin(max(0, a - b)), likewise.
inline float sin_of_clamped_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}
inline float sine_of(float cosine) { return std::sqrt(std::max(0.0f, 1.0f - cosine * cosine)); }

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
  clusters.share.resize(records.size());
  // Powers relative to the brightest cluster's: a scene of absurd Ke stays within a float.
  double brightest = 0.0;
  for (const Range& r : ranges) brightest = std::max(brightest, r.power);
  for (const Range& r : ranges) add_cluster(clusters, records, weights, order, r, 1.0 / brightest);
  clusters.first.push_back(static_cast<uint32_t>(clusters.members.size()));
  return clusters;
}

/// Weighs clusters [0, kLanes) (kLanes a multiple of four at least the count: a fixed trip count, which the compiler
/// weighs four at a time).
template <size_t kLanes>
void weigh_lanes(const LightClusters& c, const Vec3& position, const Vec3& normal, LightWeights& weights) {
  // Copies, so that the compiler need not fear that writing the weights changes them.
  const float px = position.x, py = position.y, pz = position.z, nx = normal.x, ny = normal.y, nz = normal.z;
  const float ax_nx = std::fabs(nx), ax_ny = std::fabs(ny), ax_nz = std::fabs(nz);
  LightClusters::PerCluster out{};
  for (size_t k = 0; k < kLanes; ++k) {
    const float dx = c.cx[k] - px, dy = c.cy[k] - py, dz = c.cz[k] - pz;
    const float d2 = dx * dx + dy * dy + dz * dz;
    const float r2 = c.radius[k] * c.radius[k];
    // Inside the bounding sphere every direction may reach the cluster: both cosines are bounded by 1 only.
    const bool inside = !(d2 > r2);
    const float inv_d = 1.0f / std::sqrt(inside ? r2 : d2);
    const float sin_b = std::min(1.0f, c.radius[k] * inv_d), cos_b = sine_of(sin_b);  // the sphere's half-angle
    // At the surface: the angle between the normal and the direction to the centre, less the sphere's half-angle.
    const float cos_i = (nx * dx + ny * dy + nz * dz) * inv_d;
    const float surface = cos_of_clamped_difference(cos_i, sine_of(cos_i), cos_b, sin_b);
    // At the emitters: the angle between the cone's axis and the direction to the point, less the cone's half-angle
    // and the sphere's half-angle.
    const float cos_w = -(c.ax[k] * dx + c.ay[k] * dy + c.az[k] * dz) * inv_d;
    const float sin_w = sine_of(cos_w), cos_o = c.cos_spread[k], sin_o = sine_of(cos_o);
    const float cos_x = cos_of_clamped_difference(cos_w, sin_w, cos_o, sin_o);
    const float sin_x = sin_of_clamped_difference(cos_w, sin_w, cos_o, sin_o);
    const float emitter = cos_of_clamped_difference(cos_x, sin_x, cos_b, sin_b);
    const float weight = c.power[k] * std::max(surface, 0.0f) * std::max(emitter, 0.0f) * (inv_d * inv_d);
    // Tests that hold close or far: some corner of the box above the horizon, the point in front of some emitter.
    // The first allows for rounding, which decides for an emitter in the surface's own plane (a wall lamp's other
    // triangles, seen from one of them): one whose every point is below a cosine of 1e-5 at the surface sends
    // nothing worth a shadow ray.
    const float reach = std::sqrt(d2) + c.radius[k];
    const float highest_above = nx * dx + ny * dy + nz * dz + ax_nx * c.ex[k] + ax_ny * c.ey[k] + ax_nz * c.ez[k];
    const float in_front = c.ax[k] * px + c.ay[k] * py + c.az[k] * pz - c.lowest[k] + c.tilt[k] * reach;
    const bool can_light = (highest_above > kHorizonTolerance * reach) & (in_front > 0.0f);
    out[k] = can_light ? (inside ? c.power[k] * inv_d * inv_d : weight) : 0.0f;
  }
  weights.weight = out;
  float running = 0.0f;
  for (size_t k = 0; k < kLanes; ++k) weights.cdf[k] = running += weights.weight[k];
  weights.overflowed = !std::isfinite(running);
  weights.total = weights.overflowed ? 0.0f : running;
}

void weigh_light_clusters(const LightClusters& c, const Vec3& position, const Vec3& normal, LightWeights& weights) {
  // A scene with one or two emitters weighs four lanes, not sixteen.
  static_assert(kMaxLightClusters == 16);
  if (c.count <= 4) return weigh_lanes<4>(c, position, normal, weights);
  if (c.count <= 8) return weigh_lanes<8>(c, position, normal, weights);
  weigh_lanes<16>(c, position, normal, weights);
}

LightChoice choose_weighted_light(const LightClusters& c, const LightWeights& weights, float u) {
  LightChoice choice;
  if (!(weights.total > 0.0f)) return choice;
  const size_t n = c.size();
  const float x = u * weights.total;
  // The first cluster whose running weight exceeds x (the last if none does), found without a branch: the running
  // weights never fall, so the clusters before it are exactly those at or below x. Branches on a random x missed
  // about once per choice, which made the choice 5% of a frame.
  size_t k = 0;
  for (size_t i = 0; i + 1 < kMaxLightClusters; ++i) k += static_cast<size_t>((i + 1 < n) & !(weights.cdf[i] > x));
  while (!(weights.weight[k] > 0.0f)) --k;  // x rounded up to the total: the last cluster that weighs anything
  const float below = weights.cdf[k] - weights.weight[k];
  const double v = std::clamp(static_cast<double>((x - below) / weights.weight[k]), 0.0, 1.0);
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
  return weights.weight[c.cluster_of[index]] / weights.total * c.share[index];
}

}  // namespace lueur
