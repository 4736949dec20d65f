#pragma once
// All the cloths of a world and the per-step pipeline that moves each of them: the integrator,
// stretch limiting, the colliders, self-collision and the particle constraints, each (sub)step,
// then the health check, with rollback and substeps for a step that fails it; a body keeps the
// substeps a rescue needed (StickySubsteps).

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_self_collision.hpp"
#include "core/cloth/cloth_stable_step.hpp"
#include "core/collision/collider.hpp"
#include "core/step/body_step_counts.hpp"
#include "core/step/energy_balance.hpp"
#include "core/step/health_settings.hpp"
#include "core/step/step_profile.hpp"
#include "core/step/sticky_substeps.hpp"
#include "core/step/substep_rescue.hpp"

namespace felt {

struct ClothStepSettings {
  /// m/s; a particle faster than this is taken as an exploding state and the step is retried
  /// (besides the speed limit scaled from the scene, HealthSettings::speed_growth)
  Real max_speed = std::numeric_limits<Real>::infinity();
  /// A step after which kinetic plus elastic energy exceeds this factor times what it was plus
  /// the work gravity and external forces did is taken as exploding (an unstable mode grows
  /// geometrically; a passive cloth can only lose energy).
  Real max_energy_growth = 2;
  int max_doublings = 6;  ///< retries of a failed step, each with twice the substeps
  HealthSettings health{};
};

struct ClothStepStats {
  int substeps = 1;      ///< the most substeps any cloth needed
  bool rescued = false;  ///< some cloth's step failed and was redone with substeps
  /// cloths (indices) whose step was rescued; no allocation while it stays empty
  std::vector<std::uint32_t> rescued_bodies;
  /// cloths (indices) that could not be rescued: rolled back and stopped; no allocation while
  /// it stays empty
  std::vector<std::uint32_t> unrecoverable;
  /// cloths (indices) whose step reached its budget (HealthSettings::step_budget); no
  /// allocation while it stays empty
  std::vector<std::uint32_t> over_budget;
  StepProfile profile;
};

/// The cloths of a world. Each steps on its own: cloths do not collide with each other.
class ClothSystem {
 public:
  /// The stages a cloth step goes through, in order.
  static constexpr std::array kStages{StepStage::kIntegration, StepStage::kStretchLimit,
                                      StepStage::kColliders,   StepStage::kSelfCollision,
                                      StepStage::kConstraints, StepStage::kHealth};

  explicit ClothSystem(ClothStepSettings settings = {}) : settings_(settings) {}

  const ClothStepSettings& settings() const { return settings_; }

  /// Adds a body and returns its index.
  std::uint32_t add_body(ClothBody body);
  /// Removes the body at `index`; the later ones move down by one.
  void remove_body(std::uint32_t index);
  /// Mutable access: anything that edits a cloth through it makes the next step recompute the
  /// energies its health check starts from.
  std::vector<ClothBody>& bodies() {
    energy_valid_ = false;
    return bodies_;
  }
  const std::vector<ClothBody>& bodies() const { return bodies_; }
  /// A force on particle `p` of cloth `index` for the next step. An external force does not
  /// change the energies the health check carries over, so unlike bodies() this keeps them.
  void add_external_force(std::uint32_t index, std::uint32_t p, const Vec3& force) {
    bodies_[index].add_external_force(p, force);
  }

  /// Advances every cloth from t to t + h. A cloth whose step leaves a non-finite or exploding
  /// state is rolled back and stepped again with 2, 4, ... substeps; if none works it is rolled
  /// back and brought to rest. External forces are cleared afterwards. `yield_point`, if
  /// given, is called between a substep's phases (as in World::step).
  const ClothStepStats& step(Real t, Real h, std::span<const Collider> colliders,
                             const std::function<void()>& yield_point = {});
  const ClothStepStats& last_stats() const { return stats_; }
  /// The substeps a rescue left cloth `index` with, and how many of its steps were rescued.
  const StickySubsteps& substeps(std::uint32_t index) const { return health_[index].substeps; }
  /// The substeps cloth `index` took in its last step (its stable step's, a rescue's) and how
  /// many of its steps reached their budget.
  const BodyStepCounts& step_counts(std::uint32_t index) const { return health_[index].counts; }

 private:
  /// What the health check keeps of one cloth between steps.
  struct BodyHealth {
    EnergyBalance balance;
    StickySubsteps substeps;
    Real size = 0;  ///< m, the diagonal of its bounding box when added
    Real mass = 0;  ///< kg
    Real lightest = std::numeric_limits<Real>::infinity();  ///< kg, of a particle
    CachedStableStep stable_step;
    BodyStepCounts counts;
  };
  /// The energies and forces the health check compares a step's end with.
  struct StepStart {
    Real energy = 0;  ///< kinetic + elastic
    SpeedSources speed{};
    bool first = true;  ///< the attempt is the first of the step, not a retry
  };

  /// The fewest substeps cloth `index` takes in a step of length h: its own max_step's, and
  /// its stable step's unless automatic substeps are off; beyond any budget when no step is
  /// stable.
  std::int64_t fewest_substeps(std::size_t index, Real h);
  /// Steps cloth `index` over [t, t + h] with the health check: rolled back and retried with
  /// substeps while unhealthy, stopped when no retry helps; returns the substeps it took.
  int step_checked(std::size_t index, Real t, Real h, std::int64_t relax_steps,
                   std::span<const Collider> colliders, const std::function<void()>& yield_point);
  /// The same without it (HealthSettings::enabled off): only a non-finite state is caught.
  int step_unchecked(std::size_t index, Real t, Real h, std::span<const Collider> colliders,
                     const std::function<void()>& yield_point);
  /// Steps cloth `index` over [t, t + h] in `substeps` equal parts, each integrator call
  /// within its share of what the step budget has left.
  void advance(std::size_t index, Real t, Real h, int substeps, std::span<const Collider> colliders,
               const std::function<void()>& yield_point);
  /// Stretch limiting of cloth `index` after a substep of length dt, its sweeps and projection
  /// steps each held to `share`, the substep's share of what the step budget has left (as its
  /// integrator's internal steps); a part cut short and unconverged counts as reaching the
  /// budget.
  void limit_stretch(std::size_t index, Real dt, int share);
  /// The most substeps the step budget affords cloth `index`, each of at least its integrator's
  /// least internal steps (xpbd's substeps).
  std::int64_t affordable_substeps(std::size_t index) const;
  /// Cloth `index` took `substeps` in its step, which reached its budget if `over_budget` or an
  /// integrator call stopped at its cap.
  void record_counts(std::size_t index, int substeps, bool over_budget);
  /// After a rescue of cloth `index`: takes the growth of its balance since it started out of
  /// its motion about its centre of mass, as far as that motion holds it. The retried step
  /// cannot undo the growth of the steps before it, which a window sees only once it is there;
  /// left in, it was the start of the next balance, and midpoint on an undamped spring ratcheted
  /// up to 15 times its energy in 5 s.
  void take_back_growth(std::size_t index);
  /// Brings cloth `index` to rest where it is and reports it unrecoverable.
  void stop(std::size_t index);
  /// Whether the state cloth `index` was left in by a step from `start` is healthy; on a
  /// healthy first attempt, keeps its energy and work for the balance.
  bool healthy(std::size_t index, Real t, Real h, StepStart& start);
  /// Cloth `index`'s kinetic and elastic energy (`kinetic_elastic`, J) plus its weight times
  /// its size: what the energy balance's tolerance is a fraction of.
  Real energy_scale(std::size_t index, Real kinetic_elastic) const;
  /// The energy below which a change of body `index`'s energy says nothing: rounding, and the
  /// energy its integrator's accepted position error can show.
  Real energy_floor(std::size_t index) const;
  /// Kinetic, elastic (ClothBody::elastic_energy_in_steps_of) and gravitational energy.
  static Real mechanical_energy(const ClothBody& body, Real h);

  ClothStepSettings settings_;
  std::vector<ClothBody> bodies_;
  std::vector<ClothSelfCollision> self_collision_;  ///< per cloth; keeps its hash between steps
  std::vector<StretchLimiter> limiters_;            ///< per cloth; keeps its long range attachments
  /// kinetic + elastic energy of each body after the last step, reused as the next step's
  /// starting energy unless bodies() was handed out in between
  std::vector<Real> energy_;
  bool energy_valid_ = false;
  std::vector<BodyHealth> health_;  ///< per cloth
  ParticleState backup_;
  /// applied forces (external and wind) at the start of a step, and at its end
  std::vector<Vec3> applied_before_, applied_after_;
  Real work_ = 0;           ///< by the applied forces over the attempt last checked
  std::int64_t spent_ = 0;  ///< of the step budget, by the body being stepped
  bool capped_ = false;     ///< an integrator call of the body being stepped stopped at a cap
  /// the gravitational energy the attempt last checked left, so that a healthy step's
  /// mechanical energy is not summed over every spring again
  Real gravitational_ = 0;
  int window_ = 1;  ///< steps in an energy window at the step length of the last step
  ClothStepStats stats_;
};

}  // namespace felt
