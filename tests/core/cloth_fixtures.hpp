#pragma once
// Small bodies and checks shared by the core tests.

#include <memory>
#include <string_view>

#include <gtest/gtest.h>

#include "core/cloth_body.hpp"

namespace felt::test {

/// Two particles joined by one structural spring of rest length `rest` along x, the first
/// pinned at the origin: a 1-D oscillator m ẍ = −k (x − r) along the spring (linear, f = −k x,
/// when rest is 0).
inline ClothBody spring_pair(Real mass, Real stiffness, Real rest, Real damping,
                             std::string_view integrator) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3::Zero(), Vec3(rest, 0, 0)};
  model->uv = {Vec2::Zero(), Vec2::Zero()};
  model->mass = {mass, mass};
  model->springs = {{0, 1, rest, SpringKind::kStructural}};
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, stiffness, damping};
  ClothBody body("pair", model, params, make_integrator(integrator));
  body.pin(0);
  return body;
}

inline void expect_vec_near(const Vec3& got, const Vec3& want, Real tolerance) {
  EXPECT_NEAR(got.x(), want.x(), tolerance);
  EXPECT_NEAR(got.y(), want.y(), tolerance);
  EXPECT_NEAR(got.z(), want.z(), tolerance);
}

}  // namespace felt::test
