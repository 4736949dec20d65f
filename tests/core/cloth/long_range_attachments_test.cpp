// Long range attachments (Kim, Chentanez & Müller 2012) checked against the rest geometry: on a
// flat grid the shortest path of springs is no shorter than the straight rest distance (the
// geodesic of a flat, convex sheet) and, with diagonal springs, at most cos 22.5° + (√2 − 1)
// sin 22.5° = 1.0824 times it (the octagonal metric's worst direction, 22.5° off an axis).

#include "core/cloth/long_range_attachments.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"

namespace felt {
namespace {

std::vector<Real> inverse_masses(const ClothModel& model, std::span<const std::uint32_t> pins) {
  std::vector<Real> inv_mass(model.particle_count(), 1);
  for (std::uint32_t p : pins) inv_mass[p] = 0;
  return inv_mass;
}

TEST(LongRangeAttachments, AChainIsAttachedToItsPinByTheSumOfItsRestLengths) {
  ClothModel model;
  for (int p = 0; p < 5; ++p) model.rest_positions.emplace_back(0.1 * p * p, 0, 0);
  model.mass.assign(5, 1);
  for (std::uint32_t p = 0; p + 1 < 5; ++p) {
    const Real rest = (model.rest_positions[p + 1] - model.rest_positions[p]).norm();
    model.springs.push_back({p, p + 1, rest, SpringKind::kStructural});
  }
  // a bend spring is no path: it may fold
  model.springs.push_back({0, 4, 1.6, SpringKind::kBend});
  const std::vector<std::uint32_t> pins = {0};
  const auto attachments = long_range_attachments(model, inverse_masses(model, pins));
  ASSERT_EQ(attachments.size(), 4u);
  for (const Attachment& a : attachments) {
    EXPECT_EQ(a.pin, 0u);
    EXPECT_NEAR(a.path_length, 0.1 * a.particle * a.particle, 1e-15);
  }
}

TEST(LongRangeAttachments, UnderATopRowEachParticleHangsFromThePinAboveIt) {
  GridClothSpec spec;
  spec.nx = 7;
  spec.ny = 9;
  spec.width = 0.6;
  spec.height = 0.8;
  const ClothModel model = make_grid_cloth(spec);
  const auto pins = grid_pin_indices(spec, GridPinPreset::kTopRow);
  const auto attachments = long_range_attachments(model, inverse_masses(model, pins));
  ASSERT_EQ(attachments.size(), model.particle_count() - pins.size());
  for (const Attachment& a : attachments) {
    EXPECT_EQ(a.pin, a.particle % spec.nx) << a.particle;
    const Real rows = std::floor(a.particle / spec.nx);
    EXPECT_NEAR(a.path_length, rows * 0.1, 1e-12) << a.particle;
  }
}

TEST(LongRangeAttachments, PathsAreNoShorterThanTheGeodesicOfAFlatSheet) {
  GridClothSpec spec;
  spec.nx = spec.ny = 21;
  const ClothModel model = make_grid_cloth(spec);
  const auto pins = grid_pin_indices(spec, GridPinPreset::kTopCorners);
  const auto attachments = long_range_attachments(model, inverse_masses(model, pins));
  ASSERT_EQ(attachments.size(), model.particle_count() - 2);
  const Real worst_ratio = (std::sqrt(2.0) - 1) * std::sin(M_PI / 8) + std::cos(M_PI / 8);
  for (const Attachment& a : attachments) {
    const Real straight = (model.rest_positions[a.particle] - model.rest_positions[a.pin]).norm();
    EXPECT_GE(a.path_length, straight * (1 - 1e-12)) << a.particle;
    EXPECT_LE(a.path_length, straight * worst_ratio * (1 + 1e-12)) << a.particle;
    // and the pin is the nearer of the two corners
    for (std::uint32_t other : pins) {
      const Real to_other = (model.rest_positions[a.particle] - model.rest_positions[other]).norm();
      EXPECT_LE(straight, to_other * worst_ratio * (1 + 1e-12)) << a.particle;
    }
  }
}

TEST(LongRangeAttachments, AnUnpinnedClothHasNone) {
  GridClothSpec spec;
  spec.nx = spec.ny = 4;
  const ClothModel model = make_grid_cloth(spec);
  EXPECT_TRUE(long_range_attachments(model, inverse_masses(model, {})).empty());
}

}  // namespace
}  // namespace felt
