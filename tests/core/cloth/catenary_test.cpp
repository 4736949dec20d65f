// A hanging chain of stiff springs pinned at both ends settles into the analytic catenary.

#include <cmath>
#include <string_view>

#include <gtest/gtest.h>

#include "core/world/world.hpp"

namespace felt {
namespace {

/// Solves L = 2a sinh(D / 2a) for the catenary parameter a by bisection.
Real catenary_parameter(Real span, Real length) {
  Real lo = 1e-3, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const Real a = 0.5 * (lo + hi);
    (2 * a * std::sinh(span / (2 * a)) > length ? lo : hi) = a;
  }
  return 0.5 * (lo + hi);
}

/// 81 equal masses on 80 stiff links of total length 1.5 m, ends pinned 1 m apart, stepped with
/// `integrator` until at rest, against the analytic curve.
void expect_catenary(std::string_view integrator) {
  SCOPED_TRACE(integrator);
  const int links = 80;
  const Real span = 1.0, length = 1.5, total_mass = 0.4;
  auto model = std::make_shared<ClothModel>();
  for (int i = 0; i <= links; ++i) {
    // start straight but folded into the span: the rest lengths carry the real length
    model->rest_positions.push_back(Vec3(span * i / links, 0, 0));
    model->uv.push_back(Vec2::Zero());
    // end particles carry half a link: the chain's weight is uniform along its length
    model->mass.push_back(total_mass / links * (i == 0 || i == links ? 0.5 : 1.0));
  }
  for (std::uint32_t i = 0; i < links; ++i) {
    model->springs.push_back({i, i + 1, length / links, SpringKind::kStructural});
  }
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 2e5, 2};
  params.drag = 0.05;
  World world(WorldSettings{Vec3(0, -9.81, 0), 2e-3, 100, 6});
  world.add_body(ClothBody("chain", model, params, make_integrator(integrator)));
  ClothBody& chain = world.cloths()[0];
  chain.pin(0);
  chain.pin(links);
  for (int n = 0; n < 5000; ++n) world.step();
  ASSERT_LT(chain.kinetic_energy(), 1e-12);

  // y(x) = a cosh((x − D/2)/a) − a cosh(D/2a), measured from the pins; the stretched length is
  // slightly longer than the rest length, so compare with the catenary of the actual length
  Real actual_length = 0;
  for (int i = 0; i < links; ++i)
    actual_length += (chain.state().x[i + 1] - chain.state().x[i]).norm();
  EXPECT_LT(actual_length / length - 1, 1e-3);  // stiff: stretched by less than 0.1%
  const Real a = catenary_parameter(span, actual_length);
  const Real sag = a * std::cosh(span / (2 * a)) - a;
  Real worst = 0;
  for (const Vec3& p : chain.state().x) {
    const Real expected = a * std::cosh((p.x() - span / 2) / a) - a * std::cosh(span / (2 * a));
    worst = std::max(worst, std::abs(p.y() - expected));
  }
  // a chain of 80 discrete links differs from the continuous curve by O(1/links²) of the sag
  EXPECT_LT(worst / sag, 2e-3) << "sag " << sag << " worst " << worst;
}

TEST(Catenary, HangingChainMatchesTheAnalyticCurve) {
  expect_catenary("implicit_euler");
  expect_catenary("projective_dynamics");
}

}  // namespace
}  // namespace felt
