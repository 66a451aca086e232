// Turns for tracers that share the cores: an A/B split's two sides take one frame each in the order they asked (a
// ticket lock), so that a side that finishes a frame and asks again waits behind the other instead of winning again,
// and each side's frame time is its own tracing, not a share of two frames at once. Depends on the standard library.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace lueur {

class FrameTurns {
 public:
  /// Waits for the caller's turn; every take must be followed by one give_back (FrameTurn does both).
  void take() {
    std::unique_lock lock(mutex_);
    const uint64_t ticket = next_++;
    turn_.wait(lock, [&] { return serving_ == ticket; });
  }
  void give_back() {
    {
      std::lock_guard lock(mutex_);
      ++serving_;
    }
    turn_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable turn_;
  uint64_t next_ = 0, serving_ = 0;
};

/// One turn, given back however the scope is left; no turns to take: nothing.
class FrameTurn {
 public:
  explicit FrameTurn(FrameTurns* turns) : turns_(turns) {
    if (turns_) turns_->take();
  }
  ~FrameTurn() {
    if (turns_) turns_->give_back();
  }
  FrameTurn(const FrameTurn&) = delete;
  FrameTurn& operator=(const FrameTurn&) = delete;

 private:
  FrameTurns* turns_;
};

}  // namespace lueur
