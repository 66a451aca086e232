// Thread pool: workers sleep on a condition variable between loops and pull indices from an atomic counter.
#include "core/thread_pool.h"

#include <utility>

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace lueur {

int hardware_threads() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

void set_current_thread_priority(ThreadPriority priority) {
  if (priority == ThreadPriority::kNormal) return;
#if defined(__linux__)
  // On Linux the nice value belongs to the thread, so PRIO_PROCESS with the thread id lowers this thread only.
  // Failure (a sandbox that forbids it) only costs responsiveness, never correctness.
  constexpr int kBackgroundNice = 10;
  const int current = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  if (current < kBackgroundNice) (void)setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kBackgroundNice);
#endif
}

ThreadPool::ThreadPool(int threads, ThreadPriority priority) {
  const int total = threads > 0 ? threads : hardware_threads();
  for (int w = 1; w < total; ++w)
    workers_.emplace_back([this, w, priority] {
      set_current_thread_priority(priority);
      worker_loop(w);
    });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::drain(int worker) {
  try {
    for (int i = next_.fetch_add(1, std::memory_order_relaxed); i < count_;
         i = next_.fetch_add(1, std::memory_order_relaxed))
      (*task_)(i, worker);
  } catch (...) {
    // Kept for the caller, and no further index is handed out: the loop ends as soon as the tasks running finish.
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
    next_.store(count_, std::memory_order_relaxed);
  }
}

void ThreadPool::parallel_for(int count, const std::function<void(int, int)>& task) {
  if (count <= 0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    count_ = count;
    next_.store(0, std::memory_order_relaxed);
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  wake_.notify_all();
  drain(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return busy_ == 0; });
  task_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void ThreadPool::worker_loop(int worker) {
  uint64_t seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
    }
    drain(worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

}  // namespace lueur
