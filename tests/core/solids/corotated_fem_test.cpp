#include "core/solids/corotated_fem.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/solids/solid_fixtures.hpp"

namespace felt {
namespace {

using test::box;

FemMaterial material(Real young, Real poisson, Real damping) {
  FemMaterial m;
  m.young_modulus = young;
  m.poisson_ratio = poisson;
  m.damping = damping;
  return m;
}

std::vector<Vec3> forces(const CorotatedFem& model, std::span<const Vec3> x,
                         std::span<const Vec3> v) {
  std::vector<Vec3> f(x.size(), Vec3::Zero());
  model.add_forces(x, v, f);
  return f;
}

// Corotation: a rotation by 150° (far beyond linear elasticity) and a translation, moving at a
// rigid velocity, give no elastic and no damping force.
TEST(CorotatedFem, LargeRotationHasNoForce) {
  const TetMesh mesh = box({3, 2, 2}, 0.5);
  const CorotatedFem model(mesh, material(1e4, 0.3, 0.05));
  const std::vector<Vec3> x =
      test::moved(mesh.nodes, test::rotation(Vec3(1, 1, 0), 2.6), Vec3(-2, 5, 1));
  const Vec3 omega(3, -1, 2);
  std::vector<Vec3> v;
  for (const Vec3& p : x) v.push_back(Vec3(1, 0, 0) + omega.cross(p));
  for (const Vec3& f : forces(model, x, v)) EXPECT_LT(f.norm(), 1e-9);
  EXPECT_LT(model.energy(x), 1e-20);
}

TEST(CorotatedFem, ForcesHaveNoNetForceOrTorque) {
  const TetMesh mesh = box({3, 2, 2}, 0.5);
  const CorotatedFem model(mesh, material(1e4, 0.3, 0.05));
  std::vector<Vec3> x = mesh.nodes;
  const std::vector<Vec3> offsets = test::random_vectors(x.size(), 0.15, 1);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += offsets[n];
  const std::vector<Vec3> v = test::random_vectors(x.size(), 3, 2);
  const std::vector<Vec3> f = forces(model, x, v);
  Real scale = 0;
  for (const Vec3& fn : f) scale = std::max(scale, fn.norm());
  ASSERT_GT(scale, 1);
  EXPECT_LT(test::sum(f).norm(), 1e-12 * scale * f.size());
  EXPECT_LT(test::torque(x, f).norm(), 1e-12 * scale * f.size());
}

// The elastic forces are the negative gradient of the reported energy (central differences).
TEST(CorotatedFem, ElasticForcesAreTheEnergyGradient) {
  const TetMesh mesh = box({2, 2, 1}, 0.5);
  const CorotatedFem model(mesh, material(1e4, 0.3, 0));
  std::vector<Vec3> x = mesh.nodes;
  const std::vector<Vec3> offsets = test::random_vectors(x.size(), 0.1, 3);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += offsets[n];
  const std::vector<Vec3> f = forces(model, x, std::vector<Vec3>(x.size(), Vec3::Zero()));
  constexpr Real kDelta = 1e-6;
  for (std::size_t n = 0; n < x.size(); ++n) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<Vec3> plus = x, minus = x;
      plus[n][axis] += kDelta;
      minus[n][axis] -= kDelta;
      const Real gradient = (model.energy(plus) - model.energy(minus)) / (2 * kDelta);
      EXPECT_NEAR(f[n][axis], -gradient, 1e-5 * (1 + std::abs(gradient)));
    }
  }
}

// A corner pushed through the opposite face is pushed back out, not further in.
TEST(CorotatedFem, InvertedElementIsPushedBack) {
  TetMesh tet;
  tet.nodes = {Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.tets = {{0, 1, 2, 3}};
  const CorotatedFem model(tet, material(1e3, 0.3, 0));
  std::vector<Vec3> x = tet.nodes;
  x[3].z() = -0.2;
  const std::vector<Vec3> f = forces(model, x, std::vector<Vec3>(4, Vec3::Zero()));
  EXPECT_GT(f[3].z(), 0);
}

// A bar clamped at x = 0 and pulled at x = L by a total force F spread as a uniform traction
// (consistent nodal loads, a third of each end triangle's share at its corners) settles at the
// elongation F L / (E A). With Poisson's ratio 0 the clamp does not constrain the cross
// section, and the exact solution is linear, which linear tetrahedra represent.
TEST(CorotatedFem, ClampedBarStretchesByFLOverEA) {
  constexpr Real kLength = 1, kSide = 0.2, kYoung = 1e4, kForce = 0.4;
  SolidBody body("bar", box({5, 1, 1}, kSide), test::fem(0.01, kYoung, 0, 2e-3));
  std::vector<Vec3> load(body.node_count(), Vec3::Zero());
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if (body.rest().nodes[n].x() == 0) body.pin(n);
  }
  for (const Triangle& t : body.topology().surface) {
    const auto& x = body.rest().nodes;
    if (x[t[0]].x() != kLength || x[t[1]].x() != kLength || x[t[2]].x() != kLength) continue;
    const Real area = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    for (std::uint32_t n : t) load[n].x() += kForce / (kSide * kSide) * area / 3;
  }
  ASSERT_NEAR(test::sum(load).x(), kForce, 1e-12);
  for (int s = 0; s < 1000; ++s) {
    for (std::uint32_t n = 0; n < body.node_count(); ++n) body.add_external_force(n, load[n]);
    test::step(body, 0.002, Vec3::Zero());
  }
  const Real expected = kForce * kLength / (kYoung * kSide * kSide);
  EXPECT_LT(body.kinetic_energy(), 1e-6 * kForce * expected);  // settled
  Real elongation = 0;
  int count = 0;
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if (body.rest().nodes[n].x() != kLength) continue;
    elongation += body.positions()[n].x() - kLength;
    ++count;
  }
  elongation /= count;
  EXPECT_NEAR(elongation, expected, 0.02 * expected);
}

/// Positions after `duration` of an undamped small oscillation from a random deformation at
/// rest, at fixed steps of h.
std::vector<Vec3> oscillation(Real h, Real duration) {
  SolidBody body("bar", box({2, 1, 1}, 0.5), test::fem(0.05, 1e3, 0.3, 0));
  body.pin(0);
  const std::vector<Vec3> offsets = test::random_vectors(body.node_count(), 0.01, 5);
  for (std::size_t n = 1; n < body.node_count(); ++n) body.positions()[n] += offsets[n];
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int s = 0; s < steps; ++s) {
    body.advance(h, Vec3::Zero());
    body.finish_step(h);
  }
  return body.positions();
}

// Position Verlet with its Taylor start converges with order 2: halving the step quarters the
// error against a run at a much finer step. The coarsest step is 0.35 of the stable one (a
// quarter of the true limit), where the error has reached its asymptotic order.
TEST(CorotatedFem, VerletConvergesWithOrderTwo) {
  const Real h =
      0.35 * SolidBody("bar", box({2, 1, 1}, 0.5), test::fem(0.05, 1e3, 0.3, 0)).stable_time_step();
  const Real duration = 64 * h;
  const std::vector<Vec3> reference = oscillation(h / 64, duration);
  std::vector<Real> errors;
  for (Real step : {h, h / 2, h / 4}) {
    const std::vector<Vec3> x = oscillation(step, duration);
    Real error = 0;
    for (std::size_t n = 0; n < x.size(); ++n)
      error = std::max(error, (x[n] - reference[n]).norm());
    errors.push_back(error);
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const Real order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_NEAR(order, 2, 0.25) << errors[i - 1] << " " << errors[i];
  }
}

}  // namespace
}  // namespace felt
