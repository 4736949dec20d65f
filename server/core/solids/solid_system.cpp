#include "core/solids/solid_system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math/bounds_of.hpp"
#include "core/math/check.hpp"
#include "core/solids/solid_collider_contact.hpp"
#include "core/step/energy_balance.hpp"
#include "core/step/internal_motion.hpp"
#include "core/step/substep_rescue.hpp"
#include "core/step/substeps_for.hpp"

namespace felt {
namespace {

// A failing step's retries take at most 512 substeps in all, or 4 times the substeps of the
// first attempt when that is more: a step that cannot be rescued then costs a few normal steps,
// not seconds. A body that needed 445 substeps for its damping, beside two coincident rings no
// substep could save, took 57,000 substeps (10 s) a step to fail.
constexpr RescuePolicy kRescue{.max_doublings = 6, .min_budget = 512, .budget_factor = 4};

}  // namespace

SolidSystem::SolidSystem(SolidStepSettings settings) {
  set_settings(settings);
}

std::uint32_t SolidSystem::add_body(SolidBody body) {
  mass_ += body.material().node_mass * static_cast<Real>(body.node_count());
  bodies_.push_back(std::move(body));
  energy_valid_ = false;
  Eigen::AlignedBox<Real, 3> bounds;
  for (const SolidBody& b : bodies_) bounds.extend(bounds_of(b.positions()));
  size_ = bounds.diagonal().norm();
  // thesis 2 §2.2: the grid cell is the mean edge length
  detector_.set_cell_size(mean_rest_edge_length(bodies_));
  return static_cast<std::uint32_t>(bodies_.size() - 1);
}

void SolidSystem::remove_body(std::uint32_t index) {
  FELT_CHECK(index < bodies_.size());
  mass_ -= bodies_[index].material().node_mass * static_cast<Real>(bodies_[index].node_count());
  bodies_.erase(bodies_.begin() + index);
  energy_valid_ = false;
  detector_ = SolidCollisionDetector();
  penetration_ = PenetrationDepthEstimator();
  contact_surface_ = ContactSurface();
  collisions_ = CollisionSet();
  contacts_.clear();
  saved_.clear();
  if (!bodies_.empty()) detector_.set_cell_size(mean_rest_edge_length(bodies_));
}

void SolidSystem::set_settings(const SolidStepSettings& settings) {
  FELT_CHECK(settings.max_step > 0);
  FELT_CHECK(settings.contact_iterations >= 0);
  FELT_CHECK(settings.min_depth >= 0);
  FELT_CHECK(settings.max_speed > 0);
  FELT_CHECK(settings.max_energy_growth > 1);
  settings_ = settings;
  energy_valid_ = false;
}

const SolidStepStats& SolidSystem::step(Real h, const Vec3& gravity,
                                        std::span<const Collider> colliders,
                                        const std::function<void()>& yield_point) {
  FELT_CHECK(h > 0);
  stats_ = SolidStepStats{};
  if (bodies_.empty()) return stats_;
  Real longest = settings_.max_step;
  for (const SolidBody& body : bodies_) {
    longest = std::min({longest, body.stable_time_step(), body.max_step()});
  }
  const int budget = settings_.health.step_budget;
  // past the budget any count stands for all (a stiff grab can ask for billions)
  const std::int64_t wanted = substeps_for(h, longest);
  const int stable = wanted > budget ? budget + 1 : static_cast<int>(wanted);
  if (!settings_.health.enabled) {
    step_unchecked(h, std::min(budget, stable), gravity, colliders, yield_point);
    stats_.over_budget = stable > budget;
    if (stats_.over_budget) ++counts_.over_budget_steps;
    energy_valid_ = false;  // not kept: a check turned on starts from the state as it is then
    return stats_;
  }
  const bool set_now = !energy_valid_;
  if (set_now) {
    energy_ = 0;
    for (const SolidBody& body : bodies_) energy_ += body.kinetic_energy() + body.elastic_energy();
  }
  window_ = std::max(HealthSettings::kMinWindowSteps,
                     static_cast<int>(std::ceil(settings_.health.energy_window / h)));
  const int substeps =
      std::min(budget, std::max(stable, sticky_.start(static_cast<std::int64_t>(
                                            std::ceil(settings_.health.relax_after / h)))));

  SpeedSources speed{.acceleration = gravity.norm()};
  Real lightest = std::numeric_limits<Real>::infinity();
  saved_.resize(bodies_.size());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    SolidBody& body = bodies_[b];
    body.save_step_state(saved_[b]);
    for (const Vec3& v : body.velocities()) speed.fastest = std::max(speed.fastest, v.norm());
    const Real node_mass = body.material().node_mass;
    lightest = std::min(lightest, node_mass);
    for (const Vec3& f : body.external_forces()) {
      speed.acceleration = std::max(speed.acceleration, gravity.norm() + f.norm() / node_mass);
    }
  }
  speed.reachable = std::sqrt(2 * energy_ / lightest);
  const Real max_speed =
      scaled_speed_limit(speed, size_, h, settings_.health.speed_growth, settings_.max_speed);
  StepStart start{.energy = energy_, .set_now = set_now};
  const RescueOutcome outcome = step_with_rescue(
      substeps, kRescue,
      [&](int n) {
        return attempt(h, n, gravity, colliders, max_speed, yield_point) &&
               timed(stats_.profile, StepStage::kHealth,
                     [&] { return energy_healthy(h, gravity, start); });
      },
      [&] {
        restore();
        start.first = false;
      },
      budget);
  sticky_.record(outcome);
  stats_.over_budget = stable > budget || outcome.out_of_budget;
  counts_.substeps = outcome.substeps;
  if (stats_.over_budget) ++counts_.over_budget_steps;
  stats_.rescued = outcome.rescued;
  if (outcome.rescued) take_back_growth();
  if (outcome.rescued || (outcome.ok && set_now)) {
    // the growth before a rescue cannot be undone: the balance starts over from here, as it
    // does after the first step of solids just set (energy_healthy and take_back_growth kept
    // the energies the step left)
    balance_.reset(energy_ + gravitational_);
  } else if (outcome.ok) {
    // energy_healthy measured the state the step left
    balance_.accept(energy_ + gravitational_, work_, energy_scale(energy_, gravity), window_);
  } else {
    restore();
    stop();
    energy_ = 0;
    for (const SolidBody& body : bodies_) energy_ += body.elastic_energy();
    balance_.reset(mechanical_energy(gravity));
  }
  energy_valid_ = true;
  stats_.substeps = outcome.substeps;
  for (SolidBody& body : bodies_) body.clear_external_forces();
  return stats_;
}

void SolidSystem::step_unchecked(Real h, int substeps, const Vec3& gravity,
                                 std::span<const Collider> colliders,
                                 const std::function<void()>& yield_point) {
  // the finiteness check stays: a non-finite node must not reach the spatial hash
  if (!attempt(h, substeps, gravity, colliders, std::numeric_limits<Real>::infinity(),
               yield_point)) {
    for (SolidBody& body : bodies_) body.positions() = body.rest().nodes;
    stop();
  }
  counts_.substeps = substeps;
  stats_.substeps = substeps;
  for (SolidBody& body : bodies_) body.clear_external_forces();
}

void SolidSystem::stop() {
  for (SolidBody& body : bodies_) {
    body.previous_positions() = body.positions();
    for (Vec3& v : body.velocities()) v.setZero();
  }
  stats_.unrecoverable = true;
}

bool SolidSystem::attempt(Real h, int substeps, const Vec3& gravity,
                          std::span<const Collider> colliders, Real max_speed,
                          const std::function<void()>& yield_point) {
  const Real substep_length = h / substeps;
  StepProfile& profile = stats_.profile;
  for (int s = 0; s < substeps; ++s) {
    timed(profile, StepStage::kIntegration, [&] {
      for (SolidBody& body : bodies_) body.advance(substep_length, gravity);
    });
    // a non-finite node must not reach the spatial hash
    if (!timed(profile, StepStage::kHealth, [&] { return healthy(false, max_speed); }))
      return false;
    if (yield_point) yield_point();
    substep(substep_length, gravity, colliders);
    if (!timed(profile, StepStage::kHealth, [&] { return healthy(true, max_speed); })) return false;
    if (yield_point) yield_point();
  }
  return true;
}

void SolidSystem::substep(Real h, const Vec3& gravity, std::span<const Collider> colliders) {
  timed(stats_.profile, StepStage::kDetection, [&] { detector_.detect(bodies_, collisions_); });
  timed(stats_.profile, StepStage::kTriangles,
        [&] { detector_.collect_triangles(bodies_, collisions_); });
  timed(stats_.profile, StepStage::kPenetration,
        [&] { penetration_.compute(bodies_, collisions_, settings_.min_depth, contacts_); });
  timed(stats_.profile, StepStage::kResolution, [&] {
    contact_surface_.resolve(bodies_, contacts_, settings_.contact_iterations, settings_.friction,
                             h, gravity);
  });
  timed(stats_.profile, StepStage::kColliders, [&] {
    for (SolidBody& body : bodies_) resolve_collider_contacts(colliders, body);
  });
  timed(stats_.profile, StepStage::kFinish, [&] {
    for (SolidBody& body : bodies_) body.finish_step(h);
  });
  stats_.colliding_nodes = collisions_.nodes.size();
  stats_.colliding_triangles = 0;
  for (const std::vector<std::uint32_t>& triangles : collisions_.triangles) {
    stats_.colliding_triangles += triangles.size();
  }
}

bool SolidSystem::healthy(bool check_speed, Real max_speed) const {
  const Real max_speed_sq = max_speed * max_speed;
  for (const SolidBody& body : bodies_) {
    for (const Vec3& x : body.positions()) {
      if (!x.allFinite()) return false;
    }
    if (!check_speed) continue;
    for (const Vec3& v : body.velocities()) {
      // NaN fails the comparison and is caught too
      if (!(v.squaredNorm() <= max_speed_sq)) return false;
    }
  }
  return true;
}

bool SolidSystem::energy_healthy(Real h, const Vec3& gravity, const StepStart& start) {
  // work by gravity and the external forces (constant over the step) as in ClothSystem: from
  // the displacement and from the mean of the start and end velocities, whichever is larger
  Real work_by_displacement = 0, work_by_velocity = 0;
  // the work of the external forces alone (gravity's is in the mechanical energy): exact, as
  // they are constant over the step
  Real applied_work = 0;
  // SolidBody::kinetic_energy and gravitational_energy, summed in this pass
  Real kinetic_elastic = 0, gravitational = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const SolidBody& body = bodies_[b];
    const SolidBody::StepState& before = saved_[b];
    const Real mass = body.material().node_mass;
    for (std::size_t n = 0; n < body.node_count(); ++n) {
      kinetic_elastic += 0.5 * mass * body.velocities()[n].squaredNorm();
      gravitational -= mass * gravity.dot(body.positions()[n]);
      const Vec3 displacement = body.positions()[n] - before.x[n];
      const Vec3& external = before.external_force[n];
      const Vec3 force = mass * gravity + external;
      work_by_displacement += force.dot(displacement);
      work_by_velocity += force.dot(0.5 * h * (body.velocities()[n] + before.v[n]));
      applied_work += external.dot(displacement);
    }
    kinetic_elastic += body.elastic_energy();
  }
  const Real work = std::max({work_by_displacement, work_by_velocity, Real{0}});
  // Contact is resolved by moving nodes out of each other and the colliders, which gives a
  // body set inside something energy no force supplied (the thesis's lower ring starts 0.17 m
  // into the floor: 178 J in its first step; a cube of 0.6 kg sunk as deep flies off with
  // 600 J). The first step after the solids were set is judged by its speed only, and the
  // balance starts after it.
  if (start.set_now) {
    gravitational_ = gravitational;
    energy_ = kinetic_elastic;
    return true;
  }
  // written to fail on NaN as well
  if (!(kinetic_elastic <= settings_.max_energy_growth * (start.energy + work) + kEnergyFloor))
    return false;
  // slow growth, judged on the first attempt only: a window cannot judge a retried step, and
  // the balance starts over after it
  if (start.first &&
      !balance_.within(balance_.budget_after(kinetic_elastic + gravitational, applied_work),
                       energy_scale(kinetic_elastic, gravity), settings_.health.energy_tolerance,
                       window_)) {
    return false;
  }
  work_ = applied_work;
  gravitational_ = gravitational;
  energy_ = kinetic_elastic;
  return true;
}

void SolidSystem::take_back_growth() {
  // energy_healthy() kept the energy and the work of the retried step
  const Real excess = balance_.excess(balance_.budget_after(energy_ + gravitational_, work_));
  if (excess == 0) return;
  // one factor for all the solids, each scaled about its own centre of mass (or, held in
  // place, about rest)
  std::vector<InternalMotion> motions;
  Real internal = 0;
  for (const SolidBody& body : bodies_) {
    const Real node_mass = body.material().node_mass;
    motions.push_back(internal_motion(
        body.velocities(), body.inv_mass(), [&](std::size_t) { return node_mass; },
        !body.anchors().empty()));
    internal += motions.back().energy;
  }
  const Real factor = internal_motion_factor(internal, excess);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    scale_internal_motion(bodies_[b].velocities(), bodies_[b].inv_mass(),
                          motions[b].centre_velocity, factor);
    bodies_[b].forget_history();
  }
  energy_ -= (1 - factor * factor) * internal;
}

Real SolidSystem::mechanical_energy(const Vec3& gravity) const {
  Real energy = 0;
  for (const SolidBody& body : bodies_) {
    energy += body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy(gravity);
  }
  return energy;
}

Real SolidSystem::energy_scale(Real kinetic_elastic, const Vec3& gravity) const {
  return kinetic_elastic + mass_ * gravity.norm() * size_ + kEnergyFloor;
}

void SolidSystem::restore() {
  for (std::size_t b = 0; b < bodies_.size(); ++b) bodies_[b].restore_step_state(saved_[b]);
}

}  // namespace felt
