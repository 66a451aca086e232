// The viewer's tracer thread: it accumulates exactly what the headless renderer does, restarts on every change
// that alters the estimate, shows previews first, and every snapshot it publishes is a whole, current frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <mutex>
#include <random>
#include <thread>

#include "runtime/progressive_tracer.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

RenderSettings small_settings(int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.l1_rays = 2;
  s.l2_rays = 2;
  return s;
}

CameraSpec default_camera() { return default_scene_camera(); }

/// How long the tests watch for something that must not happen (a frame while paused or of an empty image). A
/// window, not a bound on speed: a slow machine can only make such a check weaker, never fail it.
constexpr double kWatchSeconds = 0.5;

/// Waits until a snapshot of the tracer's current accumulation with at least `frames` full frames arrives.
TracerSnapshot wait_for_snapshot(ProgressiveTracer& tracer, uint64_t frames) {
  TracerSnapshot snapshot;
  EXPECT_TRUE(tracer.wait_for_frames(frames, test::kGiveUpSeconds))
      << "the tracer never reached " << frames << " frames";
  // The frame count goes up just before the frame is published: wait for the snapshot itself.
  const bool arrived = test::wait_until([&] {
    return tracer.take_snapshot(snapshot) && snapshot.preview_divisor == 1 && snapshot.film.frames >= frames;
  });
  EXPECT_TRUE(arrived) << "no snapshot with " << frames << " frames arrived";
  return snapshot;
}

TEST(ProgressiveTracer, AccumulatesTheSameBytesAsTheHeadlessRenderer) {
  const auto traced = prepare_scene(make_default_scene());
  const RenderSettings settings = small_settings(40, 32);
  ProgressiveTracer tracer(3);
  tracer.set_frame_limit(3);
  tracer.set_settings(settings);
  tracer.set_camera(default_camera());
  tracer.set_scene(traced);
  const TracerSnapshot snapshot = wait_for_snapshot(tracer, 3);
  ASSERT_EQ(snapshot.film.frames, 3u);
  EXPECT_EQ(snapshot.stats.frames, 3u);
  EXPECT_TRUE(tracer.idle()) << "the frame limit stops the tracer";

  Film film;
  film.reset(settings);
  ThreadPool pool(1);
  const Camera camera = make_camera(default_camera(), settings.width, settings.height);
  for (int f = 0; f < 3; ++f) render_frame(*traced, camera, settings, film, nullptr, pool);
  for (int l = 0; l < kLayerCount; ++l)
    EXPECT_EQ(snapshot.film.sums[static_cast<size_t>(l)], film.sums[static_cast<size_t>(l)]) << kLayerNames[l];
}

TEST(ProgressiveTracer, StopsOnceItsTimeLimitIsSpentAndGoesOnWhenItIsRaised) {
  const auto traced = prepare_scene(make_default_scene());
  ProgressiveTracer tracer(2);
  tracer.set_previews(false);
  tracer.set_time_limit(1e-9);  // spent by the first frame
  tracer.set_settings(small_settings(40, 32));
  tracer.set_camera(default_camera());
  tracer.set_scene(traced);
  wait_for_snapshot(tracer, 1);
  ASSERT_TRUE(test::wait_until([&] { return tracer.idle(); })) << "the time limit never stopped the tracer";
  const uint64_t frames = tracer.stats().frames;
  EXPECT_EQ(frames, 1u) << "only the frame in flight when the budget ran out";
  tracer.set_time_limit(0.0);
  EXPECT_FALSE(tracer.idle());
  wait_for_snapshot(tracer, frames + 2);
}

TEST(ProgressiveTracer, ShowsCoarsePreviewsFirstAfterARestart) {
  ProgressiveTracer tracer(2);
  tracer.set_frame_limit(1);
  tracer.set_settings(small_settings(128, 96));
  tracer.set_camera(default_camera());
  tracer.set_scene(prepare_scene(make_default_scene()));
  std::vector<int> divisors;
  TracerSnapshot snapshot;
  // Takes every snapshot it can until the full-resolution frame (the frame limit's one) arrives.
  const bool full_frame = test::wait_until([&] {
    if (tracer.take_snapshot(snapshot)) {
      divisors.push_back(snapshot.preview_divisor);
      EXPECT_EQ(snapshot.film.width, 128 / snapshot.preview_divisor);
      EXPECT_EQ(snapshot.film.height, 96 / snapshot.preview_divisor);
    }
    return !divisors.empty() && divisors.back() == 1;
  });
  ASSERT_TRUE(full_frame) << "no full-resolution snapshot arrived after " << divisors.size() << " previews";
  for (size_t i = 1; i < divisors.size(); ++i) EXPECT_LT(divisors[i], divisors[i - 1]) << "previews get finer";
  // 128x96 has room for all three previews (16x12, 32x24, 64x48); the display may have missed some, the tracer not.
  EXPECT_EQ(snapshot.stats.previews, 3u);

  tracer.set_previews(false);
  tracer.reset();
  TracerSnapshot full = wait_for_snapshot(tracer, 1);
  EXPECT_EQ(full.stats.previews, 0u);
}

TEST(ProgressiveTracer, PausesAndResumesAndAChangeRestarts) {
  ProgressiveTracer tracer(2);
  tracer.set_settings(small_settings(24, 24));
  tracer.set_camera(default_camera());
  tracer.set_scene(prepare_scene(make_default_scene()));
  ASSERT_TRUE(tracer.wait_for_frames(2, test::kGiveUpSeconds)) << "the tracer never reached 2 frames";
  tracer.set_paused(true);
  // Pausing lets the frame in flight finish and starts no other: from here on the count may grow by that one frame
  // at most, however long the frame takes. Small frames come every few milliseconds unpaused, so a pause that did
  // not hold would reach two more within the window.
  const uint64_t frames = tracer.stats().frames;
  EXPECT_FALSE(tracer.wait_for_frames(frames + 2, kWatchSeconds)) << "frames kept coming while paused";
  EXPECT_LE(tracer.stats().frames, frames + 1) << "no frame but the one in flight may finish while paused";
  EXPECT_TRUE(tracer.idle());

  const uint64_t generation = tracer.generation();
  RenderSettings changed = tracer.settings();
  changed.l1_rays = 3;
  tracer.set_settings(changed);
  EXPECT_EQ(tracer.generation(), generation + 1);
  EXPECT_EQ(tracer.stats().frames, 0u) << "a change drops the old accumulation at once";
  tracer.set_settings(changed);
  EXPECT_EQ(tracer.generation(), generation + 1) << "setting the same value again is not a change";
  tracer.set_paused(false);
  ASSERT_TRUE(tracer.wait_for_frames(1, test::kGiveUpSeconds)) << "no frame after resuming";
  TracerSnapshot snapshot;
  ASSERT_TRUE(test::wait_until([&] { return tracer.take_snapshot(snapshot); })) << "no snapshot after resuming";
  EXPECT_EQ(snapshot.generation, generation + 1);
}

TEST(ProgressiveTracer, AnEmptySizeIdlesInsteadOfRendering) {
  ProgressiveTracer tracer(2);
  RenderSettings settings = small_settings(0, 0);
  tracer.set_settings(settings);
  tracer.set_camera(default_camera());
  tracer.set_scene(prepare_scene(make_default_scene()));
  EXPECT_TRUE(tracer.idle());
  EXPECT_FALSE(tracer.wait_for_frames(1, kWatchSeconds)) << "a frame of an empty image";
  TracerSnapshot snapshot;
  EXPECT_FALSE(tracer.take_snapshot(snapshot)) << "a snapshot of an empty image";
  // The same tracer renders once it has a size: it idled for the empty size, not for want of anything else.
  tracer.set_settings(small_settings(8, 8));
  EXPECT_TRUE(tracer.wait_for_frames(1, test::kGiveUpSeconds)) << "no frame once the size is not empty";
}

/// Inside a closed box whose walls all emit `le`, every pixel's Le sum is exactly the same: a snapshot whose pixels
/// disagree mixes frames (torn), and one whose sum is not frames x le is inconsistent with its own frame count.
void expect_whole_frame(const TracerSnapshot& s, float le) {
  const auto& sum = s.film.sums[static_cast<size_t>(Layer::kLe)];
  ASSERT_EQ(sum.size(), 3u * s.film.pixel_count());
  ASSERT_GT(s.film.frames, 0u);
  const float expected = static_cast<float>(s.film.frames) * le;
  for (size_t i = 0; i < sum.size(); ++i) {
    ASSERT_EQ(sum[i], sum[0]) << "torn frame at value " << i;
    ASSERT_NEAR(sum[i], expected, 1e-4f * expected) << "sums disagree with the frame count " << s.film.frames;
  }
}

/// The display side of the stress tests: takes snapshots as fast as it can until `done` and checks each one that
/// is certainly of the current scene. Scene swaps run under a sequence lock: `scene_epoch` is odd while one is in
/// flight, and `current_scene` holds the index whose walls emit Le = index + 1.
struct SnapshotChecker {
  ProgressiveTracer& tracer;
  std::atomic<bool> done{false};
  std::atomic<int> scene_epoch{0}, current_scene{0};
  std::atomic<int> checked{0};   ///< snapshots taken
  std::atomic<int> verified{0};  ///< of those, snapshots certainly of the current scene, checked value by value
  std::mutex swap_gate{};        ///< held by a checkpoint so that a loader thread cannot restart the tracer endlessly

  void swap_scene(int index, std::shared_ptr<const TracedScene> scene) {
    const std::lock_guard<std::mutex> gate(swap_gate);
    ++scene_epoch;
    current_scene = index;
    tracer.set_scene(std::move(scene));
    ++scene_epoch;
  }

  void run() {
    TracerSnapshot snapshot;
    while (!done) {
      const int epoch_before = scene_epoch.load();
      const int scene = current_scene.load();
      const uint64_t generation_before = tracer.generation();
      if (tracer.take_snapshot(snapshot)) {
        // The snapshot is of the current accumulation or newer, never of one already replaced.
        EXPECT_GE(snapshot.generation, generation_before);
        if (snapshot.generation == generation_before && epoch_before % 2 == 0 && scene_epoch.load() == epoch_before) {
          expect_whole_frame(snapshot, static_cast<float>(scene + 1));
          ++verified;
        }
        ++checked;
      }
      std::this_thread::yield();
    }
  }
};

/// Waits until `counter` exceeds `target` (false if it never does, after test::kGiveUpSeconds).
bool wait_for_count(const std::atomic<int>& counter, int target) {
  return test::wait_until([&] { return counter.load() > target; });
}

/// A checkpoint inside the storm: lets the tracer run (unpaused, no frame limit, a non-empty image) until the display
/// thread has taken one more snapshot. Without it, a loaded machine can starve the display thread through the whole
/// storm, and the test would check nothing; with it, every run checks snapshots taken between changes. Scene swaps
/// wait meanwhile: a loader thread that swaps faster than a frame completes restarts the tracer before any frame.
void let_the_display_take_a_snapshot(ProgressiveTracer& tracer, SnapshotChecker& checker, RenderSettings& settings) {
  const std::lock_guard<std::mutex> no_swaps(checker.swap_gate);
  settings.width = std::max(settings.width, 1);
  settings.height = std::max(settings.height, 1);
  tracer.set_settings(settings);
  tracer.set_frame_limit(0);
  tracer.set_paused(false);
  EXPECT_TRUE(wait_for_count(checker.checked, checker.checked.load())) << "the display got no snapshot";
}

/// Leaves the tracer running normally after a storm of changes: it must still make progress (no deadlock), and the
/// display must verify a snapshot of the scene that is current once the changes stop.
void expect_progress_after_the_storm(ProgressiveTracer& tracer, SnapshotChecker& checker, RenderSettings settings) {
  settings.width = settings.height = 16;
  tracer.set_settings(settings);
  tracer.set_frame_limit(0);
  tracer.set_paused(false);
  EXPECT_TRUE(tracer.wait_for_frames(3, test::kGiveUpSeconds)) << "no progress after the storm";
  EXPECT_TRUE(wait_for_count(checker.verified, checker.verified.load())) << "no snapshot was verified";
}

TEST(ProgressiveTracer, StressEverySnapshotIsWholeAndCurrent) {
  // Each scene's walls emit a different Le, so a snapshot of a replaced scene shows up as a wrong value.
  std::vector<std::shared_ptr<const TracedScene>> scenes;
  for (int i = 1; i <= 3; ++i)
    scenes.push_back(prepare_scene(test::make_closed_emitting_box(1.0f, Vec3(0.5f), Vec3(static_cast<float>(i)))));
  ProgressiveTracer tracer(3);
  CameraSpec camera{Vec3(0.0f, 0.0f, 0.5f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f};
  RenderSettings settings = small_settings(16, 16);
  settings.enabled = {true, false, false, false};
  tracer.set_settings(settings);
  tracer.set_camera(camera);
  tracer.set_scene(scenes[0]);

  SnapshotChecker checker{tracer};
  std::thread display([&] { checker.run(); });

  std::mt19937 random(7);
  for (int change = 0; change < 3000; ++change) {
    if (change % 300 == 299) let_the_display_take_a_snapshot(tracer, checker, settings);
    switch (random() % 8) {
      case 0:
        camera.eye.x = std::uniform_real_distribution<float>(-0.5f, 0.5f)(random);
        tracer.set_camera(camera);
        break;
      case 1:
        settings.width = static_cast<int>(random() % 40);
        tracer.set_settings(settings);
        break;
      case 2:
        settings.height = static_cast<int>(random() % 40);
        tracer.set_settings(settings);
        break;
      case 3:
        tracer.set_paused(random() % 2 == 0);
        break;
      case 4:
        tracer.reset();
        break;
      case 5: {
        const int s = static_cast<int>(random() % scenes.size());
        checker.swap_scene(s, scenes[static_cast<size_t>(s)]);
        break;
      }
      case 6:
        tracer.set_frame_limit(random() % 4);
        break;
      default:
        std::this_thread::sleep_for(std::chrono::microseconds(random() % 2000));
        break;
    }
  }
  expect_progress_after_the_storm(tracer, checker, settings);
  checker.done = true;
  display.join();
  EXPECT_GT(checker.checked.load(), 10) << "one snapshot per checkpoint, and one after the storm";
}

/// Writes `scene` as an OBJ file and its materials as an MTL file beside it (Kd and Ke only).
std::string write_obj(const Scene& scene, const std::string& dir, const std::string& stem) {
  std::ofstream mtl(dir + "/" + stem + ".mtl");
  for (const Material& m : scene.materials)
    mtl << "newmtl " << m.name << "\nKd " << m.kd.r << ' ' << m.kd.g << ' ' << m.kd.b << "\nKe " << m.ke.r << ' '
        << m.ke.g << ' ' << m.ke.b << '\n';
  const std::string path = dir + "/" + stem + ".obj";
  std::ofstream obj(path);
  obj << "mtllib " << stem << ".mtl\n";
  for (const Vec3& p : scene.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const Triangle& t : scene.triangles)
    obj << "usemtl " << scene.materials[t.material].name << "\nf " << t.v[0] + 1 << ' ' << t.v[1] + 1 << ' '
        << t.v[2] + 1 << '\n';
  return path;
}

TEST(ProgressiveTracer, StressSettingsChangesWhileAnotherThreadReloadsScenes) {
  // The viewer's two writers at once: the UI thread changes every setting, camera, size (0 included), pause,
  // reset and frame limit, while a loader thread keeps reading OBJ files from disk, building their BVH and
  // swapping them in. Each file's walls emit a different Le, so a snapshot of a replaced scene shows.
  const std::string dir = test::make_temp_dir("stress-reload");
  std::vector<std::string> files;
  for (int i = 1; i <= 3; ++i)
    files.push_back(write_obj(test::make_closed_emitting_box(1.0f, Vec3(0.5f), Vec3(static_cast<float>(i))), dir,
                              "box" + std::to_string(i)));
  ProgressiveTracer tracer(3);
  CameraSpec camera{Vec3(0.0f, 0.0f, 0.5f), Vec3(0.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f};
  RenderSettings settings = small_settings(16, 16);
  tracer.set_settings(settings);
  tracer.set_camera(camera);
  tracer.set_scene(prepare_scene(load_obj(files[0]).scene));

  SnapshotChecker checker{tracer};
  std::thread display([&] { checker.run(); });
  std::atomic<bool> changes_done{false};
  std::atomic<int> reloads{0};
  std::thread loader([&] {
    std::mt19937 random(11);
    while (!changes_done) {
      const int s = static_cast<int>(random() % files.size());
      LoadOptions options;
      options.smooth_normals = random() % 2 == 0;
      checker.swap_scene(s, prepare_scene(load_obj(files[static_cast<size_t>(s)], options).scene));
      ++reloads;
    }
  });

  std::mt19937 random(7);
  auto pick = [&](int n) { return static_cast<int>(random() % static_cast<unsigned>(n)); };
  for (int change = 0; change < 3000; ++change) {
    if (change % 300 == 299) let_the_display_take_a_snapshot(tracer, checker, settings);
    switch (pick(12)) {
      case 0:
        camera.eye = Vec3(std::uniform_real_distribution<float>(-0.5f, 0.5f)(random), 0.0f, 0.5f);
        camera.fovy_degrees = 30.0f + static_cast<float>(pick(60));
        tracer.set_camera(camera);
        break;
      case 1:
        settings.width = pick(40);
        settings.height = pick(40);
        tracer.set_settings(settings);
        break;
      case 2:
        tracer.set_paused(pick(2) == 0);
        break;
      case 3:
        tracer.reset();
        break;
      case 4:
        tracer.set_frame_limit(static_cast<uint64_t>(pick(4)));
        break;
      case 5:  // Le stays on: it is what the checker reads
        for (size_t p = 1; p < kPassCount; ++p) settings.enabled[p] = pick(2) == 0;
        tracer.set_settings(settings);
        break;
      case 6:
        settings.lights = static_cast<LightStrategy>(pick(4));
        settings.l1_rays = 1 + pick(4);
        tracer.set_settings(settings);
        break;
      case 7:
        settings.reuse = static_cast<ReuseMode>(pick(3));
        settings.reuse_diffuse_only = pick(2) == 0;
        settings.recompute_ratio = 0.125f * static_cast<float>(1 + pick(8));
        settings.l2_rays = 1 + pick(3);
        tracer.set_settings(settings);
        break;
      case 8:
        settings.ao_rays = 1 + pick(3);
        settings.ao_radius = 0.1f * static_cast<float>(pick(10));
        settings.blinn_k = 0.1f * static_cast<float>(pick(11));
        tracer.set_settings(settings);
        break;
      case 9:
        tracer.set_previews(pick(2) == 0);
        break;
      default:
        std::this_thread::sleep_for(std::chrono::microseconds(random() % 2000));
        break;
    }
  }
  EXPECT_TRUE(wait_for_count(reloads, 10)) << "the loader thread made no progress";  // reloads overlap changes
  changes_done = true;
  loader.join();
  expect_progress_after_the_storm(tracer, checker, settings);
  checker.done = true;
  display.join();
  EXPECT_GT(checker.checked.load(), 10) << "one snapshot per checkpoint, and one after the storm";
}

}  // namespace
}  // namespace lueur
