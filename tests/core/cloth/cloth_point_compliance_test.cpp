// A cloth's stiffness at its points (point_compliance) against statics worked by hand: a taut
// string pinned at both ends under a point load, and a particle held by an anchor.

#include <array>
#include <memory>

#include <gtest/gtest.h>

#include "core/cloth/cloth_point_compliance.hpp"
#include "core/integrate/integrator.hpp"

namespace felt {
namespace {

constexpr int kLinks = 10;
constexpr Real kSpring = 100;  // N/m per link

/// A string of kLinks springs of rest length `rest` held straight along x at length `length`
/// each, its end particles pinned.
ClothBody taut_string(Real rest, Real length) {
  auto model = std::make_shared<ClothModel>();
  for (int i = 0; i <= kLinks; ++i) {
    model->rest_positions.push_back(Vec3(length * i, 0, 0));
    model->uv.push_back(Vec2::Zero());
    model->mass.push_back(0.01);
  }
  for (std::uint32_t i = 0; i < kLinks; ++i) {
    model->springs.push_back({i, i + 1, rest, SpringKind::kStructural});
  }
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, kSpring, 0.1};
  ClothBody body("string", model, params, make_integrator("symplectic_euler"));
  body.pin(0);
  body.pin(kLinks);
  return body;
}

Real stiffness_at(const ClothBody& body, std::uint32_t node, const Vec3& direction) {
  const std::array<WeightedNode, 1> load{WeightedNode{node, 1}};
  return point_compliance(body).stiffness(load, direction);
}

TEST(ClothPointCompliance, ATautStringResistsAPointLoadByItsTensionOverBothSides) {
  const Real rest = 0.1, length = 0.12;
  const ClothBody string = taut_string(rest, length);
  const Real tension = kSpring * (length - rest);
  for (std::uint32_t m = 1; m < kLinks; ++m) {
    // across: the string's two sides, each of tension T over its length a, in parallel
    // (k = T/a + T/(L − a), the taut string's static deflection under a point load)
    const Real a = length * m, b = length * (kLinks - m);
    EXPECT_NEAR(stiffness_at(string, m, Vec3::UnitY()), tension / a + tension / b, 1e-9) << m;
    EXPECT_NEAR(stiffness_at(string, m, Vec3::UnitZ()), tension / a + tension / b, 1e-9) << m;
    // along: m springs in series on one side, kLinks − m on the other
    EXPECT_NEAR(stiffness_at(string, m, Vec3::UnitX()), kSpring / m + kSpring / (kLinks - m), 1e-9)
        << m;
  }
}

TEST(ClothPointCompliance, APointOnASegmentIsStifferThanItsLoosestCorner) {
  const ClothBody string = taut_string(0.1, 0.12);
  const PointCompliance compliance = point_compliance(string);
  // half the load on each of nodes 4 and 5: bᵀ K⁻¹ b of a spread load is below the mean of the
  // corners' compliances (K⁻¹ is positive definite), so the point is stiffer than either corner
  const std::array<WeightedNode, 2> spread{WeightedNode{4, 0.5}, WeightedNode{5, 0.5}};
  const Real between = compliance.stiffness(spread, Vec3::UnitY());
  EXPECT_GT(between, stiffness_at(string, 4, Vec3::UnitY()));
  EXPECT_GT(between, stiffness_at(string, 5, Vec3::UnitY()));
  // a load on a pinned node alone moves nothing that is free: unknown, not infinite
  const std::array<WeightedNode, 1> pinned{WeightedNode{0, 1}};
  EXPECT_EQ(compliance.stiffness(pinned, Vec3::UnitY()), 0);
  const std::array<WeightedNode, 1> outside{WeightedNode{kLinks + 1, 1}};
  EXPECT_EQ(compliance.stiffness(outside, Vec3::UnitY()), 0);
}

TEST(ClothPointCompliance, AnAnchorHoldsItsParticleByItsOwnStiffness) {
  ClothBody string = taut_string(0.1, 0.12);
  string.unpin(kLinks);
  string.set_anchor({kLinks, Vec3(kLinks * 0.12, 0, 0), 250, 1});
  // the anchor in series with nothing else at its own particle: along the string the chain of
  // kLinks springs from the pin is in parallel with it
  EXPECT_NEAR(stiffness_at(string, kLinks, Vec3::UnitX()), 250 + kSpring / kLinks, 1e-9);
}

TEST(ClothPointCompliance, AStringNothingStretchesOrHoldsIsOfUnknownStiffness) {
  // at its rest length the string has no tension, so nothing resists a push across it: a flat
  // cloth at rest is the same, which is why the shape now is used and not the rest shape
  EXPECT_FALSE(point_compliance(taut_string(0.1, 0.1)).known());
  ClothBody loose = taut_string(0.1, 0.12);
  loose.unpin(0);
  loose.unpin(kLinks);
  EXPECT_FALSE(point_compliance(loose).known());
  EXPECT_EQ(stiffness_at(loose, 5, Vec3::UnitY()), 0);
}

TEST(ClothPointCompliance, OverAHorizonAFreeParticleResistsByItsMass) {
  // a force held for τ moves a free mass by F τ² / 2m: a spring of 2m/τ²; anchored, the anchor's
  // stiffness adds to it
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3::Zero()};
  model->uv = {Vec2::Zero()};
  model->mass = {0.02};
  ClothBody particle("particle", model, ClothParams{}, make_integrator("symplectic_euler"));
  EXPECT_FALSE(point_compliance(particle).known());
  const Real tau = 0.05, inertia = 2 * 0.02 / (tau * tau);
  const std::array<WeightedNode, 1> load{WeightedNode{0, 1}};
  EXPECT_NEAR(point_compliance(particle, tau).stiffness(load, Vec3::UnitX()), inertia, 1e-9);
  particle.set_anchor({0, Vec3::Zero(), 30, 0});
  EXPECT_NEAR(point_compliance(particle, tau).stiffness(load, Vec3::UnitY()), inertia + 30, 1e-9);
  EXPECT_NEAR(point_compliance(particle).stiffness(load, Vec3::UnitY()), 30, 1e-9);
}

}  // namespace
}  // namespace felt
