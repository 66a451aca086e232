// The window's camera moves (orbit, pan, fly, dolly, frame the scene) keep the properties a user relies on. They are
// pure functions of a CameraSpec, so no window is needed.
#include <gtest/gtest.h>

#include "ui/camera_controls.h"

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

}  // namespace
}  // namespace lueur
