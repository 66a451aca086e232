// The real window under Xvfb: camera drags measured from the press, however the cursor got there and however fast
// it moved (tests/window_fixture.h).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "window_fixture.h"

namespace lueur {
namespace {

using namespace window_test;

/// The camera's azimuth about +y (its up), from the view the state file reports.
double azimuth_of(const json& s) {
  const auto eye = s["view"]["camera"]["eye"].get<std::vector<double>>();
  const auto target = s["view"]["camera"]["target"].get<std::vector<double>>();
  return std::atan2(eye[0] - target[0], eye[2] - target[2]);
}

/// The turn from azimuth a to b, in (-pi, pi].
double turn_between(double a, double b) {
  double d = b - a;
  while (d > M_PI) d -= 2.0 * M_PI;
  while (d <= -M_PI) d += 2.0 * M_PI;
  return d;
}

TEST_F(Window, ADragTurnsTheViewByTheDistanceDraggedSinceThePressOnly) {
  // 3 radians per image height: 100 pixels of a 512-pixel image turn the view by 0.586 radians, however the
  // cursor got there and however many frames it took.
  const int panel_right = static_cast<int>(state()["widgets"]["panel"][2].get<float>());
  const double height = state()["view"]["height"].get<double>();
  const double expected = 3.0 * 100.0 / height;
  const int x0 = panel_right + 150, y = 250;
  const std::string w = " --window " + window_ + " ";
  const auto turn_of = [&](const std::function<void()>& drag) {
    wait_for_viewer_frames(2);
    const double before = azimuth_of(state());
    drag();
    wait_for_viewer_frames(3);
    xdotool("mouseup 1");
    wait_for_viewer_frames(3);
    return std::abs(turn_between(before, azimuth_of(state())));
  };
  // The cursor moved from elsewhere and pressed in one instant, then a single 100-pixel move: the way to the press
  // does not count.
  xdotool("mousemove" + w + std::to_string(x0 - 200) + " " + std::to_string(y));
  const double after_a_move_and_press = turn_of([&] {
    xdotool("mousemove" + w + std::to_string(x0) + " " + std::to_string(y) + " mousedown 1 mousemove" + w +
            std::to_string(x0 + 100) + " " + std::to_string(y));
  });
  EXPECT_NEAR(after_a_move_and_press, expected, 0.02 * expected);
  // Ten moves of 10 pixels, each in a frame of its own.
  const double in_ten_frames = turn_of([&] {
    xdotool("mousemove" + w + std::to_string(x0) + " " + std::to_string(y) + " mousedown 1");
    wait_for_viewer_frames();
    for (int step = 1; step <= 10; ++step) {
      xdotool("mousemove" + w + std::to_string(x0 + 10 * step) + " " + std::to_string(y));
      wait_for_viewer_frames();
    }
  });
  EXPECT_NEAR(in_ten_frames, expected, 0.02 * expected);
  // A flick: the press and twenty moves sent at once, faster than frames come.
  const double in_a_flick = turn_of([&] {
    std::string moves = "mousemove" + w + std::to_string(x0) + " " + std::to_string(y) + " mousedown 1";
    for (int step = 1; step <= 20; ++step)
      moves += " mousemove" + w + std::to_string(x0 + 5 * step) + " " + std::to_string(y);
    xdotool(moves);
  });
  EXPECT_NEAR(in_a_flick, expected, 0.02 * expected);
}

}  // namespace
}  // namespace lueur
