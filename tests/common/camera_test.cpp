// The one camera: the scene record keeps the field of view in radians, the shader record in degrees
// (its w) with the tangent of half of it; both conversions checked against the analytic values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/camera.hpp"

namespace {

using nano::Camera;

TEST(Camera, SceneRecordStoresRadiansAndReadsBackDegrees) {
  const Camera c{{1.0, 2.0, 3.0}, {4.0, -5.0, 6.5}, {0.0, 0.0, 1.0}, 60.0};
  nano::gpu::SceneSettings s{};
  nano::store_camera(s, c);
  EXPECT_FLOAT_EQ(s.camera_position.w, static_cast<float>(std::numbers::pi / 3.0));
  EXPECT_EQ(glm::vec3(s.camera_position), glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(glm::vec3(s.camera_look_at), glm::vec3(4.0f, -5.0f, 6.5f));
  EXPECT_EQ(glm::vec3(s.camera_up), glm::vec3(0.0f, 0.0f, 1.0f));
  const Camera back = nano::camera_from_scene(s);
  EXPECT_EQ(back.position, c.position);
  EXPECT_EQ(back.look_at, c.look_at);
  EXPECT_EQ(back.up, c.up);
  EXPECT_NEAR(back.fov_degrees, 60.0, 1e-5);  // through one float
}

TEST(Camera, ShaderRecordTakesDegreesAndTheHalfAngleTangent) {
  const Camera c{{0.0, 0.0, 10.0}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 90.0};
  const nano::gpu::Camera g = c.to_gpu(64, 32);
  EXPECT_FLOAT_EQ(g.position.w, 90.0f);
  EXPECT_NEAR(g.forward.w, 1.0f, 1e-6f);  // tan(45°)
  EXPECT_EQ(glm::vec3(g.forward), glm::vec3(0.0f, 0.0f, -1.0f));
}

TEST(Camera, RejectsDegenerateViews) {
  EXPECT_THROW((Camera{{1, 1, 1}, {1, 1, 1}, {0, 1, 0}, 40}).check(), std::invalid_argument);
  EXPECT_THROW((Camera{{0, 0, 1}, {0, 0, 0}, {0, 0, 1}, 40}).check(), std::invalid_argument);  // up along the view
  EXPECT_THROW((Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 180}).check(), std::invalid_argument);
  EXPECT_THROW((Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40}).to_gpu(0, 8), std::invalid_argument);
  EXPECT_NO_THROW((Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40}).check());
}

// problem() is what parsers report against their source; check() throws the same words.
TEST(Camera, ProblemSaysWhatCheckRefuses) {
  EXPECT_EQ((Camera{{1, 1, 1}, {1, 1, 1}, {0, 1, 0}, 40}).problem(), "camera: position and look_at are the same point");
  EXPECT_EQ((Camera{{0, 0, 1}, {0, 0, 0}, {0, 0, 1}, 40}).problem(), "camera: up is zero or parallel to the viewing direction");
  EXPECT_EQ((Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0}).problem(), "camera: fov_degrees must lie in (0, 180)");
  EXPECT_EQ((Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 40}).problem(), "");
}

TEST(Camera, TextNamesEveryFieldExactly) {
  const Camera c{{0.1, -2.0, 3e7}, {0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 33.3};
  EXPECT_EQ(c.to_string(), "position=0.1,-2,3e+07;look_at=0,0,0;up=0,1,0;fov_degrees=33.3");
}

}  // namespace
