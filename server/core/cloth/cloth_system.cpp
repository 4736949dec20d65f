#include "core/cloth/cloth_system.hpp"

#include <algorithm>
#include <cmath>

#include "core/math/check.hpp"

namespace felt {

std::uint32_t ClothSystem::add_body(ClothBody body) {
  bodies_.push_back(std::move(body));
  self_collision_.emplace_back();
  limiters_.emplace_back();
  energy_valid_ = false;
  return static_cast<std::uint32_t>(bodies_.size() - 1);
}

void ClothSystem::remove_body(std::uint32_t index) {
  FELT_CHECK(index < bodies_.size());
  bodies_.erase(bodies_.begin() + index);
  self_collision_.erase(self_collision_.begin() + index);
  limiters_.erase(limiters_.begin() + index);
  energy_valid_ = false;
}

const ClothStepStats& ClothSystem::step(Real t, Real h, std::span<const Collider> colliders,
                                        const std::function<void()>& yield_point) {
  stats_.substeps = 1;
  stats_.rescued = false;
  stats_.unrecoverable.clear();
  stats_.profile = {};
  if (!energy_valid_) {
    energy_.resize(bodies_.size());
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      energy_[b] = bodies_[b].kinetic_energy() + bodies_[b].elastic_energy();
    }
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    ClothBody& body = bodies_[b];
    // copy-assignment into equally sized vectors reuses their storage: no allocation
    backup_.x = body.state().x;
    backup_.v = body.state().v;
    const RescueOutcome outcome = step_with_rescue(
        1, settings_.rescue,
        [&](int substeps) {
          return attempt(b, t, h, substeps, colliders, energy_[b], yield_point);
        },
        [&] {
          body.state().x = backup_.x;
          body.state().v = backup_.v;
          body.integrator().reset();
        });
    stats_.rescued = stats_.rescued || outcome.rescued;
    if (!outcome.ok) {
      body.state().x = backup_.x;
      for (Vec3& v : body.state().v) v.setZero();
      body.integrator().reset();
      energy_[b] = body.elastic_energy();
      stats_.unrecoverable.push_back(static_cast<std::uint32_t>(b));
    }
    stats_.substeps = std::max(stats_.substeps, outcome.substeps);
    body.clear_external_forces();
  }
  energy_valid_ = true;
  return stats_;
}

bool ClothSystem::attempt(std::size_t index, Real t, Real h, int substeps,
                          std::span<const Collider> colliders, Real& energy,
                          const std::function<void()>& yield_point) {
  ClothBody& body = bodies_[index];
  const Real dt = h / substeps;
  StepProfile& profile = stats_.profile;
  for (int s = 0; s < substeps; ++s) {
    timed(profile, StepStage::kIntegration,
          [&] { body.integrator().step(body, body.state(), t + s * dt, dt); });
    if (yield_point) yield_point();
    timed(profile, StepStage::kStretchLimit, [&] {
      limiters_[index].apply(body.model(), body.inv_mass(), body.params().stretch, dt,
                             body.state());
    });
    timed(profile, StepStage::kColliders, [&] {
      resolve_collisions(colliders, body.inv_mass(), body.params().thickness, body.state());
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
  return timed(profile, StepStage::kHealth, [&] { return healthy(body, h, energy); });
}

bool ClothSystem::healthy(const ClothBody& body, Real h, Real& energy) const {
  const ParticleState& state = body.state();
  const Real max_speed_sq = settings_.max_speed * settings_.max_speed;
  // work by gravity and external forces over the step, estimated from the displacement and
  // from the mean of the start and end velocities, whichever is larger: the first misses the
  // energy explicit Euler gains in a step from rest (positions have not moved yet), the second
  // misjudges a step in which substeps turned a velocity around
  Real work_by_displacement = 0;
  Real work_by_velocity = 0;
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (!state.x[p].allFinite()) return false;
    const Real speed_sq = state.v[p].squaredNorm();
    if (!std::isfinite(speed_sq) || speed_sq > max_speed_sq) return false;
    const Vec3 force = body.model().mass[p] * body.gravity() + body.external_forces()[p];
    work_by_displacement += force.dot(state.x[p] - backup_.x[p]);
    work_by_velocity += force.dot(0.5 * h * (state.v[p] + backup_.v[p]));
  }
  const Real work = std::max({work_by_displacement, work_by_velocity, Real{0}});
  const Real energy_after = body.kinetic_energy() + body.elastic_energy();
  const Real growth = settings_.max_energy_growth;
  // the floor keeps rounding noise of a body at rest from counting as growth
  constexpr Real kEnergyFloor = 1e-9;
  if (energy_after > growth * (energy + work) + kEnergyFloor) return false;
  energy = energy_after;
  return true;
}

}  // namespace felt
