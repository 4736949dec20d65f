// Wind on cloth: the total force on a resting sheet against the drag law it implements.

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_grid.hpp"

namespace felt {
namespace {

ClothBody sheet(const Wind& wind) {
  GridClothSpec spec;  // 1 m² in the xy plane, facing +z
  spec.nx = spec.ny = 6;
  ClothParams params;
  params.wind = wind;
  return ClothBody("sheet", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                   make_integrator("symplectic_euler"));
}

Vec3 total_force(const ClothBody& body, Real t) {
  std::vector<Vec3> f(body.model().particle_count());
  body.compute_forces(body.state().x, body.state().v, t, f);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& fp : f) sum += fp;
  return sum;
}

TEST(Wind, PushesASheetAtRestByDragTimesAreaTimesNormalSpeed) {
  Wind wind;
  wind.enabled = true;
  wind.velocity = Vec3(3, 0, 4);  // 4 m/s through the sheet, 3 m/s along it
  wind.drag_coefficient = 0.6;
  const ClothBody body = sheet(wind);
  // c A (w·n) n = 0.6 · 1 m² · 4 m/s · (0, 0, 1)
  EXPECT_LT((total_force(body, 0) - Vec3(0, 0, 2.4)).norm(), 1e-12);
}

TEST(Wind, AlongTheSheetOrMovingWithItThereIsNoForce) {
  Wind wind;
  wind.enabled = true;
  wind.velocity = Vec3(5, -2, 0);
  ClothBody along = sheet(wind);
  EXPECT_LT(total_force(along, 0).norm(), 1e-12);

  wind.velocity = Vec3(0, 0, 4);
  ClothBody moving = sheet(wind);
  for (Vec3& v : moving.state().v) v = Vec3(0, 0, 4);  // flying with the wind
  EXPECT_LT(total_force(moving, 0).norm(), 1e-12);
}

TEST(Wind, GustsFollowTheirSine) {
  Wind wind;
  wind.enabled = true;
  wind.velocity = Vec3(0, 0, 2);
  wind.gust_amplitude = 0.5;
  wind.gust_period = 4;
  const ClothBody body = sheet(wind);
  // at a quarter period the wind blows 1.5× as hard, at three quarters 0.5×
  EXPECT_NEAR(total_force(body, 1).z(), 0.6 * 2 * 1.5, 1e-12);
  EXPECT_NEAR(total_force(body, 3).z(), 0.6 * 2 * 0.5, 1e-12);
}

}  // namespace
}  // namespace felt
