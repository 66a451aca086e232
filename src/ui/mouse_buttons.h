// Mouse buttons for a UI that samples them once per frame, without losing a release and press that arrive in the
// same frame.
//
// Dear ImGui 1.86 (Debian 12) reads each button as "pressed during this frame or down now". A release followed by
// a press before the next frame (letting go of a slider and pressing in the image a few milliseconds later) then
// looks like a button held all along: the slider stays active and swallows the drag meant for the camera. Newer
// ImGui trickles input events, one transition per button per frame; this queue does the same for 1.86 and for
// the viewer's own camera input, so that both see the same button state. Each press carries the cursor's position
// when it happened, so that a drag starts where the button went down, not where the cursor is when the frame that
// delivers the press begins.
#pragma once

#include <array>
#include <deque>

namespace lueur {

struct MouseButtons {
  static constexpr int kCount = 5;  ///< ImGui's io.MouseDown has five buttons

  struct Event {
    bool pressed;  ///< a press (true) or a release (false)
    double x, y;   ///< the cursor when it happened
  };
  std::array<std::deque<Event>, kCount> pending{};  ///< presses and releases not yet delivered
  std::array<bool, kCount> down{};                  ///< the state delivered for the current frame
  std::array<double, kCount> press_x{}, press_y{};  ///< where the delivered press of each button happened

  /// Records a press or release as the window system reports it (any number per frame), with the cursor then.
  void record(int button, bool pressed, double x = 0.0, double y = 0.0) {
    if (button >= 0 && button < kCount) pending[static_cast<size_t>(button)].push_back({pressed, x, y});
  }

  /// Starts a frame: delivers at most one change per button, so that every press and release is seen for at least
  /// one frame, in order. Events that change nothing (a repeated release) are skipped.
  void next_frame() {
    for (size_t b = 0; b < kCount; ++b) {
      std::deque<Event>& queue = pending[b];
      while (!queue.empty() && queue.front().pressed == down[b]) queue.pop_front();
      if (!queue.empty()) {
        const Event& event = queue.front();
        down[b] = event.pressed;
        if (event.pressed) press_x[b] = event.x, press_y[b] = event.y;
        queue.pop_front();
      }
    }
  }
};

}  // namespace lueur
