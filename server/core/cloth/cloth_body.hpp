#pragma once
// A simulated cloth: an immutable ClothModel plus its state, parameters and integrator.

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/cloth/cloth_model.hpp"
#include "core/cloth/constraint_force.hpp"
#include "core/cloth/particle_constraint.hpp"
#include "core/cloth/spring_colouring.hpp"
#include "core/cloth/stretch_limiter.hpp"
#include "core/integrate/dynamic_system.hpp"
#include "core/integrate/integrator.hpp"
#include "core/integrate/particle_state.hpp"

namespace felt {

/// Air moving past a cloth. Each triangle feels c·A·((w − v)·n) n, shared by its corners: w the
/// wind velocity, v the triangle's mean velocity, n its unit normal, A its area, c the drag
/// coefficient (about ½ρC_d ≈ 0.6 kg/m³ for air). Gusts scale w by 1 + a·sin(2πt/T) (the
/// thesis's sin(t²) + ½ is not periodic and speeds up without bound, so a plain sine instead).
struct Wind {
  bool enabled = false;
  Vec3 velocity = Vec3::Zero();  ///< m/s
  Real drag_coefficient = 0.6;   ///< kg/m³
  Real gust_amplitude = 0;       ///< a, relative
  Real gust_period = 2;          ///< T, s
};

/// A particle tied by a damped zero-length spring to a target it follows (thesis 1 §5, the
/// soft "follow a point" variant): f = k (target − x) − c v.
struct Anchor {
  std::uint32_t particle = 0;
  Vec3 target = Vec3::Zero();
  Real stiffness = 0;  ///< N/m
  Real damping = 0;    ///< N·s/m
};

/// Force parameters of a cloth (thesis 1 §2).
struct ClothParams {
  std::array<SpringParams, kSpringKindCount> springs;  ///< indexed by SpringKind
  Real drag = 0;                                       ///< viscous drag k_d: f = −k_d v, N·s/m
  StretchLimit stretch;                                ///< inverse dynamics after each step
  Real thickness = 0.005;  ///< m; how close particles may come to a collider or each other
  /// Particles pushed away from the cloth's own triangles (ClothSelfCollision), opt-in.
  bool self_collision = false;
  Wind wind;

  SpringParams& spring(SpringKind kind) { return springs[static_cast<int>(kind)]; }
  const SpringParams& spring(SpringKind kind) const { return springs[static_cast<int>(kind)]; }
};

class ClothBody final : public DynamicSystem {
 public:
  ClothBody(std::string name, std::shared_ptr<const ClothModel> model, ClothParams params,
            std::unique_ptr<Integrator> integrator);

  const std::string& name() const { return name_; }
  const ClothModel& model() const { return *model_; }
  const std::shared_ptr<const ClothModel>& shared_model() const { return model_; }
  /// How many vertices clients see: the particles (as SolidBody::surface_vertex_count).
  std::size_t surface_vertex_count() const { return model_->particle_count(); }
  const ClothParams& params() const { return params_; }
  void set_params(const ClothParams& params) { params_ = params; }
  const ParticleState& state() const { return state_; }
  ParticleState& state() { return state_; }
  Integrator& integrator() { return *integrator_; }
  const Integrator& integrator() const { return *integrator_; }
  void set_integrator(std::unique_ptr<Integrator> integrator);

  /// The longest step this body takes, s: a longer world step is taken in equal substeps
  /// (the user's trade of speed for accuracy; a stable step may ask for more). Infinite: none.
  Real max_step() const { return max_step_; }
  void set_max_step(Real max_step);

  /// Fixes particle p where it is (inverse mass 0, velocity 0).
  void pin(std::uint32_t p);
  void unpin(std::uint32_t p);

  /// Holds a particle in a plane or on a line through where it is now.
  void constrain(ParticleConstraint::Kind kind, std::uint32_t p, const Vec3& direction);
  const std::vector<ParticleConstraint>& constraints() const { return constraints_; }

  /// Ties a particle to a target by a soft spring, replacing any anchor it had.
  void set_anchor(const Anchor& anchor);
  void remove_anchor(std::uint32_t p);
  const std::vector<Anchor>& anchors() const { return anchors_; }

  /// Keeps a particle on a sphere or plane by a Witkin constraint force, added last in
  /// compute_forces so every integrator sees it (implicit ones explicitly: it has no Jacobian
  /// term). A particle may have several; a plane's normal is normalized here.
  void add_constraint_force(const ConstraintForce& constraint);
  /// Removes every constraint force on particle p.
  void remove_constraint_forces(std::uint32_t p);
  const std::vector<ConstraintForce>& constraint_forces() const { return constraint_forces_; }

  /// Moves a particle to `target` outright (the kinematic "follow a point" of thesis 1 §5); for
  /// pinned particles, whose position nothing else changes. Its velocity becomes 0.
  void move_particle(std::uint32_t p, const Vec3& target);
  bool is_pinned(std::uint32_t p) const { return inv_mass_[p] == 0; }

  void set_gravity(const Vec3& gravity) { gravity_ = gravity; }

  /// Adds a force on particle p for the next step only (user and haptic forces).
  void add_external_force(std::uint32_t p, const Vec3& force) { external_force_[p] += force; }
  void clear_external_forces();

  /// Σ ½ m v² over all particles, J.
  Real kinetic_energy() const;
  /// Σ ½ k (|l| − r)² over the enabled springs and ½ k |target − x|² over the anchors, J. With
  /// a `constraint_substep` h > 0 (springs projected as XPBD constraints over substeps that
  /// long), a spring counts at the stiffness its projection pushes with, k / (1 + k w h²), w
  /// the inverse masses of its ends (XPBD eq. 18: Δλ = −k h² C / (k h² w + 1) is a force
  /// k C / (1 + k w h²)): a spring stiffer than its particles can follow in one substep acts
  /// with about their m / h², and a violation a Gauss–Seidel pass leaves holds that much.
  Real elastic_energy(Real constraint_substep = 0) const;
  /// The elastic energy at the stiffness the body's integrator applies its springs with in
  /// steps of length h (the nominal one unless it projects them as constraints): what the
  /// health check counts.
  Real elastic_energy_in_steps_of(Real h) const {
    return elastic_energy(integrator_->constraint_substep(h));
  }
  /// −Σ m g·x over all particles, J: zero at the origin, so only its changes mean anything.
  Real gravitational_energy() const;
  const std::vector<Vec3>& external_forces() const { return external_force_; }
  /// The forces from outside the body that can add energy to it at time t, in the state it is
  /// in: the external forces and the wind (for the health check's energy balance).
  void applied_forces(Real t, std::span<Vec3> f) const;
  const Vec3& gravity() const { return gravity_; }
  /// Largest relative elongation |l|/r − 1 over the structural and shear springs: negative
  /// when all are compressed, NaN when a length is not finite, 0 without such springs.
  Real max_strain() const;
  /// Largest relative compression 1 − |l|/r over the same springs (negative when all are
  /// stretched), NaN as max_strain.
  Real max_compression() const;

  // DynamicSystem
  std::span<const Real> inv_mass() const override { return inv_mass_; }
  void compute_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real t,
                      std::span<Vec3> f) const override;
  bool compute_jacobian(std::span<const Vec3> x, std::span<const Vec3> v,
                        ForceJacobian& jacobian) const override;
  /// The enabled structural springs' linear part −k_s l and their damping, taken isotropic
  /// (Eberhardt et al. 2000, thesis 1 §4.4); shear and bend stay explicit.
  bool linear_force_pairs(std::vector<LinearPair>& pairs) const override;
  /// Every enabled spring, with its kind's stiffness and damping, in the classes of the
  /// springs' colouring.
  bool distance_constraints(ConstraintClasses& constraints) const override;
  void compute_forces_besides_constraints(std::span<const Vec3> x, std::span<const Vec3> v, Real t,
                                          std::span<Vec3> f) const override;

 private:
  void compute_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real t, std::span<Vec3> f,
                      bool with_springs) const;
  struct StrainRange {
    Real largest = 0;
    Real smallest = 0;
  };
  /// The largest and smallest |l|/r − 1 over the structural and shear springs.
  StrainRange strain_range() const;
  void add_wind_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real t,
                       std::span<Vec3> f) const;

  std::string name_;
  std::shared_ptr<const ClothModel> model_;
  SpringColouring spring_colouring_;  ///< of model_'s springs, for distance_constraints
  ClothParams params_;
  std::unique_ptr<Integrator> integrator_;
  Real max_step_ = std::numeric_limits<Real>::infinity();
  ParticleState state_;
  std::vector<Real> inv_mass_;
  std::vector<ParticleConstraint> constraints_;
  std::vector<Anchor> anchors_;
  std::vector<ConstraintForce> constraint_forces_;
  Vec3 gravity_ = Vec3::Zero();
  std::vector<Vec3> external_force_;
};

}  // namespace felt
