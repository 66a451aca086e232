// The world-space L1 store (issue 19): its keys keep apart what must not mix, its table never merges two keys and
// respects its cap, its cells shrink as frames accumulate, and a render with it stays a pure function of the
// settings whatever the thread count.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "store/l1_cache.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "test_support.h"

namespace lueur {
namespace {

L1CacheGrid test_grid(int generation = 0) {
  Camera camera = make_camera(CameraSpec{Vec3(0.0f, 0.0f, 5.0f), Vec3(0.0f), Vec3(0, 1, 0), 60.0f}, 64, 64);
  return make_l1_cache_grid(camera, Vec3(-1.0f), 2.0f * std::sqrt(3.0f), 8.0f, generation);
}

L1CacheRecord record_of(const L1CacheKey& key, float value, uint32_t samples) {
  return make_l1_record(key, hash_of(key), Vec3(value), samples);
}

TEST(L1CacheKeys, TheTwoSidesOfAThinWallNeverShareACell) {
  const L1CacheGrid grid = test_grid();
  Pcg32 rng(7, 1);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, 0.0f);
    const Vec3 n(0.0f, 0.0f, 1.0f);
    const float u1 = rng.next_float(), u2 = rng.next_float();
    // The same jitter on both sides: only the side differs.
    EXPECT_FALSE(jittered_key(grid, p, n, u1, u2) == jittered_key(grid, p, -n, u1, u2)) << i;
  }
}

TEST(L1CacheKeys, AFloorAndTheWallBesideItNeverShareACell) {
  const L1CacheGrid grid = test_grid();
  const Vec3 corner(0.3f, -0.2f, 0.1f);
  const int level = grid.level_at(corner);
  EXPECT_FALSE(grid.key(corner, Vec3(0, 1, 0), level) == grid.key(corner, Vec3(1, 0, 0), level));
  for (int bucket = 0; bucket < 6; ++bucket) {
    Vec3 n(0.0f);
    n[bucket / 2] = bucket % 2 ? -1.0f : 1.0f;
    EXPECT_EQ(normal_bucket(n), bucket);
  }
}

TEST(L1CacheKeys, ANonFinitePointGetsAKeyWithoutUndefinedBehaviour) {
  const L1CacheGrid grid = test_grid();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const Vec3 p : {Vec3(nan, 0.0f, 0.0f), Vec3(inf, -inf, 0.0f)}) {
    const int level = grid.level_at(p);
    EXPECT_GE(level, 0);
    EXPECT_LE(level, 40);
    const L1CacheKey key = grid.key(p, Vec3(0, 0, 1), level);
    EXPECT_EQ(hash_of(key), hash_of(key));
  }
}

TEST(L1CacheKeys, CellsCoverAboutTheSamePixelsEverywhereAndHalvePerGeneration) {
  const L1CacheGrid g0 = test_grid(0), g1 = test_grid(1), g3 = test_grid(3);
  // Twice as far: cells one level (twice) larger.
  EXPECT_EQ(g0.level_at(Vec3(0.0f, 0.0f, -3.0f)), g0.level_at(Vec3(0.0f, 0.0f, 1.0f)) + 1);
  // A cell of 8 pixels at the point's depth, to within the rounding to a power of two.
  const Vec3 p(0.0f, 0.0f, 1.0f);
  const float pixel = g0.pixel_per_depth * 4.0f;  // depth 4
  const float size = g0.size_of(g0.level_at(p));
  EXPECT_GT(size, 8.0f * pixel / std::sqrt(2.0f));
  EXPECT_LT(size, 8.0f * pixel * std::sqrt(2.0f));
  EXPECT_EQ(g1.level_at(p), g0.level_at(p) - 1);
  EXPECT_EQ(g3.level_at(p), g0.level_at(p) - 3);
  EXPECT_EQ(l1_cache_generation(0), 0);
  EXPECT_EQ(l1_cache_generation(3), 0);
  EXPECT_EQ(l1_cache_generation(4), 1);
  EXPECT_EQ(l1_cache_generation(31), 1);
  EXPECT_EQ(l1_cache_generation(32), 2);
  EXPECT_EQ(l1_cache_generation(255), 2);
  EXPECT_EQ(l1_cache_generation(256), 3);
}

TEST(L1CacheKeys, TheAutomaticCellSizeGrowsAsTheSquareRootOfTheImageHeight) {
  RenderSettings settings;
  EXPECT_EQ(settings.cache_cell_pixels, 0.0f);  // automatic by default
  settings.height = 128;
  EXPECT_FLOAT_EQ(settings.cache_cell_pixels_in_use(), 2.0f);
  settings.height = 512;
  EXPECT_FLOAT_EQ(settings.cache_cell_pixels_in_use(), 4.0f);
  settings.height = 256;
  EXPECT_NEAR(settings.cache_cell_pixels_in_use(), 2.0f * std::sqrt(2.0f), 1e-5f);
  settings.cache_cell_pixels = 3.0f;  // a size given is the size used, at any height
  EXPECT_EQ(settings.cache_cell_pixels_in_use(), 3.0f);
  settings.height = 2048;
  EXPECT_EQ(settings.cache_cell_pixels_in_use(), 3.0f);
}

/// Key number i of 3000 distinct ones, spread over positions and normal buckets.
L1CacheKey numbered_key(int i) {
  L1CacheKey key;
  key.x = i % 17;
  key.y = i / 17;
  key.z = -i;
  key.normal = static_cast<uint8_t>(i % 6);
  return key;
}

TEST(L1CacheTable, NeverMergesTwoKeysAndFindsEachOneItsOwnSum) {
  L1Cache cache;
  cache.reset(1u << 20);
  ThreadPool pool(2);
  std::vector<std::vector<L1CacheRecord>> batches(3);
  for (int i = 0; i < 3000; ++i) {
    L1CacheKey key = numbered_key(i);
    batches[static_cast<size_t>(i % 3)].push_back(record_of(key, static_cast<float>(i), 2));
    batches[static_cast<size_t>((i + 1) % 3)].push_back(record_of(key, static_cast<float>(i), 1));
  }
  cache.merge(batches, pool);
  EXPECT_EQ(cache.stats().cells, 3000u);
  EXPECT_FALSE(cache.stats().full);
  for (int i = 0; i < 3000; ++i) {
    L1CacheKey key = numbered_key(i);
    const L1CacheCell* cell = cache.find(key, hash_of(key));
    ASSERT_NE(cell, nullptr) << i;
    EXPECT_EQ(cell->samples, 3u);
    EXPECT_FLOAT_EQ(cell->sum.r / 3.0f, static_cast<float>(i));
    key.level = 1;  // the same place one level up: another cell, never stored
    EXPECT_EQ(cache.find(key, hash_of(key)), nullptr);
  }
}

TEST(L1CacheTable, StopsTakingNewCellsAtItsCapAndSaysSo) {
  L1Cache cache;
  cache.reset(64 * 1024);  // 2048 slots, 128 per shard, half of which may hold cells
  ThreadPool pool(1);
  std::vector<std::vector<L1CacheRecord>> batches(1);
  for (int i = 0; i < 10000; ++i) {
    L1CacheKey key;
    key.x = i;
    batches[0].push_back(record_of(key, 1.0f, 1));
  }
  cache.merge(batches, pool);
  const L1CacheStats stats = cache.stats();
  EXPECT_TRUE(stats.full);
  EXPECT_GT(stats.refused, 0u);
  EXPECT_LE(stats.bytes, 64u * 1024u);
  EXPECT_LE(stats.cells, 1024u);
  EXPECT_EQ(stats.cells + stats.refused, 10000u);
  // No room at all: nothing is stored.
  cache.reset(0);
  cache.merge(batches, pool);
  EXPECT_EQ(cache.stats().cells, 0u);
}

TEST(L1CacheTable, SaysBeforehandWhichNewCellsItWouldRefuse) {
  L1Cache cache;
  cache.reset(64 * 1024);  // 128 slots per shard at most
  ThreadPool pool(1);
  const auto merge_one = [&](int x) {
    L1CacheKey key;
    key.x = x;
    const L1CacheRecord record = record_of(key, 1.0f, 1);
    const bool predicted = cache.refuses_new_cell(record.hash);
    const uint64_t refused_before = cache.stats().refused;
    cache.merge({{record}}, pool);
    return std::pair{predicted, cache.stats().refused > refused_before};
  };
  int refusals = 0, acceptances = 0;
  for (int x = 0; x < 3000; ++x) {
    const auto [predicted, refused] = merge_one(x);
    ASSERT_EQ(predicted, refused) << "cell " << x;
    (refused ? refusals : acceptances) += 1;
  }
  EXPECT_GT(refusals, 0);  // both answers were checked
  EXPECT_GT(acceptances, 0);
  cache.reset(0);
  EXPECT_TRUE(cache.refuses_new_cell(hash_of(L1CacheKey{})));
}

/// The store fed, frame after frame, by jittered samples of a light that steps from 0 to 1 across x = 0 on the plane
/// z = 0 (a hard shadow edge), and looked up just on the dark side: what a look-up there gives, averaged over the
/// frames 0..n-1 for every n up to `frames` (each frame reading the store as the frames before it left it, as the
/// renderer does).
std::vector<double> dark_side_blur(int frames) {
  const Vec3 normal(0.0f, 0.0f, 1.0f);
  L1Cache cache;
  cache.reset(64u << 20);
  ThreadPool pool(2);
  Pcg32 rng(11, 3);
  double sum = 0.0;
  int lookups = 0;
  std::vector<double> running;
  for (int frame = 0; frame < frames; ++frame) {
    const int generation = l1_cache_generation(static_cast<uint64_t>(frame));
    if (cache.generation != generation) {
      cache.clear();
      cache.generation = generation;
    }
    const L1CacheGrid grid = test_grid(generation);
    // Look-ups on the dark side, within 3 pixel footprints of the edge (a footprint at depth 5 is 5 x pixel_per_depth).
    const float footprint = 5.0f * grid.pixel_per_depth;
    for (int i = 0; i < 400; ++i) {
      const Vec3 p(-3.0f * footprint * rng.next_float(), rng.next_float() - 0.5f, 0.0f);
      const L1CacheKey key = jittered_key(grid, p, normal, rng.next_float(), rng.next_float());
      const L1CacheCell* cell = cache.find(key, hash_of(key));
      // A cell not ready yet means a recomputed, unbiased value: 0 here.
      sum += cell && cell->samples >= kL1CacheMinSamples ? cell->sum.r / static_cast<float>(cell->samples) : 0.0;
      ++lookups;
    }
    std::vector<std::vector<L1CacheRecord>> batch(1);
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p(rng.next_float() * 0.4f - 0.2f, rng.next_float() - 0.5f, 0.0f);
      const L1CacheKey key = jittered_key(grid, p, normal, rng.next_float(), rng.next_float());
      batch[0].push_back(record_of(key, p.x > 0.0f ? 1.0f : 0.0f, 4));
    }
    cache.merge(batch, pool);
    running.push_back(sum / lookups);
  }
  return running;
}

TEST(L1CacheConsistency, TheBlurAtAShadowEdgeShrinksAsFramesAccumulate) {
  // The light on the dark side that the store lends from the lit side: its bias there.
  const std::vector<double> blur = dark_side_blur(2048);
  const double after_4 = blur[3], after_16 = blur[15], after_64 = blur[63], after_256 = blur[255],
               after_2048 = blur[2047];
  std::printf("dark-side blur after 4, 16, 64, 256, 2048 frames: %.4f %.4f %.4f %.4f %.4f\n", after_4, after_16,
              after_64, after_256, after_2048);
  EXPECT_GT(after_4, 0.05);  // cells of 8 pixels do blur a 3-pixel band
  // The bias after N frames is below the bias after N / 4.
  EXPECT_LT(after_16, after_4);
  EXPECT_LT(after_64, after_16);
  EXPECT_LT(after_256, after_64);
  // Each frame's blur halves per generation (8x frames), and the early frames' weight in the average falls as
  // 1 / frames: the average's bias tends to halving per 8x frames.
  EXPECT_LT(after_2048, 0.6 * after_256);
}

/// A floor lit by a small light on one side of a wall that stands on it: the shadow edge along the wall's foot is
/// perfectly hard (no penumbra, whatever the light's size), and the floor on both sides faces up, so that the
/// store's cells there can lend the lit side's light to the dark side.
Scene make_wall_on_lit_floor() {
  Scene s;
  s.name = "wall-on-floor";
  Material floor;
  floor.name = "floor";
  floor.kd = Vec3(0.8f);
  Material light;
  light.name = "light";
  light.kd = Vec3(0.0f);
  light.ke = Vec3(10.0f);
  s.materials = {floor, light};
  add_quad(s, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, 0);            // the floor, normal +y
  add_quad(s, {0, 0, -2}, {0, 1, -2}, {0, 1, 2}, {0, 0, 2}, 0);              // the wall at x = 0
  add_quad(s, {0.4f, 1.5f, -0.1f}, {0.6f, 1.5f, -0.1f}, {0.6f, 1.5f, 0.1f},  // the light on the +x side,
           {0.4f, 1.5f, 0.1f}, 1);                                           // facing down
  collect_emitters(s);
  return s;
}

/// The mean light arriving that L2's look-ups would take from the store at floor points on the dark side, within
/// three pixel footprints of the wall's foot (where the truth is 0), in each frame of a real `--reuse cache` render
/// of `frames` frames; the running mean of that bias after each frame (the image's bias after that many frames).
/// Also the light arriving on the lit side at the same distance, after the last frame.
std::vector<double> dark_side_bias_of_render(int frames, double& lit_side) {
  const auto traced = prepare_scene(make_wall_on_lit_floor());
  RenderSettings settings;
  settings.width = 64;
  settings.height = 64;
  settings.l1_rays = 16;
  settings.l2_rays = 8;
  settings.reuse = ReuseMode::kCache;
  const Camera camera =
      make_camera(CameraSpec{Vec3(0.0f, 3.0f, 0.0f), Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f), 60.0f}, 64, 64);
  Accumulation accumulation;
  accumulation.reset(settings);
  ThreadPool pool(2);
  Pcg32 rng(11, 3);
  const Vec3 up(0.0f, 1.0f, 0.0f);
  // The mean arriving light of the ready cells the look-ups at floor points x = side x [0, 3) footprints find (a cell
  // not ready means a recomputed, unbiased value: 0 on the dark side).
  const auto probe = [&](const L1CacheGrid& grid, float side) {
    const float footprint = 3.0f * grid.pixel_per_depth;  // the floor lies at depth 3
    double sum = 0.0;
    const int probes = 2000;
    for (int i = 0; i < probes; ++i) {
      const Vec3 p(side * 3.0f * footprint * rng.next_float(), 0.0f, rng.next_float() - 0.5f);
      const L1CacheKey key = jittered_key(grid, p, up, rng.next_float(), rng.next_float());
      const L1CacheCell* cell = accumulation.store.find(key, hash_of(key));
      if (cell && cell->samples >= kL1CacheMinSamples) sum += cell->sum.r / static_cast<float>(cell->samples);
    }
    return sum / probes;
  };
  std::vector<double> running;
  double total = 0.0;
  for (int f = 0; f < frames; ++f) {
    const int generation = l1_cache_generation(static_cast<uint64_t>(f));
    const L1CacheGrid grid =
        make_l1_cache_grid(camera, traced->lower, traced->diagonal, settings.cache_cell_pixels_in_use(), generation);
    // The frame starts a new generation with an empty store: its look-ups then all recompute.
    if (accumulation.store.generation == generation) total += probe(grid, -1.0f);
    running.push_back(total / (f + 1));
    render_frame(*traced, camera, settings, accumulation, pool);
    if (f + 1 == frames) lit_side = probe(grid, 1.0f);
  }
  return running;
}

TEST(L1CacheConsistency, ARenderedHardShadowsBiasAfterNFramesIsBelowItsBiasAfterNOver4) {
  double lit = 0.0;
  const std::vector<double> bias = dark_side_bias_of_render(256, lit);
  const double after_4 = bias[3], after_16 = bias[15], after_64 = bias[63], after_256 = bias[255];
  std::printf("light lent to the dark side after 4, 16, 64, 256 frames: %.5f %.5f %.5f %.5f (lit side: %.5f)\n",
              after_4, after_16, after_64, after_256, lit);
  EXPECT_GT(lit, 0.0);
  // The first generation's cells (the automatic 1.41 pixels at 64 lines, rounded to a power of two by distance, and
  // jittered across one more) do lend light across a 3-pixel band: the probe sees the blur.
  EXPECT_GT(after_4, 0.05 * lit);
  EXPECT_LT(after_16, after_4);
  EXPECT_LT(after_64, after_16);
  EXPECT_LT(after_256, after_64);
  // The image's bias goes to zero because each generation's cells lend half the light of the last one's: late in a
  // generation (once most of its cells are ready) the light lent per frame, with cells half as wide, is at most 0.6x
  // that late in the previous one (0.5x for a bias in proportion to the cell size; 1x for cells that do not shrink).
  // (The running mean above falls more slowly: the first frames of a generation find few ready cells.)
  const auto mean_of_frames = [&](int first, int end) {
    return (bias[static_cast<size_t>(end - 1)] * end - bias[static_cast<size_t>(first - 1)] * first) / (end - first);
  };
  const double late_gen1 = mean_of_frames(16, 32), late_gen2 = mean_of_frames(128, 256);
  std::printf("light lent per frame, frames 16-31: %.5f, frames 128-255: %.5f (%.3fx)\n", late_gen1, late_gen2,
              late_gen2 / late_gen1);
  EXPECT_LT(late_gen2, 0.6 * late_gen1);
}

Accumulation render_default_scene(RenderSettings settings, int frames, int threads) {
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  const auto traced = prepare_scene(std::move(scene));
  Accumulation accumulation;
  accumulation.reset(settings);
  ThreadPool pool(threads);
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  for (int f = 0; f < frames; ++f) render_frame(*traced, camera, settings, accumulation, pool);
  return accumulation;
}

TEST(L1CacheRender, BitIdenticalForAnyThreadCountAcrossAGeneration) {
  for (const ReuseMode mode : {ReuseMode::kCache, ReuseMode::kScreenCache}) {
    RenderSettings settings;
    settings.width = 45;  // not a multiple of the tile size
    settings.height = 38;
    settings.l1_rays = 8;
    settings.l2_rays = 8;
    settings.reuse = mode;
    settings.cache_cell_pixels = 4.0f;
    const Accumulation one_side = render_default_scene(settings, 6, 1);  // frames 0-3 and 4-5: two generations
    const Accumulation three_side = render_default_scene(settings, 6, 3);
    const Film &one = one_side.film, &three = three_side.film;
    EXPECT_EQ(one_side.store.stats().cells, three_side.store.stats().cells);
    EXPECT_GT(one_side.store.stats().cells, 0u);
    for (int l = 0; l < kLayerCount; ++l) {
      const auto& a = one.sums[static_cast<size_t>(l)];
      const auto& b = three.sums[static_cast<size_t>(l)];
      ASSERT_EQ(a.size(), b.size()) << kLayerNames[static_cast<size_t>(l)];
      EXPECT_TRUE(a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0)
          << kLayerNames[static_cast<size_t>(l)];
    }
    // The store served some bounce hits: its layer is not black.
    double cached = 0.0;
    for (const float v : one.sums[static_cast<size_t>(Layer::kL2Cached)]) cached += v;
    EXPECT_GT(cached, 0.0);
  }
}

TEST(L1CacheRender, ABounceHitThatFindsNoReadyCellFillsItWithTheFillRays) {
  // The first frame reads an empty store, so every bounce hit traces its L1(q) anew: each adds kL1CacheFillRays
  // samples to its cell (two of them make it ready), beside the l1_rays of each pixel's own estimate.
  const auto traced = prepare_scene(test::make_closed_emitting_box(1.0f, Vec3(0.5f), Vec3(1.0f)));
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.l1_rays = 4;  // its recompute ratio's share would be 1 ray
  settings.l2_rays = 8;
  settings.reuse = ReuseMode::kCache;
  settings.cache_cell_pixels = 2.0f;  // not the automatic 0.7 pixels of a 16-line image: cells most hits share
  const Camera camera =
      make_camera(CameraSpec{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f}, 16, 16);
  Accumulation accumulation;
  accumulation.reset(settings);
  ThreadPool pool(2);
  const FrameResult first = render_frame(*traced, camera, settings, accumulation, pool);
  EXPECT_EQ(first.l2_cached, 0u);
  ASSERT_GT(first.l2_bounce_hits, 0u);
  const uint64_t pixels = 16 * 16;  // inside the box every primary ray hits a wall
  EXPECT_EQ(accumulation.store.samples_held(),
            pixels * 4 + first.l2_bounce_hits * static_cast<uint64_t>(kL1CacheFillRays));
  EXPECT_EQ(accumulation.store.stats().refused, 0u);
  // Two fills make a cell ready: the next frame's bounce hits are mostly served.
  const FrameResult second = render_frame(*traced, camera, settings, accumulation, pool);
  EXPECT_GT(second.l2_cached, second.l2_bounce_hits / 2);
}

TEST(L1CacheRender, ABounceHitWhoseCellTheFullStoreWouldRefuseTracesOnlyTheRecomputeRays) {
  // A store with no room refuses every cell, so no fill would be kept: each bounce hit then traces the recompute
  // ratio's share, as `--reuse off` does, rather than kL1CacheFillRays for nothing.
  const auto traced = prepare_scene(test::make_closed_emitting_box(1.0f, Vec3(0.5f), Vec3(1.0f)));
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.l1_rays = 8;  // the recompute ratio's share: 1 ray
  settings.l2_rays = 8;
  const Camera camera =
      make_camera(CameraSpec{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f}, 16, 16);
  ThreadPool pool(2);
  uint64_t bounce_hits = 0;
  const auto rays_of_first_frame = [&](ReuseMode reuse, bool no_room) {
    settings.reuse = reuse;
    Accumulation accumulation;
    accumulation.reset(settings);
    if (no_room) accumulation.store.reset(0);
    const FrameResult frame = render_frame(*traced, camera, settings, accumulation, pool);
    bounce_hits = frame.l2_bounce_hits;
    if (no_room) {
      EXPECT_EQ(accumulation.store.samples_held(), 0u);
    }
    return frame.rays;
  };
  const uint64_t off = rays_of_first_frame(ReuseMode::kOff, false);
  const uint64_t no_room = rays_of_first_frame(ReuseMode::kCache, true);
  ASSERT_GT(bounce_hits, 100u);
  // A shadow sample that cannot reach its light is not traced, and the two modes draw other samples (their runs
  // differ), so the counts can differ by a few: but by less than a ray per bounce hit, where a fill costs
  // kL1CacheFillRays (8) instead of the ratio's 1, of which the samples on q's own wall (a sixth) are not traced.
  EXPECT_LE(no_room, off + bounce_hits);
  EXPECT_GE(no_room + bounce_hits, off);
  EXPECT_GT(rays_of_first_frame(ReuseMode::kCache, false), off + (kL1CacheFillRays - 1) * bounce_hits * 2 / 3);
}

}  // namespace
}  // namespace lueur
