#pragma once
// XPBD with small steps (Macklin, Müller & Chentanez, "XPBD: Position-Based Simulation of
// Compliant Constrained Dynamics", MIG 2016; Macklin et al., "Small Steps in Physics
// Simulation", SCA 2019). The system's springs become distance constraints of compliance
// α = 1/k; everything else it computes (gravity, drag, wind, anchors, external forces) stays a
// force. A step of h is split into n substeps of h_s = h/n, each with one Gauss–Seidel pass over
// the constraints:
//   v += h_s M⁻¹ f,  x_prev = x,  x += h_s v,  project every constraint once,  v = (x − x_prev)/h_s
// The pass goes class by class through the system's colouring of the constraints (no two in a
// class share a particle; Fratarcangeli, Tibaldo & Pellacini 2016, "Vivace"): in the cloth's
// row-by-row order, where each spring's correction feeds at once into the next one's, a stiff
// hanging cloth gained energy without bound (k = 4000 N/m on 40 × 40 at 1/240 s in 1-16
// substeps, docs/results/peers.md).
// The compliance and damping are in physical units, so a material behaves the same at any h
// and n, up to the method's error, which falls with h_s.

#include <vector>

#include "core/integrate/integrator.hpp"

namespace felt {

class XpbdIntegrator final : public Integrator {
 public:
  static constexpr int kDefaultSubsteps = 1;
  static constexpr int kMaxSubsteps = 1000;

  /// Takes `substeps` (1 to kMaxSubsteps) substeps per step.
  explicit XpbdIntegrator(int substeps = kDefaultSubsteps);

  std::string_view name() const override { return "xpbd"; }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override;
  Real constraint_substep(Real h) const override { return h / substeps_; }

  int substeps() const { return substeps_; }
  /// Its substeps count in the step budget as internal steps; their number is the scene's
  /// (the loader refuses one the budget cannot afford), not cut by the budget, since the
  /// springs' compliance is set for substeps of h / substeps.
  int last_internal_steps() const override { return substeps_; }
  int least_internal_steps() const override { return substeps_; }

 private:
  void project_constraints(std::span<const Real> inv_mass, Real h, ParticleState& state) const;
  void project(const DistanceConstraint& c, std::span<const Real> inv_mass, Real h,
               std::vector<Vec3>& x) const;

  int substeps_;
  ConstraintClasses constraints_;
  std::vector<Vec3> x_prev_;
  std::vector<Vec3> f_;
};

}  // namespace felt
