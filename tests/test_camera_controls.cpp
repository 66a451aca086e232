// The window's camera moves (orbit, pan, fly, dolly, frame the scene) keep the properties a user relies on. They are
// pure functions of a CameraSpec, so no window is needed.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "ui/camera_controls.h"
#include "ui/camera_drag.h"

namespace lueur {
namespace {

CameraSpec test_camera() { return CameraSpec{Vec3(1.0f, 2.0f, 5.0f), Vec3(0.0f, 0.5f, 0.0f), Vec3(0, 1, 0), 40.0f}; }

TEST(CameraControls, OrbitKeepsTheTargetAndTheDistance) {
  const CameraSpec c = test_camera();
  const CameraSpec o = orbit(c, 0.7f, 0.3f);
  EXPECT_EQ(o.target, c.target);
  EXPECT_NEAR(glm::length(o.eye - o.target), glm::length(c.eye - c.target), 1e-4f);
  EXPECT_GT(glm::length(o.eye - c.eye), 0.1f);
  // Pitching far past the pole stops short of it instead of flipping the view.
  CameraSpec p = c;
  for (int i = 0; i < 50; ++i) p = orbit(p, 0.0f, 0.2f);
  EXPECT_LT(std::abs(glm::dot(glm::normalize(p.eye - p.target), Vec3(0, 1, 0))), 0.996f);
}

TEST(CameraControls, PanAndFlyMoveEyeAndTargetTogether) {
  const CameraSpec c = test_camera();
  for (const CameraSpec& moved : {pan(c, 0.2f, -0.1f), fly(c, 1.0f, 0.5f, -0.25f)}) {
    EXPECT_NEAR(glm::length((moved.eye - moved.target) - (c.eye - c.target)), 0.0f, 1e-5f);
    EXPECT_GT(glm::length(moved.eye - c.eye), 0.01f);
  }
  // Flying forward by d moves along the view direction by exactly d.
  const CameraSpec f = fly(c, 2.0f, 0.0f, 0.0f);
  EXPECT_NEAR(glm::dot(f.eye - c.eye, glm::normalize(c.target - c.eye)), 2.0f, 1e-5f);
}

TEST(CameraControls, DollyApproachesButNeverReachesTheTarget) {
  const CameraSpec c = test_camera();
  const float d = glm::length(c.eye - c.target);
  EXPECT_NEAR(glm::length(dolly(c, 1.0f).eye - c.target), 0.85f * d, 1e-4f);
  EXPECT_NEAR(glm::length(dolly(c, -1.0f).eye - c.target), d / 0.85f, 1e-4f);
  EXPECT_GT(glm::length(dolly(c, 1000.0f).eye - c.target), 0.0f);
}

TEST(CameraControls, FrameBoundsPutsTheWholeBoxInView) {
  Box3 box;
  box.expand(Vec3(-3, -1, -2));
  box.expand(Vec3(5, 4, 1));
  const CameraSpec framed = frame_bounds(test_camera(), box, 1.5f);
  const Camera camera = make_camera(framed, 300, 200);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                 (corner & 4) ? box.hi.z : box.lo.z);
    float x = 0, y = 0;
    EXPECT_TRUE(project_to_pixel(camera, p, x, y)) << "corner " << corner << " is outside the view";
  }
}

/// How much of the view's width and height the box's projection spans, as the largest |x| and |y| of its corners
/// in [-1, 1] image coordinates; false if a corner is behind the eye.
bool projected_extent(const CameraSpec& spec, const Box3& box, int width, int height, float& x_extent,
                      float& y_extent) {
  const Camera camera = make_camera(spec, width, height);
  x_extent = y_extent = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                 (corner & 4) ? box.hi.z : box.lo.z);
    const Vec3 d = p - camera.eye;
    const float depth = glm::dot(d, camera.forward);
    if (!(depth > 0.0f)) return false;
    x_extent = std::max(x_extent, std::abs(glm::dot(d, camera.right)) / (depth * camera.tan_half_fovy * camera.aspect));
    y_extent = std::max(y_extent, std::abs(glm::dot(d, camera.up)) / (depth * camera.tan_half_fovy));
  }
  return true;
}

TEST(CameraFraming, TheModelFillsTheViewAlongItsLimitingAxisWithASmallMargin) {
  // CornellBox-Original's bounds, a flat wide model, a tall one, and a cube; square, wide and tall images.
  const std::vector<std::pair<Vec3, Vec3>> boxes = {{{-1.02f, 0.0f, -1.04f}, {1.0f, 1.99f, 0.99f}},
                                                    {{-4, 0, -1}, {4, 0.5f, 1}},
                                                    {{0, 0, 0}, {0.2f, 3, 0.2f}},
                                                    {{-1, -1, -1}, {1, 1, 1}}};
  for (const auto& [lo, hi] : boxes)
    for (const auto& [width, height] : {std::pair{512, 512}, std::pair{800, 600}, std::pair{400, 700}}) {
      Box3 box;
      box.expand(lo);
      box.expand(hi);
      const float aspect = static_cast<float>(width) / static_cast<float>(height);
      for (const CameraSpec& framed : {frame_box(box, 45.0f, aspect), frame_bounds(test_camera(), box, aspect)}) {
        float x = 0.0f, y = 0.0f;
        ASSERT_TRUE(projected_extent(framed, box, width, height, x, y));
        EXPECT_LE(std::max(x, y), kFramedShare + 1e-4f) << width << "x" << height;
        EXPECT_GE(std::max(x, y), kFramedShare - 1e-4f) << "the box does not fill its limiting axis: " << x << ", "
                                                          << y << " of " << width << "x" << height;
      }
    }
}

/// The eye's azimuth around the target, about +y.
float azimuth(const CameraSpec& c) {
  const Vec3 offset = c.eye - c.target;
  return std::atan2(offset.x, offset.z);
}

TEST(CameraDrag, TheTurnDependsOnlyOnTheDistanceFromThePress) {
  const CameraSpec c = test_camera();
  const double height = 600.0;
  // The cursor moved from 640 to 900 before the press (a move and a press within one frame): only 900 to 1000
  // counts, in one frame or in ten.
  CameraDrag flick;
  begin_drag(flick, DragMode::kOrbit, c, 900.0, 400.0);
  const CameraSpec one_frame = continue_drag(flick, DragMode::kOrbit, c, 1000.0, 400.0, height);
  CameraDrag slow;
  begin_drag(slow, DragMode::kOrbit, c, 900.0, 400.0);
  CameraSpec ten_frames = c;
  for (int step = 1; step <= 10; ++step)
    ten_frames = continue_drag(slow, DragMode::kOrbit, ten_frames, 900.0 + 10.0 * step, 400.0, height);
  EXPECT_EQ(one_frame, ten_frames);
  const float turned = azimuth(c) - azimuth(one_frame);
  EXPECT_NEAR(turned, kOrbitRadiansPerHeight * 100.0f / 600.0f, 1e-4f);
  EXPECT_NEAR(glm::length(one_frame.eye - one_frame.target), glm::length(c.eye - c.target), 1e-4f);
  // Back to the press: back to the first view.
  const CameraSpec back = continue_drag(slow, DragMode::kOrbit, ten_frames, 900.0, 400.0, height);
  EXPECT_NEAR(glm::length(back.eye - c.eye), 0.0f, 1e-5f);
}

TEST(CameraDrag, PastAPoleItStopsAndComesBackTheWayItWent) {
  const CameraSpec c = test_camera();
  CameraDrag drag;
  begin_drag(drag, DragMode::kOrbit, c, 100.0, 100.0);
  const CameraSpec far_up = continue_drag(drag, DragMode::kOrbit, c, 100.0, 100.0 + 5000.0, 500.0);
  EXPECT_LT(std::abs(glm::dot(glm::normalize(far_up.eye - far_up.target), Vec3(0, 1, 0))), 0.996f);
  const CameraSpec back = continue_drag(drag, DragMode::kOrbit, far_up, 100.0, 100.0, 500.0);
  EXPECT_NEAR(glm::length(back.eye - c.eye), 0.0f, 1e-4f);
}

TEST(CameraDrag, APanFollowsTheCursorAndOtherMovesMidDragAreKept) {
  const CameraSpec c = test_camera();
  CameraDrag drag;
  begin_drag(drag, DragMode::kPan, c, 10.0, 10.0);
  const CameraSpec panned = continue_drag(drag, DragMode::kPan, c, 60.0, 10.0, 500.0);
  EXPECT_NEAR(glm::length(panned.eye - pan(c, 0.1f, 0.0f).eye), 0.0f, 1e-5f);
  // The wheel dollies mid-drag: the drag goes on from the dollied camera, from where the cursor is.
  const CameraSpec dollied = dolly(panned, 1.0f);
  const CameraSpec after = continue_drag(drag, DragMode::kPan, dollied, 60.0, 10.0, 500.0);
  EXPECT_EQ(after, dollied);
  // Shift let go mid-drag: an orbit from here on, not a jump.
  const CameraSpec orbited = continue_drag(drag, DragMode::kOrbit, after, 60.0, 10.0, 500.0);
  EXPECT_NEAR(glm::length(orbited.eye - after.eye), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace lueur
