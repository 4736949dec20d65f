#include "core/cloth/cloth_stable_step.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/integrate/force_jacobian.hpp"
#include "core/math/largest_eigenvalue.hpp"

namespace felt {
namespace {

/// The smallest damping-to-stiffness ratio of the spring kinds the model has and of the
/// anchors, s; 0 when one of them is undamped.
Real least_damping_ratio(const ClothBody& body) {
  Real least = std::numeric_limits<Real>::infinity();
  std::array<bool, kSpringKindCount> present{};
  for (const Spring& s : body.model().springs) present[static_cast<int>(s.kind)] = true;
  for (int kind = 0; kind < kSpringKindCount; ++kind) {
    const SpringParams& sp = body.params().springs[kind];
    if (present[kind] && sp.enabled && sp.stiffness > 0) {
      least = std::min(least, sp.damping / sp.stiffness);
    }
  }
  for (const Anchor& a : body.anchors()) {
    if (a.stiffness > 0) least = std::min(least, a.damping / a.stiffness);
  }
  return std::isfinite(least) ? least : 0;
}

}  // namespace

ClothFastestMode fastest_mode(const ClothBody& body) {
  const ClothModel& model = body.model();
  const std::span<const Real> inv_mass = body.inv_mass();
  ForceJacobian jacobian;
  const std::vector<Vec3> rest_velocity(model.particle_count(), Vec3::Zero());
  body.compute_jacobian(model.rest_positions, rest_velocity, jacobian);
  std::vector<Real> scale(inv_mass.size());
  Real least_inverse_mass = std::numeric_limits<Real>::infinity();
  for (std::size_t p = 0; p < inv_mass.size(); ++p) {
    scale[p] = std::sqrt(inv_mass[p]);
    if (inv_mass[p] > 0) least_inverse_mass = std::min(least_inverse_mass, inv_mass[p]);
  }
  Eigen::SparseMatrix<Real> stiffness, damping;
  jacobian.scaled_matrices(scale, stiffness, damping);
  ClothFastestMode mode;
  mode.omega_squared = largest_eigenvalue(stiffness);
  mode.most_rate = largest_eigenvalue(damping);
  const Real drag_rate =
      std::isfinite(least_inverse_mass) ? body.params().drag * least_inverse_mass : 0;
  mode.least_rate =
      std::min(mode.most_rate, drag_rate + least_damping_ratio(body) * mode.omega_squared);
  return mode;
}

Real stable_cloth_step(const ClothBody& body) {
  const Integrator& integrator = body.integrator();
  // an integrator without a limit has none on any mode: no eigenvalues to find
  if (integrator.step_limit({1, 0}) == kNoStepLimit) return kNoStepLimit;
  return stable_cloth_step(body,
                           [&](const OscillatorMode& mode) { return integrator.step_limit(mode); });
}

Real stable_cloth_step(const ClothBody& body,
                       const std::function<Real(const OscillatorMode&)>& limit) {
  const ClothFastestMode mode = fastest_mode(body);
  if (mode.omega_squared == 0 && mode.most_rate == 0) return kNoStepLimit;
  return kClothStepMargin * std::min(limit({mode.omega_squared, mode.least_rate}),
                                     limit({mode.omega_squared, mode.most_rate}));
}

Real CachedStableStep::of(const ClothBody& body) {
  Inputs inputs = inputs_of(body);
  if (inputs_ != inputs) {
    step_ = stable_cloth_step(body);
    inputs_ = inputs;
  }
  return step_;
}

CachedStableStep::Inputs CachedStableStep::inputs_of(const ClothBody& body) {
  Inputs inputs{.integrator = body.integrator().name(),
                .springs = body.params().springs,
                .drag = body.params().drag};
  for (const Anchor& a : body.anchors()) {
    ++inputs.anchors;
    inputs.anchor_stiffness += a.stiffness;
    inputs.anchor_damping += a.damping;
  }
  for (Real w : body.inv_mass()) inputs.pinned += w == 0 ? 1 : 0;
  return inputs;
}

}  // namespace felt
