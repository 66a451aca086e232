// Chooses the emitter triangle a shadow ray goes to, per light-sampling strategy, with its probability.
// The table is sorted by decreasing area, as in the report's Algorithm 1.
// This folder, lights/, chooses an emitter and a point on it: the table, its clusters and light trees with their
// bounds, and the vector lanes that weigh them. Depends on core, the scene and passes (the strategy's name).
#pragma once

#include <vector>

#include "lights/emitter.h"
#include "lights/light_clusters.h"
#include "passes/render_settings.h"
#include "scene/scene.h"

namespace lueur {

/// A discrete CDF with its inverse made O(1): `guide[j]` is the answer for the smallest u of bucket j (u in
/// [j, j + 1) / guide.size(), a power of two so that u x size is exact), and a short walk finds the exact one.
struct LightCdf {
  std::vector<double> cdf;  ///< running sum: cdf.back() is the total
  std::vector<float> pmf;   ///< (cdf[i] - cdf[i - 1]) / total
  std::vector<uint32_t> guide;
};

struct LightTable {
  std::vector<uint32_t> triangles;     ///< emitter triangles, by decreasing area (ties keep scene order)
  std::vector<EmitterRecord> records;  ///< per table entry (its area among them)
  LightCdf by_area;                    ///< running sum of areas
  LightCdf by_power;                   ///< running sum of area x luminance(Ke)
  LightClusters clusters;              ///< for the choice per shaded point (kImportance)
  double total_area = 0.0, total_power = 0.0;
  bool power_is_area = false;  ///< no emitter has a positive luminance: choosing by power chooses by area
  bool empty() const { return triangles.empty(); }
  size_t size() const { return triangles.size(); }
};

LightTable build_light_table(const Scene& scene);

/// Fills `pmf` and `guide` from `cdf` (non-decreasing, positive total).
void index_light_cdf(LightCdf& table);

/// One emitter for u in [0, 1): uniform, area or power (the cumulative table's inverse: the first entry whose
/// running sum exceeds u x total). `LightStrategy::kAll` does not choose; the caller loops over every emitter.
/// kImportance chooses per shaded point (choose_weighted_light); with no point to weigh the emitters at, as here,
/// it chooses by power.
LightChoice choose_light(const LightTable& table, LightStrategy strategy, float u);

/// The density per unit area of a point chosen by power (choose_light with kPower) and then uniformly on its
/// emitter, at an emitter of emission `ke`: luminance(ke) / total power. What a path that meets an emitter needs to
/// weigh its light against a shadow ray's (multiple importance sampling), with no look-up of the emitter.
float power_point_density(const LightTable& table, const Vec3& ke);

/// Probability that `choose_light` returns `index`.
float light_pmf(const LightTable& table, LightStrategy strategy, uint32_t index);

/// The report's Algorithm 1, kept as the reference: a linear scan over the cumulative area of the sources sorted
/// by decreasing area. Returns exactly what `choose_light(kArea)` returns for the same u.
uint32_t choose_light_linear_scan(const LightTable& table, float u);

}  // namespace lueur
