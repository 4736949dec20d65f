#pragma once
// Lattice bodies, rigid motions, random deformations and the stepping loop shared by the
// soft-solid model tests.

#include <array>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "core/solids/solid_body.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt::test {

/// A box of nx × ny × nz cubic cells of edge `cell`, its minimum corner at the origin.
inline TetMesh box(std::array<int, 3> cells, Real cell) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.cell_size = Vec3::Constant(cell);
  return make_box_lattice(grid);
}

inline SolidMaterial mass_spring(Real node_mass, Real k_d, Real k_v, Real d_c) {
  SolidMaterial material;
  material.model = SolidModel::kMassSpring;
  material.node_mass = node_mass;
  material.mass_spring.distance_stiffness = k_d;
  material.mass_spring.volume_stiffness = k_v;
  material.mass_spring.damping = d_c;
  return material;
}

inline SolidMaterial fem(Real node_mass, Real young, Real poisson, Real damping) {
  SolidMaterial material;
  material.model = SolidModel::kCorotatedFem;
  material.node_mass = node_mass;
  material.fem.young_modulus = young;
  material.fem.poisson_ratio = poisson;
  material.fem.damping = damping;
  return material;
}

inline Mat3 rotation(const Vec3& axis, Real angle) {
  return Eigen::AngleAxis<Real>(angle, axis.normalized()).toRotationMatrix();
}

/// Every point moved by x → R x + t.
inline std::vector<Vec3> moved(std::span<const Vec3> x, const Mat3& r, const Vec3& t) {
  std::vector<Vec3> out;
  for (const Vec3& p : x) out.push_back(r * p + t);
  return out;
}

/// Independent uniform offsets in [−amplitude, amplitude]³, the same for the same seed.
inline std::vector<Vec3> random_vectors(std::size_t n, Real amplitude, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> uniform(-amplitude, amplitude);
  std::vector<Vec3> out(n);
  for (Vec3& v : out) v = Vec3(uniform(random), uniform(random), uniform(random));
  return out;
}

inline Vec3 sum(std::span<const Vec3> f) {
  Vec3 s = Vec3::Zero();
  for (const Vec3& v : f) s += v;
  return s;
}

/// Σ x × f about the origin.
inline Vec3 torque(std::span<const Vec3> x, std::span<const Vec3> f) {
  Vec3 s = Vec3::Zero();
  for (std::size_t n = 0; n < x.size(); ++n) s += x[n].cross(f[n]);
  return s;
}

/// A step of length h as the solid system takes it: n = ⌈h / stable step⌉ equal substeps, then
/// the external forces are cleared.
inline void step(SolidBody& body, Real h, const Vec3& gravity) {
  const int substeps = std::max(1, static_cast<int>(std::ceil(h / body.stable_time_step())));
  for (int s = 0; s < substeps; ++s) {
    body.advance(h / substeps, gravity);
    body.finish_step(h / substeps);
  }
  body.clear_external_forces();
}

/// Kinetic, elastic and gravitational energy.
inline Real total_energy(const SolidBody& body, const Vec3& gravity) {
  Real potential = 0;
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    potential -= body.mass(n) * gravity.dot(body.positions()[n]);
  }
  return body.kinetic_energy() + body.elastic_energy() + potential;
}

inline bool all_finite(const SolidBody& body) {
  for (std::size_t n = 0; n < body.node_count(); ++n) {
    if (!body.positions()[n].allFinite() || !body.velocities()[n].allFinite()) return false;
  }
  return true;
}

}  // namespace felt::test
