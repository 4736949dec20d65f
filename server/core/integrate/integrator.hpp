#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "core/integrate/dynamic_system.hpp"
#include "core/integrate/particle_state.hpp"
#include "core/integrate/stability_limit.hpp"

namespace felt {

/// Advances a DynamicSystem by one time step. An instance belongs to one body and keeps its
/// scratch buffers between steps, so stepping allocates nothing once sized.
class Integrator {
 public:
  virtual ~Integrator() = default;

  /// The name a scene selects it by.
  virtual std::string_view name() const = 0;

  /// Advances `state` from time t to t + h.
  virtual void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) = 0;

  /// Forgets history kept between steps (position Verlet's previous positions, ...); called
  /// when the state was changed from outside, e.g. rolled back or teleported.
  virtual void reset() {}

  /// The longest step that keeps `mode` from growing (stability_limit.hpp): kNoStepLimit for
  /// the implicit schemes and for adaptive_rk, which chooses its own steps.
  virtual Real step_limit(const OscillatorMode& /*mode*/) const { return kNoStepLimit; }

  /// For an integrator that divides a step itself or iterates in it (adaptive_rk's internal
  /// steps, implicit Euler's conjugate-gradient iterations, projective dynamics' iterations,
  /// xpbd's substeps): the most internal steps each later call may take (never more than its
  /// own cap), and how many the last call took; 1 for the others. A world's step budget counts
  /// them (HealthSettings::step_budget).
  virtual void limit_internal_steps(int /*cap*/) {}
  virtual int last_internal_steps() const { return 1; }
  /// The internal steps every call takes however it is limited: xpbd's substeps, which set its
  /// springs' compliance; 1 for the others.
  virtual int least_internal_steps() const { return 1; }
  /// The last call stopped at a cap before it was done: adaptive_rk accepted an internal step
  /// its error control rejected, implicit Euler's conjugate gradients stopped unconverged.
  virtual bool last_step_capped() const { return false; }

  /// For an integrator with error control (adaptive_rk): the position error on any particle it
  /// accepts per internal step, m; 0 for the others. An error this size shows as elastic and
  /// kinetic energy in a stiff body, which the health check must not count as growth.
  virtual Real position_tolerance() const { return 0; }

  /// For an integrator that projects the springs as constraints (xpbd): how long the substeps
  /// it projects them over are when a step is h; 0 for the others, which apply them as forces.
  virtual Real constraint_substep(Real /*h*/) const { return 0; }
};

/// The integrator called `name`, or nullptr when there is none.
std::unique_ptr<Integrator> make_integrator(std::string_view name);

/// Every name make_integrator accepts.
std::vector<std::string_view> integrator_names();

/// What an integrator asks of a DynamicSystem beyond its masses and forces.
enum class IntegratorNeeds : std::uint8_t {
  kForces,               ///< nothing more: the explicit and symplectic schemes
  kJacobian,             ///< compute_jacobian (implicit Euler)
  kLinearPairs,          ///< linear_force_pairs for its implicit part (IMEX, Desbrun, Kang)
  kDistanceConstraints,  ///< distance_constraints for its springs (XPBD)
};

/// What the integrator called `name` needs, or nothing for an unknown name.
std::optional<IntegratorNeeds> integrator_needs(std::string_view name);

}  // namespace felt
