#include "core/solids/generalized_mass_spring.hpp"

#include <gtest/gtest.h>

#include "core/solids/solid_fixtures.hpp"

namespace felt {
namespace {

using test::box;

MassSpringMaterial material(Real k_d, Real k_v, Real d_c, Real k_a) {
  MassSpringMaterial m;
  m.distance_stiffness = k_d;
  m.volume_stiffness = k_v;
  m.damping = d_c;
  m.area_stiffness = k_a;
  return m;
}

struct Lattice {
  TetMesh mesh = box({3, 2, 2}, 0.5);
  TetTopology topology = build_topology(mesh);
};

std::vector<Vec3> forces(const GeneralizedMassSpring& model, std::span<const Vec3> x,
                         std::span<const Vec3> v) {
  std::vector<Vec3> f(x.size(), Vec3::Zero());
  model.add_forces(x, v, f);
  return f;
}

// A rigid motion changes no length, area or volume, and a rigid velocity field (v = v₀ + ω × x)
// changes none of them either, so neither the elastic nor the damping terms may act.
TEST(GeneralizedMassSpring, RigidMotionHasNoForce) {
  const Lattice lattice;
  const GeneralizedMassSpring model(lattice.mesh, lattice.topology, material(60, 20, 2, 5));
  const std::vector<Vec3> x =
      test::moved(lattice.mesh.nodes, test::rotation(Vec3(1, 2, 3), 2.1), Vec3(4, -1, 7));
  const Vec3 omega(0.3, -2, 1.5), v0(1, 2, -3);
  std::vector<Vec3> v;
  for (const Vec3& p : x) v.push_back(v0 + omega.cross(p));
  for (const Vec3& f : forces(model, x, v)) EXPECT_LT(f.norm(), 1e-10);
  EXPECT_LT(model.energy(x), 1e-20);
}

// (3.8) conserves linear and angular momentum for any positions and velocities.
TEST(GeneralizedMassSpring, ForcesHaveNoNetForceOrTorque) {
  const Lattice lattice;
  const GeneralizedMassSpring model(lattice.mesh, lattice.topology, material(60, 20, 2, 5));
  std::vector<Vec3> x = lattice.mesh.nodes;
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

// The elastic forces are the negative gradient of the reported energy (central differences),
// which also pins the volume term's energy 3 k_V V₀ C² to the printed force (6.2).
TEST(GeneralizedMassSpring, ElasticForcesAreTheEnergyGradient) {
  const Lattice lattice;
  const GeneralizedMassSpring model(lattice.mesh, lattice.topology, material(60, 20, 0, 5));
  std::vector<Vec3> x = lattice.mesh.nodes;
  const std::vector<Vec3> offsets = test::random_vectors(x.size(), 0.1, 3);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += offsets[n];
  const std::vector<Vec3> zero(x.size(), Vec3::Zero());
  const std::vector<Vec3> f = forces(model, x, zero);
  constexpr Real kDelta = 1e-6;
  for (std::size_t n = 0; n < x.size(); n += 5) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<Vec3> plus = x, minus = x;
      plus[n][axis] += kDelta;
      minus[n][axis] -= kDelta;
      const Real gradient = (model.energy(plus) - model.energy(minus)) / (2 * kDelta);
      EXPECT_NEAR(f[n][axis], -gradient, 1e-6 * (1 + std::abs(gradient)));
    }
  }
}

// The damping term must remove energy: its power Σ f·v = −d_C Σ Ċ² is never positive. The
// printed (6.1) has the opposite sign and would make it positive.
TEST(GeneralizedMassSpring, DampingPowerIsNegative) {
  const Lattice lattice;
  const GeneralizedMassSpring model(lattice.mesh, lattice.topology, material(0, 0, 2, 0));
  for (unsigned seed = 0; seed < 5; ++seed) {
    const std::vector<Vec3> v = test::random_vectors(lattice.mesh.nodes.size(), 1, 10 + seed);
    const std::vector<Vec3> f = forces(model, lattice.mesh.nodes, v);
    Real power = 0;
    for (std::size_t n = 0; n < v.size(); ++n) power += f[n].dot(v[n]);
    EXPECT_LT(power, 0);
  }
}

// A single tetrahedron with the volume term off, one corner moved out along an edge: every edge
// pulls with the magnitude k_D (l − l₀)/l₀² of (6.1) along itself.
TEST(GeneralizedMassSpring, StretchedEdgePullsBackWithHookeForce) {
  TetMesh tet;
  tet.nodes = {Vec3::Zero(), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 2)};
  tet.tets = {{0, 1, 2, 3}};
  const GeneralizedMassSpring model(tet, build_topology(tet), material(60, 0, 0, 0));
  std::vector<Vec3> x = tet.nodes;
  x[1].x() = 2.2;
  const std::vector<Vec3> f = forces(model, x, std::vector<Vec3>(4, Vec3::Zero()));
  // edge 0–1: 60·0.2/4 = 3 N; edges 1–2 and 1–3 (l₀ = 2√2, l = √(2.2² + 4)) pull node 1 too
  const Real l0 = 2 * std::sqrt(2.0), l = std::sqrt(2.2 * 2.2 + 4);
  const Real diagonal = 60 * (l - l0) / (l0 * l0) * 2.2 / l;
  EXPECT_NEAR(f[1].x(), -(3 + 2 * diagonal), 1e-12);
  EXPECT_NEAR(f[0].x(), 3, 1e-12);
}

}  // namespace
}  // namespace felt
