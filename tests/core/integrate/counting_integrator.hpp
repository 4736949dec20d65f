#pragma once
// An integrator that passes every call on to another and counts the work: the internal steps
// (Integrator::last_internal_steps) of all its calls since the count was last taken.

#include <memory>
#include <utility>

#include "core/integrate/integrator.hpp"

namespace felt::test {

class CountingIntegrator final : public Integrator {
 public:
  explicit CountingIntegrator(std::unique_ptr<Integrator> inner) : inner_(std::move(inner)) {}

  std::string_view name() const override { return inner_->name(); }
  void step(const DynamicSystem& system, ParticleState& state, Real t, Real h) override {
    inner_->step(system, state, t, h);
    work_ += inner_->last_internal_steps();
  }
  void reset() override { inner_->reset(); }
  Real step_limit(const OscillatorMode& mode) const override { return inner_->step_limit(mode); }
  void limit_internal_steps(int cap) override { inner_->limit_internal_steps(cap); }
  int last_internal_steps() const override { return inner_->last_internal_steps(); }
  int least_internal_steps() const override { return inner_->least_internal_steps(); }
  Real constraint_substep(Real h) const override { return inner_->constraint_substep(h); }
  bool last_step_capped() const override { return inner_->last_step_capped(); }
  Real position_tolerance() const override { return inner_->position_tolerance(); }

  /// The internal steps since the last call.
  long take_work() { return std::exchange(work_, 0); }

 private:
  std::unique_ptr<Integrator> inner_;
  long work_ = 0;
};

}  // namespace felt::test
