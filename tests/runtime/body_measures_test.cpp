// What feltd run --trace and feltd compare measure of bodies: strain and compression from the
// rest lengths, NaN passed on rather than skipped, and distances from a reference run.

#include "runtime/body_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/cloth/cloth_grid.hpp"
#include "runtime/trajectory_error.hpp"

namespace felt {
namespace {

/// A 3 x 3 cloth of 0.9 kg, 1 m square, in the xy plane about the origin, at rest.
ClothBody square_cloth() {
  GridClothSpec spec;
  spec.nx = spec.ny = 3;
  spec.total_mass = 0.9;
  return ClothBody("square", std::make_shared<const ClothModel>(make_grid_cloth(spec)), {},
                   make_integrator("symplectic_euler"));
}

TEST(BodyMeasures, StrainAndCompressionAreMeasuredFromTheRestLengths) {
  ClothBody cloth = square_cloth();
  // particle 1 (top middle) 0.1 m right: the structural spring 0-1 (rest 0.5 m) stretches by
  // 20 %, 1-2 shortens by 20 %; no shear spring changes as much
  cloth.state().x[1].x() += 0.1;
  const BodyMeasures m = measure_body(cloth);
  EXPECT_NEAR(m.max_strain, 0.2, 1e-12);
  EXPECT_NEAR(m.max_compression, 0.2, 1e-12);
  // nine particles of 0.1 kg; one moved by 0.1 m
  EXPECT_NEAR(m.centre_of_mass.x(), 0.1 / 9, 1e-12);
  EXPECT_EQ(m.lower, Vec3(-0.5, -0.5, 0));
  EXPECT_EQ(m.upper, Vec3(0.5, 0.5, 0));
}

TEST(BodyMeasures, ANonFinitePositionIsReportedNotSkipped) {
  ClothBody cloth = square_cloth();
  cloth.state().x[4].y() = std::numeric_limits<Real>::quiet_NaN();
  const BodyMeasures m = measure_body(cloth);
  EXPECT_TRUE(std::isnan(m.max_strain));
  EXPECT_TRUE(std::isnan(m.max_compression));
  EXPECT_TRUE(std::isnan(m.lower.y()));
  EXPECT_TRUE(std::isnan(m.upper.x()));
  EXPECT_TRUE(std::isnan(m.centre_of_mass.y()));
}

TEST(TrajectoryError, DistancesFromTheReferenceOverParticlesAndSamples) {
  World reference_world;
  reference_world.add_body(square_cloth());
  ReferenceTrajectory reference;
  reference.add(reference_world);
  reference.add(reference_world);

  World world;
  world.add_body(square_cloth());
  TrajectoryError error(reference);
  ASSERT_TRUE(error.add(world, 0));
  world.cloths()[0].state().x[0].z() += 0.3;  // one particle of nine, at the second sample
  ASSERT_TRUE(error.add(world, 1));
  const std::vector<BodyError> errors = error.errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].name, "square");
  EXPECT_NEAR(errors[0].max, 0.3, 1e-15);
  EXPECT_NEAR(errors[0].end, 0.3, 1e-15);
  EXPECT_NEAR(errors[0].rms, std::sqrt(0.09 / 18), 1e-15);

  World other;  // not the reference's bodies
  EXPECT_FALSE(TrajectoryError(reference).add(other, 0));
}

}  // namespace
}  // namespace felt
