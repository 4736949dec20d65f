// A cloth's strain per particle, for clients to colour: (length - rest) / rest of its structural
// and shear springs, averaged over the springs at each particle; bend springs left out.

#include "core/cloth/vertex_strain.hpp"

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"

namespace felt {
namespace {

TEST(VertexStrain, AveragesTheStretchSpringsAtEachParticleAndLeavesBendSpringsOut) {
  ClothModel model;
  model.rest_positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)};
  model.springs = {{0, 1, 1.0, SpringKind::kStructural},
                   {1, 2, 1.0, SpringKind::kShear},
                   {2, 3, 1.0, SpringKind::kBend}};
  // 0-1 stretched by half, 1-2 squeezed to 0.8, the bend spring stretched threefold
  const std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(2.3, 0, 0), Vec3(5.3, 0, 0)};
  std::vector<float> strain;
  vertex_strain(model, x, strain);
  ASSERT_EQ(strain.size(), 4u);
  EXPECT_FLOAT_EQ(strain[0], 0.5f);
  EXPECT_FLOAT_EQ(strain[1], (0.5f - 0.2f) / 2);
  EXPECT_FLOAT_EQ(strain[2], -0.2f);
  EXPECT_FLOAT_EQ(strain[3], 0.0f);  // only a bend spring meets it
}

TEST(VertexStrain, AGridScaledUniformlyHasThatStrainEverywhere) {
  GridClothSpec spec;
  spec.nx = 5;
  spec.ny = 4;
  const ClothModel model = make_grid_cloth(spec);
  std::vector<Vec3> x = model.rest_positions;
  for (Vec3& p : x) p *= 1.25;  // about the origin: every length grows by a quarter
  std::vector<float> strain;
  vertex_strain(model, x, strain);
  for (float s : strain) EXPECT_NEAR(s, 0.25f, 1e-6f);
  vertex_strain(model, model.rest_positions, strain);
  for (float s : strain) EXPECT_NEAR(s, 0.0f, 1e-6f);
}

}  // namespace
}  // namespace felt
