// A fixed set of worker threads that run parallel loops over task indices taken from an atomic counter.
// Depends on the standard library only.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace lueur {

/// How the pool's threads compete for the CPU with the rest of the process.
enum class ThreadPriority {
  kNormal,
  /// Below the process's other threads (nice +10 on Linux): a viewer's tracer uses every idle cycle, yet the
  /// window's thread and the GL driver's threads run first when they need a core, so drawing never waits for it.
  kBackground,
};

/// Lowers the calling thread's scheduling priority as `priority` says (per thread on Linux; a no-op elsewhere).
/// A lowered priority cannot be raised again without privileges, so only threads that stay in the background
/// call it.
void set_current_thread_priority(ThreadPriority priority);

class ThreadPool {
 public:
  /// `threads` <= 0 means one per hardware thread. The calling thread works too, so threads - 1 are spawned;
  /// the spawned ones run at `priority` (the caller sets its own).
  explicit ThreadPool(int threads = 0, ThreadPriority priority = ThreadPriority::kNormal);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int thread_count() const { return static_cast<int>(workers_.size()) + 1; }

  /// Calls task(index, worker) for every index in [0, count), spread over all threads; returns when all are done.
  /// `worker` is in [0, thread_count()) and identifies per-thread scratch storage. A task that throws, on any
  /// thread, stops the loop handing out indices; parallel_for waits for the tasks still running, then rethrows the
  /// first exception on the calling thread.
  void parallel_for(int count, const std::function<void(int index, int worker)>& task);

 private:
  void worker_loop(int worker);
  void drain(int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int)>* task_ = nullptr;
  int count_ = 0;
  std::atomic<int> next_{0};
  int busy_ = 0;
  uint64_t generation_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;  ///< the first exception a task of the current loop threw
};

/// Hardware threads, at least 1.
int hardware_threads();

}  // namespace lueur
