// The real window under Xvfb, driven with synthetic input from xdotool: a pass checkbox, a weight slider and a
// camera drag, each checked against the state the viewer reports (--state-file), and a display that keeps drawing
// while a traced frame is in progress. Every wait is for an event the state file shows, with a give-up time that
// only keeps a hang from stalling the suite; the display's timing figures are scripts/bench-window.sh's to report.
// CTest runs this executable inside xvfb-run (see tests/CMakeLists.txt).
#include "window_fixture.h"

namespace lueur {
namespace {

using namespace window_test;

bool has_pass(const json& s, const std::string& pass) {
  for (const json& p : s["view"]["passes"])
    if (p.get<std::string>() == pass) return true;
  return false;
}

TEST_F(Window, SyntheticInputDrivesThePanelAndTheCamera) {
  // A pass checkbox: L2 turns off and the accumulation restarts.
  uint64_t generation = state()["generation"].get<uint64_t>();
  ASSERT_TRUE(has_pass(state(), "l2"));
  const auto [cx, cy] = centre_of("pass-l2");
  xdotool("mousemove --window " + window_ + " " + std::to_string(cx) + " " + std::to_string(cy) + " click 1");
  ASSERT_TRUE(wait_for([&](const json& s) {
    return !has_pass(s, "l2") && s["generation"].get<uint64_t>() > generation;
  })) << "clicking the L2 checkbox did not turn L2 off";

  // The AO radius: unticking "Automatic" types in the radius automatic stands for; ticking it again gives 0 back.
  const float automatic = state()["automatic_ao_radius"].get<float>();
  ASSERT_GT(automatic, 0.0f);
  ASSERT_EQ(state()["view"]["ao_radius"].get<float>(), 0.0f);
  const auto [ax, ay] = centre_of("ao-automatic");
  const std::string click_automatic =
      "mousemove --window " + window_ + " " + std::to_string(ax) + " " + std::to_string(ay) + " click 1";
  xdotool(click_automatic);
  ASSERT_TRUE(wait_for([&](const json& s) { return s["view"]["ao_radius"].get<float>() == automatic; }))
      << "unticking Automatic AO radius did not type in the automatic radius";
  xdotool(click_automatic);
  ASSERT_TRUE(wait_for([&](const json& s) { return s["view"]["ao_radius"].get<float>() == 0.0f; }))
      << "ticking Automatic AO radius did not go back to 0";

  // A weight slider: the weight changes live and nothing restarts.
  ASSERT_TRUE(wait_for([](const json& s) { return s["frames"].get<int>() >= 1; }));
  generation = state()["generation"].get<uint64_t>();
  const float weight = state()["view"]["weights"]["l1"].get<float>();
  const auto [wx, wy] = centre_of("weight-l1");
  press_and_drag(wx, wy, wx + 40, wy);
  ASSERT_TRUE(wait_for([&](const json& s) { return s["view"]["weights"]["l1"].get<float>() > weight + 0.05f; }))
      << "dragging the L1 weight slider did not raise the weight";
  EXPECT_EQ(state()["generation"].get<uint64_t>(), generation) << "a weight change must not restart the tracer";

  // A camera drag in the image, right of the panel, pressed in the same instant as the slider is let go (as a
  // quick hand does): the slider must let go, and the eye moves and the accumulation restarts.
  const float dragged_weight = state()["view"]["weights"]["l1"].get<float>();
  const std::vector<float> eye = state()["view"]["camera"]["eye"].get<std::vector<float>>();
  const int panel_right = static_cast<int>(state()["widgets"]["panel"][2].get<float>());
  press_and_drag(panel_right + 60, 300, panel_right + 120, 320, "mouseup 1 ");
  xdotool("mouseup 1");
  ASSERT_TRUE(wait_for([&](const json& s) {
    return s["view"]["camera"]["eye"].get<std::vector<float>>() != eye && s["generation"].get<uint64_t>() > generation;
  })) << "dragging in the image did not move the camera; the viewer reports "
      << state().dump();
  EXPECT_EQ(state()["view"]["weights"]["l1"].get<float>(), dragged_weight) << "the camera drag moved the slider";

  // Resizing re-renders at the new size: the image is what the panel's column leaves of the window.
  xdotool("windowsize " + window_ + " " + std::to_string(panel_right + 320) + " 240");
  EXPECT_TRUE(wait_for([](const json& s) {
    return s["view"]["width"] == 320 && s["view"]["height"] == 240 && s["shown_frames"].get<int>() >= 0;
  })) << "the render size did not follow the window";
}

TEST_F(Window, TheImageSitsBesideThePanelWhichTabHidesAndItsEdgeWidens) {
  // --size 512x512 opens a window as wide as the panel and the image together: the image has the size asked for.
  const json start = state();
  const int panel_right = static_cast<int>(start["widgets"]["panel"][2].get<float>());
  EXPECT_EQ(start["widgets"]["panel"][0].get<float>(), 0.0f) << "the panel is docked to the left edge";
  EXPECT_EQ(start["view"]["width"], 512);
  const std::string geometry = run_command("xdotool getwindowgeometry --shell " + window_);
  EXPECT_NE(geometry.find("WIDTH=" + std::to_string(panel_right + 512)), std::string::npos) << geometry;

  // Tab hides the panel: the image takes the whole window; Tab again gives the column back.
  xdotool("windowfocus --sync " + window_ + " key Tab");
  ASSERT_TRUE(wait_for([&](const json& s) {
    return s["view"]["width"] == panel_right + 512 && !s["widgets"].contains("panel");
  })) << "Tab did not hide the panel: "
      << state().dump();
  xdotool("windowfocus --sync " + window_ + " key Tab");
  ASSERT_TRUE(wait_for([&](const json& s) { return s["view"]["width"] == 512 && s["widgets"].contains("panel"); }))
      << "Tab did not show the panel again: " << state().dump();

  // Dragging the panel's right edge widens it, and the image beside it narrows by as much.
  press_and_drag(panel_right - 2, 300, panel_right + 98, 300);
  xdotool("mouseup 1");
  ASSERT_TRUE(wait_for([&](const json& s) {
    const int right = static_cast<int>(s["widgets"]["panel"][2].get<float>());
    return right > panel_right + 50 && s["view"]["width"] == panel_right + 512 - right;
  })) << "dragging the panel's edge did not widen it: "
      << state().dump();
}

TEST_F(Window, TheFieldOfViewSliderZoomsWithTheEyeKept) {
  // A taller window, so that the View section's slider is on screen without scrolling the panel.
  xdotool("windowsize " + window_ + " 852 1000");
  ASSERT_TRUE(wait_for([](const json& s) {
    return s["view"]["height"] == 1000 && s["widgets"].contains("field-of-view") &&
           s["widgets"]["field-of-view"][3].get<float>() < 990.0f;
  })) << state().dump();
  const json before = state();
  const float fovy = before["view"]["camera"]["fovy_degrees"].get<float>();
  const auto [x, y] = centre_of("field-of-view");
  press_and_drag(x, y, x + 40, y);
  xdotool("mouseup 1");
  ASSERT_TRUE(wait_for([&](const json& s) {
    return s["view"]["camera"]["fovy_degrees"].get<float>() > fovy + 1.0f &&
           s["generation"].get<uint64_t>() > before["generation"].get<uint64_t>();
  })) << "dragging the field of view did not widen the view and restart: "
      << state().dump();
  EXPECT_EQ(state()["view"]["camera"]["eye"], before["view"]["camera"]["eye"]) << "a lens zoom keeps the eye";
}

TEST_F(Window, SurvivesATinyWindowAndBeingHidden) {
  // Shrunk to a single pixel, the render follows (and still traces).
  xdotool("windowsize " + window_ + " 1 1");
  ASSERT_TRUE(wait_for([](const json& s) { return s["view"]["width"] == 1 && s["view"]["height"] == 1; }))
      << "the render size did not follow a 1x1 window";
  // Unmapped, as a minimised window is: nothing is shown, and the viewer must neither crash nor hang; it keeps
  // running its loop.
  xdotool("windowunmap " + window_);
  wait_for_viewer_frames(10.0);
  int status = 0;
  ASSERT_NE(::waitpid(pid_, &status, WNOHANG), pid_) << "the viewer exited while its window was hidden";
  // Shown again at a usable size: it renders and draws at that size.
  xdotool("windowmap " + window_);
  xdotool("windowsize " + window_ + " 400 300");
  const double drawn = state()["display_frames"].get<double>();
  EXPECT_TRUE(wait_for([&](const json& s) {
    return s["view"]["width"] == 400 && s["view"]["height"] == 300 && s["frames"].get<int>() >= 1 &&
           s["display_frames"].get<double>() > drawn + 10;
  })) << "after being hidden the viewer did not render and draw at the new size";
}

TEST_F(Window, KeepsDrawingWhileTheTracerWorks) {
  // Frames of 16 L2 rays at 512x512 take the tracer a while; a display that waited for them would draw about one
  // frame per traced frame. Two states of the same accumulation and traced frame count, kDrawn display frames
  // apart, show the display drawing while one traced frame is in progress; that frame must then finish (the
  // tracer was working, not idle). How fast the display draws is a figure for scripts/bench-window.sh, which
  // reports the interval between displayed frames while the tracer works.
  constexpr double kDrawn = 5.0;
  json first;
  const bool drew = wait_for([&](const json& s) {
    if (!first.is_object() || s["generation"] != first["generation"] || s["frames"] != first["frames"]) {
      first = s;
      return false;
    }
    return s["display_frames"].get<double>() >= first["display_frames"].get<double>() + kDrawn;
  });
  ASSERT_TRUE(drew) << "the display never drew " << kDrawn << " frames while a traced frame was in progress";
  EXPECT_TRUE(wait_for([&](const json& s) {
    return s["generation"] == first["generation"] && s["frames"].get<int>() > first["frames"].get<int>();
  })) << "the traced frame never finished: the tracer was not working";
}

TEST_F(Window, ThePixelInspectorReadsThePixelUnderTheMouseAndARightClickPinsIt) {
  // The image starts at the panel's right edge; it and the film are both 512 x 512 once the previews are done, so
  // a window pixel is a film pixel once the column is taken off.
  const int image_left = static_cast<int>(state()["widgets"]["panel"][2].get<float>());
  const int x0 = 50, y0 = 200, x1 = 120, y1 = 300;
  const auto at = [](const json& s, int x, int y) {
    return s.contains("probe") && s["probe"]["x"] == x && s["probe"]["y"] == y;
  };
  const auto move_to = [&](int x, int y) {
    xdotool("mousemove --window " + window_ + " " + std::to_string(image_left + x) + " " + std::to_string(y));
  };
  move_to(x0, y0);
  ASSERT_TRUE(wait_for([&](const json& s) { return at(s, x0, y0) && !s["probe"]["pinned"].get<bool>(); }))
      << state().dump();
  // The image's value there is the weighted sum of the passes' (the report's weights, Le + L1 + L2).
  const json probe = state()["probe"];
  for (int c = 0; c < 3; ++c) {
    const double expected = probe["layers"]["le"][c].get<double>() + 0.6 * probe["layers"]["l1"][c].get<double>() +
                            0.4 * probe["layers"]["l2"][c].get<double>();
    EXPECT_NEAR(probe["image"][c].get<double>(), expected, 1e-5 * (1.0 + expected)) << probe.dump();
  }
  EXPECT_GT(probe["layers"]["l1"][0].get<double>(), 0.0) << "the floor of the lit room, in the image";

  // A right click pins it: the mouse moves on, the inspected pixel stays, and its frames keep coming.
  xdotool("click 3");
  ASSERT_TRUE(wait_for([&](const json& s) { return at(s, x0, y0) && s["probe"]["pinned"].get<bool>(); }))
      << state().dump();
  const uint64_t frames = state()["probe"]["frames"].get<uint64_t>();
  move_to(x1, y1);
  wait_for_viewer_frames(3.0);
  EXPECT_TRUE(at(state(), x0, y0)) << state().dump();
  EXPECT_TRUE(wait_for([&](const json& s) { return at(s, x0, y0) && s["probe"]["frames"].get<uint64_t>() > frames; }))
      << "the pinned pixel's values did not follow the accumulation";
  EXPECT_TRUE(wait_for([](const json& s) { return s["probe"]["history"].get<int>() >= 2; }))
      << "the convergence plot has no history: " << state().dump();

  // Another right click lets it go: the inspector follows the mouse again.
  xdotool("click 3");
  EXPECT_TRUE(wait_for([&](const json& s) { return at(s, x1, y1) && !s["probe"]["pinned"].get<bool>(); }))
      << state().dump();
}

/// The viewer started with an A/B split of the light choice, its divider at 0.7 of the width.
class SplitWindow : public Window {
 protected:
  std::vector<std::string> extra_arguments() const override {
    return {"--compare", "lights=uniform", "--compare-split", "0.7"};
  }
};

TEST_F(SplitWindow, BothSidesAccumulateAndTheDividerFollowsTheMouse) {
  // Both sides take turns: each gets frames.
  ASSERT_TRUE(wait_for([](const json& s) { return s["right_frames"].get<int>() >= 2 && s["frames"].get<int>() >= 2; }))
      << state().dump();
  const json before = state();
  EXPECT_EQ(before["view"]["compare"], "lights=uniform");
  // Drag the divider (at 0.7 of the image's 512 pixels, right of the panel) to 0.5: it moves, the camera does not.
  const int image_left = static_cast<int>(before["widgets"]["panel"][2].get<float>());
  press_and_drag(image_left + 358, 300, image_left + 256, 300);
  xdotool("mouseup 1");
  wait_for_viewer_frames();
  const json after = state();
  EXPECT_NEAR(after["view"]["compare_split"].get<double>(), 0.5, 0.02) << after.dump();
  EXPECT_EQ(after["view"]["camera"], before["view"]["camera"]);
  // Moving the divider is a display change: neither side restarted.
  EXPECT_EQ(after["generation"], before["generation"]);
  EXPECT_EQ(after["right_generation"], before["right_generation"]);
}

/// The viewer started on a scene file of its own (a floor and a light: four triangles), watching it.
class ReloadWindow : public Window {
 protected:
  ReloadWindow() : scene_dir_(test::make_temp_dir("window-scene")) { save(kFloor + kLight); }

  std::vector<std::string> extra_arguments() const override { return {scene_dir_ + "/scene.obj"}; }

  /// Writes the scene as a new version: a rename into place with a later time, as an exporter may write it.
  void save(const std::string& obj) {
    ++version_;
    const std::string part = scene_dir_ + "/scene.obj.part";
    { std::ofstream(part, std::ios::binary) << "mtllib scene.mtl\n" << obj; }
    const timespec times[2] = {{1000000 + version_, 0}, {1000000 + version_, 0}};
    ::utimensat(AT_FDCWD, part.c_str(), times, 0);
    std::rename(part.c_str(), (scene_dir_ + "/scene.obj").c_str());
    std::ofstream(scene_dir_ + "/scene.mtl") << "newmtl white\nKd 0.8 0.8 0.8\nnewmtl light\nKe 5 5 5\n";
  }

  static inline const std::string kFloor =
      "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nusemtl white\nf 1 3 2\nf 1 4 3\n";
  static inline const std::string kLight =
      "v -0.2 1 -0.2\nv 0.2 1 -0.2\nv 0.2 1 0.2\nv -0.2 1 0.2\nusemtl light\nf 5 6 7\nf 5 7 8\n";
  std::string scene_dir_;
  int version_ = 0;
};

/// The same viewer started on a scene file that cannot be loaded.
class BrokenSceneWindow : public ReloadWindow {
 protected:
  BrokenSceneWindow() { save(kFloor + "f 1 2 99\n"); }
  bool renders_at_start() const override { return false; }
};

TEST_F(BrokenSceneWindow, TheFirstSceneIsLoadedOnceItIsMended) {
  ASSERT_TRUE(wait_for([](const json& s) {
    return s["message_is_error"].get<bool>() && s["message"].get<std::string>().find("out of range") != std::string::npos;
  })) << state().dump();
  EXPECT_EQ(state()["frames"], 0);
  save(kFloor + kLight);
  ASSERT_TRUE(wait_for([](const json& s) { return s["triangles"] == 4 && s["frames"].get<int>() >= 1; }))
      << "the mended scene was not loaded: " << state().dump();
  EXPECT_FALSE(state()["message_is_error"].get<bool>()) << state().dump();
}

TEST_F(ReloadWindow, ASavedSceneIsReloadedWithTheCameraKeptAndABrokenOneLeavesTheOldScene) {
  ASSERT_TRUE(wait_for([](const json& s) { return s["triangles"] == 4 && !s["loading"].get<bool>(); }))
      << state().dump();
  const json camera = state()["view"]["camera"];
  const uint64_t generation = state()["generation"].get<uint64_t>();

  // A fifth triangle that widens the scene (its own default view would frame it differently): reloaded, camera kept.
  save(kFloor + kLight + "v 3 0 3\nusemtl white\nf 2 9 3\n");
  ASSERT_TRUE(wait_for([&](const json& s) {
    return s["triangles"] == 5 && s["message"].get<std::string>().find("reloaded") != std::string::npos;
  })) << state().dump();
  EXPECT_EQ(state()["view"]["camera"], camera) << "the reload moved the camera";
  EXPECT_GT(state()["generation"].get<uint64_t>(), generation) << "the new scene did not restart the accumulation";

  // Saved broken: the error shows, the old scene stays (and is not reloaded over and over).
  save(kFloor + "f 1 2 99\n");
  ASSERT_TRUE(wait_for([](const json& s) {
    return s["message_is_error"].get<bool>() && s["message"].get<std::string>().find("cannot load") != std::string::npos;
  })) << state().dump();
  EXPECT_EQ(state()["triangles"], 5);
  const std::string error = state()["message"].get<std::string>();
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
  const uint64_t loads = state()["scene_loads"].get<uint64_t>();
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // six of the watch's polls
  EXPECT_EQ(state()["scene_loads"].get<uint64_t>(), loads) << "the broken file was read again unchanged";

  // Mended: loaded again.
  save(kFloor + kLight + "v 3 0 3\nv 3 1 3\nusemtl white\nf 2 9 3\nf 3 9 10\n");
  ASSERT_TRUE(wait_for([](const json& s) { return s["triangles"] == 6 && !s["message_is_error"].get<bool>(); }))
      << state().dump();

  // F5 reads it again unchanged: a new accumulation of the same scene.
  const uint64_t before_f5 = state()["generation"].get<uint64_t>();
  // Held for a few of the viewer's frames, as a hand presses a key (it reads the keys' state once per frame).
  xdotool("windowfocus --sync " + window_ + " keydown F5");
  wait_for_viewer_frames(3.0);
  xdotool("keyup F5");
  EXPECT_TRUE(wait_for([&](const json& s) {
    return s["generation"].get<uint64_t>() > before_f5 && s["triangles"] == 6 && !s["loading"].get<bool>();
  })) << "F5 did not reload the scene: " << state().dump();
}

}  // namespace
}  // namespace lueur
