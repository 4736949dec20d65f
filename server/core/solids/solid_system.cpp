#include "core/solids/solid_system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math/bounds_of.hpp"
#include "core/math/check.hpp"
#include "core/solids/solid_collider_contact.hpp"
#include "core/step/energy_balance.hpp"
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
  bodies_.push_back(std::move(body));
  Eigen::AlignedBox<Real, 3> bounds;
  for (const SolidBody& b : bodies_) bounds.extend(bounds_of(b.positions()));
  size_ = bounds.diagonal().norm();
  // thesis 2 §2.2: the grid cell is the mean edge length
  detector_.set_cell_size(mean_rest_edge_length(bodies_));
  return static_cast<std::uint32_t>(bodies_.size() - 1);
}

void SolidSystem::remove_body(std::uint32_t index) {
  FELT_CHECK(index < bodies_.size());
  bodies_.erase(bodies_.begin() + index);
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
  settings_ = settings;
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
    return stats_;
  }
  const int substeps =
      std::min(budget, std::max(stable, sticky_.start(static_cast<std::int64_t>(
                                            std::ceil(settings_.health.relax_after / h)))));

  SpeedSources speed{.acceleration = gravity.norm()};
  saved_.resize(bodies_.size());
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    SolidBody& body = bodies_[b];
    body.save_step_state(saved_[b]);
    for (const Vec3& v : body.velocities()) speed.fastest = std::max(speed.fastest, v.norm());
    const Real node_mass = body.material().node_mass;
    for (const Vec3& f : body.external_forces()) {
      speed.acceleration = std::max(speed.acceleration, gravity.norm() + f.norm() / node_mass);
    }
    speed.reachable =
        std::max(speed.reachable,
                 std::sqrt(2 * (body.kinetic_energy() + body.elastic_energy()) / node_mass));
  }
  const Real max_speed =
      scaled_speed_limit(speed, size_, h, settings_.health.speed_growth, settings_.max_speed);
  const RescueOutcome outcome = step_with_rescue(
      substeps, kRescue,
      [&](int n) { return attempt(h, n, gravity, colliders, max_speed, yield_point); },
      [&] { restore(); }, budget);
  sticky_.record(outcome);
  stats_.over_budget = stable > budget || outcome.out_of_budget;
  counts_.substeps = outcome.substeps;
  if (stats_.over_budget) ++counts_.over_budget_steps;
  stats_.rescued = outcome.rescued;
  if (!outcome.ok) {
    restore();
    stop();
  }
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

void SolidSystem::restore() {
  for (std::size_t b = 0; b < bodies_.size(); ++b) bodies_[b].restore_step_state(saved_[b]);
}

}  // namespace felt
