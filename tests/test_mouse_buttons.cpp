// The viewer's mouse-button queue: a release and a press within one frame reach the UI as two frames, so that a
// slider let go of just before a press in the image does not swallow the camera drag (ImGui 1.86 would).
#include <gtest/gtest.h>

#include <vector>

#include "ui/mouse_buttons.h"

namespace lueur {
namespace {

/// The left button's state in each of `frames` frames, with `events` recorded before the first.
std::vector<bool> left_states(const std::vector<bool>& events, int frames) {
  MouseButtons buttons;
  for (bool pressed : events) buttons.record(0, pressed);
  std::vector<bool> states;
  for (int f = 0; f < frames; ++f) {
    buttons.next_frame();
    states.push_back(buttons.down[0]);
  }
  return states;
}

TEST(MouseButtons, AReleaseAndAPressInOneFrameAreSeenInTwoFrames) {
  MouseButtons buttons;
  buttons.record(0, true);
  buttons.next_frame();
  ASSERT_TRUE(buttons.down[0]);
  buttons.record(0, false);  // letting go of a slider...
  buttons.record(0, true);   // ...and pressing in the image before the next frame
  buttons.next_frame();
  EXPECT_FALSE(buttons.down[0]) << "the release must be seen";
  buttons.next_frame();
  EXPECT_TRUE(buttons.down[0]) << "then the new press";
  buttons.next_frame();
  EXPECT_TRUE(buttons.down[0]) << "and the button stays down";
}

TEST(MouseButtons, AClickWithinOneFrameIsDownForOneFrame) {
  EXPECT_EQ(left_states({true, false}, 3), (std::vector<bool>{true, false, false}));
  EXPECT_EQ(left_states({true, false, true, false}, 5), (std::vector<bool>{true, false, true, false, false}));
}

TEST(MouseButtons, RepeatedEventsChangeNothingAndButtonsAreIndependent) {
  EXPECT_EQ(left_states({false, false, true, true}, 2), (std::vector<bool>{true, true}));
  MouseButtons buttons;
  buttons.record(0, true);
  buttons.record(2, true);
  buttons.record(2, false);
  buttons.record(7, true);  // GLFW has eight buttons, ImGui five: the rest is ignored
  buttons.record(-1, true);
  buttons.next_frame();
  EXPECT_TRUE(buttons.down[0]);
  EXPECT_TRUE(buttons.down[2]);
  EXPECT_FALSE(buttons.down[1]);
  buttons.next_frame();
  EXPECT_TRUE(buttons.down[0]);
  EXPECT_FALSE(buttons.down[2]);
}

}  // namespace
}  // namespace lueur
