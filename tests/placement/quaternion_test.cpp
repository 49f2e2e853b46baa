// Quaternion helpers vs Rodrigues' rotation formula in double (an independent construction).
#include <gtest/gtest.h>

#include "shared/quaternion.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
using nano::gpu::quat_conjugate;
using nano::gpu::quat_from_axis_angle;
using nano::gpu::quat_identity;
using nano::gpu::quat_mul;
using nano::gpu::quat_rotate;
using nano::gpu::quat_to_mat3;

// Rodrigues: rotate v by angle about unit axis k, right-handed.
dvec3 rodrigues(dvec3 k, double angle, dvec3 v) {
  k = glm::normalize(k);
  return v * std::cos(angle) + glm::cross(k, v) * std::sin(angle) + k * glm::dot(k, v) * (1 - std::cos(angle));
}

TEST(Quaternion, AxisAngleRotationMatchesRodrigues) {
  Rng rng(11);
  double worst = 0;
  for (int i = 0; i < 5000; ++i) {
    glm::vec3 axis = rng.unit_vector() * float(rng.uniform(0.1, 10.0));  // any length
    float angle = float(rng.uniform(-7.0, 7.0));
    glm::vec3 v = rng.in_box(-50, 50);
    glm::vec4 q = quat_from_axis_angle(axis, angle);
    dvec3 want = rodrigues(D(axis), angle, D(v));
    dvec3 got_r = D(quat_rotate(q, v));
    dvec3 got_m = D(quat_to_mat3(q) * v);
    double scale = std::max(glm::length(D(v)), 1e-3);
    worst = std::max({worst, glm::length(got_r - want) / scale, glm::length(got_m - want) / scale});
  }
  EXPECT_LT(worst, 2e-6);
  RecordProperty("max_rel_error", std::to_string(worst));
}

TEST(Quaternion, KnownRotations) {
  const float pi = 3.14159265358979f;
  glm::vec4 qz = quat_from_axis_angle(glm::vec3(0, 0, 2), pi / 2);  // +90° about z: x → y
  glm::vec3 r = quat_rotate(qz, glm::vec3(1, 0, 0));
  EXPECT_NEAR(r.x, 0.0f, 1e-6f);
  EXPECT_NEAR(r.y, 1.0f, 1e-6f);
  EXPECT_NEAR(r.z, 0.0f, 1e-6f);
  glm::vec3 id = quat_rotate(quat_identity(), glm::vec3(3, -4, 5));
  EXPECT_EQ(id, glm::vec3(3, -4, 5));
}

TEST(Quaternion, ProductComposesRotationsAndConjugateInverts) {
  Rng rng(12);
  double worst = 0;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 a1 = rng.unit_vector(), a2 = rng.unit_vector();
    double g1 = rng.uniform(-3.2, 3.2), g2 = rng.uniform(-3.2, 3.2);
    glm::vec4 q1 = quat_from_axis_angle(a1, float(g1));
    glm::vec4 q2 = quat_from_axis_angle(a2, float(g2));
    glm::vec3 v = rng.in_box(-10, 10);
    dvec3 want = rodrigues(D(a1), g1, rodrigues(D(a2), g2, D(v)));  // q2 first, then q1
    dvec3 got = D(quat_rotate(quat_mul(q1, q2), v));
    double s = std::max(glm::length(D(v)), 1e-3);
    worst = std::max(worst, glm::length(got - want) / s);
    dvec3 back = D(quat_rotate(quat_conjugate(q1), quat_rotate(q1, v)));
    worst = std::max(worst, glm::length(back - D(v)) / s);
  }
  EXPECT_LT(worst, 3e-6);
}

TEST(Quaternion, MatrixIsProperRotation) {
  Rng rng(13);
  for (int i = 0; i < 2000; ++i) {
    glm::mat3 m = quat_to_mat3(quat_from_axis_angle(rng.unit_vector(), float(rng.uniform(-7, 7))));
    glm::dmat3 md(m);
    glm::dmat3 e = glm::transpose(md) * md;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) ASSERT_NEAR(e[c][r], c == r ? 1.0 : 0.0, 5e-6);
    ASSERT_NEAR(glm::determinant(md), 1.0, 5e-6);  // |q| = 1 only to float rounding
  }
}
}  // namespace
