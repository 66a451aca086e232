// Chooses the emitter triangle a shadow ray goes to, per light-sampling strategy, with its probability.
// The table is sorted by decreasing area, as in the report's Algorithm 1. Depends on the scene layer.
#pragma once

#include "render/settings.h"
#include "scene/scene.h"

#include <vector>

namespace lueur {

struct LightTable {
  std::vector<uint32_t> triangles;  ///< emitter triangles, by decreasing area (ties keep scene order)
  std::vector<float> areas;
  std::vector<double> cdf_area;     ///< running sum of areas: cdf_area.back() is the total area
  std::vector<double> cdf_power;    ///< running sum of area x luminance(Ke)
  bool empty() const { return triangles.empty(); }
  size_t size() const { return triangles.size(); }
};

LightTable build_light_table(const Scene& scene);

struct LightChoice {
  uint32_t index = 0;  ///< position in the table
  float pmf = 0.0f;    ///< probability of choosing it
};

/// One emitter for u in [0, 1): uniform, area (cumulative table and binary search) or power.
/// `LightStrategy::kAll` does not choose; it is handled by the caller looping over every emitter.
LightChoice choose_light(const LightTable& table, LightStrategy strategy, float u);

/// Probability that `choose_light` returns `index`.
float light_pmf(const LightTable& table, LightStrategy strategy, uint32_t index);

/// The report's Algorithm 1, kept as the reference: a linear scan over the cumulative area of the sources sorted
/// by decreasing area. Returns exactly what the binary search of `choose_light(kArea)` returns for the same u.
uint32_t choose_light_linear_scan(const LightTable& table, float u);

}  // namespace lueur
