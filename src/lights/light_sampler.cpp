// Light-sampling tables: uniform, by area (the report's Algorithm 1 made O(1) with a guide table), by power.
#include "lights/light_sampler.h"

#include <algorithm>
#include <numeric>

namespace lueur {
namespace {

/// The first index whose running sum exceeds x, starting from `first`, which must not be past it.
uint32_t walk_cdf(const std::vector<double>& cdf, uint32_t first, double x) {
  const auto last = static_cast<uint32_t>(cdf.size() - 1);
  uint32_t i = first;
  while (i < last && cdf[i] <= x) ++i;
  return i;
}

/// Guide buckets: a power of two at least twice the entries, so that most buckets hold at most one step.
size_t guide_size(size_t entries) {
  size_t size = 1;
  while (size < 2 * entries) size *= 2;
  return size;
}

uint32_t invert_cdf(const LightCdf& table, float u) {
  const auto buckets = static_cast<uint32_t>(table.guide.size());
  // u x buckets is exact (a power of two), so u is at least this bucket's smallest u, and so is x.
  const uint32_t bucket = std::min(static_cast<uint32_t>(u * static_cast<float>(buckets)), buckets - 1);
  return walk_cdf(table.cdf, table.guide[bucket], static_cast<double>(u) * table.cdf.back());
}

}  // namespace

void index_light_cdf(LightCdf& table) {
  const size_t n = table.cdf.size();
  const double total = table.cdf.back();
  table.pmf.resize(n);
  for (size_t i = 0; i < n; ++i)
    table.pmf[i] = static_cast<float>((table.cdf[i] - (i == 0 ? 0.0 : table.cdf[i - 1])) / total);
  table.guide.resize(guide_size(n));
  const auto buckets = static_cast<float>(table.guide.size());
  uint32_t answer = 0;
  for (size_t j = 0; j < table.guide.size(); ++j) {
    // The smallest u of bucket j, and the x it gives: every u of the bucket gives at least that x.
    const float u = static_cast<float>(j) / buckets;
    answer = walk_cdf(table.cdf, answer, static_cast<double>(u) * total);
    table.guide[j] = answer;
  }
}

LightTable build_light_table(const Scene& scene) {
  LightTable table;
  std::vector<uint32_t> order(scene.emitters.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<float> areas(scene.emitters.size());
  for (size_t i = 0; i < order.size(); ++i) areas[i] = scene.area(scene.emitters[i]);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return areas[a] > areas[b]; });

  double area_sum = 0.0, power_sum = 0.0;
  for (const uint32_t i : order) {
    const uint32_t tri = scene.emitters[i];
    const Triangle& t = scene.triangles[tri];
    table.triangles.push_back(tri);
    EmitterRecord record;
    record.p0 = scene.positions[t.v[0]];
    record.p1 = scene.positions[t.v[1]];
    record.p2 = scene.positions[t.v[2]];
    record.normal = glm::normalize(scene.geometric_normal_raw(tri));  // emitters have a positive area
    record.ke = scene.material_of(tri).ke;
    record.area = areas[i];
    table.records.push_back(record);
    area_sum += areas[i];
    power_sum += emitter_power(record);
    table.by_area.cdf.push_back(area_sum);
    table.by_power.cdf.push_back(power_sum);
  }
  if (table.empty()) return table;
  // An emitter whose luminance is zero everywhere would make the power table empty: fall back to area.
  if (!(power_sum > 0.0)) table.by_power.cdf = table.by_area.cdf;
  table.total_area = area_sum;
  table.total_power = power_sum;
  table.power_is_area = !(power_sum > 0.0);
  index_light_cdf(table.by_area);
  index_light_cdf(table.by_power);
  table.clusters = build_light_clusters(table.records);
  return table;
}

LightChoice choose_light(const LightTable& table, LightStrategy strategy, float u) {
  LightChoice choice;
  const auto n = static_cast<uint32_t>(table.size());
  switch (strategy) {
    case LightStrategy::kUniform:
    case LightStrategy::kAll:
      choice.index = std::min(static_cast<uint32_t>(u * static_cast<float>(n)), n - 1);
      choice.pmf = 1.0f / static_cast<float>(n);
      break;
    case LightStrategy::kArea:
      choice.index = invert_cdf(table.by_area, u);
      choice.pmf = table.by_area.pmf[choice.index];
      break;
    case LightStrategy::kPower:
    case LightStrategy::kImportance:
      choice.index = invert_cdf(table.by_power, u);
      choice.pmf = table.by_power.pmf[choice.index];
      break;
  }
  return choice;
}

float power_point_density(const LightTable& table, const Vec3& ke) {
  if (table.empty()) return 0.0f;
  if (table.power_is_area) return static_cast<float>(1.0 / table.total_area);
  return static_cast<float>(luminance(ke) / table.total_power);
}

float light_pmf(const LightTable& table, LightStrategy strategy, uint32_t index) {
  switch (strategy) {
    case LightStrategy::kArea:
      return table.by_area.pmf[index];
    case LightStrategy::kPower:
    case LightStrategy::kImportance:
      return table.by_power.pmf[index];
    case LightStrategy::kUniform:
    case LightStrategy::kAll:
      break;
  }
  return 1.0f / static_cast<float>(table.size());
}

uint32_t choose_light_linear_scan(const LightTable& table, float u) {
  // Algorithm 1: walk the sources, largest first, until the cumulative area passes u x total.
  const std::vector<double>& cdf = table.by_area.cdf;
  const double x = static_cast<double>(u) * cdf.back();
  for (uint32_t i = 0; i < cdf.size(); ++i)
    if (x < cdf[i]) return i;
  return static_cast<uint32_t>(table.size() - 1);
}

}  // namespace lueur
