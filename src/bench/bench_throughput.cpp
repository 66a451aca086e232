// Ray throughput and build time of the two back-ends.
#include "bench/bench_throughput.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "core/stopwatch.h"

namespace lueur::bench {
namespace {

// Rays per task: large enough that handing out tasks costs nothing, small enough to balance two threads.
constexpr int kChunk = 512;

/// Per-worker sink, padded apart, so that the results are used and the compiler cannot drop the queries.
struct alignas(64) Sink {
  uint64_t value = 0;
};

/// One pass over every ray with `trace(ray) -> uint32_t`, spread over the pool.
template <typename Trace>
void trace_all(const std::vector<Ray>& rays, ThreadPool& pool, std::vector<Sink>& sinks, const Trace& trace) {
  const int chunks = static_cast<int>((rays.size() + kChunk - 1) / kChunk);
  pool.parallel_for(chunks, [&](int chunk, int worker) {
    const size_t begin = static_cast<size_t>(chunk) * kChunk, end = std::min(rays.size(), begin + kChunk);
    uint64_t sum = 0;
    for (size_t i = begin; i < end; ++i) sum += trace(rays[i]);
    sinks[static_cast<size_t>(worker)].value += sum;
  });
}

/// Mrays/s of whole passes repeated for at least `seconds`.
template <typename Trace>
double time_passes(const std::vector<Ray>& rays, ThreadPool& pool, double seconds, const Trace& trace) {
  std::vector<Sink> sinks(static_cast<size_t>(pool.thread_count()));
  const Clock::time_point start = Clock::now();
  uint64_t traced = 0;
  double elapsed = 0.0;
  do {
    trace_all(rays, pool, sinks, trace);
    traced += rays.size();
    elapsed = seconds_since(start);
  } while (elapsed < seconds);
  volatile uint64_t keep = 0;
  for (const Sink& s : sinks) keep = keep + s.value;
  return static_cast<double>(traced) * 1e-6 / elapsed;
}

}  // namespace

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

Throughput measure_throughput(const std::vector<Ray>& rays, Query query, const Bvh& bvh, const EmbreeScene* embree,
                              ThreadPool& pool, const TimingOptions& options) {
  Throughput result;
  if (rays.empty()) return result;
  const auto lueur_closest = [&](const Ray& r) { return intersect_closest(bvh, r).triangle; };
  const auto lueur_any = [&](const Ray& r) { return static_cast<uint32_t>(intersect_any(bvh, r)); };
  const auto embree_closest = [&](const Ray& r) { return embree_intersect_closest_raw(*embree, r).triangle; };
  const auto embree_any = [&](const Ray& r) { return static_cast<uint32_t>(embree_intersect_any(*embree, r)); };

  std::vector<double> lueur_rounds, embree_rounds;
  for (int round = 0; round < std::max(1, options.rounds); ++round) {
    lueur_rounds.push_back(query == Query::kClosest ? time_passes(rays, pool, options.seconds_per_round, lueur_closest)
                                                    : time_passes(rays, pool, options.seconds_per_round, lueur_any));
    if (!embree) continue;
    embree_rounds.push_back(query == Query::kClosest
                                ? time_passes(rays, pool, options.seconds_per_round, embree_closest)
                                : time_passes(rays, pool, options.seconds_per_round, embree_any));
  }
  result.lueur = median(lueur_rounds);
  if (embree) {
    result.embree = median(embree_rounds);
    size_t same = 0;
    for (const Ray& r : rays)
      same += query == Query::kClosest ? lueur_closest(r) == embree_closest(r) : lueur_any(r) == embree_any(r);
    result.agreement = static_cast<double>(same) / static_cast<double>(rays.size());
  }
  return result;
}

BuildFigures measure_builds(const std::vector<Vec3>& corners, int repeats, Bvh& bvh,
                            std::shared_ptr<const EmbreeScene>& embree) {
  BuildFigures f;
  const double triangles = std::max<double>(1.0, static_cast<double>(corners.size() / 3));
  f.lueur_ms = kInfinity;
  double embree_ms = kInfinity;
  // Alternating, like the throughput rounds, so that a slow spell of a shared machine cannot fall on one back-end's
  // builds only.
  // The lean build the renderer makes (prepare_scene): over indexed corners, keeping only what queries read.
  std::vector<uint32_t> indices(corners.size());
  std::iota(indices.begin(), indices.end(), 0u);
  IndexedTriangles indexed;
  indexed.positions = corners.data();
  indexed.indices = indices.data();
  indexed.count = corners.size() / 3;
  for (int r = 0; r < repeats; ++r) {
    bvh = Bvh{};  // the previous tree is freed before timing, as a fresh build would find memory
    const Clock::time_point start = Clock::now();
    bvh = build_bvh(indexed);
    f.lueur_ms = std::min(f.lueur_ms, 1e3 * seconds_since(start));
    if (!embree_available()) continue;
    embree.reset();
    embree = build_embree_scene(corners);
    embree_ms = std::min(embree_ms, 1e3 * embree_commit_seconds(*embree));
  }
  Accelerator lueur;
  lueur.bvh = std::move(bvh);
  f.lueur_bytes = static_cast<double>(accelerator_bytes(lueur)) / triangles;
  f.lueur_resident_bytes = static_cast<double>(accelerator_resident_bytes(lueur)) / triangles;
  bvh = std::move(lueur.bvh);
  if (!embree_available()) return f;
  f.embree_ms = embree_ms;
  f.embree_bytes = static_cast<double>(embree_bytes(*embree)) / triangles;
  f.embree_resident_bytes = static_cast<double>(embree_resident_bytes(*embree)) / triangles;
  return f;
}

}  // namespace lueur::bench
