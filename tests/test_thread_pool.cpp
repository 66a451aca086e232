// The thread pool and the renderer's use of it under stress: every index runs exactly once, worker ids are valid
// and never used by two threads at once, pools start and stop in any rhythm, and a frame cancelled from another
// thread leaves the film untouched. Run under ThreadSanitizer by scripts/sanitize.sh.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "integrator/renderer.h"
#include "core/thread_pool.h"
#include "scene/default_scene.h"
#include "test_support.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace lueur {
namespace {

TEST(ThreadPool, EveryIndexRunsExactlyOnceOnAValidWorker) {
  for (const int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    ASSERT_EQ(pool.thread_count(), threads);
    std::vector<std::atomic<int>> in_use(static_cast<size_t>(threads));
    for (int round = 0; round < 200; ++round) {
      const int count = (round * 37) % 300;  // includes 0, fewer than threads and many more
      std::vector<std::atomic<int>> visits(static_cast<size_t>(count));
      std::atomic<bool> worker_shared{false}, worker_out_of_range{false};
      pool.parallel_for(count, [&](int index, int worker) {
        if (worker < 0 || worker >= threads) {
          worker_out_of_range = true;
          return;
        }
        // A worker id stands for per-thread scratch: two threads must never hold the same one at once.
        if (in_use[static_cast<size_t>(worker)].fetch_add(1) != 0) worker_shared = true;
        visits[static_cast<size_t>(index)].fetch_add(1);
        in_use[static_cast<size_t>(worker)].fetch_sub(1);
      });
      ASSERT_FALSE(worker_out_of_range) << threads << " threads, round " << round;
      ASSERT_FALSE(worker_shared) << threads << " threads, round " << round;
      for (int i = 0; i < count; ++i)
        ASSERT_EQ(visits[static_cast<size_t>(i)].load(), 1) << "index " << i << ", " << threads << " threads";
    }
  }
}

TEST(ThreadPool, ResultsWrittenByWorkersAreVisibleAfterTheLoop) {
  ThreadPool pool(4);
  std::vector<uint64_t> values(10000);  // plain memory: parallel_for must publish it to the caller
  for (int round = 0; round < 50; ++round) {
    pool.parallel_for(static_cast<int>(values.size()),
                      [&](int i, int) { values[static_cast<size_t>(i)] = static_cast<uint64_t>(i) * round; });
    uint64_t sum = 0;
    for (const uint64_t v : values) sum += v;
    ASSERT_EQ(sum, static_cast<uint64_t>(round) * 9999 * 10000 / 2);
  }
}

TEST(ThreadPool, StartsAndStopsInAnyRhythm) {
  for (int i = 0; i < 100; ++i) {
    ThreadPool idle(3);  // destroyed without ever running a loop
  }
  for (int i = 0; i < 100; ++i) {
    ThreadPool pool(3);
    std::atomic<int> ran{0};
    pool.parallel_for(i % 7, [&](int, int) { ran.fetch_add(1); });
    EXPECT_EQ(ran.load(), i % 7);
  }  // destroyed right after a loop, while workers may still be on their way back to sleep
}

TEST(ThreadPool, SeveralPoolsFromSeveralThreads) {
  std::vector<std::thread> owners;
  std::atomic<int> total{0};
  for (int t = 0; t < 3; ++t)
    owners.emplace_back([&] {
      ThreadPool pool(2);
      for (int round = 0; round < 100; ++round) pool.parallel_for(10, [&](int, int) { total.fetch_add(1); });
    });
  for (std::thread& owner : owners) owner.join();
  EXPECT_EQ(total.load(), 3 * 100 * 10);
}

#if defined(__linux__)
/// This thread's nice value (Linux keeps one per thread).
int current_thread_nice() { return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())); }

TEST(ThreadPool, AThrowOnAWorkerReachesTheCallerAfterEveryTaskEnded) {
  ThreadPool pool(4);
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> running{0}, ran{0};
    bool caught = false;
    try {
      pool.parallel_for(64, [&](int index, int worker) {
        ++running;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        ++ran;
        --running;
        if (worker != 0 && index % 5 == 1) throw std::runtime_error("worker task failed");
      });
    } catch (const std::runtime_error& e) {
      caught = std::string(e.what()) == "worker task failed";
      EXPECT_EQ(running.load(), 0) << "parallel_for returned while a task still ran";
    }
    // A loop where only the caller's thread happened to take the throwing indices does not throw.
    if (!caught) {
      EXPECT_EQ(ran.load(), 64);
    }
  }
  // The pool is whole afterwards.
  std::atomic<int> visits{0};
  pool.parallel_for(100, [&](int, int) { ++visits; });
  EXPECT_EQ(visits.load(), 100);
}

TEST(ThreadPool, AThrowOnTheCallersThreadWaitsForTheWorkersBeforeItLeaves) {
  ThreadPool pool(3);
  for (int round = 0; round < 20; ++round) {
    std::atomic<int> running{0};
    std::atomic<bool> worker_started{false};
    try {
      pool.parallel_for(8, [&](int, int worker) {
        ++running;
        if (worker == 0) {
          // The caller's thread throws while the workers' tasks still run.
          while (!worker_started) std::this_thread::yield();
          --running;
          throw std::logic_error("caller task failed");
        }
        worker_started = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        --running;
      });
      ADD_FAILURE() << "the caller's throw was lost";
    } catch (const std::logic_error&) {
      EXPECT_EQ(running.load(), 0) << "parallel_for left while a worker still ran a task of the loop";
    }
  }
  std::atomic<int> visits{0};
  pool.parallel_for(50, [&](int, int) { ++visits; });
  EXPECT_EQ(visits.load(), 50);
}

TEST(ThreadPool, BackgroundWorkersRunBelowTheCallersPriority) {
  // The viewer's tracer runs its pool in the background so that the window's thread gets a core first.
  const int caller_nice = current_thread_nice();
  for (const ThreadPriority priority : {ThreadPriority::kNormal, ThreadPriority::kBackground}) {
    ThreadPool pool(3, priority);
    std::vector<std::atomic<int>> nice_of_worker(3);
    for (auto& n : nice_of_worker) n = -100;
    // Each thread's first task waits until all three threads have taken one (three tasks held at once, of 30), so
    // that every thread records its priority whatever order the scheduler runs them in.
    std::atomic<int> arrived{0};
    std::atomic<bool> all_arrived{true};
    pool.parallel_for(30, [&](int, int worker) {
      if (nice_of_worker[static_cast<size_t>(worker)].exchange(current_thread_nice()) != -100) return;
      ++arrived;
      if (!test::wait_until([&] { return arrived.load() == 3; })) all_arrived = false;
    });
    EXPECT_TRUE(all_arrived) << "a thread of the pool never took a task";
    EXPECT_EQ(nice_of_worker[0].load(), caller_nice) << "the calling thread keeps its own priority";
    for (int w = 1; w < 3; ++w) {
      if (priority == ThreadPriority::kNormal)
        EXPECT_EQ(nice_of_worker[static_cast<size_t>(w)].load(), caller_nice) << "worker " << w;
      else
        EXPECT_EQ(nice_of_worker[static_cast<size_t>(w)].load(), std::max(caller_nice, 10)) << "worker " << w;
    }
  }
  EXPECT_EQ(current_thread_nice(), caller_nice);
}
#endif

TEST(CancelledFrame, LeavesTheFilmUntouchedWhenCancelledFromAnotherThread) {
  Scene scene = make_default_scene();
  const std::shared_ptr<const TracedScene> traced = prepare_scene(std::move(scene));
  RenderSettings settings;
  settings.width = settings.height = 96;
  settings.enabled = {true, true, true, true};
  settings.l1_rays = settings.l2_rays = 4;
  const Camera camera = make_camera(default_scene_camera(), 96, 96);
  ThreadPool pool(3);
  Film film;
  film.reset(settings);
  // How long a frame takes here, so that the cancels below land inside frames: a measurement to aim with, never a
  // bound (the test passes however fast or slow the machine is).
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(render_frame(*traced, camera, settings, film, nullptr, pool).completed);
  const std::chrono::duration<double> frame_time = std::chrono::steady_clock::now() - start;
  const Film after_one = film;

  // Cancels at moments spread over one frame time and a little beyond, until some frame was cancelled and some
  // finished first (or many attempts went by): a frame that ignored its cancel would never count as cancelled.
  int cancelled = 0, finished = 0, attempt = 0;
  for (; attempt < 200 && (attempt < 20 || cancelled == 0 || finished == 0); ++attempt) {
    const double fraction = 1.2 * static_cast<double>(attempt % 20) / 20.0;
    std::atomic<bool> cancel{false};
    std::thread canceller([&] {
      std::this_thread::sleep_for(fraction * frame_time);
      cancel.store(true);
    });
    const FrameResult r = render_frame(*traced, camera, settings, film, nullptr, pool, &cancel);
    canceller.join();
    if (r.completed) {
      // Finished before the cancel arrived: one more frame, as if uncancelled; start over from one frame.
      ++finished;
      EXPECT_EQ(film.frames, 2u);
      film = after_one;
      continue;
    }
    ++cancelled;
    ASSERT_EQ(film.frames, 1u);
    for (size_t l = 0; l < film.sums.size(); ++l) ASSERT_EQ(film.sums[l], after_one.sums[l]) << "layer " << l;
  }
  EXPECT_GT(cancelled, 0) << "no frame of " << attempt << " was cancelled: render_frame does not heed its cancel";
  std::printf("[ cancel   ] %d of %d frames cancelled from another thread, %d finished first\n", cancelled, attempt,
              finished);
}

}  // namespace
}  // namespace lueur
