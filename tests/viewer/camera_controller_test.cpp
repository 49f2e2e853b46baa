// Orbit and fly cameras: orbit keeps the distance and never degenerates at the poles, pan follows
// the cursor at the target's depth, dolly is scale-free and clamped, fly speed follows distance.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "runtime/viewer/camera_controller.hpp"

namespace nano::viewer {
namespace {

Camera spec(glm::dvec3 eye, glm::dvec3 at) {
  Camera c;
  c.position = eye;
  c.look_at = at;
  c.up = {0, 1, 0};
  c.fov_degrees = 40;
  return c;
}

TEST(CameraController, OrbitKeepsDistanceAndTarget) {
  CameraController c(spec({100, 200, 900}, {10, 20, 30}), 1000);
  const double d = c.distance();
  for (int i = 0; i < 500; ++i) {
    c.orbit(7.3, (i % 50 < 25 ? 13.1 : -11.7), 480);
    ASSERT_NEAR(c.distance(), d, 1e-9 * d);
    ASSERT_EQ(c.camera().look_at, glm::dvec3(10, 20, 30));
    ASSERT_NO_THROW(c.camera().check());
  }
}

TEST(CameraController, OrbitStopsShortOfThePoles) {
  CameraController c(spec({0, 0, 500}, {0, 0, 0}), 1000);
  c.orbit(0, 10000, 480);  // dragging down moves the camera up over the target, far past 90°
  const glm::dvec3 dir = glm::normalize(c.camera().position - c.camera().look_at);
  EXPECT_LT(glm::dot(dir, glm::dvec3(0, 1, 0)), std::cos(glm::radians(0.5)));
  EXPECT_GT(glm::dot(dir, glm::dvec3(0, 1, 0)), std::cos(glm::radians(1.5)));
  EXPECT_NO_THROW(c.camera().check());
  c.orbit(0, -20000, 480);  // and all the way under it
  EXPECT_LT(glm::dot(glm::normalize(c.camera().position - c.camera().look_at), glm::dvec3(0, 1, 0)), -std::cos(glm::radians(1.5)));
  EXPECT_NO_THROW(c.camera().check());
}

TEST(CameraController, HorizontalDragTurnsAboutUp) {
  CameraController c(spec({0, 0, 500}, {0, 0, 0}), 1000);
  c.orbit(240, 0, 480);  // half the viewport height: 90°
  EXPECT_NEAR(std::abs(c.camera().position.x), 500, 1e-6);
  EXPECT_NEAR(c.camera().position.y, 0, 1e-9);
  EXPECT_NEAR(c.camera().position.z, 0, 1e-6);
}

TEST(CameraController, PanMovesEyeAndTargetByTheCursorsWorldSpan) {
  CameraController c(spec({0, 0, 500}, {0, 0, 0}), 1000);
  c.pan(480, 0, 480);  // a full viewport height to the right
  const double span = 2 * 500 * std::tan(glm::radians(20.0));
  // Dragging right moves the scene right, so the camera moves left (−x here).
  EXPECT_NEAR(c.camera().look_at.x, -span, 1e-9);
  EXPECT_NEAR(c.camera().position.x, -span, 1e-9);
  EXPECT_NEAR(c.distance(), 500, 1e-9);
}

TEST(CameraController, DollyIsScaleFreeAndClamped) {
  for (double d : {5.0, 500.0, 5e5}) {
    CameraController c(spec({0, 0, d}, {0, 0, 0}), 1e6);
    c.dolly(1);
    EXPECT_NEAR(c.distance() / d, 0.85, 1e-12);
    c.dolly(-1);
    EXPECT_NEAR(c.distance(), d, 1e-9 * d);
  }
  CameraController c(spec({0, 0, 10}, {0, 0, 0}), 100);
  c.dolly(1000);
  EXPECT_NEAR(c.distance(), 0.5, 1e-12);
  c.dolly(-1000);
  EXPECT_NEAR(c.distance(), 100 * 100, 1e-6);
}

TEST(CameraController, FlySpeedScalesWithDistance) {
  // From nanometres to micrometres: the speed is proportional to what lies ahead.
  CameraController near(spec({0, 0, 20}, {0, 0, 0}), 1e5);
  CameraController far(spec({0, 0, 2e4}, {0, 0, 0}), 1e5);
  EXPECT_NEAR(far.fly_speed() / near.fly_speed(), 1000, 1e-9);
  near.set_focus_depth(4.0);  // a surface 4 Å ahead slows the camera down
  EXPECT_NEAR(near.fly_speed(), 2.0, 1e-12);
  near.set_focus_depth(std::nullopt);
  EXPECT_NEAR(near.fly_speed(), 10.0, 1e-12);
}

TEST(CameraController, FlyMovesAlongTheViewAndKeepsDirection) {
  CameraController c(spec({0, 0, 100}, {0, 0, 0}), 1000);
  c.set_mode(CameraController::Mode::fly);
  const double speed = c.fly_speed();
  c.fly({0, 0, 1}, 0.5, false);  // W for half a second
  EXPECT_NEAR(c.camera().position.z, 100 - 0.5 * speed, 1e-9);
  EXPECT_NEAR(c.camera().look_at.z, -0.5 * speed, 1e-9);
  c.fly({1, 0, 0}, 1, true);  // D with Shift: ×5, to the right (+x)
  EXPECT_NEAR(c.camera().position.x, 5 * speed, 1e-9);
  EXPECT_NEAR(c.distance(), 100, 1e-9);
}

TEST(CameraController, LookTurnsTheViewAboutTheEye) {
  CameraController c(spec({0, 0, 100}, {0, 0, 0}), 1000);
  c.set_mode(CameraController::Mode::fly);
  c.look(30, -20, 480);
  EXPECT_EQ(c.camera().position, glm::dvec3(0, 0, 100));
  EXPECT_NEAR(c.distance(), 100, 1e-9);
  EXPECT_GT(c.camera().look_at.y, 0);  // mouse up looks up
  EXPECT_NO_THROW(c.camera().check());
}

TEST(CameraController, OrbitAfterFlyCentresOnWhatWasInFront) {
  CameraController c(spec({0, 0, 100}, {0, 0, 0}), 1000);
  c.set_mode(CameraController::Mode::fly);
  c.set_focus_depth(30.0);
  c.set_mode(CameraController::Mode::orbit);
  EXPECT_NEAR(c.camera().look_at.z, 70, 1e-9);
  EXPECT_NEAR(c.distance(), 30, 1e-9);
}

TEST(CameraController, RejectsADegenerateCamera) {
  CameraController c(spec({0, 0, 100}, {0, 0, 0}), 1000);
  EXPECT_THROW(c.set_camera(spec({1, 1, 1}, {1, 1, 1})), std::invalid_argument);
}

}  // namespace
}  // namespace nano::viewer
