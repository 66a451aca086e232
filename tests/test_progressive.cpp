// The viewer's tracer thread: it accumulates exactly what the headless renderer does, restarts on every change
// that alters the estimate, shows previews first, and every snapshot it publishes is a whole, current frame.
#include <gtest/gtest.h>

#include <atomic>
#include <random>
#include <thread>

#include "render/progressive_tracer.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
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

CameraSpec default_camera() {
  const DefaultView v;
  return CameraSpec{v.eye, v.target, v.up, v.fovy_degrees};
}

/// Waits until a snapshot of the tracer's current accumulation with at least `frames` full frames arrives.
TracerSnapshot wait_for_snapshot(ProgressiveTracer& tracer, uint64_t frames) {
  TracerSnapshot snapshot;
  EXPECT_TRUE(tracer.wait_for_frames(frames, 120.0));
  for (int i = 0; i < 2000; ++i) {
    if (tracer.take_snapshot(snapshot) && snapshot.preview_divisor == 1 && snapshot.film.frames >= frames)
      return snapshot;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ADD_FAILURE() << "no snapshot with " << frames << " frames arrived";
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
  for (int f = 0; f < 3; ++f) render_frame(*traced, camera, settings, film, pool);
  for (int l = 0; l < kLayerCount; ++l)
    EXPECT_EQ(snapshot.film.sums[static_cast<size_t>(l)], film.sums[static_cast<size_t>(l)]) << kLayerNames[l];
}

TEST(ProgressiveTracer, ShowsCoarsePreviewsFirstAfterARestart) {
  ProgressiveTracer tracer(2);
  tracer.set_frame_limit(1);
  tracer.set_settings(small_settings(128, 96));
  tracer.set_camera(default_camera());
  tracer.set_scene(prepare_scene(make_default_scene()));
  std::vector<int> divisors;
  TracerSnapshot snapshot;
  for (int i = 0; i < 20000 && (divisors.empty() || divisors.back() != 1); ++i) {
    if (tracer.take_snapshot(snapshot)) {
      divisors.push_back(snapshot.preview_divisor);
      EXPECT_EQ(snapshot.film.width, 128 / snapshot.preview_divisor);
      EXPECT_EQ(snapshot.film.height, 96 / snapshot.preview_divisor);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_FALSE(divisors.empty());
  EXPECT_EQ(divisors.back(), 1);
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
  ASSERT_TRUE(tracer.wait_for_frames(2, 60.0));
  tracer.set_paused(true);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // lets a frame in flight finish
  const uint64_t frames = tracer.stats().frames;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(tracer.stats().frames, frames) << "no frame while paused";
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
  ASSERT_TRUE(tracer.wait_for_frames(1, 60.0));
  TracerSnapshot snapshot;
  for (int i = 0; i < 2000 && !tracer.take_snapshot(snapshot); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_EQ(snapshot.generation, generation + 1);
}

TEST(ProgressiveTracer, AnEmptySizeIdlesInsteadOfRendering) {
  ProgressiveTracer tracer(2);
  RenderSettings settings = small_settings(0, 0);
  tracer.set_settings(settings);
  tracer.set_scene(prepare_scene(make_default_scene()));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(tracer.idle());
  TracerSnapshot snapshot;
  EXPECT_FALSE(tracer.take_snapshot(snapshot));
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

  std::atomic<bool> done{false};
  // A sequence lock around scene swaps: `scene_epoch` is odd while one is in flight.
  std::atomic<int> scene_epoch{0}, current_scene{0};
  std::atomic<int> checked{0};
  std::thread display([&] {
    TracerSnapshot snapshot;
    while (!done) {
      const int epoch_before = scene_epoch.load();
      const int scene = current_scene.load();
      const uint64_t generation_before = tracer.generation();
      if (tracer.take_snapshot(snapshot)) {
        // The snapshot is of the current accumulation or newer, never of one already replaced.
        EXPECT_GE(snapshot.generation, generation_before);
        if (snapshot.generation == generation_before && epoch_before % 2 == 0 && scene_epoch.load() == epoch_before)
          expect_whole_frame(snapshot, static_cast<float>(scene + 1));
        ++checked;
      }
      std::this_thread::yield();
    }
  });

  std::mt19937 random(7);
  for (int change = 0; change < 3000; ++change) {
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
        ++scene_epoch;
        current_scene = s;
        tracer.set_scene(scenes[static_cast<size_t>(s)]);
        ++scene_epoch;
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
  // Leave it running normally at the end: it must still make progress (no deadlock).
  settings.width = settings.height = 16;
  tracer.set_settings(settings);
  tracer.set_frame_limit(0);
  tracer.set_paused(false);
  EXPECT_TRUE(tracer.wait_for_frames(3, 60.0));
  done = true;
  display.join();
  EXPECT_GT(checked.load(), 10);
}

}  // namespace
}  // namespace lueur
