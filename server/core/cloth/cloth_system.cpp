#include "core/cloth/cloth_system.hpp"

#include <algorithm>
#include <cmath>

#include "core/math/all_finite.hpp"
#include "core/math/bounds_of.hpp"
#include "core/math/check.hpp"
#include "core/step/internal_motion.hpp"
#include "core/step/substeps_for.hpp"

namespace felt {

std::uint32_t ClothSystem::add_body(ClothBody body) {
  BodyHealth health;
  if (!body.state().x.empty()) health.size = bounds_of(body.state().x).diagonal().norm();
  for (Real m : body.model().mass) {
    health.mass += m;
    health.lightest = std::min(health.lightest, m);
  }
  bodies_.push_back(std::move(body));
  self_collision_.emplace_back();
  limiters_.emplace_back();
  health_.push_back(health);
  energy_valid_ = false;
  return static_cast<std::uint32_t>(bodies_.size() - 1);
}

void ClothSystem::remove_body(std::uint32_t index) {
  FELT_CHECK(index < bodies_.size());
  bodies_.erase(bodies_.begin() + index);
  self_collision_.erase(self_collision_.begin() + index);
  limiters_.erase(limiters_.begin() + index);
  health_.erase(health_.begin() + index);
  energy_valid_ = false;
}

Real ClothSystem::mechanical_energy(const ClothBody& body, Real h) {
  return body.kinetic_energy() + body.elastic_energy_in_steps_of(h) + body.gravitational_energy();
}

Real ClothSystem::energy_scale(std::size_t index, Real kinetic_elastic) const {
  return kinetic_elastic +
         health_[index].mass * bodies_[index].gravity().norm() * health_[index].size +
         energy_floor(index);
}

Real ClothSystem::energy_floor(std::size_t index) const {
  const ClothBody& body = bodies_[index];
  const Real tolerance = body.integrator().position_tolerance();
  if (tolerance == 0) return kEnergyFloor;
  // each spring's ends off by the tolerance in opposite directions: ½ k (2τ)². adaptive_rk at
  // 1e-6 m leaves a 1 g cloth of 1e4 N/m with 5e-7 J of kinetic energy in a step in which
  // gravity does 1e-8 J of work: its stiff modes rung at the tolerance's amplitude
  Real stiffness = 0;
  for (const Spring& spring : body.model().springs) {
    const SpringParams& params = body.params().spring(spring.kind);
    if (params.enabled) stiffness += params.stiffness;
  }
  return kEnergyFloor + 2 * stiffness * tolerance * tolerance;
}

const ClothStepStats& ClothSystem::step(Real t, Real h, std::span<const Collider> colliders,
                                        const std::function<void()>& yield_point) {
  stats_.substeps = 1;
  stats_.rescued = false;
  stats_.rescued_bodies.clear();
  stats_.unrecoverable.clear();
  stats_.over_budget.clear();
  stats_.profile = {};
  if (!settings_.health.enabled) {
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      stats_.substeps = std::max(stats_.substeps, step_unchecked(b, t, h, colliders, yield_point));
      bodies_[b].clear_external_forces();
    }
    energy_valid_ = false;  // not kept: a check turned on starts from the state as it is then
    return stats_;
  }
  if (!energy_valid_) {
    energy_.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      energy_[b] = bodies_[b].kinetic_energy() + bodies_[b].elastic_energy_in_steps_of(h);
      health_[b].balance.reset(mechanical_energy(bodies_[b], h));
    }
  }
  const auto relax_steps = static_cast<std::int64_t>(std::ceil(settings_.health.relax_after / h));
  window_ = std::max(HealthSettings::kMinWindowSteps,
                     static_cast<int>(std::ceil(settings_.health.energy_window / h)));
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    stats_.substeps =
        std::max(stats_.substeps, step_checked(b, t, h, relax_steps, colliders, yield_point));
    bodies_[b].clear_external_forces();
  }
  energy_valid_ = true;
  return stats_;
}

int ClothSystem::step_checked(std::size_t index, Real t, Real h, std::int64_t relax_steps,
                              std::span<const Collider> colliders,
                              const std::function<void()>& yield_point) {
  ClothBody& body = bodies_[index];
  // copy-assignment into equally sized vectors reuses their storage: no allocation
  backup_.x = body.state().x;
  backup_.v = body.state().v;
  applied_before_.resize(body.state().size());
  body.applied_forces(t, applied_before_);
  StepStart start{.energy = energy_[index]};
  // squared, so that one square root is taken for all
  Real fastest_sq = 0, acceleration_sq = 0;
  for (std::size_t p = 0; p < backup_.size(); ++p) {
    const Real mass = body.model().mass[p];
    fastest_sq = std::max(fastest_sq, backup_.v[p].squaredNorm());
    acceleration_sq = std::max(acceleration_sq, applied_before_[p].squaredNorm() / (mass * mass));
  }
  start.speed.fastest = std::sqrt(fastest_sq);
  start.speed.acceleration = body.gravity().norm() + std::sqrt(acceleration_sq);
  start.speed.reachable = std::sqrt(2 * start.energy / health_[index].lightest);
  StickySubsteps& sticky = health_[index].substeps;
  const std::int64_t budget = settings_.health.step_budget;
  const std::int64_t affordable = affordable_substeps(index);
  const std::int64_t fewest = fewest_substeps(index, h);
  spent_ = 0;
  capped_ = false;
  const RescueOutcome outcome = step_with_rescue(
      static_cast<int>(
          std::min(affordable, std::max<std::int64_t>(fewest, sticky.start(relax_steps)))),
      settings_.max_doublings,
      [&](int substeps) {
        advance(index, t, h, substeps, colliders, yield_point);
        return timed(stats_.profile, StepStage::kHealth,
                     [&] { return healthy(index, t, h, start); });
      },
      [&] {
        body.state().x = backup_.x;
        body.state().v = backup_.v;
        body.integrator().reset();
        start.first = false;
      },
      // each substep takes at least the internal steps no limit cuts (xpbd's substeps)
      [&](int next) {
        return spent_ + std::int64_t{next} * body.integrator().least_internal_steps() <= budget;
      });
  sticky.record(outcome);
  record_counts(index, outcome.substeps, fewest > affordable || outcome.out_of_budget);
  if (outcome.rescued) {
    stats_.rescued = true;
    stats_.rescued_bodies.push_back(static_cast<std::uint32_t>(index));
    take_back_growth(index);
    health_[index].balance.reset(mechanical_energy(body, h));
  } else if (outcome.ok) {
    // healthy() measured the state the step left
    health_[index].balance.accept(energy_[index] + gravitational_, work_,
                                  energy_scale(index, energy_[index]), window_);
  } else {
    body.state().x = backup_.x;
    stop(index);
    energy_[index] = body.elastic_energy_in_steps_of(h);
    health_[index].balance.reset(mechanical_energy(body, h));
  }
  return outcome.substeps;
}

int ClothSystem::step_unchecked(std::size_t index, Real t, Real h,
                                std::span<const Collider> colliders,
                                const std::function<void()>& yield_point) {
  const std::int64_t affordable = affordable_substeps(index);
  const std::int64_t fewest = fewest_substeps(index, h);
  const int substeps = static_cast<int>(std::min(affordable, fewest));
  spent_ = 0;
  capped_ = false;
  advance(index, t, h, substeps, colliders, yield_point);
  record_counts(index, substeps, fewest > affordable);
  ClothBody& body = bodies_[index];
  const bool finite = timed(stats_.profile, StepStage::kHealth, [&] {
    return all_finite(body.state().x) && all_finite(body.state().v);
  });
  if (!finite) {
    body.state().x = body.model().rest_positions;
    stop(index);
  }
  return substeps;
}

void ClothSystem::take_back_growth(std::size_t index) {
  ClothBody& body = bodies_[index];
  const EnergyBalance& balance = health_[index].balance;
  // healthy() kept the energy and the work of the retried step
  const Real excess = balance.excess(balance.budget_after(energy_[index] + gravitational_, work_));
  if (excess == 0) return;
  const std::vector<Real>& mass = body.model().mass;
  const InternalMotion motion = internal_motion(
      body.state().v, body.inv_mass(), [&](std::size_t p) { return mass[p]; },
      !body.anchors().empty());
  const Real factor = internal_motion_factor(motion.energy, excess);
  scale_internal_motion(body.state().v, body.inv_mass(), motion.centre_velocity, factor);
  energy_[index] -= (1 - factor * factor) * motion.energy;
  body.integrator().reset();
}

std::int64_t ClothSystem::affordable_substeps(std::size_t index) const {
  return std::max<std::int64_t>(
      1, settings_.health.step_budget / bodies_[index].integrator().least_internal_steps());
}

void ClothSystem::record_counts(std::size_t index, int substeps, bool over_budget) {
  BodyStepCounts& counts = health_[index].counts;
  counts.substeps = substeps;
  if (over_budget || capped_) {
    ++counts.over_budget_steps;
    stats_.over_budget.push_back(static_cast<std::uint32_t>(index));
  }
}

void ClothSystem::stop(std::size_t index) {
  ClothBody& body = bodies_[index];
  for (Vec3& v : body.state().v) v.setZero();
  body.integrator().reset();
  stats_.unrecoverable.push_back(static_cast<std::uint32_t>(index));
}

std::int64_t ClothSystem::fewest_substeps(std::size_t index, Real h) {
  const ClothBody& body = bodies_[index];
  const std::int64_t asked = substeps_for(h, body.max_step());
  if (!settings_.health.auto_substeps) return asked;
  return std::max(asked, substeps_for(h, health_[index].stable_step.of(body)));
}

void ClothSystem::advance(std::size_t index, Real t, Real h, int substeps,
                          std::span<const Collider> colliders,
                          const std::function<void()>& yield_point) {
  ClothBody& body = bodies_[index];
  const Real dt = h / substeps;
  StepProfile& profile = stats_.profile;
  Integrator& integrator = body.integrator();
  for (int s = 0; s < substeps; ++s) {
    // an even share of what the budget has left: the attempt, started only when its substeps
    // fit, never spends beyond it
    const int share = static_cast<int>(
        std::max<std::int64_t>(1, (settings_.health.step_budget - spent_) / (substeps - s)));
    integrator.limit_internal_steps(share);
    timed(profile, StepStage::kIntegration,
          [&] { integrator.step(body, body.state(), t + s * dt, dt); });
    spent_ += integrator.last_internal_steps();
    capped_ = capped_ || integrator.last_step_capped();
    if (yield_point) yield_point();
    timed(profile, StepStage::kStretchLimit, [&] {
      if (body.params().stretch.enabled) limit_stretch(index, dt, share);
    });
    timed(profile, StepStage::kColliders, [&] {
      limiters_[index].set_pushed_by_colliders(resolve_collisions(colliders, body.inv_mass(),
                                                                  body.params().thickness,
                                                                  body.state()) > 0);
    });
    if (body.params().self_collision) {
      timed(profile, StepStage::kSelfCollision, [&] {
        self_collision_[index].resolve(body.model().triangles, body.inv_mass(),
                                       body.params().thickness, body.state());
      });
    }
    timed(profile, StepStage::kConstraints,
          [&] { apply_constraints(body.constraints(), body.state()); });
    if (yield_point) yield_point();
  }
}

void ClothSystem::limit_stretch(std::size_t index, Real dt, int share) {
  ClothBody& body = bodies_[index];
  StretchLimit limit = body.params().stretch;
  limit.iterations = std::min(limit.iterations, share);
  limit.projection_iterations = std::min(limit.projection_iterations, share);
  const StretchLimitStats done =
      limiters_[index].apply(body.model(), body.inv_mass(), limit, dt, body.state());
  // the positions' last part (the projection after the sweeps, if they left a spring beyond
  // its bound) used all the share cut it to: stopped unconverged (the velocities' sweeps fall
  // back on a direct solve)
  const StretchLimit& asked = body.params().stretch;
  const bool cut =
      done.position_projections > 0
          ? limit.projection_iterations < asked.projection_iterations &&
                done.position_projections == limit.projection_iterations
          : limit.iterations < asked.iterations && done.position_sweeps == limit.iterations;
  capped_ = capped_ || cut;
}

bool ClothSystem::healthy(std::size_t index, Real t, Real h, StepStart& start) {
  const ClothBody& body = bodies_[index];
  const ParticleState& state = body.state();
  const HealthSettings& health = settings_.health;
  const Real max_speed = scaled_speed_limit(start.speed, health_[index].size, h,
                                            health.speed_growth, settings_.max_speed);
  const Real max_speed_sq = max_speed * max_speed;
  // the applied forces change within a step only with the wind (external ones are cleared after)
  std::span<const Vec3> applied_after = applied_before_;
  if (body.params().wind.enabled) {
    applied_after_.resize(state.size());
    body.applied_forces(t + h, applied_after_);
    applied_after = applied_after_;
  }
  // work by gravity and external forces over the step, estimated from the displacement and
  // from the mean of the start and end velocities, whichever is larger: the first misses the
  // energy explicit Euler gains in a step from rest (positions have not moved yet), the second
  // misjudges a step in which substeps turned a velocity around
  Real work_by_displacement = 0;
  Real work_by_velocity = 0;
  // the work of the applied forces alone (gravity's is in the mechanical energy), by the
  // trapezoidal rule: exact for a force constant over the step
  Real applied_work = 0;
  // ClothBody::kinetic_energy and gravitational_energy, summed in the same order in this pass
  Real kinetic = 0, gravitational = 0;
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (!state.x[p].allFinite()) return false;
    const Real speed_sq = state.v[p].squaredNorm();
    if (!std::isfinite(speed_sq) || speed_sq > max_speed_sq) return false;
    const Real mass = body.model().mass[p];
    kinetic += 0.5 * mass * speed_sq;
    gravitational -= mass * body.gravity().dot(state.x[p]);
    const Vec3 displacement = state.x[p] - backup_.x[p];
    const Vec3 force = mass * body.gravity() + body.external_forces()[p];
    work_by_displacement += force.dot(displacement);
    work_by_velocity += force.dot(0.5 * h * (state.v[p] + backup_.v[p]));
    applied_work += 0.5 * (applied_before_[p] + applied_after[p]).dot(displacement);
  }
  const Real work = std::max({work_by_displacement, work_by_velocity, Real{0}});
  const Real energy_after = kinetic + body.elastic_energy_in_steps_of(h);
  const Real growth = settings_.max_energy_growth;
  if (energy_after > growth * (start.energy + work) + energy_floor(index)) return false;
  // slow growth, judged on the first attempt only: a window cannot judge a retried step, and
  // the balance starts over after it
  const EnergyBalance& balance = health_[index].balance;
  if (start.first &&
      !balance.within(balance.budget_after(energy_after + gravitational, applied_work),
                      energy_scale(index, energy_after), health.energy_tolerance, window_)) {
    return false;
  }
  work_ = applied_work;
  gravitational_ = gravitational;
  energy_[index] = energy_after;
  return true;
}

}  // namespace felt
