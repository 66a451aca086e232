// Light-sampling tables: uniform, by area (the report's Algorithm 1 made O(log n)), by power.
#include "render/light_sampler.h"

#include <algorithm>
#include <numeric>

namespace lueur {
namespace {

/// First index whose cumulative value exceeds u x total: the inverse of the discrete CDF (std::upper_bound's
/// answer). Branch-free: the halving picks its side with a conditional move, since with stratified numbers every
/// comparison is a coin toss that a branch predictor would lose half the time.
uint32_t search_cdf(const std::vector<double>& cdf, float u) {
  const double x = static_cast<double>(u) * cdf.back();
  const double* base = cdf.data();
  size_t length = cdf.size();
  // The answer stays within [base, base + length]; each step keeps the half that can hold it.
  while (length > 1) {
    const size_t half = length / 2;
    base = base[half - 1] <= x ? base + half : base;
    length -= half;
  }
  const size_t index = static_cast<size_t>(base - cdf.data()) + (*base <= x ? 1 : 0);
  return static_cast<uint32_t>(std::min(index, cdf.size() - 1));
}

float cdf_pmf(const std::vector<double>& cdf, uint32_t index) {
  const double previous = index == 0 ? 0.0 : cdf[index - 1];
  return static_cast<float>((cdf[index] - previous) / cdf.back());
}

}  // namespace

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
    table.triangles.push_back(tri);
    table.areas.push_back(areas[i]);
    area_sum += areas[i];
    power_sum += static_cast<double>(areas[i]) * luminance(scene.material_of(tri).ke);
    table.cdf_area.push_back(area_sum);
    table.cdf_power.push_back(power_sum);
  }
  // An emitter whose luminance is zero everywhere would make the power table empty: fall back to area.
  if (!table.empty() && !(power_sum > 0.0)) table.cdf_power = table.cdf_area;
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
      choice.index = search_cdf(table.cdf_area, u);
      choice.pmf = cdf_pmf(table.cdf_area, choice.index);
      break;
    case LightStrategy::kPower:
      choice.index = search_cdf(table.cdf_power, u);
      choice.pmf = cdf_pmf(table.cdf_power, choice.index);
      break;
  }
  return choice;
}

float light_pmf(const LightTable& table, LightStrategy strategy, uint32_t index) {
  switch (strategy) {
    case LightStrategy::kArea: return cdf_pmf(table.cdf_area, index);
    case LightStrategy::kPower: return cdf_pmf(table.cdf_power, index);
    case LightStrategy::kUniform:
    case LightStrategy::kAll: break;
  }
  return 1.0f / static_cast<float>(table.size());
}

uint32_t choose_light_linear_scan(const LightTable& table, float u) {
  // Algorithm 1: walk the sources, largest first, until the cumulative area passes u x total.
  const double x = static_cast<double>(u) * table.cdf_area.back();
  for (uint32_t i = 0; i < table.cdf_area.size(); ++i)
    if (x < table.cdf_area[i]) return i;
  return static_cast<uint32_t>(table.size() - 1);
}

}  // namespace lueur
